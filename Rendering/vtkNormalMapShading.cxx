// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMapShading.h"

#include "vtkActor.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLCamera.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTexture.h"

#include "vtkNormalMapFS.h"
#include "vtkNormalMapGS.h"
#include "vtkNormalMapVS.h"

#include <algorithm>

using Mapper = vtkNormalMapPolyDataMapper;

/// Reasons the mappers warn about, once per actor and datasets each.
enum class vtkNormalMapShading::Reason : unsigned
{
  NoTCoords = 1u << 0,
  OneChannel = 1u << 1,
  TwoChannelAsRGB = 1u << 2,
  ObjectSpaceTwoChannel = 1u << 3,
  MissingTangents = 1u << 5,
  BadTangents = 1u << 6,
  SRGBTexture = 1u << 7,
  BadSigns = 1u << 8,
  MappedScalars = 1u << 9
};

namespace
{
const char* const NormalTextureName = "normalTex";

/// The block "//NM::Begin <name>" ... "//NM::End" of an embedded shader source.
std::string Block(const char* source, const char* name)
{
  const std::string text(source);
  const std::string begin = std::string("//NM::Begin ") + name + "\n";
  const auto start = text.find(begin);
  const auto stop = start == std::string::npos ? start : text.find("//NM::End", start);
  if (stop == std::string::npos)
  {
    // Only reachable if the embedded sources and this file disagree: a build defect.
    vtkGenericWarningMacro("vtkNormalMapShading: shader block " << name << " not found");
    return std::string();
  }
  return text.substr(start + begin.size(), stop - start - begin.size());
}

/// Put `code` in front of `tag`, keeping the tag for VTK's own replacements that follow.
bool InsertBefore(std::string& source, const std::string& tag, const std::string& code)
{
  return vtkShaderProgram::Substitute(source, tag, code + tag, false);
}

/// The scalars of a normal texture's image, or null.
vtkDataArray* TextureScalars(vtkTexture* texture)
{
  vtkImageData* image = texture->GetInput();
  return image ? image->GetPointData()->GetScalars() : nullptr;
}

/// Number of components of a normal texture's image (0 when it has none). VTK uploads images
/// of 1 or 2 components as RGBA (luminance, luminance-alpha), so the texture object cannot tell.
int TextureChannels(vtkTexture* texture)
{
  vtkDataArray* scalars = TextureScalars(texture);
  return scalars ? scalars->GetNumberOfComponents() : 0;
}

/// Whether VTK maps the texture's values through its lookup table instead of taking them as
/// colors: the texture's color mode says so, or, in its default mode, they are not unsigned
/// char (a float map, say). A normal map read that way is colors of a color map, not normals.
bool MapsThroughLookupTable(vtkTexture* texture)
{
  vtkDataArray* scalars = TextureScalars(texture);
  const int mode = texture->GetColorMode();
  return scalars &&
    (mode == VTK_COLOR_MODE_MAP_SCALARS ||
      (mode == VTK_COLOR_MODE_DEFAULT && scalars->GetDataType() != VTK_UNSIGNED_CHAR));
}

bool IsTangentSpace(int encoding)
{
  return encoding != Mapper::OBJECT_SPACE;
}

bool IsTwoChannel(int encoding)
{
  return encoding == Mapper::TWO_CHANNEL_OPENGL || encoding == Mapper::TWO_CHANNEL_DIRECTX;
}

/// What the normal-map code of one shader program will be.
struct ShaderPlan
{
  int Frame = Mapper::NOT_APPLIED;
  bool PerDatasetFrame = false; // tangents for some datasets, derivatives for others
  bool TwoChannel = false;
  bool LuminanceAlpha = false; // a 2-component image: x in red, y in alpha
  bool SRGB = false;
};

/// Copies tangents (3 or 4 components, any numeric type) into 4 floats per point, w the sign as
/// stored (the shader reads its sign: negative for -1, anything else for +1), or 0 for tangents
/// without signs (the shader then takes the orientation of the texture coordinates).
struct PackTangents
{
  template<typename TangentArray>
  void operator()(TangentArray* tangents, vtkDataArray* signs, vtkFloatArray* packed) const
  {
    const auto in = vtk::DataArrayTupleRange(tangents);
    auto out = vtk::DataArrayTupleRange<4>(packed);
    const int components = tangents->GetNumberOfComponents();
    for (vtkIdType i = 0; i < in.size(); ++i)
    {
      float sign = 0.0f;
      if (components == 4)
      {
        sign = static_cast<float>(in[i][3]);
      }
      else if (signs)
      {
        sign = static_cast<float>(signs->GetComponent(i, 0));
      }
      out[i][0] = static_cast<float>(in[i][0]);
      out[i][1] = static_cast<float>(in[i][1]);
      out[i][2] = static_cast<float>(in[i][2]);
      out[i][3] = sign;
    }
  }
};
}

//------------------------------------------------------------------------------
unsigned vtkNormalMapShading::FrameMix::Key() const
{
  return (this->PointTangents ? 1u : 0u) | (this->SeparateSigns ? 2u : 0u) |
    (this->Unsigned ? 4u : 0u) | (this->Derivatives ? 8u : 0u) | (this->SomeUnsigned ? 16u : 0u);
}

//------------------------------------------------------------------------------
vtkTexture* vtkNormalMapShading::NormalTexture(vtkActor* actor)
{
  return actor->GetProperty()->GetTexture(NormalTextureName);
}

//------------------------------------------------------------------------------
bool vtkNormalMapShading::WantsMap(vtkActor* actor)
{
  return NormalTexture(actor) && actor->GetProperty()->GetNormalScale() != 0.0;
}

//------------------------------------------------------------------------------
bool vtkNormalMapShading::WantsPointTangents(vtkActor* actor, const Settings& settings)
{
  return WantsMap(actor) && IsTangentSpace(settings.MapEncoding) &&
    settings.FrameSource != Mapper::SCREEN_DERIVATIVES;
}

//------------------------------------------------------------------------------
std::string vtkNormalMapShading::SampledTCoords(vtkMapper* mapper,
  vtkActor* actor,
  const std::string& vtkName)
{
  const bool colorCoordinates =
    mapper->GetInterpolateScalarsBeforeMapping() && mapper->GetScalarVisibility();
  return vtkName == "tcoord" && colorCoordinates && WantsMap(actor) ? TCoordAttribute : vtkName;
}

//------------------------------------------------------------------------------
bool vtkNormalMapShading::VTKUsesTangents(vtkActor* actor)
{
  vtkProperty* property = actor->GetProperty();
  return property->GetInterpolation() == VTK_PBR &&
    (property->GetAnisotropy() != 0.0 ||
      (property->GetCoatStrength() > 0.0 && property->GetTexture("coatNormalTex")));
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkNormalMapShading::WithoutUnusedVTKTangents(vtkPolyData* poly,
  vtkActor* actor)
{
  if (!poly || !poly->GetPointData()->GetTangents() || VTKUsesTangents(actor))
  {
    return nullptr;
  }
  // The copy shares every array; only its attribute flags differ, so the input is untouched
  // (its modification time too, which decides when the buffers are rebuilt).
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(poly);
  copy->GetPointData()->SetActiveAttribute(-1, vtkDataSetAttributes::TANGENTS);
  return copy;
}

//------------------------------------------------------------------------------
vtkNormalMapShading::Tangents vtkNormalMapShading::FindTangents(vtkPolyData* poly,
  vtkActor* actor,
  const Settings& settings)
{
  Tangents found;
  if (!poly || !WantsPointTangents(actor, settings))
  {
    return found;
  }
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* tangents = settings.TangentsArrayName.empty()
    ? pd->GetTangents()
    : pd->GetArray(settings.TangentsArrayName.c_str());
  if (!tangents)
  {
    found.Missing = settings.FrameSource == Mapper::POINT_TANGENTS;
    return found;
  }
  const vtkIdType n = poly->GetNumberOfPoints();
  const int comps = tangents->GetNumberOfComponents();
  if (comps != 3 && comps != 4)
  {
    found.Problem = "tangent array '" +
      std::string(tangents->GetName() ? tangents->GetName() : "") + "' has " +
      std::to_string(comps) + " components (3 or 4 needed)";
    return found;
  }
  if (tangents->GetNumberOfTuples() != n)
  {
    found.Problem = "tangent array has " + std::to_string(tangents->GetNumberOfTuples()) +
      " tuples for " + std::to_string(n) + " points";
    return found;
  }
  found.Vectors = tangents;
  found.Use = comps == 4 ? TangentUse::Signed : TangentUse::Unsigned;
  if (comps == 3 && !settings.TangentSignsArrayName.empty())
  {
    vtkDataArray* signs = pd->GetArray(settings.TangentSignsArrayName.c_str());
    if (signs && signs->GetNumberOfComponents() == 1 && signs->GetNumberOfTuples() == n)
    {
      found.Signs = signs;
      found.Use = TangentUse::SeparateSigns;
    }
    else if (signs)
    {
      found.Problem =
        "sign array '" + settings.TangentSignsArrayName + "' is not one value per point";
    }
  }
  return found;
}

//------------------------------------------------------------------------------
vtkFloatArray* vtkNormalMapShading::NewPackedTangents(const Tangents& tangents)
{
  if (tangents.Use == TangentUse::Derivatives)
  {
    return nullptr;
  }
  vtkFloatArray* packed = vtkFloatArray::New();
  packed->SetNumberOfComponents(4);
  packed->SetNumberOfTuples(tangents.Vectors->GetNumberOfTuples());
  PackTangents worker;
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(
        tangents.Vectors, worker, tangents.Signs, packed))
  {
    worker(tangents.Vectors, tangents.Signs, packed); // integer tangents: the generic path
  }
  return packed;
}

//------------------------------------------------------------------------------
void vtkNormalMapShading::Warn(vtkObject* reporter,
  vtkActor* actor,
  const std::string& where,
  Reason reason,
  const std::string& message)
{
  WarnedReasons& done = this->Warned[std::make_pair(actor, where)];
  if (done.Actor != actor)
  {
    done.Actor = actor;
    done.Reasons = 0;
  }
  if (!(done.Reasons & static_cast<unsigned>(reason)))
  {
    done.Reasons |= static_cast<unsigned>(reason);
    vtkWarningWithObjectMacro(reporter, << where << message);
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapShading::WarnAboutTangents(vtkObject* reporter,
  vtkActor* actor,
  const Tangents& tangents,
  const Settings& settings,
  const std::string& where)
{
  if (!tangents.Problem.empty())
  {
    this->Warn(reporter,
      actor,
      where,
      tangents.Vectors ? Reason::BadSigns : Reason::BadTangents,
      "Point tangents: " + tangents.Problem +
        (tangents.Vectors ? "; taking the handedness from the texture coordinates."
                          : "; using screen-space derivatives."));
  }
  else if (tangents.Missing)
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::MissingTangents,
      "FrameSource is PointTangents but the input has no tangent array" +
        (settings.TangentsArrayName.empty() ? std::string()
                                            : " named '" + settings.TangentsArrayName + "'") +
        "; using screen-space derivatives.");
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapShading::FilterTextures(
  std::vector<std::pair<vtkTexture*, std::string>>& textures) const
{
  if (this->HidingNormalTexture)
  {
    textures.erase(
      std::remove_if(textures.begin(),
        textures.end(),
        [](const std::pair<vtkTexture*, std::string>& t) { return t.second == NormalTextureName; }),
      textures.end());
  }
}

//------------------------------------------------------------------------------
namespace
{
/// Whether the actor transforms its texture coordinates (vtkNormalMapShading::TextureTransformKey):
/// VTK compiles the transform into its shader only when the actor has one at the build.
const double* TextureTransform(vtkActor* actor)
{
  vtkInformation* keys = actor->GetPropertyKeys();
  vtkInformationDoubleVectorKey* key = vtkNormalMapShading::TextureTransformKey();
  return keys && keys->Has(key) ? keys->Get(key) : nullptr;
}
}

bool vtkNormalMapShading::NeedsRebuild(const vtkOpenGLHelper* cellBO,
  vtkActor* actor,
  unsigned framesKey,
  const std::string& tcoordName,
  int tcoordComponents)
{
  // The normal-map state depends on the texture and the vertex buffers, which VTK's own test
  // does not cover in full (a texture's channels, its sRGB flag, the tangent attributes, the
  // texture coordinates it is sampled with and their components), and on whether VTK's shader
  // applies a texture transform, which nmTextureFrame and the mapper's own texture coordinates
  // must match.
  std::uint64_t key = 0;
  vtkTexture* texture = NormalTexture(actor);
  if (texture)
  {
    key = 1u + (texture->GetUseSRGBColorSpace() ? 2u : 0u) +
      (static_cast<unsigned>(TextureChannels(texture)) << 2) + (framesKey << 5) +
      (static_cast<std::uint64_t>(std::max(tcoordComponents, 0)) << 32) +
      (MapsThroughLookupTable(texture) ? std::uint64_t(1) << 40 : 0) +
      (TextureTransform(actor) ? std::uint64_t(1) << 41 : 0) +
      (tcoordName == TCoordAttribute ? std::uint64_t(1) << 42 : 0);
  }
  std::uint64_t& stored = this->ShaderKeys[cellBO];
  if (stored != key)
  {
    stored = key;
    return true;
  }
  return false;
}

namespace
{
/// The frame a tangent-space map gets from the datasets' frames; perDataset: tangents for some
/// datasets, derivatives for others.
int FrameOf(int encoding, const vtkNormalMapShading::FrameMix& frames, bool& perDataset)
{
  perDataset = false;
  if (!IsTangentSpace(encoding))
  {
    return Mapper::APPLIED_OBJECT_SPACE;
  }
  if (!frames.PointTangents)
  {
    return Mapper::APPLIED_DERIVATIVES;
  }
  perDataset = frames.Derivatives;
  return frames.Unsigned ? Mapper::APPLIED_UNSIGNED_TANGENTS : Mapper::APPLIED_POINT_TANGENTS;
}

/// Passes an attribute from the vertex shader, through the geometry shader when there is one, to
/// the fragment shader: the named blocks of vtkNormalMapVS.glsl and vtkNormalMapGS.glsl.
void PassAttribute(std::map<vtkShader::Type, vtkShader*>& shaders,
  const char* vertexDec,
  const char* vertexImpl,
  const char* geometryBlocks)
{
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  InsertBefore(vs, "//VTK::Normal::Dec", Block(vtkNormalMapVS, vertexDec));
  InsertBefore(vs, "//VTK::Normal::Impl", Block(vtkNormalMapVS, vertexImpl));
  shaders[vtkShader::Vertex]->SetSource(vs);
  std::string gs = shaders[vtkShader::Geometry]->GetSource();
  if (!gs.empty())
  {
    const std::string name(geometryBlocks);
    InsertBefore(gs, "//VTK::Normal::Dec", Block(vtkNormalMapGS, (name + "Dec").c_str()));
    InsertBefore(gs, "//VTK::Normal::Impl", Block(vtkNormalMapGS, (name + "Impl").c_str()));
    shaders[vtkShader::Geometry]->SetSource(gs);
  }
}

/// Inserts the planned normal-map code into VTK's shaders.
void AddMapCode(std::map<vtkShader::Type, vtkShader*>& shaders,
  const ShaderPlan& plan,
  const vtkNormalMapShading::ShaderContext& context)
{
  const bool pointTangents =
    plan.Frame == Mapper::APPLIED_POINT_TANGENTS || plan.Frame == Mapper::APPLIED_UNSIGNED_TANGENTS;
  // Derivatives also give the handedness of tangents without signs.
  const bool unsignedTangents = pointTangents && context.Frames.SomeUnsigned;
  const bool derivatives =
    plan.Frame == Mapper::APPLIED_DERIVATIVES || plan.PerDatasetFrame || unsignedTangents;
  if (pointTangents)
  {
    const bool signs = context.Frames.SeparateSigns;
    PassAttribute(shaders,
      signs ? "TangentSignDec" : "TangentDec",
      signs ? "TangentSignImpl" : (context.Frames.Unsigned ? "TangentUnsignedImpl" : "TangentImpl"),
      "Tangent");
  }
  const bool ownTCoords = context.TCoordName == vtkNormalMapShading::TCoordAttribute;
  if (ownTCoords)
  {
    const bool transformed = TextureTransform(context.Actor) != nullptr;
    PassAttribute(
      shaders, "TCoordDec", transformed ? "TCoordTransformedImpl" : "TCoordImpl", "TCoord");
  }
  std::string fs = shaders[vtkShader::Fragment]->GetSource();

  // Declarations go before VTK's lighting declarations (after its normal ones, which a cell
  // normal path consumes); the code goes just before the lighting, where the normal is final.
  // VTK derives the normal from the position's derivatives (oriented to the camera) where it has
  // neither point normals to interpolate nor cell normals; it flips those on back faces.
  const bool derivedNormal = fs.find("normalize(cross(fdx,fdy))") != std::string::npos;
  std::string declarations = Block(vtkNormalMapFS, "Dec") +
    Block(vtkNormalMapFS, plan.SRGB ? "TexelSRGB" : "TexelLinear") +
    Block(vtkNormalMapFS, derivedNormal ? "FlippedDerived" : "FlippedAttribute") +
    (ownTCoords ? Block(vtkNormalMapFS, "TCoordDec") : std::string());
  std::string code;
  if (plan.Frame == Mapper::APPLIED_OBJECT_SPACE)
  {
    code = Block(vtkNormalMapFS, "ImplObjectSpace");
  }
  else
  {
    std::string decode = Block(vtkNormalMapFS, plan.TwoChannel ? "DecodeTwoChannel" : "DecodeRGB");
    vtkShaderProgram::Substitute(decode, "@XY@", plan.LuminanceAlpha ? "ra" : "rg");
    declarations += decode;
    if (pointTangents)
    {
      declarations += Block(vtkNormalMapFS, "TangentDec");
    }
    if (derivatives)
    {
      declarations += Block(vtkNormalMapFS, "DerivativeDec");
      std::string flow = Block(vtkNormalMapFS, "DerivativeUniformFlow");
      vtkShaderProgram::Substitute(flow, "@TCOORD@", context.TCoordName);
      InsertBefore(fs, "//VTK::UniformFlow::Impl", flow);
    }
    if (pointTangents)
    {
      declarations +=
        Block(vtkNormalMapFS, unsignedTangents ? "HandednessDerived" : "HandednessStored") +
        Block(vtkNormalMapFS, "TangentFrame");
    }
    declarations += Block(vtkNormalMapFS,
      plan.PerDatasetFrame ? "FramePerDataset"
                           : (pointTangents ? "FrameFromTangents" : "FrameFromDerivatives"));
    code = Block(vtkNormalMapFS, "ImplTangentSpace");
  }
  vtkShaderProgram::Substitute(code, "@TCOORD@", context.TCoordName);
  InsertBefore(fs, "//VTK::Light::Dec", declarations);
  InsertBefore(fs, "//VTK::Light::Impl", code);

  shaders[vtkShader::Fragment]->SetSource(fs);
}
}

//------------------------------------------------------------------------------
int vtkNormalMapShading::ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*>& shaders,
  const ShaderContext& context,
  const Settings& settings)
{
  vtkActor* actor = context.Actor;
  vtkProperty* property = actor->GetProperty();
  vtkTexture* texture = NormalTexture(actor);
  if (!WantsMap(actor) || context.DrawingVertices || property->GetRepresentation() != VTK_SURFACE ||
    context.LightComplexity <= 0)
  {
    // Nothing to show: no map, zero strength, or an unlit or non-surface drawing. VTK writes its
    // normal code only for a positive light complexity; a render pass chain without a lights
    // pass (a value pass, say) leaves it at -1.
    return Mapper::NOT_APPLIED;
  }
  vtkObject* reporter = context.Reporter;
  const std::string& where = context.Where;

  if (context.TCoordComponents != 2)
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::NoTCoords,
      context.TCoordComponents == 0
        ? std::string("The normal texture is not applied: the input has no texture coordinates.")
        : "The normal texture is not applied: texture coordinates have " +
          std::to_string(context.TCoordComponents) + " components (2 needed).");
    return Mapper::NOT_APPLIED;
  }

  ShaderPlan plan;
  const int encoding = settings.MapEncoding;
  const int channels = TextureChannels(texture);
  if (channels < 2)
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::OneChannel,
      "The normal texture is not applied: it has " + std::to_string(channels) +
        " channel(s); a normal map needs 2 (RG), 3 or 4.");
    return Mapper::NOT_APPLIED;
  }
  if (MapsThroughLookupTable(texture))
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::MappedScalars,
      std::string("The normal texture is not applied: its ") +
        TextureScalars(texture)->GetDataTypeAsString() +
        " values go through the texture's lookup table in its color mode; use "
        "SetColorModeToDirectScalars (floating-point values in [0, 1]) or unsigned char values.");
    return Mapper::NOT_APPLIED;
  }
  plan.TwoChannel = IsTwoChannel(encoding);
  if (channels == 2 && IsTangentSpace(encoding) && !plan.TwoChannel)
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::TwoChannelAsRGB,
      "The normal texture has 2 channels but the encoding is " +
        std::string(Mapper::GetMapEncodingName(encoding)) +
        "; decoding it as a two-channel map (z reconstructed).");
    plan.TwoChannel = true;
  }
  plan.LuminanceAlpha = channels == 2;
  if (channels == 2 && !IsTangentSpace(encoding))
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::ObjectSpaceTwoChannel,
      "The normal texture is not applied: an object-space map needs 3 channels, it has 2.");
    return Mapper::NOT_APPLIED;
  }
  plan.SRGB = texture->GetUseSRGBColorSpace();
  if (plan.SRGB)
  {
    this->Warn(reporter,
      actor,
      where,
      Reason::SRGBTexture,
      "The normal texture is marked sRGB; a normal map holds data, not colour. Decoding it "
      "back to its stored values (turn UseSRGBColorSpace off to avoid the round trip).");
  }

  plan.Frame = FrameOf(encoding, context.Frames, plan.PerDatasetFrame);
  AddMapCode(shaders, plan, context);
  return plan.Frame;
}

//------------------------------------------------------------------------------
void vtkNormalMapShading::SetCameraUniforms(vtkShaderProgram* program,
  vtkRenderer* renderer,
  vtkActor* actor)
{
  if (!program->IsUniformUsed("nmNormalMatrix") && !program->IsUniformUsed("nmNormalMatrixInverse"))
  {
    return;
  }
  // The same normal matrix as VTK's (model to view, inverse transpose, without the vertex
  // buffer's shift and scale, which normals and tangents do not have), and its inverse.
  vtkMatrix4x4* wcvc;
  vtkMatrix3x3* normals;
  vtkMatrix4x4* vcdc;
  vtkMatrix4x4* wcdc;
  static_cast<vtkOpenGLCamera*>(renderer->GetActiveCamera())
    ->GetKeyMatrices(renderer, wcvc, normals, vcdc, wcdc);
  vtkNew<vtkMatrix3x3> normalMatrix;
  if (actor->GetIsIdentity())
  {
    normalMatrix->DeepCopy(normals);
  }
  else
  {
    vtkMatrix4x4* mcwc;
    vtkMatrix3x3* actorNormals;
    static_cast<vtkOpenGLActor*>(actor)->GetKeyMatrices(mcwc, actorNormals);
    vtkMatrix3x3::Multiply3x3(actorNormals, normals, normalMatrix);
  }
  vtkNew<vtkMatrix3x3> inverse;
  vtkMatrix3x3::Invert(normalMatrix, inverse);
  program->SetUniformMatrix("nmNormalMatrix", normalMatrix);
  program->SetUniformMatrix("nmNormalMatrixInverse", inverse);
  if (program->IsUniformUsed("nmMirrored"))
  {
    // The inverse transpose has the sign of the model-view matrix's determinant.
    program->SetUniformi("nmMirrored", normalMatrix->Determinant() < 0.0 ? 1 : 0);
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapShading::SetMapUniforms(vtkShaderProgram* program,
  vtkActor* actor,
  const Settings& settings)
{
  if (program->IsUniformUsed("nmNormalScale"))
  {
    program->SetUniformf(
      "nmNormalScale", static_cast<float>(actor->GetProperty()->GetNormalScale()));
  }
  if (program->IsUniformUsed("nmGreenSign"))
  {
    const bool directX = settings.MapEncoding == Mapper::TANGENT_SPACE_DIRECTX ||
      settings.MapEncoding == Mapper::TWO_CHANNEL_DIRECTX;
    program->SetUniformf("nmGreenSign", directX ? -1.0f : 1.0f);
  }
  if (program->IsUniformUsed("nmTextureFrame"))
  {
    // VTK transforms the texture coordinates by the actor's matrix (u' = m0 u + m1 v + m3,
    // v' = m4 u + m5 v + m7; ParaView's Flip Textures sets one), so the map's u' axis runs along
    // M^-1's first column, (m5, -m4) / det M, in the frame of the point tangents.
    float frame[3] = { 1.0f, 0.0f, 1.0f };
    if (const double* m = TextureTransform(actor))
    {
      const double det = m[0] * m[5] - m[1] * m[4];
      if (det != 0.0)
      {
        const double sign = det > 0.0 ? 1.0 : -1.0;
        frame[0] = static_cast<float>(sign * m[5]);
        frame[1] = static_cast<float>(-sign * m[4]);
        frame[2] = static_cast<float>(sign);
      }
    }
    program->SetUniform3f("nmTextureFrame", frame);
  }
}
