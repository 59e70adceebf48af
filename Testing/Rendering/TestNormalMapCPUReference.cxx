// SPDX-License-Identifier: BSD-3-Clause
// The rendered pixels of a normal-mapped flat quad against the same shading computed on the
// CPU in double precision from the analytic normals of the map's height field.
#include "NormalMapTestScenes.h"

#include "vtkNormalMapPolyDataMapper.h"

#include <cmath>
#include <iostream>

int TestNormalMapCPUReference(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  const auto pattern = nmtest::Pattern::SineBump;
  // 128 texels over ~190 pixels: the map is magnified, so texture filtering is bilinear
  // interpolation of a smooth field (43 texels per period: relative error ~ (2 pi / 43)^2 / 8,
  // 0.3%), not a mipmap average the CPU would have to imitate.
  auto texture =
    nmtest::MakeNormalTexture(nmtest::MakeNormalMapImage(pattern, 128, nmtest::Storage::OpenGL));
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(1));

  // Error budget per channel, in 8-bit levels: the map's 8-bit quantization (half a level per
  // component, ~0.004 rad of normal, under 1 level of colour at these slopes), the
  // interpolation above (well under 1 level), float arithmetic in the shader (far under 1),
  // and the final rounding to 8 bits (half a level). 3 levels leaves room for the sum; 99.5%
  // of the pixels, because specular highlights amplify normal error by the exponent (20).
  const int bound = 3;
  const double share = 0.995;
  struct Case
  {
    const char* Name;
    int FrameSource;
    bool Stock;
  };
  const Case cases[] = {
    { "ours, point tangents", vtkNormalMapPolyDataMapper::POINT_TANGENTS, false },
    { "ours, screen-space derivatives", vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES, false },
    { "VTK's stock mapper (tangents, unmirrored)", 0, true },
  };
  for (const Case& c : cases)
  {
    nmtest::FlatActor actor;
    actor.Mesh = quad;
    actor.NormalTexture = texture;
    actor.FrameSource = c.FrameSource;
    actor.StockMapper = c.Stock;
    const auto pixels = nmtest::RenderFlat(setup, { actor });
    const nmtest::Difference d = nmtest::CompareWithReferenceShading(setup, pixels, pattern, bound);
    std::cout << c.Name << ": " << d.Compared << " pixels, " << 100.0 * d.WithinFraction
              << "% within " << bound << " levels, max error " << d.MaxChannel << std::endl;
    check(d.Compared > 30000, std::string(c.Name) + ": the quad covers the view");
    check(d.WithinFraction >= share, std::string(c.Name) + ": matches the CPU reference");
  }

  // Non-uniform scale: the normal-mapped quad must shade like the scaled displaced surface.
  // VTK's mapper keeps the unscaled tangent-space normal (it re-derives an orthonormal frame
  // in view space), which is wrong wherever the map tilts the normal.
  // Squeezed to 0.7 in y the quad is ~134 pixels tall for 128 texels: the map stays magnified
  // (minified, the mipmaps' averaging would be part of the error; with fewer texels the
  // bilinear error would be, as a 48-texel map showed: 89% within 3 levels).
  for (int stock = 0; stock < 2; ++stock)
  {
    nmtest::FlatActor scaled;
    scaled.Mesh = quad;
    scaled.NormalTexture = texture;
    scaled.StockMapper = stock != 0;
    scaled.Scale[0] = 1.6;
    scaled.Scale[1] = 0.7;
    const nmtest::Difference d = nmtest::CompareWithReferenceShading(
      setup, nmtest::RenderFlat(setup, { scaled }), pattern, bound, glm::dvec2(1.6, 0.7));
    const std::string name =
      stock ? "VTK's stock mapper, scale (1.6, 0.7, 1)" : "ours, scale (1.6, 0.7, 1)";
    std::cout << name << ": " << d.Compared << " pixels, " << 100.0 * d.WithinFraction
              << "% within " << bound << " levels, max error " << d.MaxChannel << std::endl;
    if (stock)
    {
      check(d.WithinFraction < 0.9, name + ": differs from the scaled geometry");
    }
    else
    {
      check(d.WithinFraction >= share, name + ": matches the scaled geometry");
    }
  }

  // The comparison can fail: the same map read with the wrong green convention (bumps lit
  // from below) must be far from the reference.
  {
    nmtest::FlatActor wrong;
    wrong.Mesh = quad;
    wrong.NormalTexture = texture;
    wrong.Encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX;
    const nmtest::Difference d = nmtest::CompareWithReferenceShading(
      setup, nmtest::RenderFlat(setup, { wrong }), pattern, bound);
    std::cout << "wrong convention (control): " << 100.0 * d.WithinFraction << "% within " << bound
              << " levels, max error " << d.MaxChannel << std::endl;
    check(d.WithinFraction < 0.8, "a wrong green convention is detected");
  }

  // Without its map the quad is flat: the reference with the unperturbed normal must match
  // too, and the mapped image must differ from it (the map is visible at all).
  nmtest::FlatActor plain;
  plain.Mesh = quad;
  const auto flatPixels = nmtest::RenderFlat(setup, { plain });
  int flatWithin = 0, flatCount = 0;
  for (int py = 40; py < 216; ++py)
  {
    for (int px = 40; px < 216; ++px)
    {
      const glm::dvec3 color = nmtest::ReferenceShade(setup, px, py, glm::dvec3(0, 0, 1));
      int m = 0;
      for (int c = 0; c < 3; ++c)
      {
        m = std::max(m,
          std::abs(int(flatPixels[3 * (py * setup.Width + px) + c]) - int(std::lround(color[c]))));
      }
      flatWithin += m <= 1 ? 1 : 0;
      ++flatCount;
    }
  }
  check(flatWithin == flatCount, "unmapped quad: every pixel within 1 level of the reference");
  return check.Result();
}
