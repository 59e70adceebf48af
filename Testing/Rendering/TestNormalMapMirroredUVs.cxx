// SPDX-License-Identifier: BSD-3-Clause
// Image test: a quad with rivets (u along +x) next to its mirror image (u along -x), both with
// point tangents and their signs, under a light on the mirror plane: the picture is symmetric
// and every dome is lit from above. It fails when the signs are all +1 (the mirrored quad's
// domes lit from the other side) or the green is read in the other convention.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"

int TestNormalMapMirroredUVs(int argc, char* argv[])
{
  using Layout = nmtest::TangentLayout;
  const nmtest::MirrorScene scene = nmtest::MakeMirrorScene();
  auto ignoredRight = nmtest::WithTangentLayout(scene.Right, Layout::SignsIgnored);
  return nmtest::RunImageTest(argc,
    argv,
    { "the tangent signs all +1", "the other green convention" },
    [&](int alteration)
    {
      nmtest::FlatActor left, right;
      left.Mesh = scene.Left;
      right.Mesh = alteration == 0 ? ignoredRight.Get() : scene.Right.Get();
      left.NormalTexture = right.NormalTexture = scene.Texture;
      left.Encoding = right.Encoding = alteration == 1
        ? vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX
        : vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
      return nmtest::MakeFlatScene(scene.Setup, { left, right });
    });
}
