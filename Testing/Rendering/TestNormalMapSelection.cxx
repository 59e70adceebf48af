// SPDX-License-Identifier: BSD-3-Clause
// Hardware selection (ParaView's cell, point and block selection, and vtkRenderer::PickProp)
// renders through the mappers with VTK's picking shader code: the normal map must leave it
// alone, so the mappers select exactly what VTK's own mappers select in the same scene.
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAssemblyPath.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"

#include <iostream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;
/// One selected element: the index of its actor in the renderer, its block's flat index (0 for a
/// polydata), its cell or point id.
using Selected = std::tuple<int, unsigned int, vtkIdType>;

/// Counts the errors and warnings an object reports.
struct MessageCounter
{
  int Count = 0;
  void Watch(vtkObject* object)
  {
    for (unsigned long event : { vtkCommand::ErrorEvent, vtkCommand::WarningEvent })
    {
      object->AddObserver(event, this, &MessageCounter::OnMessage);
    }
  }
  void OnMessage(vtkObject*, unsigned long, void* text)
  {
    ++this->Count;
    std::cout << "message: " << static_cast<const char*>(text) << std::endl;
  }
};

/// What a hardware selection of the whole window finds, for cells or points.
std::set<Selected> SelectAll(vtkRenderWindow* window, int association, MessageCounter& messages)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  std::vector<vtkProp*> actors;
  vtkActorCollection* collection = renderer->GetActors();
  collection->InitTraversal();
  while (vtkActor* actor = collection->GetNextActor())
  {
    actors.push_back(actor);
    messages.Watch(actor->GetMapper());
  }
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(renderer);
  const int* size = window->GetSize();
  selector->SetArea(0, 0, size[0] - 1, size[1] - 1);
  selector->SetFieldAssociation(association);
  auto selection = vtk::TakeSmartPointer(selector->Select());
  std::set<Selected> found;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    vtkInformation* properties = node->GetProperties();
    const auto prop = vtkProp::SafeDownCast(properties->Get(vtkSelectionNode::PROP()));
    const int actor =
      static_cast<int>(std::find(actors.begin(), actors.end(), prop) - actors.begin());
    const unsigned int block = properties->Has(vtkSelectionNode::COMPOSITE_INDEX())
      ? static_cast<unsigned int>(properties->Get(vtkSelectionNode::COMPOSITE_INDEX()))
      : 0u;
    vtkIdTypeArray* ids = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    for (vtkIdType i = 0; ids && i < ids->GetNumberOfTuples(); ++i)
    {
      found.emplace(actor, block, ids->GetValue(i));
    }
  }
  return found;
}

/// The actor vtkRenderer::PickProp finds where the world point (x, y, 0) shows, as its index in
/// the renderer (-1: none).
int PickedAt(vtkRenderWindow* window, double x, double y)
{
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  renderer->SetWorldPoint(x, y, 0.0, 1.0);
  renderer->WorldToDisplay();
  const double* display = renderer->GetDisplayPoint();
  vtkAssemblyPath* path = renderer->PickProp(display[0], display[1]);
  if (!path)
  {
    return -1;
  }
  vtkProp* picked = path->GetFirstNode()->GetViewProp();
  vtkActorCollection* collection = renderer->GetActors();
  collection->InitTraversal();
  for (int i = 0; vtkActor* actor = collection->GetNextActor(); ++i)
  {
    if (actor == picked)
    {
      return i;
    }
  }
  return -1;
}
}

int TestNormalMapSelection(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  // Meshes that take each path of the shaders: point tangents (a sphere, and a quad with mirrored
  // texture coordinates), derivatives (no tangents), the mappers' own texture coordinates (point
  // scalars interpolated before mapping), and, with edges shown, VTK's geometry shader.
  auto sphere = nmtest::Placed(nmtest::WithTangents(nmtest::MakeSphere(24)), -0.9, 0.6);
  auto mirrored = nmtest::Placed(nmtest::WithTangents(nmtest::MakeQuad(8, true)), 0.8, 0.6, 0.5);
  auto bare = nmtest::Placed(nmtest::MakeQuad(6), -0.9, -0.8, 0.5);
  auto colored = vtkSmartPointer<vtkPolyData>::New();
  colored->ShallowCopy(nmtest::Placed(nmtest::WithTangents(nmtest::MakeQuad(5)), 0.8, -0.8, 0.5));
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Value");
  scalars->SetNumberOfTuples(colored->GetNumberOfPoints());
  for (vtkIdType p = 0; p < colored->GetNumberOfPoints(); ++p)
  {
    scalars->SetValue(p, static_cast<float>(p % 7) / 6.0f);
  }
  colored->GetPointData()->SetScalars(scalars);
  vtkPolyData* meshes[] = { sphere, mirrored, bare, colored };
  vtkNew<vtkMultiBlockDataSet> blocks;
  for (unsigned int b = 0; b < 4; ++b)
  {
    blocks->SetBlock(b, meshes[b]);
  }

  // The four meshes as four actors, or as the blocks of one composite actor, rendered once. Each
  // window has a texture of its own: in VTK 9.1 a vtkTexture that another window has loaded since
  // samples wrong, with VTK's own mappers too.
  const auto scene = [&](bool stock, bool composite, bool edges)
  {
    auto texture = nmtest::MakeNormalTexture(
      nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 128, nmtest::Storage::OpenGL));
    std::vector<nmtest::FlatActor> actors;
    for (vtkPolyData* mesh : meshes)
    {
      nmtest::FlatActor a;
      a.Mesh = mesh;
      a.Blocks = composite ? blocks.Get() : nullptr;
      a.StockMapper = stock;
      a.NormalTexture = texture;
      a.InterpolateScalars = true;
      a.EdgeVisibility = edges;
      actors.push_back(a);
      if (composite)
      {
        break;
      }
    }
    auto window = nmtest::MakeFlatScene(setup, actors);
    window->Render();
    nmtest::ReportRenderPath(window);
    return window;
  };
  for (bool composite : { false, true })
  {
    for (bool edges : { false, true })
    {
      const std::string what = std::string(composite ? "composite mapper" : "single mappers") +
        (edges ? ", edges shown" : "");
      auto ours = scene(false, composite, edges);
      auto theirs = scene(true, composite, edges);
      const auto before = nmtest::ReadPixels(ours);
      MessageCounter messages;
      for (int association :
        { vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataObject::FIELD_ASSOCIATION_POINTS })
      {
        const std::string kind =
          association == vtkDataObject::FIELD_ASSOCIATION_CELLS ? "cells" : "points";
        const auto mine = SelectAll(ours, association, messages);
        const auto reference = SelectAll(theirs, association, messages);
        std::set<int> actorsFound;
        std::set<unsigned int> blocksFound;
        for (const Selected& s : mine)
        {
          actorsFound.insert(std::get<0>(s));
          blocksFound.insert(std::get<1>(s));
        }
        std::cout << what << ", " << kind << ": " << mine.size() << " selected ("
                  << reference.size() << " by VTK's mappers), " << actorsFound.size() << " actors, "
                  << blocksFound.size() << " blocks" << std::endl;
        // Every mesh shows, so each is found, with the ids VTK's mappers find.
        check(mine == reference, what + ": the " + kind + " VTK's mappers select");
        check(composite ? blocksFound.size() == 4 : actorsFound.size() == 4,
          what + ": " + kind + " of every mesh");
      }
      check(messages.Count == 0, what + ": no errors or warnings while selecting");

      // The sphere's centre: the first actor, or the composite one.
      const int picked = PickedAt(ours, -0.9, 0.6);
      std::cout << what << ": PickProp at the sphere finds actor " << picked << std::endl;
      check(picked == PickedAt(theirs, -0.9, 0.6) && picked == 0,
        what + ": PickProp finds the actor VTK's mappers' scene gives");

      // The selection's shaders do not stay: the scene renders as before it, map included.
      const auto after =
        nmtest::Compare(nmtest::ReadPixels(ours), before, nmtest::CoveredPixels(before, before), 0);
      std::cout << what << ": rendered after selecting, " << 100.0 * after.WithinFraction
                << "% of the pixels as before" << std::endl;
      check(after.WithinFraction == 1.0, what + ": the image after selecting is the one before");
    }
  }
  return check.Result();
}
