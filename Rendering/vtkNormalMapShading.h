// SPDX-License-Identifier: BSD-3-Clause
/**
 * The normal-mapping logic that vtkNormalMapPolyDataMapper and the per-block helpers of
 * vtkNormalMapCompositePolyDataMapper share: which tangent frame a dataset gets, the warnings,
 * the shader plan and its GLSL substitutions, the uniforms and the shader rebuild key. Each
 * mapper keeps its VTK hooks (they need its protected state) and delegates to one of these.
 * Private to the module: not installed, not wrapped.
 */
#ifndef vtkNormalMapShading_h
#define vtkNormalMapShading_h

#include "vtkProp.h"          // For the texture-transform key
#include "vtkShader.h"        // For vtkShader::Type
#include "vtkSmartPointer.h"  // For the dataset without tangents
#include "vtkVersionMacros.h" // For the texture-transform key's name
#include "vtkWeakPointer.h"   // For the actors warned about

#include <cstdint> // For std::uint64_t
#include <map>     // For per-shader and per-actor state
#include <string>  // For array names and messages
#include <utility> // For std::pair
#include <vector>  // For the texture list

class vtkActor;
class vtkDataArray;
class vtkFloatArray;
class vtkMapper;
class vtkObject;
class vtkOpenGLHelper;
class vtkPolyData;
class vtkRenderer;
class vtkShaderProgram;
class vtkTexture;

class vtkNormalMapShading
{
public:
  /// The vertex attributes of the point tangents and of their signs (vtkNormalMapVS.glsl).
  static constexpr const char* TangentAttribute = "nmTangentMC";
  static constexpr const char* SignAttribute = "nmTangentSignMC";
  /// The vertex attribute of the mapper's own copy of the texture coordinates (SampledTCoords).
  static constexpr const char* TCoordAttribute = "nmTCoord";

  /// The actor key of a texture-coordinate transform, under its name in this VTK.
  static vtkInformationDoubleVectorKey* TextureTransformKey();

  /// The settings of a normal-mapping mapper (values of vtkNormalMapPolyDataMapper's enums).
  struct Settings
  {
    int MapEncoding = 0;
    int FrameSource = 0;
    std::string TangentsArrayName;
    std::string TangentSignsArrayName = "TangentSigns";

    bool operator==(const Settings& other) const
    {
      return this->MapEncoding == other.MapEncoding && this->FrameSource == other.FrameSource &&
        this->TangentsArrayName == other.TangentsArrayName &&
        this->TangentSignsArrayName == other.TangentSignsArrayName;
    }
  };

  /// The settings of either mapper class (they have the same getters).
  template<class MapperType>
  static Settings SettingsOf(MapperType* mapper)
  {
    Settings settings;
    settings.MapEncoding = mapper->GetMapEncoding();
    settings.FrameSource = mapper->GetFrameSource();
    settings.TangentsArrayName = mapper->GetTangentsArrayName();
    settings.TangentSignsArrayName = mapper->GetTangentSignsArrayName();
    return settings;
  }

  /// Gives either mapper class these settings.
  template<class MapperType>
  static void ApplySettings(MapperType* mapper, const Settings& settings)
  {
    mapper->SetMapEncoding(settings.MapEncoding);
    mapper->SetFrameSource(settings.FrameSource);
    mapper->SetTangentsArrayName(settings.TangentsArrayName);
    mapper->SetTangentSignsArrayName(settings.TangentSignsArrayName);
  }

  /// How one dataset's tangent frame is obtained.
  enum class TangentUse
  {
    Derivatives,   // no usable point tangents (or not wanted): screen-space derivatives
    Signed,        // 4-component tangents, the sign in w
    SeparateSigns, // 3-component tangents and a sign array
    Unsigned       // 3-component tangents without signs: the handedness from the UV map
  };

  /// One dataset's tangent arrays, checked against the settings.
  struct Tangents
  {
    TangentUse Use = TangentUse::Derivatives;
    vtkDataArray* Vectors = nullptr; // 3 or 4 components, one tuple per point
    vtkDataArray* Signs = nullptr;   // with SeparateSigns: 1 component per point
    std::string Problem;             // why a present tangent or sign array cannot be used
    bool Missing = false;            // FrameSource is PointTangents and there is no array
  };

  /// Which frames the datasets drawn by one shader program use.
  struct FrameMix
  {
    bool PointTangents = false; // some dataset has point tangents (attribute nmTangentMC)
    bool SeparateSigns = false; // ... whose signs are their own attribute (nmTangentSignMC)
    bool Unsigned = false;      // every dataset with tangents has them without signs
    bool SomeUnsigned = false;  // some dataset has tangents without signs
    bool Derivatives = false;   // some dataset has none: frame from screen-space derivatives
    /// A small number that changes whenever the shader code, or the frame it reports, would.
    unsigned Key() const;
  };

  /// What a mapper knows when VTK builds the shader of one primitive type.
  struct ShaderContext
  {
    vtkObject* Reporter = nullptr; // the mapper the application holds: warnings come from it
    vtkActor* Actor = nullptr;
    bool DrawingVertices = false;
    int LightComplexity = 0;
    std::string TCoordName;   // the attribute the normal texture is sampled with (SampledTCoords)
    int TCoordComponents = 0; // its components in the vertex buffers
    FrameMix Frames;          // of the tangent-space map
    std::string Where;        // names the datasets in warnings ("" or "Blocks 1, 3: ")
  };

  /// The normal texture of the actor's property, or nullptr.
  static vtkTexture* NormalTexture(vtkActor* actor);
  /// Whether the actor asks for a normal map (a normal texture and a non-zero strength).
  static bool WantsMap(vtkActor* actor);
  /// Whether a dataset's point tangents will be used (read from the settings and the actor).
  static bool WantsPointTangents(vtkActor* actor, const Settings& settings);

  /**
   * The texture coordinate attribute the normal texture is sampled with, given the one VTK would
   * sample it with (`vtkName`, from GetTextureCoordinateName). That is VTK's own, unless it is
   * VTK's "tcoord", which holds the color map's coordinates instead of the dataset's while the
   * mapper shows scalars interpolated before mapping: then the mapper's own copy
   * (TCoordAttribute), which the mapper uploads.
   */
  static std::string SampledTCoords(vtkMapper* mapper, vtkActor* actor, const std::string& vtkName);

  /// Whether VTK's own shader code reads its Tangents attribute (tangentMC): PBR anisotropy or a
  /// clear-coat normal map.
  static bool VTKUsesTangents(vtkActor* actor);
  /**
   * The dataset VTK's own vertex buffer code should see: a shallow copy of `poly` without an
   * active Tangents attribute when VTK's shader would not read it (so it is not uploaded);
   * nullptr when `poly` itself will do.
   */
  static vtkSmartPointer<vtkPolyData> WithoutUnusedVTKTangents(vtkPolyData* poly, vtkActor* actor);

  /// The tangent arrays of a dataset, checked (Derivatives when point tangents are not wanted).
  static Tangents FindTangents(vtkPolyData* poly, vtkActor* actor, const Settings& settings);

  /**
   * The tangents as 4 floats per point, the handedness sign in w (0 for unsigned tangents);
   * nullptr when the dataset's frame comes from derivatives.
   */
  static vtkFloatArray* NewPackedTangents(const Tangents& tangents);

  /// Warns once per actor, datasets and reason why point tangents are not used as they are.
  void WarnAboutTangents(vtkObject* reporter,
    vtkActor* actor,
    const Tangents& tangents,
    const Settings& settings,
    const std::string& where);

  /// While hiding, the normal texture is removed from the list (VTK's own code must not see it).
  void SetHidingNormalTexture(bool hiding) { this->HidingNormalTexture = hiding; }
  void FilterTextures(std::vector<std::pair<vtkTexture*, std::string>>& textures) const;

  /**
   * Adds the normal-map code to the shaders VTK built for one primitive type (after VTK's
   * own normal code) and returns the frame applied (vtkNormalMapPolyDataMapper::AppliedFrames),
   * or NOT_APPLIED with a warning where the map cannot be applied.
   */
  int ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*>& shaders,
    const ShaderContext& context,
    const Settings& settings);

  /// True when the shader must be rebuilt for the normal map: the texture, the frames, or the
  /// texture coordinates it is sampled with (`tcoordName`, `tcoordComponents`, as in
  /// ShaderContext) changed.
  bool NeedsRebuild(const vtkOpenGLHelper* cellBO,
    vtkActor* actor,
    unsigned framesKey,
    const std::string& tcoordName,
    int tcoordComponents);

  /// The normal matrix and its inverse (nmNormalMatrix, nmNormalMatrixInverse).
  static void SetCameraUniforms(vtkShaderProgram* program, vtkRenderer* renderer, vtkActor* actor);
  /// The strength and the green channel's sign (nmNormalScale, nmGreenSign).
  static void SetMapUniforms(vtkShaderProgram* program, vtkActor* actor, const Settings& settings);

  /// Forgets the shader state (the graphics resources were released).
  void ReleaseShaders() { this->ShaderKeys.clear(); }

private:
  enum class Reason : unsigned;
  void Warn(vtkObject* reporter,
    vtkActor* actor,
    const std::string& where,
    Reason reason,
    const std::string& message);

  bool HidingNormalTexture = false;
  /// Per shader program (one per primitive type), the normal-map state it was built for.
  std::map<const vtkOpenGLHelper*, std::uint64_t> ShaderKeys;
  /// Reasons already warned about for an actor, which the entry watches: an actor made later
  /// at the address of a deleted one is warned about afresh.
  struct WarnedReasons
  {
    vtkWeakPointer<vtkActor> Actor;
    unsigned Reasons = 0;
  };
  /// Per actor and datasets, the reasons already warned about.
  std::map<std::pair<const vtkActor*, std::string>, WarnedReasons> Warned;
};

inline vtkInformationDoubleVectorKey* vtkNormalMapShading::TextureTransformKey()
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  return vtkProp::GENERAL_TEXTURE_TRANSFORM();
#else
  return vtkProp::GeneralTextureTransform();
#endif
}

#endif
