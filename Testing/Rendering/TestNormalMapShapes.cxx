// Plane (bricks), sphere (rivets) and torus (sine bump), each with tangents from
// vtkPolyDataTangentFrames, in Phong (top row) and PBR (bottom row).
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"

int TestNormalMapShapes(int argc, char* argv[])
{
  vtkNormalMapping::TorusOptions torusOptions;
  torusOptions.U = 96;
  torusOptions.V = 48;
  vtkSmartPointer<vtkPolyData> meshes[3] = { nmtest::WithTangents(nmtest::MakeQuad(8)),
    nmtest::WithTangents(nmtest::MakeSphere(48)),
    nmtest::WithTangents(vtkNormalMapping::MakeTorus(torusOptions)) };
  const nmtest::Pattern patterns[3] = {
    nmtest::Pattern::Bricks, nmtest::Pattern::Rivets, nmtest::Pattern::SineBump
  };

  auto window = nmtest::MakeWindow(600, 400);
  for (int row = 0; row < 2; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      vtkNew<vtkRenderer> renderer;
      renderer->SetViewport(column / 3.0, (1 - row) / 2.0, (column + 1) / 3.0, (2 - row) / 2.0);
      renderer->SetBackground(0.1, 0.1, 0.12);
      nmtest::AddSceneLight(renderer, glm::dvec3(-1.0, 1.5, 2.0));

      vtkNew<vtkNormalMapPolyDataMapper> mapper;
      mapper->SetInputData(meshes[column]);
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      auto texture = nmtest::MakeNormalTexture(
        nmtest::MakeNormalMapImage(patterns[column], 256, nmtest::Storage::OpenGL));
      actor->GetProperty()->SetNormalTexture(texture);
      actor->GetProperty()->SetColor(0.8, 0.55, 0.4);
      if (row == 0)
      {
        actor->GetProperty()->SetInterpolationToPhong();
        actor->GetProperty()->SetSpecular(0.4);
        actor->GetProperty()->SetSpecularPower(30.0);
      }
      else
      {
        actor->GetProperty()->SetInterpolationToPBR();
        actor->GetProperty()->SetRoughness(0.4);
        actor->GetProperty()->SetMetallic(0.1);
      }
      if (column == 1)
      {
        actor->RotateX(-60.0);
      }
      if (column == 2)
      {
        actor->RotateX(-50.0);
      }
      renderer->AddActor(actor);
      renderer->ResetCamera();
      renderer->GetActiveCamera()->Zoom(1.3);
      window->AddRenderer(renderer);
    }
  }
  window->Render();
  nmtest::ReportRenderPath(window);

  return nmtest::CompareWithBaseline(window, argc, argv);
}
