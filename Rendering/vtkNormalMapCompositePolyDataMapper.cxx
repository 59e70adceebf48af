#include "vtkNormalMapCompositePolyDataMapper.h"

// GLenum, which vtkCompositeMapperHelper2.h uses without including its declaration.
#include "vtk_glew.h"

#include "vtkCompositeMapperHelper2.h"
#include "vtkFloatArray.h"
#include "vtkNormalMapShading.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShaderProgram.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace
{
/// "Block 3: " or "Blocks 1, 4: ", for warnings.
std::string BlockNames(std::vector<unsigned int> flatIndices)
{
  std::sort(flatIndices.begin(), flatIndices.end());
  std::string names = flatIndices.size() == 1 ? "Block " : "Blocks ";
  for (size_t i = 0; i < flatIndices.size(); ++i)
  {
    names += (i ? ", " : "") + std::to_string(flatIndices[i]);
  }
  return names + ": ";
}
}

/**
 * The per-block helper: VTK's composite helper (which draws every block with the same
 * signature from one vertex buffer group) with the normal mapping of vtkNormalMapShading.
 * Each block appends its tangents (4 floats per point, the sign in w) the way the superclass
 * appends its other point attributes; blocks without tangents append zeros and a per-block
 * uniform gives them the derivative frame.
 */
class vtkNormalMapCompositeMapperHelper : public vtkCompositeMapperHelper2
{
public:
  static vtkNormalMapCompositeMapperHelper* New();
  vtkTypeMacro(vtkNormalMapCompositeMapperHelper, vtkCompositeMapperHelper2);

  /// The parent's settings, and the shading state the parent keeps across its helpers.
  void Configure(const vtkNormalMapShading::Settings& settings, vtkNormalMapShading* shading)
  {
    if (!(settings == this->Settings))
    {
      this->Settings = settings;
      this->Modified(); // rebuilds the vertex buffers: which tangents are uploaded changes
    }
    this->Shading = shading;
  }

  /// Each block's frame in the last render, by flat index (NOT_APPLIED when hidden).
  void CollectAppliedFrames(std::map<unsigned int, int>& frames) const
  {
    for (const auto& block : this->BlockTangents)
    {
      frames[block.first->FlatIndex] = this->AppliedFrame(*block.first, block.second.Use);
    }
  }

protected:
  vtkNormalMapCompositeMapperHelper() = default;
  ~vtkNormalMapCompositeMapperHelper() override = default;

  void BuildBufferObjects(vtkRenderer* ren, vtkActor* actor) override
  {
    // Each block's tangents, before the superclass appends the blocks: whether blocks without
    // tangents need a zero placeholder depends on the others.
    this->BlockTangents.clear();
    this->Frames = vtkNormalMapShading::FrameMix();
    bool allUnsigned = true;
    for (const auto& block : this->Data)
    {
      auto tangents = vtkNormalMapShading::FindTangents(block.first, actor, this->Settings);
      const bool has = tangents.Use != vtkNormalMapShading::TangentUse::Derivatives;
      this->Frames.PointTangents = this->Frames.PointTangents || has;
      this->Frames.Derivatives = this->Frames.Derivatives || !has;
      allUnsigned =
        allUnsigned && (!has || tangents.Use == vtkNormalMapShading::TangentUse::Unsigned);
      this->BlockTangents[block.second] = tangents;
    }
    this->Frames.Unsigned = this->Frames.PointTangents && allUnsigned;
    this->Superclass::BuildBufferObjects(ren, actor);
  }

  void AppendOneBufferObject(vtkRenderer* ren,
    vtkActor* actor,
    vtkCompositeMapperHelperData* hdata,
    vtkIdType& voffset,
    std::vector<unsigned char>& colors,
    std::vector<float>& normals) override
  {
    vtkPoints* points = hdata->Data->GetPoints();
    vtkIdType reusedOffset = 0;
    vtkIdType appendedBefore = 0;
    if (points && points->GetNumberOfPoints() > 0)
    {
      this->VBOs->ArrayExists("vertexMC", points->GetData(), reusedOffset, appendedBefore);
    }
    // VTK's own code appends the block's active Tangents (tangentMC) whenever they exist; it
    // sees a copy without them unless its shader reads them.
    vtkPolyData* block = hdata->Data;
    const auto forVTK = vtkNormalMapShading::WithoutUnusedVTKTangents(block, actor);
    if (forVTK)
    {
      hdata->Data = forVTK;
    }
    this->Superclass::AppendOneBufferObject(ren, actor, hdata, voffset, colors, normals);
    hdata->Data = block;
    // Nothing appended (no points), or the block reuses vertices appended for an earlier block
    // with the same point arrays (then it also has that block's tangents).
    if (!points || points->GetNumberOfPoints() == 0 || voffset != appendedBefore ||
      !this->Frames.PointTangents)
    {
      return;
    }
    vtkFloatArray* packed = vtkNormalMapShading::NewPackedTangents(this->BlockTangents[hdata]);
    if (!packed)
    {
      // A block without tangents: zeros keep the attribute aligned with the vertices.
      packed = vtkFloatArray::New();
      packed->SetNumberOfComponents(4);
      packed->SetNumberOfTuples(points->GetNumberOfPoints());
      packed->Fill(0.0);
    }
    this->VBOs->AppendDataArray(vtkNormalMapShading::TangentAttribute, packed, VTK_FLOAT);
    packed->Delete();
  }

  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* actor) override
  {
    const bool rebuild = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, actor);
    const bool mapChanged = this->Shading->NeedsRebuild(&cellBO, actor, this->Frames.Key());
    return rebuild || mapChanged;
  }

  void ReplaceShaderNormal(std::map<vtkShader::Type, vtkShader*> shaders,
    vtkRenderer* ren,
    vtkActor* actor) override
  {
    this->Shading->SetHidingNormalTexture(true);
    this->Superclass::ReplaceShaderNormal(shaders, ren, actor);
    this->Shading->SetHidingNormalTexture(false);

    vtkOpenGLHelper* cellBO = this->LastBoundBO;
    if (cellBO != &this->Primitives[PrimitiveTris] &&
      cellBO != &this->Primitives[PrimitiveTriStrips])
    {
      return;
    }
    std::vector<unsigned int> flatIndices;
    for (const auto& block : this->Data)
    {
      flatIndices.push_back(block.second->FlatIndex);
    }
    vtkNormalMapShading::ShaderContext context;
    context.Reporter = this->Parent;
    context.Actor = actor;
    context.DrawingVertices = this->DrawingVertices;
    context.LightComplexity = this->PrimitiveInfo[cellBO].LastLightComplexity;
    context.TCoordName = this->GetTextureCoordinateName("normalTex");
    context.TCoordComponents = this->VBOs->GetNumberOfComponents(context.TCoordName.c_str());
    context.Frames = this->Frames;
    context.Where = BlockNames(flatIndices);
    this->SurfaceFrame = this->Shading->ReplaceShaderNormal(shaders, context, this->Settings);
    if (this->SurfaceFrame != vtkNormalMapPolyDataMapper::NOT_APPLIED)
    {
      for (const auto& block : this->BlockTangents)
      {
        this->Shading->WarnAboutTangents(this->Parent,
          actor,
          block.second,
          this->Settings,
          BlockNames({ block.first->FlatIndex }));
      }
    }
  }

  void SetCameraShaderParameters(vtkOpenGLHelper& cellBO,
    vtkRenderer* ren,
    vtkActor* actor) override
  {
    this->Superclass::SetCameraShaderParameters(cellBO, ren, actor);
    vtkNormalMapShading::SetCameraUniforms(cellBO.Program, ren, actor);
  }

  void SetMapperShaderParameters(vtkOpenGLHelper& cellBO,
    vtkRenderer* ren,
    vtkActor* actor) override
  {
    this->Superclass::SetMapperShaderParameters(cellBO, ren, actor);
    vtkNormalMapShading::SetMapUniforms(cellBO.Program, actor, this->Settings);
  }

  /// Per block, before its draw: whether its frame comes from its tangents.
  void SetShaderValues(vtkShaderProgram* program,
    vtkCompositeMapperHelperData* hdata,
    size_t primOffset) override
  {
    this->Superclass::SetShaderValues(program, hdata, primOffset);
    if (program->IsUniformUsed("nmDatasetHasTangents"))
    {
      const auto found = this->BlockTangents.find(hdata);
      const bool has = found != this->BlockTangents.end() &&
        found->second.Use != vtkNormalMapShading::TangentUse::Derivatives;
      program->SetUniformi("nmDatasetHasTangents", has ? 1 : 0);
    }
  }

  std::vector<std::pair<vtkTexture*, std::string>> GetTextures(vtkActor* actor) override
  {
    auto textures = this->Superclass::GetTextures(actor);
    this->Shading->FilterTextures(textures);
    return textures;
  }

private:
  vtkNormalMapCompositeMapperHelper(const vtkNormalMapCompositeMapperHelper&) = delete;
  void operator=(const vtkNormalMapCompositeMapperHelper&) = delete;

  int AppliedFrame(const vtkCompositeMapperHelperData& block,
    vtkNormalMapShading::TangentUse use) const
  {
    if (!block.Visibility)
    {
      return vtkNormalMapPolyDataMapper::NOT_APPLIED;
    }
    if (this->SurfaceFrame == vtkNormalMapPolyDataMapper::NOT_APPLIED ||
      this->SurfaceFrame == vtkNormalMapPolyDataMapper::APPLIED_OBJECT_SPACE)
    {
      return this->SurfaceFrame;
    }
    switch (use)
    {
      case vtkNormalMapShading::TangentUse::Derivatives:
        return vtkNormalMapPolyDataMapper::APPLIED_DERIVATIVES;
      case vtkNormalMapShading::TangentUse::Unsigned:
        return vtkNormalMapPolyDataMapper::APPLIED_UNSIGNED_TANGENTS;
      default:
        return vtkNormalMapPolyDataMapper::APPLIED_POINT_TANGENTS;
    }
  }

  vtkNormalMapShading::Settings Settings;
  vtkNormalMapShading* Shading = nullptr;
  /// Per block, its tangents as found at the last vertex buffer build (the array pointers are
  /// read during that build only).
  std::map<const vtkCompositeMapperHelperData*, vtkNormalMapShading::Tangents> BlockTangents;
  vtkNormalMapShading::FrameMix Frames;
  /// The frame of the last surface shader built.
  int SurfaceFrame = vtkNormalMapPolyDataMapper::NOT_APPLIED;
};

vtkStandardNewMacro(vtkNormalMapCompositeMapperHelper);

struct vtkNormalMapCompositePolyDataMapper::Internals
{
  /// Shared by the helpers: warnings once per actor and blocks, shader keys per program.
  vtkNormalMapShading Shading;
  /// Per flat index, the frame of the last render.
  std::map<unsigned int, int> Frames;
};

vtkStandardNewMacro(vtkNormalMapCompositePolyDataMapper);

//------------------------------------------------------------------------------
vtkNormalMapCompositePolyDataMapper::vtkNormalMapCompositePolyDataMapper()
  : Internal(new Internals)
{
}

//------------------------------------------------------------------------------
vtkNormalMapCompositePolyDataMapper::~vtkNormalMapCompositePolyDataMapper() = default;

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::SetTangentsArrayName(const std::string& name)
{
  if (this->TangentsArrayName != name)
  {
    this->TangentsArrayName = name;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::SetTangentSignsArrayName(const std::string& name)
{
  if (this->TangentSignsArrayName != name)
  {
    this->TangentSignsArrayName = name;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkCompositeMapperHelper2* vtkNormalMapCompositePolyDataMapper::CreateHelper()
{
  return vtkNormalMapCompositeMapperHelper::New();
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::CopyMapperValuesToHelper(
  vtkCompositeMapperHelper2* helper)
{
  this->Superclass::CopyMapperValuesToHelper(helper);
  if (auto* ours = vtkNormalMapCompositeMapperHelper::SafeDownCast(helper))
  {
    ours->Configure(vtkNormalMapShading::SettingsOf(this), &this->Internal->Shading);
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::Render(vtkRenderer* ren, vtkActor* actor)
{
  this->Superclass::Render(ren, actor);
  // Each drawn block's frame, kept after the helpers are gone (released graphics resources).
  this->Internal->Frames.clear();
  for (const auto& helper : this->Helpers)
  {
    if (auto* ours = vtkNormalMapCompositeMapperHelper::SafeDownCast(helper.second))
    {
      ours->CollectAppliedFrames(this->Internal->Frames);
    }
  }
}

//------------------------------------------------------------------------------
int vtkNormalMapCompositePolyDataMapper::GetLastAppliedFrame(unsigned int flatIndex)
{
  const auto found = this->Internal->Frames.find(flatIndex);
  return found == this->Internal->Frames.end() ? vtkNormalMapPolyDataMapper::NOT_APPLIED
                                               : found->second;
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->Shading.ReleaseShaders();
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "MapEncoding: " << vtkNormalMapPolyDataMapper::GetMapEncodingName(this->MapEncoding)
     << "\n";
  os << indent
     << "FrameSource: " << vtkNormalMapPolyDataMapper::GetFrameSourceName(this->FrameSource)
     << "\n";
  os << indent << "TangentsArrayName: "
     << (this->TangentsArrayName.empty() ? "(active tangents)" : this->TangentsArrayName) << "\n";
  os << indent << "TangentSignsArrayName: " << this->TangentSignsArrayName << "\n";
}
