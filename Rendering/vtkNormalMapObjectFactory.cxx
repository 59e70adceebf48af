#include "vtkNormalMapObjectFactory.h"

#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactoryCollection.h"
#include "vtkVersion.h"

vtkStandardNewMacro(vtkNormalMapObjectFactory);

namespace
{
vtkObject* CreateNormalMapPolyDataMapper()
{
  return vtkNormalMapPolyDataMapper::New();
}

/// The registered factory, or nullptr.
vtkNormalMapObjectFactory* Registered()
{
  vtkObjectFactoryCollection* factories = vtkObjectFactory::GetRegisteredFactories();
  vtkCollectionSimpleIterator it;
  factories->InitTraversal(it);
  while (vtkObjectFactory* factory = factories->GetNextObjectFactory(it))
  {
    if (auto* ours = vtkNormalMapObjectFactory::SafeDownCast(factory))
    {
      return ours;
    }
  }
  return nullptr;
}
}

//------------------------------------------------------------------------------
vtkNormalMapObjectFactory::vtkNormalMapObjectFactory()
{
  this->RegisterOverride("vtkPolyDataMapper",
    "vtkNormalMapPolyDataMapper",
    "Normal-mapping polydata mapper",
    1,
    CreateNormalMapPolyDataMapper);
}

//------------------------------------------------------------------------------
const char* vtkNormalMapObjectFactory::GetVTKSourceVersion()
{
  return VTK_SOURCE_VERSION;
}

//------------------------------------------------------------------------------
const char* vtkNormalMapObjectFactory::GetDescription()
{
  return "VTK::NormalMapping: vtkNormalMapPolyDataMapper for vtkPolyDataMapper";
}

//------------------------------------------------------------------------------
void vtkNormalMapObjectFactory::Install()
{
  if (!Registered())
  {
    vtkNew<vtkNormalMapObjectFactory> factory;
    vtkObjectFactory::RegisterFactory(factory);
  }
  // The first enabled override wins; VTK's OpenGL module registered its own earlier.
  vtkObjectFactory::SetAllEnableFlags(false, "vtkPolyDataMapper");
  vtkObjectFactory::SetAllEnableFlags(true, "vtkPolyDataMapper", "vtkNormalMapPolyDataMapper");
}

//------------------------------------------------------------------------------
void vtkNormalMapObjectFactory::Uninstall()
{
  if (vtkNormalMapObjectFactory* factory = Registered())
  {
    vtkObjectFactory::UnRegisterFactory(factory);
  }
  vtkObjectFactory::SetAllEnableFlags(true, "vtkPolyDataMapper");
}

//------------------------------------------------------------------------------
bool vtkNormalMapObjectFactory::IsInstalled()
{
  return Registered() != nullptr;
}
