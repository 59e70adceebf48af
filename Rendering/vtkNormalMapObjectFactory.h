// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkNormalMapObjectFactory
 * @brief   Makes VTK's object factory create the module's normal-mapping mappers.
 *
 * For applications that create their mappers through VTK's object factory (ParaView-like
 * applications, readers and importers): after Install(), every vtkPolyDataMapper::New()
 * returns a vtkNormalMapPolyDataMapper, and the factory creates a
 * vtkNormalMapCompositePolyDataMapper for VTK's composite mapper (vtkCompositePolyDataMapper2
 * up to VTK 9.2, vtkCompositePolyDataMapper from 9.3); both render exactly like VTK's mappers
 * where no normal texture is set. Nothing changes until Install() is called: linking the
 * module does not override anything. Uninstall() restores VTK's own.
 *
 * The composite mappers' New() asks the object factory only in VTK builds with
 * VTK_ALL_NEW_OBJECT_FACTORY (Debian's VTK 9.1 is built without it); elsewhere the override
 * reaches code that creates the class by name (vtkObjectFactory::CreateInstance), and
 * applications create vtkNormalMapCompositePolyDataMapper directly.
 * vtkPolyDataMapper::New() always asks the factory.
 *
 * VTK's OpenGL module registers its own vtkPolyDataMapper override first, and the factory
 * returns the first enabled override, so Install() disables the others for each overridden
 * class and Uninstall() enables again the ones it disabled (those the application had disabled
 * itself stay so).
 */
#ifndef vtkNormalMapObjectFactory_h
#define vtkNormalMapObjectFactory_h

#include "vtkNormalMappingModule.h" // For export macro
#include "vtkObjectFactory.h"

class VTKNORMALMAPPING_EXPORT vtkNormalMapObjectFactory : public vtkObjectFactory
{
public:
  static vtkNormalMapObjectFactory* New();
  vtkTypeMacro(vtkNormalMapObjectFactory, vtkObjectFactory);

  const char* GetVTKSourceVersion() override;
  const char* GetDescription() override;

  /// Register the factory (once) and make its override the one in effect.
  static void Install();
  /// Unregister it; the overrides Install() disabled are enabled again.
  static void Uninstall();
  /// Whether Install() is in effect.
  static bool IsInstalled();

protected:
  vtkNormalMapObjectFactory();
  ~vtkNormalMapObjectFactory() override = default;

private:
  vtkNormalMapObjectFactory(const vtkNormalMapObjectFactory&) = delete;
  void operator=(const vtkNormalMapObjectFactory&) = delete;
};

#endif
