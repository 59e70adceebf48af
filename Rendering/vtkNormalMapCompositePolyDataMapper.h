// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkNormalMapCompositePolyDataMapper
 * @brief   VTK's composite polydata mapper with the normal mapping of vtkNormalMapPolyDataMapper.
 *
 * For multiblock data (what VTK's glTF, OBJ and Exodus readers give, and what ParaView
 * renders): every block is drawn with the same normal mapping, settings and warnings as
 * vtkNormalMapPolyDataMapper gives one vtkPolyData (see there). The normal map is the actor
 * property's "normalTex" texture (vtkProperty::SetNormalTexture), its strength the property's
 * NormalScale. The settings take the values of vtkNormalMapPolyDataMapper's enums
 * (MapEncodings, FrameSources, AppliedFrames).
 *
 * Per block: each block's own point tangents and signs are used (float or double, 3 components
 * with a sign array or 4 with the sign in w, 3 without signs: the handedness from the texture
 * coordinates' orientation, as in vtkNormalMapPolyDataMapper); a block
 * without tangents gets the frame from screen-space derivatives, in the same draw as blocks
 * with them. A block without 2-component texture coordinates is drawn without the map, with a
 * warning naming it. Per-block visibility, colour and opacity (vtkCompositeDataDisplayAttributes)
 * work as in the superclass. Warnings name the blocks by flat index ("Block 3: ...").
 *
 * Its superclass is the composite mapper VTK renders multiblock data with:
 * vtkCompositePolyDataMapper2 up to VTK 9.2, vtkCompositePolyDataMapper from VTK 9.3 (which
 * removed vtkCompositePolyDataMapper2 in 9.5). vtkNormalMapObjectFactory::Install() registers
 * this class as the override of that superclass (see there for when VTK consults it).
 */
#ifndef vtkNormalMapCompositePolyDataMapper_h
#define vtkNormalMapCompositePolyDataMapper_h

#include "vtkNormalMapPolyDataMapper.h" // For the enums
#include "vtkNormalMappingModule.h"     // For export macro
#include "vtkVersionMacros.h"           // For the superclass

#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 3, 0)
#include "vtkCompositePolyDataMapper.h" // For the superclass
#include "vtkSmartPointer.h"            // For the delegator list
#include <vector>                       // For the delegator list
#define VTK_NORMALMAPPING_BATCHED_COMPOSITE 1
#else
#include "vtkCompositePolyDataMapper2.h" // For the superclass
#define VTK_NORMALMAPPING_BATCHED_COMPOSITE 0
#endif

#include <memory> // For the private state
#include <string> // For array names

class VTKNORMALMAPPING_EXPORT vtkNormalMapCompositePolyDataMapper
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
  : public vtkCompositePolyDataMapper
#else
  : public vtkCompositePolyDataMapper2
#endif
{
public:
  static vtkNormalMapCompositePolyDataMapper* New();
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
  vtkTypeMacro(vtkNormalMapCompositePolyDataMapper, vtkCompositePolyDataMapper);
#else
  vtkTypeMacro(vtkNormalMapCompositePolyDataMapper, vtkCompositePolyDataMapper2);
#endif
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Also copies this class's settings from another vtkNormalMapCompositePolyDataMapper.
  void ShallowCopy(vtkAbstractMapper* mapper) override;

  ///@{
  /// The normal texture's encoding (vtkNormalMapPolyDataMapper::MapEncodings; default
  /// TANGENT_SPACE_OPENGL).
  vtkSetClampMacro(MapEncoding,
    int,
    vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL,
    vtkNormalMapPolyDataMapper::OBJECT_SPACE);
  vtkGetMacro(MapEncoding, int);
  ///@}

  ///@{
  /// The tangent frame source (vtkNormalMapPolyDataMapper::FrameSources; default AUTOMATIC).
  vtkSetClampMacro(FrameSource,
    int,
    vtkNormalMapPolyDataMapper::AUTOMATIC,
    vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES);
  vtkGetMacro(FrameSource, int);
  ///@}

  ///@{
  /// Point array with each block's tangents; empty (the default): the active Tangents.
  void SetTangentsArrayName(const std::string& name);
  const std::string& GetTangentsArrayName() const
  {
    return this->TangentsArrayName;
  }
  ///@}

  ///@{
  /// Point array with each block's handedness signs (default "TangentSigns"; empty: none).
  void SetTangentSignsArrayName(const std::string& name);
  const std::string& GetTangentSignsArrayName() const
  {
    return this->TangentSignsArrayName;
  }
  ///@}

  /**
   * The frame the block with this flat index was drawn with in the last render
   * (vtkNormalMapPolyDataMapper::AppliedFrames; NOT_APPLIED for a block not drawn, hidden, or
   * drawn without the map).
   */
  int GetLastAppliedFrame(unsigned int flatIndex);

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkNormalMapCompositePolyDataMapper();
  ~vtkNormalMapCompositePolyDataMapper() override;

#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
  vtkCompositePolyDataMapperDelegator* CreateADelegator() override;
  void PreRender(
    const std::vector<vtkSmartPointer<vtkCompositePolyDataMapperDelegator>>& delegators,
    vtkRenderer* ren,
    vtkActor* actor) override;
  void PostRender(
    const std::vector<vtkSmartPointer<vtkCompositePolyDataMapperDelegator>>& delegators,
    vtkRenderer* ren,
    vtkActor* actor) override;
#else
public:
  void Render(vtkRenderer* ren, vtkActor* actor) override;

protected:
  vtkCompositeMapperHelper2* CreateHelper() override;
  void CopyMapperValuesToHelper(vtkCompositeMapperHelper2* helper) override;
#endif

  int MapEncoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
  int FrameSource = vtkNormalMapPolyDataMapper::AUTOMATIC;
  std::string TangentsArrayName;
  std::string TangentSignsArrayName = "TangentSigns";

private:
  vtkNormalMapCompositePolyDataMapper(const vtkNormalMapCompositePolyDataMapper&) = delete;
  void operator=(const vtkNormalMapCompositePolyDataMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
