// SPDX-License-Identifier: BSD-3-Clause
// The Khronos NormalTangentTest and NormalTangentMirrorTest models (glTF sample models by Ed
// Mackey, (c) 2017-2018 Analytical Graphics, Inc., CC-BY 4.0; read from ../shared/data/gltf
// with VTK's glTF reader). In each row of their test grid the left cell is real geometry and
// the right one a flat quad with the normal map: with right tangents and right shading both
// look alike. Tangents come from vtkPolyDataTangentFrames (MikkTSpace), whose signs the mirrored
// model's right half needs.
#include "NormalMapImageTest.h"

#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkTestUtilities.h"

#include <algorithm>
#include <iostream>

namespace
{
std::vector<unsigned char> Render(vtkPolyData* model,
  vtkTexture* normalMap,
  int size,
  const char* picture,
  int encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL)
{
  auto window = nmtest::MakeWindow(size, size);
  const double whole[4] = { 0.0, 0.0, 1.0, 1.0 };
  nmtest::AddKhronosView(window, whole, model, normalMap, encoding);
  window->Render();
  if (picture)
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(nmtest::GrabImage(window));
    writer->SetFileName(picture);
    writer->Write();
  }
  return nmtest::ReadPixels(window);
}

}

int TestNormalMapKhronosModels(int argc, char* argv[])
{
  nmtest::Checks check;
  // The renders are also written to the test's temporary folder (-T, as ctest passes it), to be
  // looked at.
  char* temporary = vtkTestUtilities::GetArgOrEnvOrDefault("-T", argc, argv, "VTK_TEMP_DIR", "");
  const std::string folder = temporary;
  delete[] temporary;
  for (const char* name : { "NormalTangentTest", "NormalTangentMirrorTest" })
  {
    const std::string dir = nmtest::KhronosModelFolder(name);
    if (dir.empty())
    {
      return 125;
    }
    auto model = nmtest::LoadKhronosModel(dir + name + ".gltf");
    check(model != nullptr, std::string(name) + ": read");
    auto texture = nmtest::LoadKhronosNormalMap(dir + name + "_Normal.png");
    const std::string picture = folder + "/" + name + ".png";
    const int size = 512;
    // A cell is 53-70 pixels wide; the real hemisphere and the mapped one differ at its rim
    // (a geometric silhouette against texels) and by the map's 8 bits: measured worst cells
    // 95.5% (NormalTangentTest) and 93.5% (mirror test) within 12 levels; the wrong green
    // convention gives about 60%. Bound: 90% of every cell within 12 levels.
    const int bound = 12;
    int cells = 0;
    const double worst = nmtest::WorstCell(
      Render(model, texture, size, folder.empty() ? nullptr : picture.c_str()), size, bound, cells);
    std::cout << name << ": " << cells << " normal-mapped cells, worst " << 100.0 * worst
              << "% of its pixels within " << bound << " levels of its geometry cell" << std::endl;
    check(cells >= 15, std::string(name) + ": the grid's cells were found");
    check(worst >= 0.9, std::string(name) + ": every normal-mapped cell looks like its geometry");
    // The same tangents without their signs, as VTK's glTF reader and importer give TANGENT
    // (they drop w): each triangle's handedness comes from its texture coordinates, and every
    // cell still looks like its geometry, within the same bound.
    int unsignedCells = 0;
    const double unsignedWorst = nmtest::WorstCell(
      Render(
        nmtest::WithTangentLayout(model, nmtest::TangentLayout::Unsigned), texture, size, nullptr),
      size,
      bound,
      unsignedCells);
    std::cout << name << " with unsigned tangents: worst cell " << 100.0 * unsignedWorst << "%"
              << std::endl;
    check(unsignedCells == cells && unsignedWorst >= 0.9,
      std::string(name) + ": unsigned tangents: every normal-mapped cell looks like its geometry");
    // Control: the map read with the wrong green convention lights the mapped cells from below.
    int controlCells = 0;
    const double control = nmtest::WorstCell(
      Render(model, texture, size, nullptr, vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX),
      size,
      bound,
      controlCells);
    std::cout << name << " with the wrong green convention (control): worst cell "
              << 100.0 * control << "%" << std::endl;
    check(control < 0.9, std::string(name) + ": the control fails the comparison");
  }
  return check.Result();
}
