// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapPatterns.h"

#include <vtkImageData.h>
#include <vtkType.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace NormalMapPatterns
{
double BrickHeight(const Bricks& bricks, double u, double v)
{
  u -= std::floor(u);
  v -= std::floor(v);
  const double rowHeight = 1.0 / bricks.Rows;
  const double brickWidth = 1.0 / bricks.Columns;
  const int row = std::min(static_cast<int>(v / rowHeight), bricks.Rows - 1);
  const double shifted = u + (row % 2 == 1 ? 0.5 * brickWidth : 0.0);
  // Position inside the brick, in texture units from its lower-left corner.
  const double x = shifted - std::floor(shifted / brickWidth) * brickWidth;
  const double y = v - row * rowHeight;
  const double edge = std::min(std::min(x, brickWidth - x), std::min(y, rowHeight - y));
  double height = bricks.Depth * std::min(1.0, edge / bricks.Bevel);
  if (bricks.RivetRadius > 0.0)
  {
    const double dx = x - 0.5 * brickWidth, dy = y - 0.5 * rowHeight;
    const double r2 = (dx * dx + dy * dy) / (bricks.RivetRadius * bricks.RivetRadius);
    if (r2 < 1.0)
    {
      // (1 - r^2)^1.5: a dome whose slope falls to zero at its rim (a hemisphere's vertical rim
      // would alias).
      height += bricks.RivetHeight * std::pow(1.0 - r2, 1.5);
    }
  }
  return height;
}

vtkSmartPointer<vtkImageData> MakeBrickNormalMap(const Bricks& bricks, int size, Encoding encoding)
{
  size = std::max(size, 4);
  const double step = 1.0 / size;
  std::vector<double> height(static_cast<size_t>(size) * size);
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      height[static_cast<size_t>(j) * size + i] =
        BrickHeight(bricks, (i + 0.5) * step, (j + 0.5) * step);
    }
  }
  auto at = [&](int i, int j)
  {
    i = (i + size) % size;
    j = (j + size) % size;
    return height[static_cast<size_t>(j) * size + i];
  };

  const int components = encoding == Encoding::TwoChannel ? 2 : 3;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, components);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  auto store = [](double c)
  { return static_cast<unsigned char>(std::lround(std::clamp(c * 0.5 + 0.5, 0.0, 1.0) * 255.0)); };
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      // The surface (u, v, h(u, v)) has the normal (-dh/du, -dh/dv, 1).
      const double dhdu = (at(i + 1, j) - at(i - 1, j)) / (2.0 * step);
      const double dhdv = (at(i, j + 1) - at(i, j - 1)) / (2.0 * step);
      const double length = std::sqrt(dhdu * dhdu + dhdv * dhdv + 1.0);
      const double nx = -dhdu / length, ny = -dhdv / length, nz = 1.0 / length;
      unsigned char* texel = out + (static_cast<size_t>(j) * size + i) * components;
      texel[0] = store(nx);
      texel[1] = store(encoding == Encoding::DirectX ? -ny : ny);
      if (components == 3)
      {
        texel[2] = store(nz);
      }
    }
  }
  return image;
}
}
