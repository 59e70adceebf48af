// SPDX-License-Identifier: BSD-3-Clause
// Image test: a rivets-mapped quad at strength (vtkProperty::NormalScale) 0, 0.5 and 1, left to
// right: flat, shallow domes, full domes. It fails when any one of them is drawn at another of
// these strengths (VTK's default comparison passes strength 1 drawn as 0 with an error of 0).
#include "NormalMapImageTest.h"

int TestNormalMapStrength(int argc, char* argv[])
{
  auto map = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  const double strengths[3] = { 0.0, 0.5, 1.0 };
  const double altered[3] = { 0.5, 1.0, 0.0 }; // what alteration i draws view i at
  return nmtest::RunImageTest(argc,
    argv,
    { "strength 0 drawn as 0.5", "strength 0.5 drawn as 1", "strength 1 drawn as 0" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(450, 150);
      for (int i = 0; i < 3; ++i)
      {
        nmtest::Panel p;
        p.Mesh = quad;
        p.Texture = map;
        p.Strength = alteration == i ? altered[i] : strengths[i];
        nmtest::AddPanel(window, 3, 1, i, 0, p);
      }
      return window;
    });
}
