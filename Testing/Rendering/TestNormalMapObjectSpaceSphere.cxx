// SPDX-License-Identifier: BSD-3-Clause
// Image test: an object-space map of rivets on a sphere without tangents, turned by the actor
// (rotations about x and y), so the map's normals go through a frame that changes over the
// surface and through the actor's rotation. Every dome is lit from the upper left, as with a
// tangent-space map. It fails when the map is read as tangent space or dropped.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"

int TestNormalMapObjectSpaceSphere(int argc, char* argv[])
{
  using Mapper = vtkNormalMapPolyDataMapper;
  auto map =
    nmtest::MakeNormalTexture(nmtest::MakeObjectSpaceSphereMap(nmtest::Pattern::Rivets, 256));
  auto sphere = nmtest::MakeSphere(48);
  return nmtest::RunImageTest(argc,
    argv,
    { "read as a tangent-space map", "the map dropped" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(400, 200);
      nmtest::Panel p;
      p.Mesh = sphere;
      p.Texture = alteration == 1 ? nullptr : map.Get();
      p.Encoding = alteration == 0 ? Mapper::TANGENT_SPACE_OPENGL : Mapper::OBJECT_SPACE;
      p.RotateX = -60.0;
      nmtest::AddPanel(window, 2, 1, 0, 0, p);
      p.RotateY = 70.0;
      nmtest::AddPanel(window, 2, 1, 1, 0, p);
      return window;
    });
}
