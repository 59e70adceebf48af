// SPDX-License-Identifier: BSD-3-Clause
// The vertex buffers both mappers build hold only what the scene uses: the point tangents (and
// their signs) when a tangent-space map reads them, and VTK's own tangent attribute (tangentMC)
// only when VTK's shader reads it (PBR anisotropy), never on the derivative path or without a
// normal texture; composite blocks share vertices only with their tangents. Read back from each
// mapper's vertex buffer group after a render.
#include "NormalMapTestScenes.h"

#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
#include "vtkCompositePolyDataMapperDelegator.h"
#include "vtkOpenGLPolyDataMapper.h"
#else
// GLenum, which vtkCompositeMapperHelper2.h uses without including its declaration.
#include "vtk_glew.h"

#include "vtkColor.h" // vtkColor3d, which vtkCompositeMapperHelper2.h uses without including it
#include "vtkCompositeMapperHelper2.h"
#endif

#include "vtkActor.h"
#include "vtkFloatArray.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;

/// The composite mapper with its per-block helpers' vertex buffer groups exposed (VTK 9.3 and
/// later: its delegators' batched mappers' groups).
class CompositeMapperProbe : public vtkNormalMapCompositePolyDataMapper
{
public:
  static CompositeMapperProbe* New();
  vtkTypeMacro(CompositeMapperProbe, vtkNormalMapCompositePolyDataMapper);
#if VTK_NORMALMAPPING_BATCHED_COMPOSITE
  std::vector<vtkOpenGLVertexBufferObjectGroup*> HelperBuffers() const
  {
    return this->Buffers;
  }

protected:
  void PostRender(
    const std::vector<vtkSmartPointer<vtkCompositePolyDataMapperDelegator>>& delegators,
    vtkRenderer* ren,
    vtkActor* actor) override
  {
    this->Superclass::PostRender(delegators, ren, actor);
    this->Buffers.clear();
    for (const auto& delegator : delegators)
    {
      this->Buffers.push_back(
        vtkOpenGLPolyDataMapper::SafeDownCast(delegator->GetDelegate())->GetVBOs());
    }
  }

private:
  std::vector<vtkOpenGLVertexBufferObjectGroup*> Buffers;
#else
  std::vector<vtkOpenGLVertexBufferObjectGroup*> HelperBuffers() const
  {
    std::vector<vtkOpenGLVertexBufferObjectGroup*> groups;
    for (const auto& helper : this->Helpers)
    {
      groups.push_back(helper.second->GetVBOs());
    }
    return groups;
  }
#endif
};
vtkStandardNewMacro(CompositeMapperProbe);

/// Per attribute present, its components, its buffer's bytes per vertex and its vertices.
struct Attribute
{
  int Components = 0;
  int Stride = 0;
  unsigned int Vertices = 0;
};
using Attributes = std::map<std::string, Attribute>;

Attributes Read(vtkOpenGLVertexBufferObjectGroup* group)
{
  Attributes found;
  for (const char* name :
    { "vertexMC", "normalMC", "tcoord", "tangentMC", "nmTangentMC", "nmTangentSignMC" })
  {
    if (vtkOpenGLVertexBufferObject* vbo = group->GetVBO(name))
    {
      found[name] = { group->GetNumberOfComponents(name),
        static_cast<int>(vbo->GetStride()),
        vbo->GetNumberOfTuples() };
    }
  }
  return found;
}

std::string Describe(const Attributes& attributes)
{
  std::string text;
  for (const auto& a : attributes)
  {
    text += (text.empty() ? "" : ", ") + a.first + " " + std::to_string(a.second.Components) +
      " (" + std::to_string(a.second.Stride) + " bytes)";
  }
  return text;
}

/// What one scene must (and must not) upload, besides positions, normals and coordinates.
struct Case
{
  std::string Name;
  bool NormalTexture = true;
  int FrameSource = Mapper::AUTOMATIC;
  bool PBRAnisotropy = false;
  bool PointTangents = false; // nmTangentMC (3 floats) and nmTangentSignMC (1 float)
  bool VTKTangents = false;   // tangentMC (3 floats)
};

/// Renders a polydata or a multiblock dataset once with the case's settings; returns the vertex
/// buffer groups of the polydata mapper (or of each composite helper).
std::vector<Attributes> Render(const Case& c, vtkDataObject* input, vtkTexture* texture)
{
  const bool blocks = input->IsA("vtkMultiBlockDataSet");
  nmtest::FlatSetup setup;
  auto window = nmtest::MakeWindow(setup.Width, setup.Height);
  vtkNew<vtkRenderer> renderer;
  nmtest::AddSceneLight(renderer, setup.LightPosition);
  vtkNew<vtkActor> actor;
  vtkProperty* property = actor->GetProperty();
  if (c.NormalTexture)
  {
    property->SetNormalTexture(texture);
  }
  if (c.PBRAnisotropy)
  {
    property->SetInterpolationToPBR();
    property->SetAnisotropy(0.5);
  }
  vtkNew<Mapper> single;
  vtkNew<CompositeMapperProbe> composite;
  if (blocks)
  {
    composite->SetInputDataObject(input);
    composite->SetFrameSource(c.FrameSource);
    actor->SetMapper(composite);
  }
  else
  {
    single->SetInputDataObject(input);
    single->SetFrameSource(c.FrameSource);
    actor->SetMapper(single);
  }
  renderer->AddActor(actor);
  nmtest::SetFlatCamera(renderer, setup);
  window->AddRenderer(renderer);
  window->Render();
  nmtest::ReportRenderPath(window);
  std::vector<Attributes> groups;
  if (blocks)
  {
    for (auto* group : composite->HelperBuffers())
    {
      groups.push_back(Read(group));
    }
  }
  else
  {
    groups.push_back(Read(single->GetVBOs()));
  }
  return groups;
}

bool Has(const Attributes& a, const std::string& name, int components, int stride)
{
  const auto found = a.find(name);
  return found != a.end() && found->second.Components == components &&
    found->second.Stride == stride;
}

/**
 * Two blocks with the mesh's point, normal and texture-coordinate arrays: VTK's helper appends
 * their vertices once, unless the blocks' tangents differ (or only one has tangents); then it
 * appends them once per block, each with its block's tangents.
 */
void SharedPointArrays(nmtest::Checks& check, vtkPolyData* mesh, vtkTexture* texture)
{
  const unsigned int n = static_cast<unsigned int>(mesh->GetNumberOfPoints());
  const auto share = [mesh]()
  {
    auto block = vtkSmartPointer<vtkPolyData>::New();
    block->ShallowCopy(mesh);
    return block;
  };
  auto sameTangents = share();
  auto ownTangents = share();
  vtkNew<vtkFloatArray> copy;
  copy->DeepCopy(mesh->GetPointData()->GetTangents());
  ownTangents->GetPointData()->SetTangents(copy);
  auto noTangents = share();
  noTangents->GetPointData()->RemoveArray("Tangents");
  struct SharingCase
  {
    const char* Name;
    vtkPolyData* Second;
    unsigned int Vertices;
  };
  const SharingCase cases[] = {
    { "the same tangents: one copy of the vertices", sameTangents, n },
    { "other tangents: a copy each", ownTangents, 2 * n },
    { "no tangents in one: a copy each (zeros for that one)", noTangents, 2 * n },
  };
  for (const SharingCase& c : cases)
  {
    vtkNew<vtkMultiBlockDataSet> multiblock;
    multiblock->SetBlock(0, mesh);
    multiblock->SetBlock(1, c.Second);
    const Case pointTangents{ "point tangents", true, Mapper::AUTOMATIC, false, true, false };
    const auto groups = Render(pointTangents, multiblock, texture);
    const Attributes a = groups.empty() ? Attributes() : groups[0];
    const auto vertices = [&a](const char* name)
    { return a.count(name) ? a.at(name).Vertices : 0u; };
    std::cout << "blocks sharing point arrays, " << c.Name << ": " << groups.size()
              << " group(s), vertexMC " << vertices("vertexMC") << ", nmTangentMC "
              << vertices("nmTangentMC") << " vertices (" << n << " points)" << std::endl;
    check(groups.size() == 1 && vertices("vertexMC") == c.Vertices &&
        vertices("nmTangentMC") == c.Vertices,
      std::string("blocks sharing point arrays, ") + c.Name);
  }
}
}

int TestNormalMapVertexBuffers(int, char*[])
{
  nmtest::Checks check;
  // A mesh with what vtkPolyDataTangentFrames writes: active float Tangents and TangentSigns.
  auto mesh = nmtest::WithTangents(nmtest::MakeQuad(4));
  check(mesh->GetPointData()->GetTangents() != nullptr, "the mesh has an active Tangents array");
  auto texture = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::SineBump, 64, nmtest::Storage::OpenGL));
  const vtkMTimeType meshTime = mesh->GetMTime();

  const Case cases[] = {
    { "point tangents", true, Mapper::AUTOMATIC, false, true, false },
    { "screen derivatives", true, Mapper::SCREEN_DERIVATIVES, false, false, false },
    { "no normal texture", false, Mapper::AUTOMATIC, false, false, false },
    { "PBR anisotropy, point tangents", true, Mapper::AUTOMATIC, true, true, true },
    { "PBR anisotropy, no normal texture", false, Mapper::AUTOMATIC, true, false, true },
  };
  for (bool blocks : { false, true })
  {
    for (const Case& c : cases)
    {
      const std::string name =
        std::string(blocks ? "composite mapper, " : "polydata mapper, ") + c.Name;
      vtkNew<vtkMultiBlockDataSet> multiblock;
      multiblock->SetBlock(0, mesh);
      multiblock->SetBlock(1, nmtest::Placed(mesh, 2.5, 0.0));
      const auto groups =
        Render(c, blocks ? static_cast<vtkDataObject*>(multiblock) : mesh, texture);
      check(!groups.empty(), name + ": the mapper built vertex buffers");
      for (const Attributes& a : groups)
      {
        std::cout << name << ": " << Describe(a) << std::endl;
        // Always positions and normals (3 floats each); texture coordinates (2 floats) at
        // least when the normal texture reads them (VTK's composite helper leaves them out
        // when no texture does).
        check(Has(a, "vertexMC", 3, 12) && Has(a, "normalMC", 3, 12) &&
            (!c.NormalTexture || Has(a, "tcoord", 2, 8)),
          name + ": positions, normals and texture coordinates");
        check(c.VTKTangents ? Has(a, "tangentMC", 3, 12) : a.count("tangentMC") == 0,
          name + (c.VTKTangents ? ": VTK's tangentMC, 3 floats" : ": no tangentMC"));
        // The polydata mapper uploads the tangents and their signs as they are; the composite
        // helpers append them packed, 4 floats with the sign in w.
        const bool ours = blocks ? Has(a, "nmTangentMC", 4, 16) && a.count("nmTangentSignMC") == 0
                                 : Has(a, "nmTangentMC", 3, 12) && Has(a, "nmTangentSignMC", 1, 4);
        const bool none = a.count("nmTangentMC") == 0 && a.count("nmTangentSignMC") == 0;
        check(c.PointTangents ? ours : none,
          name + (c.PointTangents ? ": the point tangents and signs" : ": no point tangents"));
      }
    }
  }
  SharedPointArrays(check, mesh, texture);
  // The mappers hide VTK's tangents through a copy: the input itself is never modified.
  check(mesh->GetMTime() == meshTime && mesh->GetPointData()->GetTangents() != nullptr,
    "the input's Tangents attribute and modification time are untouched");
  return check.Result();
}
