// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkNormalMapPolyDataMapper
 * @brief   A polydata mapper that applies normal maps correctly, and only when a scene needs it.
 *
 * A drop-in replacement for vtkOpenGLPolyDataMapper (directly, or for every
 * vtkPolyDataMapper::New() through vtkNormalMapObjectFactory). It is driven by the same actor
 * property as VTK's own mapper: the normal map is the property's "normalTex" texture
 * (vtkProperty::SetNormalTexture) and its strength is vtkProperty::GetNormalScale().
 *
 * What it does differently from VTK 9.1's mapper:
 * - The bitangent is sign * cross(N, T), with the handedness sign from vtkPolyDataTangentFrames
 *   (point array `TangentSigns`) or from the w of a glTF-style 4-component tangent array, so
 *   mirrored UV islands shade right. Three-component tangents without a sign (VTK's
 *   vtkPolyDataTangents, VTK's glTF reader and importer, which drop TANGENT's w) take the
 *   handedness of each triangle from the orientation of its texture coordinates, found from
 *   screen-space derivatives, so mirrored UVs shade right with them too.
 * - Without tangents, the frame is built per fragment from screen-space derivatives of the
 *   position and the texture coordinates: no vertex memory, mirroring handled by itself.
 * - The perturbed normal is built in model coordinates from a frame re-orthogonalized per
 *   fragment and then transformed like every normal, with the inverse transpose of the
 *   model-view matrix. That is exact under non-uniform and mirroring actor transforms (the
 *   lit result equals that of the displaced geometry under the same transform; with point
 *   normals, VTK 9.1 lights a mirroring actor's faces as back faces, and this mapper follows
 *   it); VTK's mapper transforms tangents with the normal matrix and re-derives the bitangent
 *   in view space.
 * - Map encodings: tangent space with +Y (OpenGL) or -Y (DirectX) green, two-channel (RG,
 *   z = sqrt(1 - x^2 - y^2)) in either convention, and object space (no tangents needed).
 * - Back faces (two-sided lighting) see the mirror of the front's perturbed normal.
 * - Strength (NormalScale) 0 builds exactly the shader of an unmapped surface.
 * - Float or double tangent arrays, 3 or 4 components.
 *
 * The shader holds only what the scene needs: no normal-map code without a normal texture
 * (or with strength 0, lighting off, a non-surface representation); no tangent attribute or
 * varying when the frame comes from derivatives or the map is in object space; VTK's own
 * tangent attribute is not uploaded unless PBR anisotropy or a clear-coat normal map uses it.
 *
 * Never silent: when the map cannot be applied (no 2-component texture coordinates, a
 * one-channel texture), the surface is drawn without it and a warning is given once per actor
 * and reason. An sRGB normal texture gets a warning and is decoded back to its stored values.
 * The normal texture is sampled as it is set up: for trilinear filtering of a minified map turn
 * its mipmaps on (vtkTexture::MipmapOn), as for any texture; the mapper does not change it.
 *
 * Flat, Gouraud, Phong and PBR interpolation all show the map (VTK lights every model per
 * fragment). Wireframe and point representations, vertices and lines draw without it.
 *
 * For multiblock data, vtkNormalMapCompositePolyDataMapper does the same per block.
 */
#ifndef vtkNormalMapPolyDataMapper_h
#define vtkNormalMapPolyDataMapper_h

#include "vtkNormalMappingModule.h" // For export macro
#include "vtkOpenGLPolyDataMapper.h"

#include <map>    // For ReplaceShaderNormal's signature
#include <memory> // For the private state
#include <string> // For array names

class VTKNORMALMAPPING_EXPORT vtkNormalMapPolyDataMapper : public vtkOpenGLPolyDataMapper
{
public:
  static vtkNormalMapPolyDataMapper* New();
  vtkTypeMacro(vtkNormalMapPolyDataMapper, vtkOpenGLPolyDataMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Also copies this class's settings from another vtkNormalMapPolyDataMapper.
  void ShallowCopy(vtkAbstractMapper* mapper) override;

  /// How the normal texture encodes the normal.
  enum MapEncodings
  {
    /// RGB, tangent space, green = +bitangent (OpenGL, glTF, Blender, MikkTSpace bakers).
    TANGENT_SPACE_OPENGL = 0,
    /// RGB, tangent space, green = -bitangent (DirectX, Unreal, 3ds Max).
    TANGENT_SPACE_DIRECTX,
    /// Two channels (R, G) in the OpenGL convention; z = sqrt(1 - x^2 - y^2).
    TWO_CHANNEL_OPENGL,
    /// Two channels (R, G) in the DirectX convention.
    TWO_CHANNEL_DIRECTX,
    /// RGB, the normal in model coordinates; no tangent frame needed.
    OBJECT_SPACE
  };

  ///@{
  /// The normal texture's encoding (default TANGENT_SPACE_OPENGL).
  vtkSetClampMacro(MapEncoding, int, TANGENT_SPACE_OPENGL, OBJECT_SPACE);
  vtkGetMacro(MapEncoding, int);
  static const char* GetMapEncodingName(int encoding);
  ///@}

  /// Where the tangent frame of a tangent-space map comes from.
  enum FrameSources
  {
    /// Point tangents when the input has them, else screen-space derivatives.
    AUTOMATIC = 0,
    /// The point tangent array (a warning and derivatives when it is missing or unusable).
    POINT_TANGENTS,
    /// Per fragment, from derivatives of position and texture coordinates.
    SCREEN_DERIVATIVES
  };

  ///@{
  /// The tangent frame source (default AUTOMATIC).
  vtkSetClampMacro(FrameSource, int, AUTOMATIC, SCREEN_DERIVATIVES);
  vtkGetMacro(FrameSource, int);
  static const char* GetFrameSourceName(int source);
  ///@}

  ///@{
  /**
   * Point array with the tangents (3 components, or 4 with the sign in w as in glTF).
   * Empty (the default): the active Tangents attribute.
   */
  void SetTangentsArrayName(const std::string& name);
  const std::string& GetTangentsArrayName() const { return this->TangentsArrayName; }
  ///@}

  ///@{
  /**
   * Point array with the handedness signs, used with 3-component tangents (default
   * "TangentSigns", what vtkPolyDataTangentFrames writes). Bitangent = sign * cross(N, T).
   * Empty, or no such array: 3-component tangents are unsigned, and each triangle's
   * handedness is the orientation of its texture coordinates (screen-space derivatives).
   */
  void SetTangentSignsArrayName(const std::string& name);
  const std::string& GetTangentSignsArrayName() const { return this->TangentSignsArrayName; }
  ///@}

  /// What the last shader build chose, for a scene's one surface primitive (after Render).
  enum AppliedFrames
  {
    /// The normal map was not applied (see the warnings).
    NOT_APPLIED = 0,
    /// Tangent-space map with point tangents and their signs.
    APPLIED_POINT_TANGENTS,
    /// Tangent-space map with point tangents without signs (the handedness from the texture
    /// coordinates' orientation).
    APPLIED_UNSIGNED_TANGENTS,
    /// Tangent-space map with a frame from screen-space derivatives.
    APPLIED_DERIVATIVES,
    /// Object-space map.
    APPLIED_OBJECT_SPACE
  };
  /// The frame the last built surface shader used (NOT_APPLIED before any render).
  int GetLastAppliedFrame() const { return this->LastAppliedFrame; }
  static const char* GetAppliedFrameName(int frame);

  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkNormalMapPolyDataMapper();
  ~vtkNormalMapPolyDataMapper() override;

  void BuildBufferObjects(vtkRenderer* ren, vtkActor* actor) override;
  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* actor) override;
  void ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*> shaders,
    vtkRenderer* ren,
    vtkActor* actor) override;
  void SetCameraShaderParameters(vtkOpenGLHelper& cellBO,
    vtkRenderer* ren,
    vtkActor* actor) override;
  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO,
    vtkRenderer* ren,
    vtkActor* actor) override;
  std::vector<std::pair<vtkTexture*, std::string>> GetTextures(vtkActor* actor) override;

  int MapEncoding = TANGENT_SPACE_OPENGL;
  int FrameSource = AUTOMATIC;
  std::string TangentsArrayName;
  std::string TangentSignsArrayName = "TangentSigns";
  int LastAppliedFrame = NOT_APPLIED;

private:
  vtkNormalMapPolyDataMapper(const vtkNormalMapPolyDataMapper&) = delete;
  void operator=(const vtkNormalMapPolyDataMapper&) = delete;

  /// The attribute the normal texture is sampled with (vtkNormalMapShading::SampledTCoords).
  std::string NormalTCoords(vtkActor* actor);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
