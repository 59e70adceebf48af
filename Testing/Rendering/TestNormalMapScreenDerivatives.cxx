// SPDX-License-Identifier: BSD-3-Clause
// Image test: a torus with mirrored texture coordinates (the two halves use the texture
// mirrored) and no tangents: the frame comes from screen-space derivatives, which follow the
// mirroring by themselves, so every dome on both halves is lit from the light's side. It fails
// when the frame ignores the mirroring (point tangents with signs all +1: the mirrored half
// inverted) or the green is read in the other convention.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"

int TestNormalMapScreenDerivatives(int argc, char* argv[])
{
  using Mapper = vtkNormalMapPolyDataMapper;
  auto map = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  vtkNormalMapping::TorusOptions options;
  options.U = 96;
  options.V = 48;
  options.MirrorU = true;
  auto torus = vtkNormalMapping::MakeTorus(options);
  auto ignoredTorus =
    nmtest::WithTangentLayout(nmtest::WithTangents(torus), nmtest::TangentLayout::SignsIgnored);
  return nmtest::RunImageTest(argc,
    argv,
    { "point tangents with signs all +1", "the other green convention" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(300, 300);
      nmtest::Panel p;
      p.Mesh = alteration == 0 ? ignoredTorus.Get() : torus.Get();
      p.Texture = map;
      p.FrameSource = alteration == 0 ? Mapper::POINT_TANGENTS : Mapper::SCREEN_DERIVATIVES;
      p.Encoding = alteration == 1 ? Mapper::TANGENT_SPACE_DIRECTX : Mapper::TANGENT_SPACE_OPENGL;
      p.RotateX = -50.0;
      nmtest::AddPanel(window, 1, 1, 0, 0, p);
      return window;
    });
}
