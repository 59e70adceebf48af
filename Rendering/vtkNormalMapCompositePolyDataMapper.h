/**
 * @class   vtkNormalMapCompositePolyDataMapper
 * @brief   vtkCompositePolyDataMapper2 with the normal mapping of vtkNormalMapPolyDataMapper.
 *
 * For multiblock data (what VTK's glTF, OBJ and Exodus readers give, and what ParaView
 * renders): every block is drawn with the same normal mapping, settings and warnings as
 * vtkNormalMapPolyDataMapper gives one vtkPolyData (see there). The normal map is the actor
 * property's "normalTex" texture (vtkProperty::SetNormalTexture), its strength the property's
 * NormalScale. The settings take the values of vtkNormalMapPolyDataMapper's enums
 * (MapEncodings, FrameSources, AppliedFrames).
 *
 * Per block: each block's own point tangents and signs are used (float or double, 3 components
 * with a sign array or 4 with the sign in w, 3 without signs: sign +1 and a warning); a block
 * without tangents gets the frame from screen-space derivatives, in the same draw as blocks
 * with them. A block without 2-component texture coordinates is drawn without the map, with a
 * warning naming it. Per-block visibility, colour and opacity (vtkCompositeDataDisplayAttributes)
 * work as in the superclass. Warnings name the blocks by flat index ("Block 3: ...").
 *
 * vtkNormalMapObjectFactory::Install() registers this class as the override of
 * vtkCompositePolyDataMapper2 (see there for when VTK consults it).
 */
#ifndef vtkNormalMapCompositePolyDataMapper_h
#define vtkNormalMapCompositePolyDataMapper_h

#include "vtkCompositePolyDataMapper2.h"
#include "vtkNormalMapPolyDataMapper.h" // For the enums
#include "vtkNormalMappingModule.h"     // For export macro

#include <memory> // For the private state
#include <string> // For array names

class VTKNORMALMAPPING_EXPORT vtkNormalMapCompositePolyDataMapper
  : public vtkCompositePolyDataMapper2
{
public:
  static vtkNormalMapCompositePolyDataMapper* New();
  vtkTypeMacro(vtkNormalMapCompositePolyDataMapper, vtkCompositePolyDataMapper2);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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
  const std::string& GetTangentsArrayName() const { return this->TangentsArrayName; }
  ///@}

  ///@{
  /// Point array with each block's handedness signs (default "TangentSigns").
  void SetTangentSignsArrayName(const std::string& name);
  const std::string& GetTangentSignsArrayName() const { return this->TangentSignsArrayName; }
  ///@}

  /**
   * The frame the block with this flat index was drawn with in the last render
   * (vtkNormalMapPolyDataMapper::AppliedFrames; NOT_APPLIED for a block not drawn, hidden, or
   * drawn without the map).
   */
  int GetLastAppliedFrame(unsigned int flatIndex);

  void Render(vtkRenderer* ren, vtkActor* actor) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkNormalMapCompositePolyDataMapper();
  ~vtkNormalMapCompositePolyDataMapper() override;

  vtkCompositeMapperHelper2* CreateHelper() override;
  void CopyMapperValuesToHelper(vtkCompositeMapperHelper2* helper) override;

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
