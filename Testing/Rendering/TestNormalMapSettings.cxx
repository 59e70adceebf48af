// SPDX-License-Identifier: BSD-3-Clause
// One view per setting of the mapper. Top row: the four encodings of one bricks map on a quad
// (OpenGL, DirectX, two-channel, object space), the derivative frame on a quad without
// tangents, and the quad seen from the back with two-sided lighting (bevels still lit from the
// light's side). Bottom row: strength 0, 0.5 and 1, a torus with mirrored UVs (bricks), a
// sphere scaled (1.6, 0.6, 1) and the mirrored torus with rivets. It fails when the strength-1
// rivets are drawn at strength 0, the DirectX map is read as OpenGL, or the mirrored torus's
// tangent signs are all +1.
#include "NormalMapImageTest.h"

#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMappingMeshes.h"

int TestNormalMapSettings(int argc, char* argv[])
{
  using nmtest::Pattern;
  using nmtest::Storage;
  using Mapper = vtkNormalMapPolyDataMapper;
  auto texture = [](Pattern p, Storage s)
  { return nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(p, 256, s)); };
  auto openGL = texture(Pattern::Bricks, Storage::OpenGL);
  auto directX = texture(Pattern::Bricks, Storage::DirectX);
  auto twoChannel = texture(Pattern::Bricks, Storage::TwoChannel);
  auto rivets = texture(Pattern::Rivets, Storage::OpenGL);
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  auto bareQuad = nmtest::MakeQuad(4);
  vtkNormalMapping::TorusOptions options;
  options.U = 96;
  options.V = 48;
  options.MirrorU = true;
  auto mirroredTorus = nmtest::WithTangents(vtkNormalMapping::MakeTorus(options));
  auto ignoredTorus = nmtest::WithTangentLayout(mirroredTorus, nmtest::TangentLayout::SignsIgnored);
  auto sphere = nmtest::WithTangents(nmtest::MakeSphere(48));

  return nmtest::RunImageTest(argc,
    argv,
    { "strength 1 rivets drawn at strength 0",
      "the DirectX map read as OpenGL",
      "the mirrored torus without tangent signs" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(900, 300);
      const auto add = [&](int column, int row, const nmtest::Panel& p)
      { nmtest::AddPanel(window, 6, 2, column, row, p); };
      nmtest::Panel v;
      v.Mesh = quad;
      v.Texture = openGL;
      add(0, 0, v);
      v.Texture = directX;
      v.Encoding = alteration == 1 ? Mapper::TANGENT_SPACE_OPENGL : Mapper::TANGENT_SPACE_DIRECTX;
      add(1, 0, v);
      v.Texture = twoChannel;
      v.Encoding = Mapper::TWO_CHANNEL_OPENGL;
      add(2, 0, v);
      v.Texture = openGL; // on this quad the object-space map holds the same texels
      v.Encoding = Mapper::OBJECT_SPACE;
      add(3, 0, v);
      nmtest::Panel d;
      d.Mesh = bareQuad;
      d.Texture = openGL;
      d.FrameSource = Mapper::SCREEN_DERIVATIVES;
      add(4, 0, d);
      nmtest::Panel back;
      back.Mesh = quad;
      back.Texture = openGL;
      back.RotateY = 180.0; // the quad's back faces the camera
      add(5, 0, back);

      for (int i = 0; i < 3; ++i)
      {
        nmtest::Panel s;
        s.Mesh = quad;
        s.Texture = rivets;
        s.Strength = (i == 2 && alteration == 0) ? 0.0 : 0.5 * i;
        add(i, 1, s);
      }
      nmtest::Panel torus;
      torus.Mesh = mirroredTorus;
      torus.Texture = openGL;
      torus.RotateX = -50.0;
      add(3, 1, torus);
      nmtest::Panel scaled;
      scaled.Mesh = sphere;
      scaled.Texture = rivets;
      scaled.Scale[0] = 1.6;
      scaled.Scale[1] = 0.6;
      scaled.RotateX = -60.0;
      add(4, 1, scaled);
      torus.Mesh = alteration == 2 ? ignoredTorus.Get() : mirroredTorus.Get();
      torus.Texture = rivets;
      add(5, 1, torus);
      return window;
    });
}
