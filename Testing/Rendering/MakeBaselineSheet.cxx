// SPDX-License-Identifier: BSD-3-Clause
// Not a test: the contact sheet of the image tests' baselines, each tile labelled with its test.
//   NormalMappingRenderingTests MakeBaselineSheet <baseline dir> <sheet.png>
// The build target NormalMappingBaselines runs it after rewriting the baselines.
#include "NormalMapTestScenes.h"

#include "vtkCamera.h"
#include "vtkDirectory.h"
#include "vtkImageActor.h"
#include "vtkImageData.h"
#include "vtkImageMapper3D.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const int Columns = 4, TileWidth = 320, TileHeight = 180, LabelHeight = 24;

/// Shows a PNG fit into the renderer's viewport (aspect kept, centred).
void AddTile(vtkRenderWindow* window, const double viewport[4], const std::string& file)
{
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  int d[3];
  reader->GetOutput()->GetDimensions(d);
  vtkNew<vtkImageActor> image;
  image->GetMapper()->SetInputConnection(reader->GetOutputPort());
  image->InterpolateOn();
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  renderer->SetBackground(0.3, 0.3, 0.3);
  renderer->AddActor(image);
  vtkCamera* camera = renderer->GetActiveCamera();
  const double cx = 0.5 * (d[0] - 1), cy = 0.5 * (d[1] - 1);
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(cx, cy, 0.0);
  camera->SetPosition(cx, cy, 1000.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  const double aspect = static_cast<double>(TileWidth) / TileHeight;
  camera->SetParallelScale(0.5 * std::max<double>(d[1], d[0] / aspect));
  renderer->ResetCameraClippingRange();
  window->AddRenderer(renderer);
}

void AddLabel(vtkRenderWindow* window, const double viewport[4], const std::string& text)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  renderer->SetBackground(0.12, 0.12, 0.12);
  vtkNew<vtkTextActor> label;
  label->SetInput(text.c_str());
  label->GetTextProperty()->SetFontSize(14);
  label->GetTextProperty()->SetColor(1.0, 1.0, 1.0);
  label->SetPosition(6.0, 5.0); // viewport coordinates
  renderer->AddViewProp(label);
  window->AddRenderer(renderer);
}
}

int MakeBaselineSheet(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: MakeBaselineSheet <baseline dir> <sheet.png>" << std::endl;
    return EXIT_FAILURE;
  }
  vtkNew<vtkDirectory> directory;
  if (!directory->Open(argv[1]))
  {
    std::cerr << "cannot open " << argv[1] << std::endl;
    return EXIT_FAILURE;
  }
  std::vector<std::string> names;
  for (vtkIdType i = 0; i < directory->GetNumberOfFiles(); ++i)
  {
    const std::string file = directory->GetFile(i);
    if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0)
    {
      names.push_back(file.substr(0, file.size() - 4));
    }
  }
  std::sort(names.begin(), names.end());
  const int rows = static_cast<int>((names.size() + Columns - 1) / Columns);
  const int height = rows * (TileHeight + LabelHeight);
  auto window = nmtest::MakeWindow(Columns * TileWidth, height);
  for (size_t i = 0; i < names.size(); ++i)
  {
    const double x0 = static_cast<double>(i % Columns) / Columns, x1 = x0 + 1.0 / Columns;
    const double top = 1.0 - static_cast<double>(i / Columns) / rows;
    const double labelBottom = top - static_cast<double>(LabelHeight) / height;
    const double bottom = top - 1.0 / rows;
    const double label[4] = { x0, labelBottom, x1, top };
    const double tile[4] = { x0, bottom, x1, labelBottom };
    AddLabel(window, label, names[i]);
    AddTile(window, tile, std::string(argv[1]) + "/" + names[i] + ".png");
  }
  window->Render();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(nmtest::GrabImage(window));
  writer->SetFileName(argv[2]);
  writer->Write();
  std::cout << "Wrote " << argv[2] << " (" << names.size() << " baselines)" << std::endl;
  return EXIT_SUCCESS;
}
