// SPDX-License-Identifier: BSD-3-Clause
// Not a test: writes the README's mapper pictures into the directory given as argument.
//   NormalMappingRenderingTests MakeDocPictures <dir>
// VTK's stock mapper (left) and vtkNormalMapPolyDataMapper (right), same data, same tangents
// (from vtkPolyDataTangentFrames), on mirrored UVs and under non-uniform scale; and the
// settings baseline is copied as docs/mapper-settings.png by hand.
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCoordinate.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPNGWriter.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

#include <iostream>
#include <vector>

namespace
{
void Side(vtkRenderWindow* window,
  int side,
  const std::vector<vtkPolyData*>& meshes,
  vtkTexture* texture,
  const double scale[3],
  double rotateX,
  const char* label)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(side * 0.5, 0.0, side * 0.5 + 0.5, 1.0);
  renderer->SetBackground(0.1, 0.1, 0.12);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(0.0, 1.5, 2.0);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->AddLight(light);
  for (vtkPolyData* mesh : meshes)
  {
    vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
    if (side == 0)
    {
      mapper = vtkSmartPointer<vtkOpenGLPolyDataMapper>::New();
    }
    else
    {
      mapper = vtkSmartPointer<vtkNormalMapPolyDataMapper>::New();
    }
    mapper->SetInputData(mesh);
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetScale(scale[0], scale[1], scale[2]);
    actor->RotateX(rotateX);
    actor->GetProperty()->SetNormalTexture(texture);
    actor->GetProperty()->SetColor(0.8, 0.55, 0.4);
    actor->GetProperty()->SetSpecular(0.4);
    actor->GetProperty()->SetSpecularPower(30.0);
    actor->GetProperty()->SetInterpolationToPhong();
    renderer->AddActor(actor);
  }
  vtkNew<vtkTextActor> text;
  text->SetInput(label);
  text->GetTextProperty()->SetFontSize(16);
  text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  text->SetPosition(0.03, 0.04);
  renderer->AddViewProp(text);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  window->AddRenderer(renderer);
}

void Write(vtkRenderWindow* window, const std::string& path)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(path.c_str());
  writer->Write();
  std::cout << "wrote " << path << std::endl;
}
}

int MakeDocPictures(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: NormalMappingRenderingTests MakeDocPictures <output directory>\n";
    return EXIT_FAILURE;
  }
  const std::string dir = argv[1];
  using nmtest::Pattern;
  using nmtest::Storage;
  auto bricks =
    nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(Pattern::Bricks, 256, Storage::OpenGL));

  auto rivets =
    nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(Pattern::Rivets, 256, Storage::OpenGL));
  // A quad (u along +x) and its mirror image (u along -x), the light above the mirror plane.
  auto left = nmtest::WithTangents(nmtest::MakeQuad(4, false));
  auto right = nmtest::WithTangents(nmtest::MakeQuad(4, true));
  for (vtkPolyData* q : { left.GetPointer(), right.GetPointer() })
  {
    vtkPoints* points = q->GetPoints();
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      p[0] += q == left.GetPointer() ? -1.02 : 1.02;
      points->SetPoint(i, p);
    }
  }
  const double one[3] = { 1.0, 1.0, 1.0 };
  auto mirrored = nmtest::MakeWindow(800, 260);
  Side(mirrored, 0, { left, right }, rivets, one, 0.0, "VTK 9.1 mapper: right half lit from below");
  Side(mirrored, 1, { left, right }, rivets, one, 0.0, "vtkNormalMapPolyDataMapper");
  Write(mirrored, dir + "/mapper-mirrored-uvs.png");

  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  const double squash[3] = { 1.0, 0.35, 1.0 };
  auto scaled = nmtest::MakeWindow(800, 300);
  Side(scaled, 0, { quad }, bricks, squash, 0.0, "VTK 9.1 mapper, scale (1, 0.35, 1)");
  Side(scaled, 1, { quad }, bricks, squash, 0.0, "ours: bevels as steep as the squashed geometry");
  Write(scaled, dir + "/mapper-nonuniform-scale.png");
  return EXIT_SUCCESS;
}
