// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMapPolyDataMapper.h"

#include "vtkNormalMapShading.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"

#include <string>

vtkStandardNewMacro(vtkNormalMapPolyDataMapper);

namespace
{
/// The frame the vertex buffers hold (BuildBufferObjects uploaded what FindTangents found).
vtkNormalMapShading::FrameMix FramesOf(vtkOpenGLVertexBufferObjectGroup* vbos)
{
  vtkNormalMapShading::FrameMix frames;
  const int tangentComponents = vbos->GetNumberOfComponents(vtkNormalMapShading::TangentAttribute);
  frames.PointTangents = tangentComponents >= 3;
  frames.SeparateSigns =
    tangentComponents == 3 && vbos->GetNumberOfComponents(vtkNormalMapShading::SignAttribute) == 1;
  frames.Unsigned = tangentComponents == 3 && !frames.SeparateSigns;
  frames.SomeUnsigned = frames.Unsigned;
  frames.Derivatives = !frames.PointTangents;
  return frames;
}
}

struct vtkNormalMapPolyDataMapper::Internals
{
  vtkNormalMapShading Shading;
};

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
  this->Internal->Shading.FilterTextures(textures);
  return textures;
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* actor)
{
  // Point tangents are uploaded only when a tangent-space map will use them. They go into the
  // same vertex buffer group, before the superclass builds it; the buffer cache shares one
  // buffer between attributes that read the same array.
  const auto tangents = vtkNormalMapShading::FindTangents(
    this->CurrentInput, actor, vtkNormalMapShading::SettingsOf(this));
  auto* cache = static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())->GetVBOCache();
  this->VBOs->CacheDataArray(
    vtkNormalMapShading::TangentAttribute, tangents.Vectors, cache, VTK_FLOAT);
  this->VBOs->CacheDataArray(vtkNormalMapShading::SignAttribute, tangents.Signs, cache, VTK_FLOAT);
  // The dataset's texture coordinates under the mapper's own name, where VTK's may be the color
  // map's; when they are not, both names share one buffer.
  const bool ownTCoords = this->NormalTCoords(actor) == vtkNormalMapShading::TCoordAttribute;
  this->VBOs->CacheDataArray(vtkNormalMapShading::TCoordAttribute,
    ownTCoords ? this->CurrentInput->GetPointData()->GetTCoords() : nullptr,
    cache,
    VTK_FLOAT);
  // VTK's own code uploads the active Tangents (tangentMC) whenever they exist; it sees a copy
  // without them unless its shader reads them.
  vtkPolyData* input = this->CurrentInput;
  const auto forVTK = vtkNormalMapShading::WithoutUnusedVTKTangents(input, actor);
  if (forVTK)
  {
    this->CurrentInput = forVTK;
  }
  this->Superclass::BuildBufferObjects(ren, actor);
  this->CurrentInput = input;
}

//------------------------------------------------------------------------------
std::string vtkNormalMapPolyDataMapper::NormalTCoords(vtkActor* actor)
{
  return vtkNormalMapShading::SampledTCoords(
    this, actor, this->GetTextureCoordinateName("normalTex"));
}

//------------------------------------------------------------------------------
bool vtkNormalMapPolyDataMapper::GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  // The superclass also records the light complexity that the shader plan depends on.
  const bool rebuild = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, actor);
  const std::string tcoords = this->NormalTCoords(actor);
  const bool mapChanged = this->Internal->Shading.NeedsRebuild(&cellBO,
    actor,
    FramesOf(this->VBOs).Key(),
    tcoords,
    this->VBOs->GetNumberOfComponents(tcoords.c_str()));
  return rebuild || mapChanged;
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*> shaders,
  vtkRenderer* ren,
  vtkActor* actor)
{
  // VTK's own normal code (point, cell or derivative normals), without its normal mapping.
  vtkNormalMapShading& shading = this->Internal->Shading;
  shading.SetHidingNormalTexture(true);
  this->Superclass::ReplaceShaderNormal(shaders, ren, actor);
  shading.SetHidingNormalTexture(false);

  vtkOpenGLHelper* cellBO = this->LastBoundBO;
  if (cellBO != &this->Primitives[PrimitiveTris] && cellBO != &this->Primitives[PrimitiveTriStrips])
  {
    return; // points and lines keep VTK's normals; LastAppliedFrame is about surfaces
  }
  const vtkNormalMapShading::Settings settings = vtkNormalMapShading::SettingsOf(this);
  vtkNormalMapShading::ShaderContext context;
  context.Reporter = this;
  context.Actor = actor;
  context.DrawingVertices = this->DrawingVertices;
  context.LightComplexity = this->PrimitiveInfo[cellBO].LastLightComplexity;
  context.TCoordName = this->NormalTCoords(actor);
  context.TCoordComponents = this->VBOs->GetNumberOfComponents(context.TCoordName.c_str());
  context.Frames = FramesOf(this->VBOs);
  this->LastAppliedFrame = shading.ReplaceShaderNormal(shaders, context, settings);
  if (this->LastAppliedFrame != NOT_APPLIED)
  {
    // Say why point tangents were not used.
    shading.WarnAboutTangents(this,
      actor,
      vtkNormalMapShading::FindTangents(this->CurrentInput, actor, settings),
      settings,
      std::string());
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetCameraShaderParameters(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::SetCameraShaderParameters(cellBO, ren, actor);
  vtkNormalMapShading::SetCameraUniforms(cellBO.Program, ren, actor);
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::SetMapperShaderParameters(vtkOpenGLHelper& cellBO,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, actor);
  vtkNormalMapShading::SetMapUniforms(cellBO.Program, actor, vtkNormalMapShading::SettingsOf(this));
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->Shading.ReleaseShaders();
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkNormalMapPolyDataMapper::ShallowCopy(vtkAbstractMapper* mapper)
{
  this->Superclass::ShallowCopy(mapper);
  if (auto* other = vtkNormalMapPolyDataMapper::SafeDownCast(mapper))
  {
    vtkNormalMapShading::ApplySettings(this, vtkNormalMapShading::SettingsOf(other));
  }
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
