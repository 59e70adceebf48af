// SPDX-License-Identifier: BSD-3-Clause
// VTK's glTF importer with vtkNormalMapObjectFactory installed: the importer makes its mappers
// through vtkPolyDataMapper::New(), so the scene is drawn by ours, with the importer's own
// materials and textures. VTK's glTF loader keeps three of TANGENT's four components, so the
// tangents arrive without their signs; in each row of the Khronos test models' grids the
// normal-mapped cells must still look like the real-geometry cell. Without the factory (VTK's
// mapper) the mirror model's mirrored cells do not. Skipped (125) when the shared data is
// absent.
#include "NormalMapImageTest.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkGLTFImporter.h"
#include "vtkMapper.h"
#include "vtkNew.h"
#include "vtkNormalMapObjectFactory.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <iostream>
#include <string>

namespace
{
/**
 * The importer's scene of `file`, only its normal-mapped actors shown, head-on with a parallel
 * camera on the left half of the first of them (the mirror model's front grid) and one scene
 * light from the upper left (nmtest::SetKhronosViewpoint). That actor's mapper class goes to
 * `mapperClass`, and, for our mapper, the frame it applied to `appliedFrame`.
 */
std::vector<unsigned char> RenderImported(const std::string& file,
  int size,
  std::string& mapperClass,
  int& appliedFrame)
{
  auto window = nmtest::MakeWindow(size, size);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkGLTFImporter> importer;
  importer->SetFileName(file.c_str());
  importer->SetRenderWindow(window);
  importer->Update();
  renderer->RemoveAllLights();
  renderer->AutomaticLightCreationOff();
  double bounds[6] = { 1.0, -1.0, 1.0, -1.0, 1.0, -1.0 };
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    const bool mapped = actor->GetProperty()->GetTexture("normalTex") != nullptr;
    actor->SetVisibility(mapped);
    if (mapped && mapperClass.empty())
    {
      mapperClass = actor->GetMapper()->GetClassName();
      actor->GetBounds(bounds);
    }
  }
  // The left half of the model: its front grid (the right half is the grid's back, unlit).
  bounds[1] = 0.5 * (bounds[0] + bounds[1]);
  nmtest::SetKhronosViewpoint(renderer, bounds);
  window->Render();
  nmtest::ReportRenderPath(window);
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    if (auto* ours = vtkNormalMapPolyDataMapper::SafeDownCast(actor->GetMapper()))
    {
      appliedFrame = actor->GetVisibility() ? ours->GetLastAppliedFrame() : appliedFrame;
    }
  }
  return nmtest::ReadPixels(window);
}
}

int TestNormalMapGLTFImporter(int, char*[])
{
  nmtest::Checks check;
  for (const char* name : { "NormalTangentTest", "NormalTangentMirrorTest" })
  {
    const std::string folder = nmtest::KhronosModelFolder(name);
    if (folder.empty())
    {
      return 125;
    }
    const std::string file = folder + name + ".gltf";
    const int size = 512;
    const int bound = 12; // TestNormalMapKhronosModels' bound, for the same reasons
    for (bool factory : { true, false })
    {
      if (factory)
      {
        vtkNormalMapObjectFactory::Install();
      }
      std::string mapperClass;
      int applied = -1;
      const auto pixels = RenderImported(file, size, mapperClass, applied);
      if (factory)
      {
        vtkNormalMapObjectFactory::Uninstall();
      }
      int cells = 0;
      const double worst = nmtest::WorstCell(pixels, size, bound, cells);
      const std::string what = std::string(name) + (factory ? ", our mapper" : ", VTK's mapper");
      std::cout << what << " (" << mapperClass
                << (factory ? std::string(", frame ") +
                         vtkNormalMapPolyDataMapper::GetAppliedFrameName(applied)
                            : std::string())
                << "): " << cells << " normal-mapped cells, worst " << 100.0 * worst
                << "% of its pixels within " << bound << " levels of its geometry cell"
                << std::endl;
      // The normal-mapped cells in this framing: 10 of NormalTangentTest, 15 of the mirror
      // model's front grid (5 rows).
      check(cells >= 10, what + ": the grid's cells were found");
      if (factory)
      {
        check(mapperClass == "vtkNormalMapPolyDataMapper" &&
            applied == vtkNormalMapPolyDataMapper::APPLIED_UNSIGNED_TANGENTS,
          what + ": the importer's mapper is ours, with the tangents it read, unsigned");
        check(worst >= 0.9, what + ": every normal-mapped cell looks like its geometry");
      }
      else if (std::string(name) == "NormalTangentMirrorTest")
      {
        check(worst < 0.9, what + ": fails the comparison (control)");
      }
    }
  }
  return check.Result();
}
