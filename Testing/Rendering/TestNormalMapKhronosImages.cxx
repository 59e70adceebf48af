// SPDX-License-Identifier: BSD-3-Clause
// Image test: the Khronos NormalTangentTest (left) and NormalTangentMirrorTest (right) models
// (glTF sample models by Ed Mackey, (c) 2017-2018 Analytical Graphics, Inc., CC-BY 4.0; read
// from ../shared/data/gltf) with MikkTSpace tangents and signs: in each row of their grids the
// normal-mapped cells look like the real-geometry cell on their left. It fails when the map's
// green is read in the other convention or the tangent signs are all +1 (the mirror model's
// mirrored cells lit from below). Skipped (125) when the shared data is absent.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"

#include <cstdlib>
#include <iostream>

int TestNormalMapKhronosImages(int argc, char* argv[])
{
  using Mapper = vtkNormalMapPolyDataMapper;
  vtkSmartPointer<vtkPolyData> models[2], ignoredModels[2];
  vtkSmartPointer<vtkTexture> maps[2];
  int m = 0;
  for (const std::string name : { "NormalTangentTest", "NormalTangentMirrorTest" })
  {
    const std::string folder = nmtest::KhronosModelFolder(name);
    if (folder.empty())
    {
      return 125;
    }
    const std::string file = folder + name + ".gltf";
    models[m] = nmtest::LoadKhronosModel(file);
    if (!models[m])
    {
      std::cout << "Could not read " << file << std::endl;
      return EXIT_FAILURE;
    }
    ignoredModels[m] = nmtest::WithTangentLayout(models[m], nmtest::TangentLayout::SignsIgnored);
    maps[m] = nmtest::LoadKhronosNormalMap(folder + name + "_Normal.png");
    ++m;
  }
  return nmtest::RunImageTest(argc,
    argv,
    { "the other green convention", "the tangent signs all +1" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(800, 400);
      for (int i = 0; i < 2; ++i)
      {
        const double viewport[4] = { 0.5 * i, 0.0, 0.5 * (i + 1), 1.0 };
        nmtest::AddKhronosView(window,
          viewport,
          alteration == 1 ? ignoredModels[i] : models[i],
          maps[i],
          alteration == 0 ? Mapper::TANGENT_SPACE_DIRECTX : Mapper::TANGENT_SPACE_OPENGL);
      }
      return window;
    });
}
