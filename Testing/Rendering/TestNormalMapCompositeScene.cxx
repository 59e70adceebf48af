// SPDX-License-Identifier: BSD-3-Clause
// One actor, one vtkNormalMapCompositePolyDataMapper, one Rivets map, seven blocks:
// top row, quads: float tangents + signs; mirrored with glTF-style double 4-component
// tangents; mirrored without tangents (derivatives). Bottom row: a sphere with tangents, a
// quad without texture coordinates (drawn without the map, with a warning), a sphere without
// tangents coloured blue by a block colour. A seventh block, a quad in front of everything,
// is hidden by block visibility. Every dome is lit from the upper left where the map applies.
// It fails when drawn with VTK's composite mapper (signs and named tangents ignored) or when the
// hidden block is shown.
#include "NormalMapImageTest.h"

#include "vtkActor.h"
#include "vtkCompositeDataDisplayAttributes.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkPoints.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <string>

namespace
{
/// Renders the scene and checks the frame each block is drawn with, as the comment above says.
void CheckAppliedFrames(vtkRenderWindow* window,
  vtkNormalMapCompositePolyDataMapper* mapper,
  nmtest::Checks& check)
{
  window->Render();
  using Mapper = vtkNormalMapPolyDataMapper;
  const int expected[7] = { Mapper::APPLIED_POINT_TANGENTS,
    Mapper::APPLIED_POINT_TANGENTS,
    Mapper::APPLIED_DERIVATIVES,
    Mapper::APPLIED_POINT_TANGENTS,
    Mapper::NOT_APPLIED,
    Mapper::APPLIED_DERIVATIVES,
    Mapper::NOT_APPLIED };
  for (unsigned int i = 1; i <= 7; ++i)
  {
    const int frame = mapper->GetLastAppliedFrame(i);
    check(frame == expected[i - 1],
      "block " + std::to_string(i) + ": " + Mapper::GetAppliedFrameName(frame));
  }
}
}

int TestNormalMapCompositeScene(int argc, char* argv[])
{
  using Layout = nmtest::TangentLayout;
  auto quad = nmtest::MakeQuad(4);
  auto mirrored = nmtest::MakeQuad(4, true);
  auto sphere = nmtest::MakeSphere(48);
  vtkSmartPointer<vtkPolyData> meshes[] = {
    nmtest::WithTangentLayout(
      nmtest::WithTangents(nmtest::Placed(quad, -2.3, 1.15)), Layout::NamedFloat3WithSigns),
    nmtest::WithTangentLayout(
      nmtest::WithTangents(nmtest::Placed(mirrored, 0.0, 1.15)), Layout::NamedDouble4),
    nmtest::Placed(mirrored, 2.3, 1.15),
    nmtest::WithTangentLayout(
      nmtest::WithTangents(nmtest::Placed(sphere, -2.3, -1.15)), Layout::NamedFloat3WithSigns),
    nmtest::WithoutTCoords(nmtest::Placed(quad, 0.0, -1.15)),
    nmtest::Placed(sphere, 2.3, -1.15),
    vtkSmartPointer<vtkPolyData>::New(),
  };
  // Block 7: a quad covering the whole scene, in front of it (z = 1).
  meshes[6]->DeepCopy(quad);
  for (vtkIdType p = 0; p < meshes[6]->GetNumberOfPoints(); ++p)
  {
    const double* x = meshes[6]->GetPoint(p);
    meshes[6]->GetPoints()->SetPoint(p, 4.0 * x[0], 3.0 * x[1], 1.0);
  }
  vtkNew<vtkMultiBlockDataSet> blocks;
  for (unsigned int i = 0; i < 7; ++i)
  {
    blocks->SetBlock(i, meshes[i]);
  }

  auto texture = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  vtkNew<vtkNormalMapCompositePolyDataMapper> mapper;
  nmtest::Checks check;
  const int image = nmtest::RunImageTest(argc,
    argv,
    { "VTK's composite mapper", "the hidden block shown" },
    [&](int alteration)
    {
      vtkSmartPointer<nmtest::StockCompositeMapper> used = mapper.Get();
      if (alteration == 0)
      {
        used = vtkSmartPointer<nmtest::StockCompositeMapper>::New();
      }
      used->SetInputDataObject(blocks);
      mapper->SetTangentsArrayName("TANGENT");
      vtkNew<vtkCompositeDataDisplayAttributes> attributes;
      const double blue[3] = { 0.35, 0.5, 1.0 };
      attributes->SetBlockColor(blocks->GetBlock(5), blue);
      attributes->SetBlockVisibility(blocks->GetBlock(6), alteration == 1);
      used->SetCompositeDataDisplayAttributes(attributes);

      vtkNew<vtkActor> actor;
      actor->SetMapper(used);
      vtkProperty* property = actor->GetProperty();
      property->SetNormalTexture(texture);
      property->SetColor(0.8, 0.55, 0.4);
      property->SetInterpolationToPhong();
      property->SetSpecular(0.4);
      property->SetSpecularPower(30.0);

      auto window = nmtest::MakeWindow(480, 320);
      vtkNew<vtkRenderer> renderer;
      renderer->SetBackground(0.1, 0.1, 0.12);
      nmtest::AddSceneLight(renderer, glm::dvec3(-1.0, 1.5, 2.0));
      renderer->AddActor(actor);
      nmtest::FlatSetup setup;
      setup.CameraDistance = 11.0;
      nmtest::SetFlatCamera(renderer, setup);
      window->AddRenderer(renderer);
      if (alteration < 0)
      {
        CheckAppliedFrames(window, mapper, check);
      }
      return window;
    });
  return check.Result() == EXIT_SUCCESS ? image : EXIT_FAILURE;
}
