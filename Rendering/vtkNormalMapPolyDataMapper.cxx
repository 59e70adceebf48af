#include "vtkNormalMapPolyDataMapper.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexBufferObjectCache.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
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
#include <string>

vtkStandardNewMacro(vtkNormalMapPolyDataMapper);

namespace
{
const char* const NormalTextureName = "normalTex";
const char* const TangentAttribute = "nmTangentMC";
const char* const SignAttribute = "nmTangentSignMC";

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
    vtkGenericWarningMacro("vtkNormalMapPolyDataMapper: shader block " << name << " not found");
    return std::string();
  }
  return text.substr(start + begin.size(), stop - start - begin.size());
}

/// Put `code` in front of `tag`, keeping the tag for VTK's own replacements that follow.
bool InsertBefore(std::string& source, const std::string& tag, const std::string& code)
{
  return vtkShaderProgram::Substitute(source, tag, code + tag, false);
}

/// Number of components of a normal texture's image (0 when it has none). VTK uploads images
/// of 1 or 2 components as RGBA (luminance, luminance-alpha), so the texture object cannot tell.
int TextureChannels(vtkTexture* texture)
{
  vtkImageData* image = texture->GetInput();
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  return scalars ? scalars->GetNumberOfComponents() : 0;
}

bool IsTangentSpace(int encoding)
{
  return encoding != vtkNormalMapPolyDataMapper::OBJECT_SPACE;
}

bool IsTwoChannel(int encoding)
{
  return encoding == vtkNormalMapPolyDataMapper::TWO_CHANNEL_OPENGL ||
    encoding == vtkNormalMapPolyDataMapper::TWO_CHANNEL_DIRECTX;
}
}

/// Reasons the mapper warns about, once per actor each.
enum class WarningReason : unsigned
{
  NoTCoords = 1u << 0,
  OneChannel = 1u << 1,
  TwoChannelAsRGB = 1u << 2,
  ObjectSpaceTwoChannel = 1u << 3,
  UnsignedTangents = 1u << 4,
  MissingTangents = 1u << 5,
  BadTangents = 1u << 6,
  SRGBTexture = 1u << 7,
  BadSigns = 1u << 8
};

struct vtkNormalMapPolyDataMapper::Internals
{
  /// While set, GetTextures() leaves the normal texture out, so that the superclass does not
  /// write its own normal-mapping code.
  bool HideNormalTexture = false;
  /// Per shader program (one per primitive type), the normal-map state it was built for.
  std::map<const vtkOpenGLHelper*, unsigned> ShaderKeys;
  /// Reasons already warned about, per actor.
  std::map<const vtkActor*, unsigned> Warned;

  void Warn(vtkNormalMapPolyDataMapper* self,
    const vtkActor* actor,
    WarningReason reason,
    const std::string& message)
  {
    unsigned& done = this->Warned[actor];
    if (!(done & static_cast<unsigned>(reason)))
    {
      done |= static_cast<unsigned>(reason);
      vtkWarningWithObjectMacro(self, << message);
    }
  }
};

/// The tangent arrays of the input, checked.
struct TangentArrays
{
  vtkDataArray* Tangents = nullptr; // 3 or 4 components, one tuple per point
  vtkDataArray* Signs = nullptr;    // with 3-component tangents: 1 component per point
  std::string Problem;              // why a present tangent array cannot be used
};

namespace
{
TangentArrays FindTangents(vtkPolyData* poly,
  const std::string& tangentsName,
  const std::string& signsName)
{
  TangentArrays found;
  vtkPointData* pd = poly->GetPointData();
  vtkDataArray* tangents =
    tangentsName.empty() ? pd->GetTangents() : pd->GetArray(tangentsName.c_str());
  if (!tangents)
  {
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
  found.Tangents = tangents;
  if (comps == 3 && !signsName.empty())
  {
    vtkDataArray* signs = pd->GetArray(signsName.c_str());
    if (signs && signs->GetNumberOfComponents() == 1 && signs->GetNumberOfTuples() == n)
    {
      found.Signs = signs;
    }
    else if (signs)
    {
      found.Problem = "sign array '" + signsName + "' is not one value per point";
    }
  }
  return found;
}
}

//------------------------------------------------------------------------------
vtkNormalMapPolyDataMapper::vtkNormalMapPolyDataMapper()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkNormalMapPolyDataMapper::~vtkNormalMapPolyDataMapper() = default;

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetTangentsArrayName(const std::string& name)
{
  if (this->TangentsArrayName != name)
  {
    this->TangentsArrayName = name;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetTangentSignsArrayName(const std::string& name)
{
  if (this->TangentSignsArrayName != name)
  {
    this->TangentSignsArrayName = name;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
const char* vtkNormalMapPolyDataMapper::GetMapEncodingName(int encoding)
{
  switch (encoding)
  {
    case TANGENT_SPACE_OPENGL:
      return "TangentSpaceOpenGL";
    case TANGENT_SPACE_DIRECTX:
      return "TangentSpaceDirectX";
    case TWO_CHANNEL_OPENGL:
      return "TwoChannelOpenGL";
    case TWO_CHANNEL_DIRECTX:
      return "TwoChannelDirectX";
    case OBJECT_SPACE:
      return "ObjectSpace";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
const char* vtkNormalMapPolyDataMapper::GetFrameSourceName(int source)
{
  switch (source)
  {
    case AUTOMATIC:
      return "Automatic";
    case POINT_TANGENTS:
      return "PointTangents";
    case SCREEN_DERIVATIVES:
      return "ScreenDerivatives";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
const char* vtkNormalMapPolyDataMapper::GetAppliedFrameName(int frame)
{
  switch (frame)
  {
    case NOT_APPLIED:
      return "NotApplied";
    case APPLIED_POINT_TANGENTS:
      return "PointTangents";
    case APPLIED_UNSIGNED_TANGENTS:
      return "UnsignedPointTangents";
    case APPLIED_DERIVATIVES:
      return "ScreenDerivatives";
    case APPLIED_OBJECT_SPACE:
      return "ObjectSpace";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
std::vector<std::pair<vtkTexture*, std::string>> vtkNormalMapPolyDataMapper::GetTextures(
  vtkActor* actor)
{
  auto textures = this->Superclass::GetTextures(actor);
  if (this->Internal->HideNormalTexture)
  {
    textures.erase(
      std::remove_if(textures.begin(),
        textures.end(),
        [](const std::pair<vtkTexture*, std::string>& t) { return t.second == NormalTextureName; }),
      textures.end());
  }
  return textures;
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* actor)
{
  vtkPolyData* poly = this->CurrentInput;
  vtkProperty* property = actor->GetProperty();
  vtkTexture* normalTexture = property->GetTexture(NormalTextureName);
  const bool wantsMap = normalTexture && property->GetNormalScale() != 0.0;

  if (wantsMap && normalTexture->GetInterpolate() && !normalTexture->GetMipmap())
  {
    // Trilinear filtering of a minified normal map needs mipmaps. The property rendered the
    // texture already this frame; load it again so the first frame has them too.
    normalTexture->MipmapOn();
    normalTexture->Load(ren);
  }

  // Point tangents are uploaded only when a tangent-space map will use them. They go into the
  // same vertex buffer group, before the superclass builds it; the buffer cache shares one
  // buffer between attributes that read the same array.
  if (poly && wantsMap && IsTangentSpace(this->MapEncoding) &&
    this->FrameSource != SCREEN_DERIVATIVES)
  {
    const TangentArrays arrays =
      FindTangents(poly, this->TangentsArrayName, this->TangentSignsArrayName);
    if (arrays.Tangents)
    {
      auto* cache = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())->GetVBOCache();
      this->VBOs->CacheDataArray(TangentAttribute, arrays.Tangents, cache, VTK_FLOAT);
      if (arrays.Signs)
      {
        this->VBOs->CacheDataArray(SignAttribute, arrays.Signs, cache, VTK_FLOAT);
      }
    }
  }
  this->Superclass::BuildBufferObjects(ren, actor);
}

//------------------------------------------------------------------------------
namespace
{
/// What the normal-map code of one shader program will be.
struct ShaderPlan
{
  int Frame = vtkNormalMapPolyDataMapper::NOT_APPLIED;
  bool SeparateSigns = false;
  bool TwoChannel = false;
  bool LuminanceAlpha = false; // a 2-component image: x in red, y in alpha
  bool SRGB = false;
  std::string TCoordName;
};
}

//------------------------------------------------------------------------------
bool vtkNormalMapPolyDataMapper::GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  // The superclass also records the light complexity that the plan below depends on.
  const bool rebuild = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, actor);

  // The normal-map state depends on the texture and the vertex buffers, which the
  // superclass's test does not cover in full (a texture's channels, its sRGB flag).
  unsigned key = 0;
  vtkProperty* property = actor->GetProperty();
  vtkTexture* texture = property->GetTexture(NormalTextureName);
  if (texture)
  {
    key = 1u + (texture->GetUseSRGBColorSpace() ? 2u : 0u) +
      (static_cast<unsigned>(TextureChannels(texture)) << 2) +
      (static_cast<unsigned>(this->VBOs->GetNumberOfComponents(TangentAttribute)) << 5) +
      (static_cast<unsigned>(this->VBOs->GetNumberOfComponents(SignAttribute)) << 8);
  }
  unsigned& stored = this->Internal->ShaderKeys[&cellBO];
  if (stored != key)
  {
    stored = key;
    return true;
  }
  return rebuild;
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*> shaders,
  vtkRenderer* ren,
  vtkActor* actor)
{
  // VTK's own normal code (point, cell or derivative normals), without its normal mapping.
  this->Internal->HideNormalTexture = true;
  this->Superclass::ReplaceShaderNormal(shaders, ren, actor);
  this->Internal->HideNormalTexture = false;

  vtkOpenGLHelper* cellBO = this->LastBoundBO;
  const bool surfacePrimitive =
    cellBO == &this->Primitives[PrimitiveTris] || cellBO == &this->Primitives[PrimitiveTriStrips];
  if (!surfacePrimitive)
  {
    return;
  }
  this->LastAppliedFrame = NOT_APPLIED;

  vtkProperty* property = actor->GetProperty();
  vtkTexture* texture = property->GetTexture(NormalTextureName);
  if (!texture || property->GetNormalScale() == 0.0 || this->DrawingVertices ||
    property->GetRepresentation() != VTK_SURFACE ||
    this->PrimitiveInfo[cellBO].LastLightComplexity == 0)
  {
    // Nothing to show: no map, zero strength, or an unlit or non-surface drawing.
    return;
  }

  ShaderPlan plan;
  plan.TCoordName = this->GetTextureCoordinateName(NormalTextureName);
  const int tcoordComponents = this->VBOs->GetNumberOfComponents(plan.TCoordName.c_str());
  if (tcoordComponents != 2)
  {
    this->Internal->Warn(this,
      actor,
      WarningReason::NoTCoords,
      tcoordComponents == 0
        ? std::string("The normal texture is not applied: the input has no texture coordinates.")
        : "The normal texture is not applied: texture coordinates have " +
          std::to_string(tcoordComponents) + " components (2 needed).");
    return;
  }

  const int channels = TextureChannels(texture);
  if (channels < 2)
  {
    this->Internal->Warn(this,
      actor,
      WarningReason::OneChannel,
      "The normal texture is not applied: it has " + std::to_string(channels) +
        " channel(s); a normal map needs 2 (RG), 3 or 4.");
    return;
  }
  plan.TwoChannel = IsTwoChannel(this->MapEncoding);
  if (channels == 2 && IsTangentSpace(this->MapEncoding) && !plan.TwoChannel)
  {
    this->Internal->Warn(this,
      actor,
      WarningReason::TwoChannelAsRGB,
      "The normal texture has 2 channels but the encoding is " +
        std::string(GetMapEncodingName(this->MapEncoding)) +
        "; decoding it as a two-channel map (z reconstructed).");
    plan.TwoChannel = true;
  }
  plan.LuminanceAlpha = channels == 2;
  if (channels == 2 && !IsTangentSpace(this->MapEncoding))
  {
    this->Internal->Warn(this,
      actor,
      WarningReason::ObjectSpaceTwoChannel,
      "The normal texture is not applied: an object-space map needs 3 channels, it has 2.");
    return;
  }
  plan.SRGB = texture->GetUseSRGBColorSpace();
  if (plan.SRGB)
  {
    this->Internal->Warn(this,
      actor,
      WarningReason::SRGBTexture,
      "The normal texture is marked sRGB; a normal map holds data, not colour. Decoding it "
      "back to its stored values (turn UseSRGBColorSpace off to avoid the round trip).");
  }

  if (!IsTangentSpace(this->MapEncoding))
  {
    plan.Frame = APPLIED_OBJECT_SPACE;
  }
  else
  {
    const int tangentComponents = this->VBOs->GetNumberOfComponents(TangentAttribute);
    if (tangentComponents >= 3)
    {
      plan.SeparateSigns =
        tangentComponents == 3 && this->VBOs->GetNumberOfComponents(SignAttribute) == 1;
      plan.Frame = (tangentComponents == 4 || plan.SeparateSigns) ? APPLIED_POINT_TANGENTS
                                                                  : APPLIED_UNSIGNED_TANGENTS;
    }
    else
    {
      plan.Frame = APPLIED_DERIVATIVES;
    }
    // Say why point tangents were not used or are used without signs.
    if (this->FrameSource != SCREEN_DERIVATIVES && this->CurrentInput)
    {
      const TangentArrays arrays =
        FindTangents(this->CurrentInput, this->TangentsArrayName, this->TangentSignsArrayName);
      if (!arrays.Problem.empty())
      {
        this->Internal->Warn(this,
          actor,
          arrays.Tangents ? WarningReason::BadSigns : WarningReason::BadTangents,
          "Point tangents: " + arrays.Problem +
            (arrays.Tangents ? "; using sign +1." : "; using screen-space derivatives."));
      }
      else if (!arrays.Tangents && this->FrameSource == POINT_TANGENTS)
      {
        this->Internal->Warn(this,
          actor,
          WarningReason::MissingTangents,
          "FrameSource is PointTangents but the input has no tangent array" +
            (this->TangentsArrayName.empty() ? std::string()
                                             : " named '" + this->TangentsArrayName + "'") +
            "; using screen-space derivatives.");
      }
      if (plan.Frame == APPLIED_UNSIGNED_TANGENTS && arrays.Problem.empty())
      {
        this->Internal->Warn(this,
          actor,
          WarningReason::UnsignedTangents,
          "Point tangents have no handedness sign (no 4th component, no '" +
            this->TangentSignsArrayName +
            "' array); using +1, so mirrored UVs shade inverted. vtkPolyDataTangentFrames "
            "writes the signs.");
      }
    }
  }
  this->LastAppliedFrame = plan.Frame;

  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string gs = shaders[vtkShader::Geometry]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();

  const bool pointTangents =
    plan.Frame == APPLIED_POINT_TANGENTS || plan.Frame == APPLIED_UNSIGNED_TANGENTS;
  if (pointTangents)
  {
    InsertBefore(vs,
      "//VTK::Normal::Dec",
      Block(vtkNormalMapVS, plan.SeparateSigns ? "TangentSignDec" : "TangentDec"));
    InsertBefore(vs,
      "//VTK::Normal::Impl",
      Block(vtkNormalMapVS, plan.SeparateSigns ? "TangentSignImpl" : "TangentImpl"));
    if (!gs.empty())
    {
      InsertBefore(gs, "//VTK::Normal::Dec", Block(vtkNormalMapGS, "TangentDec"));
      InsertBefore(gs, "//VTK::Normal::Impl", Block(vtkNormalMapGS, "TangentImpl"));
    }
  }

  // Declarations go before VTK's lighting declarations (after its normal ones, which a cell
  // normal path consumes); the code goes just before the lighting, where the normal is final.
  std::string declarations =
    Block(vtkNormalMapFS, "Dec") + Block(vtkNormalMapFS, plan.SRGB ? "TexelSRGB" : "TexelLinear");
  std::string code;
  if (plan.Frame == APPLIED_OBJECT_SPACE)
  {
    code = Block(vtkNormalMapFS, "ImplObjectSpace");
  }
  else
  {
    std::string decode = Block(vtkNormalMapFS, plan.TwoChannel ? "DecodeTwoChannel" : "DecodeRGB");
    vtkShaderProgram::Substitute(decode, "@XY@", plan.LuminanceAlpha ? "ra" : "rg");
    declarations += decode;
    declarations += Block(vtkNormalMapFS, pointTangents ? "TangentDec" : "DerivativeDec");
    code = Block(vtkNormalMapFS, "ImplTangentSpace");
    if (!pointTangents)
    {
      std::string flow = Block(vtkNormalMapFS, "DerivativeUniformFlow");
      vtkShaderProgram::Substitute(flow, "@TCOORD@", plan.TCoordName);
      InsertBefore(fs, "//VTK::UniformFlow::Impl", flow);
    }
  }
  vtkShaderProgram::Substitute(code, "@TCOORD@", plan.TCoordName);
  InsertBefore(fs, "//VTK::Light::Dec", declarations);
  InsertBefore(fs, "//VTK::Light::Impl", code);

  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Geometry]->SetSource(gs);
  shaders[vtkShader::Fragment]->SetSource(fs);
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetCameraShaderParameters(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::SetCameraShaderParameters(cellBO, ren, actor);
  vtkShaderProgram* program = cellBO.Program;
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
  static_cast<vtkOpenGLCamera*>(ren->GetActiveCamera())
    ->GetKeyMatrices(ren, wcvc, normals, vcdc, wcdc);
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
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetMapperShaderParameters(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, actor);
  vtkShaderProgram* program = cellBO.Program;
  if (program->IsUniformUsed("nmNormalScale"))
  {
    program->SetUniformf(
      "nmNormalScale", static_cast<float>(actor->GetProperty()->GetNormalScale()));
  }
  if (program->IsUniformUsed("nmGreenSign"))
  {
    const bool directX =
      this->MapEncoding == TANGENT_SPACE_DIRECTX || this->MapEncoding == TWO_CHANNEL_DIRECTX;
    program->SetUniformf("nmGreenSign", directX ? -1.0f : 1.0f);
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->ShaderKeys.clear();
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MapEncoding: " << GetMapEncodingName(this->MapEncoding) << "\n";
  os << indent << "FrameSource: " << GetFrameSourceName(this->FrameSource) << "\n";
  os << indent << "TangentsArrayName: "
     << (this->TangentsArrayName.empty() ? "(active tangents)" : this->TangentsArrayName) << "\n";
  os << indent << "TangentSignsArrayName: " << this->TangentSignsArrayName << "\n";
  os << indent << "LastAppliedFrame: " << GetAppliedFrameName(this->LastAppliedFrame) << "\n";
}
