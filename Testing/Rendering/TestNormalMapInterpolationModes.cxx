// SPDX-License-Identifier: BSD-3-Clause
// Image test: one rivets-mapped sphere in Flat, Gouraud, Phong and PBR interpolation, left to
// right; each shows the domes (VTK lights every model per fragment). It fails when any one of
// the four draws without the map.
#include "NormalMapImageTest.h"

#include "vtkProperty.h"

int TestNormalMapInterpolationModes(int argc, char* argv[])
{
  auto map = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  auto sphere = nmtest::WithTangents(nmtest::MakeSphere(48));
  const int models[4] = { VTK_FLAT, VTK_GOURAUD, VTK_PHONG, VTK_PBR };
  return nmtest::RunImageTest(argc,
    argv,
    { "Flat without the map",
      "Gouraud without the map",
      "Phong without the map",
      "PBR without the map" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(600, 150);
      for (int i = 0; i < 4; ++i)
      {
        nmtest::Panel p;
        p.Mesh = sphere;
        p.Texture = alteration == i ? nullptr : map.Get();
        p.Interpolation = models[i];
        p.RotateX = -60.0;
        nmtest::AddPanel(window, 4, 1, i, 0, p);
      }
      return window;
    });
}
