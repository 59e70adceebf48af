// SPDX-License-Identifier: BSD-3-Clause
// Image test: a quad with rivets under actor scale (1, 0.35, 1) and a sphere under
// (1.6, 0.6, 1): the perturbed normals transform like those of the displaced geometry, so the
// squashed domes are steeper across their short axis. It fails when the scene is drawn with
// VTK 9.1's mapper, which keeps the unscaled slopes.
#include "NormalMapImageTest.h"

int TestNormalMapNonUniformScale(int argc, char* argv[])
{
  auto map = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  auto sphere = nmtest::WithTangents(nmtest::MakeSphere(48));
  return nmtest::RunImageTest(argc,
    argv,
    { "VTK's mapper" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(400, 200);
      nmtest::Panel p;
      p.Mesh = quad;
      p.Texture = map;
      p.StockMapper = alteration == 0;
      p.Scale[1] = 0.35;
      nmtest::AddPanel(window, 2, 1, 0, 0, p);
      p.Mesh = sphere;
      p.Scale[0] = 1.6;
      p.Scale[1] = 0.6;
      p.RotateX = -60.0;
      nmtest::AddPanel(window, 2, 1, 1, 0, p);
      return window;
    });
}
