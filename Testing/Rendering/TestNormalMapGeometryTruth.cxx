// SPDX-License-Identifier: BSD-3-Clause
// A normal-mapped flat quad against real geometry: a finely tessellated quad displaced by the
// same height field, whose point normals are the field's analytic normals. Both are rendered
// with the same camera and light; the normal map should light the flat quad like the geometry.
#include "NormalMapTestScenes.h"

#include <iostream>

int TestNormalMapGeometryTruth(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  // Parallel projection: a displaced point then lands on the same pixel as the flat one (with
  // perspective, parallax of up to a pixel at the steep specular highlights measured 91% within
  // 4 levels, max 36: a property of the comparison, not of the map).
  setup.Parallel = true;
  // 384 x 384 quads: several per pixel, so the geometry's normals are sampled as finely as
  // the map's texels are.
  const vtkSmartPointer<vtkPolyData> displacedQuad = nmtest::MakeDisplacedQuad(384);
  nmtest::FlatActor displaced;
  displaced.Mesh = displacedQuad;
  const auto geometry = nmtest::RenderFlat(setup, { displaced });

  nmtest::FlatActor mapped;
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(1));
  auto texture = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::SineBump, 128, nmtest::Storage::OpenGL));
  mapped.Mesh = quad;
  mapped.NormalTexture = texture;
  const auto normalMapped = nmtest::RenderFlat(setup, { mapped });
  nmtest::FlatActor plain;
  plain.Mesh = quad;
  const auto flat = nmtest::RenderFlat(setup, { plain });

  // Pixels well inside the quad (the displaced silhouette differs from the flat one at the
  // border by up to 2 * 0.03 world units of relief).
  const std::vector<bool> inner = nmtest::InnerPixels(setup.Width, setup.Height, 30);
  // What still differs, by design: the 8-bit map and its bilinear filtering (about 1 level,
  // as in TestNormalMapCPUReference); the interpolation of vertex normals across 384 quads
  // (1/128 of a period each: ~0.03% of the slope); the view vector, which VTK takes from the
  // displaced position (up to 0.06 units in 5). Bound: 4 levels on 99% of the pixels; the flat
  // quad without a map is the control that fails it.
  const int bound = 4;
  const auto d = nmtest::Compare(normalMapped, geometry, inner, bound);
  const auto control = nmtest::Compare(flat, geometry, inner, bound);
  std::cout << "normal-mapped quad vs displaced geometry: " << d.Compared << " pixels, "
            << 100.0 * d.WithinFraction << "% within " << bound << " levels, max " << d.MaxChannel
            << std::endl;
  std::cout << "flat quad (control) vs displaced geometry: " << 100.0 * control.WithinFraction
            << "% within " << bound << " levels, max " << control.MaxChannel << std::endl;
  check(d.WithinFraction >= 0.99, "the normal map lights the quad like the geometry");
  check(control.WithinFraction < 0.5, "the control (no map) does not");
  return check.Result();
}
