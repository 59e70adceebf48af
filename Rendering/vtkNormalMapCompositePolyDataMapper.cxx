// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMapCompositePolyDataMapper.h"

#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
#include "vtkOpenGLBatchedPolyDataMapper.h"
#include "vtkOpenGLCompositePolyDataMapperDelegator.h"
#else
// GLenum, which vtkCompositeMapperHelper2.h uses without including its declaration.
#include "vtk_glew.h"

#include "vtkCompositeMapperHelper2.h"
#endif
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkNormalMapShading.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
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

/// Whether two blocks' tangents come from the same arrays, used the same way.
bool SameArrays(const vtkNormalMapShading::Tangents& a, const vtkNormalMapShading::Tangents& b)
{
  return a.Use == b.Use && a.Vectors == b.Vectors && a.Signs == b.Signs;
}

/// A shallow copy of `poly` whose points are a new array sharing the same values.
vtkSmartPointer<vtkPolyData> WithOwnPointArray(vtkPolyData* poly)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(poly);
  vtkDataArray* values = poly->GetPoints()->GetData();
  auto data = vtk::TakeSmartPointer(values->NewInstance());
  data->ShallowCopy(values);
  vtkNew<vtkPoints> points;
  points->SetData(data);
  copy->SetPoints(points);
  return copy;
}

/// `poly` when its texture coordinates have 2 components or none, else a shallow copy whose
/// texture coordinates are the first two components of its own (a second of zeros for one).
vtkSmartPointer<vtkPolyData> WithTwoComponentTCoords(vtkPolyData* poly)
{
  vtkDataArray* tcoords = poly->GetPointData()->GetTCoords();
  if (!tcoords || tcoords->GetNumberOfComponents() == 2)
  {
    return poly;
  }
  vtkNew<vtkFloatArray> uv;
  uv->SetName(tcoords->GetName());
  uv->SetNumberOfComponents(2);
  uv->SetNumberOfTuples(tcoords->GetNumberOfTuples());
  const bool hasV = tcoords->GetNumberOfComponents() > 1;
  for (vtkIdType p = 0; p < tcoords->GetNumberOfTuples(); ++p)
  {
    uv->SetTypedTuple(p,
      std::array<float, 2>{ static_cast<float>(tcoords->GetComponent(p, 0)),
        hasV ? static_cast<float>(tcoords->GetComponent(p, 1)) : 0.0f }
        .data());
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(poly);
  copy->GetPointData()->SetTCoords(uv);
  return copy;
}

/*
 * What differs between VTK's two composite designs: up to VTK 9.2 a helper
 * (vtkCompositeMapperHelper2) draws the blocks of one signature, each block a
 * vtkCompositeMapperHelperData; from VTK 9.3 a batched mapper (vtkOpenGLBatchedPolyDataMapper,
 * held by a delegator) draws them, each block a GLBatchElement. The helper below is written once
 * against these names.
 */
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
using HelperBase = vtkOpenGLBatchedPolyDataMapper;
using BlockData = vtkOpenGLCompositePolyDataMapperDelegator::GLBatchElement;
vtkPolyData*& PolyDataOf(BlockData* block)
{
  return block->Parent.PolyData;
}
unsigned int FlatIndexOf(const BlockData& block)
{
  return block.Parent.FlatIndex;
}
bool IsVisible(const BlockData& block)
{
  return block.Parent.Visibility;
}
#else
using HelperBase = vtkCompositeMapperHelper2;
using BlockData = vtkCompositeMapperHelperData;
vtkPolyData*& PolyDataOf(BlockData* block)
{
  return block->Data;
}
unsigned int FlatIndexOf(const BlockData& block)
{
  return block.FlatIndex;
}
bool IsVisible(const BlockData& block)
{
  return block.Visibility;
}
#endif
}

/**
 * The per-block helper: VTK's helper or batched mapper (which draws every block with the same
 * signature from one vertex buffer group) with the normal mapping of vtkNormalMapShading.
 * Each block appends its tangents (4 floats per point, the sign in w) the way the superclass
 * appends its other point attributes; blocks without tangents append zeros and a per-block
 * uniform gives them the derivative frame.
 */
class vtkNormalMapCompositeMapperHelper : public HelperBase
{
public:
  static vtkNormalMapCompositeMapperHelper* New();
  vtkTypeMacro(vtkNormalMapCompositeMapperHelper, HelperBase);

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
      frames[FlatIndexOf(*block.first)] = this->AppliedFrame(*block.first, block.second.Use);
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
    this->Appended.clear();
    this->TCoords =
      vtkNormalMapShading::SampledTCoords(this, actor, this->GetTextureCoordinateName("normalTex"));
    this->Frames = vtkNormalMapShading::FrameMix();
    bool allUnsigned = true;
    bool allTCoords = true;
    int components = 2; // the first count of texture-coordinate components other than 2
    int firstCount = 0; // the first block's count
    this->MixedTCoordCounts = false;
    this->ForEachBlock(
      [&](BlockData* block)
      {
        vtkDataArray* tcoords = PolyDataOf(block)->GetPointData()->GetTCoords();
        const int count = tcoords ? tcoords->GetNumberOfComponents() : 0;
        allTCoords = allTCoords && tcoords;
        components = components == 2 && tcoords ? count : components;
        firstCount = firstCount ? firstCount : count;
        this->MixedTCoordCounts = this->MixedTCoordCounts || (tcoords && count != firstCount);
        auto tangents = vtkNormalMapShading::FindTangents(PolyDataOf(block), actor, this->Settings);
        const bool has = tangents.Use != vtkNormalMapShading::TangentUse::Derivatives;
        this->Frames.PointTangents = this->Frames.PointTangents || has;
        this->Frames.Derivatives = this->Frames.Derivatives || !has;
        const bool unsignedTangents = tangents.Use == vtkNormalMapShading::TangentUse::Unsigned;
        allUnsigned = allUnsigned && (!has || unsignedTangents);
        this->Frames.SomeUnsigned = this->Frames.SomeUnsigned || unsignedTangents;
        this->BlockTangents[block] = tangents;
      });
    this->Frames.Unsigned = this->Frames.PointTangents && allUnsigned;
    // The blocks' own texture coordinates are uploaded only when every block has them, with 2
    // components: VTK draws blocks with and without texture coordinates with separate helpers
    // (VTK 9.1 and 9.6 do), but blocks whose counts differ with one (VTK 9.1 does), and one
    // vertex buffer cannot hold arrays of different counts. Otherwise the attribute is absent,
    // and the shader code warns with the count found.
    this->BlockTCoordComponents = allTCoords ? components : 0;
    this->OwnTCoords =
      this->TCoords == vtkNormalMapShading::TCoordAttribute && this->BlockTCoordComponents == 2;
    this->Superclass::BuildBufferObjects(ren, actor);
  }

  void AppendOneBufferObject(vtkRenderer* ren,
    vtkActor* actor,
    BlockData* hdata,
    vtkIdType& voffset,
    std::vector<unsigned char>& colors,
    std::vector<float>& normals) override
  {
    vtkPolyData* block = PolyDataOf(hdata);
    vtkPoints* points = block->GetPoints();
    const bool hasPoints = points && points->GetNumberOfPoints() > 0;
    vtkIdType reusedOffset = 0;
    vtkIdType appendedBefore = 0;
    const bool pointsAppended = hasPoints &&
      this->VBOs->ArrayExists("vertexMC", points->GetData(), reusedOffset, appendedBefore);
    // VTK's own code appends the block's active Tangents (tangentMC) whenever they exist; it
    // sees a copy without them unless its shader reads them.
    vtkSmartPointer<vtkPolyData> forVTK =
      vtkNormalMapShading::WithoutUnusedVTKTangents(block, actor);
    // VTK fills one vertex buffer with every block's texture coordinates, with the first
    // block's count of components for all, reading past the end of a shorter array: blocks
    // whose counts differ give it theirs with 2 components.
    if (this->MixedTCoordCounts)
    {
      forVTK = WithTwoComponentTCoords(forVTK ? forVTK.Get() : block);
    }
    // VTK lets a block reuse the vertices appended for an earlier block with the same point,
    // normal and texture-coordinate arrays. With other tangents, or other texture coordinates of
    // the mapper's own, it must not: a new array over the same points makes VTK append the
    // block's vertices again.
    const AppendedArrays arrays{ this->BlockTangents[hdata],
      this->OwnTCoords ? block->GetPointData()->GetTCoords() : nullptr };
    const auto appended = this->Appended.find(reusedOffset);
    if (pointsAppended && (this->Frames.PointTangents || this->OwnTCoords) &&
      (appended == this->Appended.end() || !appended->second.Same(arrays)))
    {
      forVTK = WithOwnPointArray(forVTK ? forVTK.Get() : block);
    }
    if (forVTK)
    {
      PolyDataOf(hdata) = forVTK;
    }
    this->Superclass::AppendOneBufferObject(ren, actor, hdata, voffset, colors, normals);
    PolyDataOf(hdata) = block;
    // Nothing appended (no points), or the block reuses vertices appended for an earlier block
    // with the same point arrays and the same arrays of ours.
    if (!hasPoints || voffset != appendedBefore)
    {
      return;
    }
    const vtkIdType numPoints = points->GetNumberOfPoints();
    if (this->Frames.PointTangents)
    {
      auto packed = vtk::TakeSmartPointer(vtkNormalMapShading::NewPackedTangents(arrays.Tangents));
      this->AppendPoints(vtkNormalMapShading::TangentAttribute, packed, 4, numPoints);
    }
    if (this->OwnTCoords)
    {
      this->AppendPoints(vtkNormalMapShading::TCoordAttribute, arrays.TCoords, 2, numPoints);
    }
    this->Appended[voffset] = arrays;
  }

  /// The components of the texture coordinates the normal texture is sampled with. Where they
  /// are the blocks' active ones (VTK's or the helper's own copy), blocks whose counts differ give
  /// the first count other than 2: a vertex buffer of either count misplaces the others' values.
  int SampledComponents()
  {
    const bool active =
      this->TCoords == vtkNormalMapShading::TCoordAttribute || this->TCoords == "tcoord";
    return active && this->BlockTCoordComponents != 2
      ? this->BlockTCoordComponents
      : this->VBOs->GetNumberOfComponents(this->TCoords.c_str());
  }

  /// Appends a block's array of an attribute, or zeros (for a block without one: they keep the
  /// attribute aligned with the vertices).
  void AppendPoints(const char* attribute,
    vtkDataArray* values,
    int components,
    vtkIdType numPoints)
  {
    vtkSmartPointer<vtkDataArray> appended = values;
    if (!appended)
    {
      auto zeros = vtkSmartPointer<vtkFloatArray>::New();
      zeros->SetNumberOfComponents(components);
      zeros->SetNumberOfTuples(numPoints);
      zeros->Fill(0.0);
      appended = zeros;
    }
    this->VBOs->AppendDataArray(attribute, appended, VTK_FLOAT);
  }

  bool GetNeedToRebuildShaders(vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* actor) override
  {
    const bool rebuild = this->Superclass::GetNeedToRebuildShaders(cellBO, ren, actor);
    const bool mapChanged = this->Shading->NeedsRebuild(
      &cellBO, actor, this->Frames.Key(), this->TCoords, this->SampledComponents());
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
    this->ForEachBlock([&](BlockData* block) { flatIndices.push_back(FlatIndexOf(*block)); });
    vtkNormalMapShading::ShaderContext context;
    context.Reporter = this->Parent;
    context.Actor = actor;
    context.DrawingVertices = this->DrawingVertices;
    context.LightComplexity = this->PrimitiveInfo[cellBO].LastLightComplexity;
    context.TCoordName = this->TCoords;
    context.TCoordComponents = this->SampledComponents();
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
          BlockNames({ FlatIndexOf(*block.first) }));
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
  void SetShaderValues(vtkShaderProgram* program, BlockData* hdata, size_t primOffset) override
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

  /// f(block) for each block this helper draws.
  template<typename F>
  void ForEachBlock(F&& f)
  {
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
    for (const auto& block : this->VTKPolyDataToGLBatchElement)
    {
      f(block.second.get());
    }
#else
    for (const auto& block : this->Data)
    {
      f(block.second);
    }
#endif
  }

  int AppliedFrame(const BlockData& block, vtkNormalMapShading::TangentUse use) const
  {
    if (!IsVisible(block))
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
  std::map<const BlockData*, vtkNormalMapShading::Tangents> BlockTangents;
  /// What a block appends besides VTK's own attributes.
  struct AppendedArrays
  {
    vtkNormalMapShading::Tangents Tangents;
    vtkDataArray* TCoords; // with OwnTCoords
    bool Same(const AppendedArrays& other) const
    {
      return SameArrays(this->Tangents, other.Tangents) && this->TCoords == other.TCoords;
    }
  };
  /// By first vertex, the arrays appended for the vertices from there, in the current build.
  std::map<vtkIdType, AppendedArrays> Appended;
  /// The attribute the normal texture is sampled with in the current build, and whether it is
  /// the helper's own (vtkNormalMapShading::SampledTCoords) and uploaded (every block has point
  /// texture coordinates of 2 components).
  std::string TCoords;
  bool OwnTCoords = false;
  /// The blocks' texture-coordinate components: 0 when a block has none, else the first count
  /// other than 2, else 2.
  int BlockTCoordComponents = 0;
  /// Whether blocks' texture coordinates have different counts of components.
  bool MixedTCoordCounts = false;
  vtkNormalMapShading::FrameMix Frames;
  /// The frame of the last surface shader built.
  int SurfaceFrame = vtkNormalMapPolyDataMapper::NOT_APPLIED;
};

vtkStandardNewMacro(vtkNormalMapCompositeMapperHelper);

#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
/// VTK's OpenGL delegator, whose batched mapper is vtkNormalMapCompositeMapperHelper.
class vtkNormalMapCompositeDelegator : public vtkOpenGLCompositePolyDataMapperDelegator
{
public:
  static vtkNormalMapCompositeDelegator* New();
  vtkTypeMacro(vtkNormalMapCompositeDelegator, vtkOpenGLCompositePolyDataMapperDelegator);

protected:
  vtkNormalMapCompositeDelegator()
  {
    // In place of the batched mapper the superclass made (released with its smart pointer).
    auto* helper = vtkNormalMapCompositeMapperHelper::New();
    this->GLDelegate = helper;
    this->Delegate = vtk::TakeSmartPointer(helper);
  }
  ~vtkNormalMapCompositeDelegator() override = default;

private:
  vtkNormalMapCompositeDelegator(const vtkNormalMapCompositeDelegator&) = delete;
  void operator=(const vtkNormalMapCompositeDelegator&) = delete;
};

vtkStandardNewMacro(vtkNormalMapCompositeDelegator);
#endif

struct vtkNormalMapCompositePolyDataMapper::Internals
{
  /// Shared by the helpers: warnings once per actor and blocks, shader keys per program.
  vtkNormalMapShading Shading;
  /// Per flat index, the frame of the last render.
  std::map<unsigned int, int> FrameOfBlock;
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

#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
//------------------------------------------------------------------------------
vtkCompositePolyDataMapperDelegator* vtkNormalMapCompositePolyDataMapper::CreateADelegator()
{
  return vtkNormalMapCompositeDelegator::New();
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::PreRender(
  const std::vector<vtkSmartPointer<vtkCompositePolyDataMapperDelegator>>& delegators,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::PreRender(delegators, ren, actor);
  for (const auto& delegator : delegators)
  {
    if (auto* ours = vtkNormalMapCompositeMapperHelper::SafeDownCast(delegator->GetDelegate()))
    {
      ours->Configure(vtkNormalMapShading::SettingsOf(this), &this->Internal->Shading);
    }
  }
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::PostRender(
  const std::vector<vtkSmartPointer<vtkCompositePolyDataMapperDelegator>>& delegators,
  vtkRenderer* ren,
  vtkActor* actor)
{
  this->Superclass::PostRender(delegators, ren, actor);
  // Each drawn block's frame, kept after the delegators are gone (released graphics resources).
  this->Internal->FrameOfBlock.clear();
  for (const auto& delegator : delegators)
  {
    if (auto* ours = vtkNormalMapCompositeMapperHelper::SafeDownCast(delegator->GetDelegate()))
    {
      ours->CollectAppliedFrames(this->Internal->FrameOfBlock);
    }
  }
}
#else
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
  this->Internal->FrameOfBlock.clear();
  for (const auto& helper : this->Helpers)
  {
    if (auto* ours = vtkNormalMapCompositeMapperHelper::SafeDownCast(helper.second))
    {
      ours->CollectAppliedFrames(this->Internal->FrameOfBlock);
    }
  }
}
#endif

//------------------------------------------------------------------------------
int vtkNormalMapCompositePolyDataMapper::GetLastAppliedFrame(unsigned int flatIndex)
{
  const auto found = this->Internal->FrameOfBlock.find(flatIndex);
  return found == this->Internal->FrameOfBlock.end() ? vtkNormalMapPolyDataMapper::NOT_APPLIED
                                                     : found->second;
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->Shading.ReleaseShaders();
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkNormalMapCompositePolyDataMapper::ShallowCopy(vtkAbstractMapper* mapper)
{
  this->Superclass::ShallowCopy(mapper);
  if (auto* other = vtkNormalMapCompositePolyDataMapper::SafeDownCast(mapper))
  {
    vtkNormalMapShading::ApplySettings(this, vtkNormalMapShading::SettingsOf(other));
  }
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
