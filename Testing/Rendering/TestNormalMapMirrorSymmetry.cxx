// A quad and its mirror image (mirrored geometry and mirrored texture coordinates, the same
// map), under a light on the mirror plane, must render as mirror images of each other. VTK's
// stock mapper fails this: it takes the bitangent as cross(N, T) on both sides.
#include "NormalMapTestScenes.h"

#include "vtkNormalMapPolyDataMapper.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <iostream>

namespace
{
/// The quad moved to x in [x0, x0 + 2].
vtkSmartPointer<vtkPolyData> Moved(vtkPolyData* quad, double dx)
{
  vtkNew<vtkTransform> move;
  move->Translate(dx, 0.0, 0.0);
  vtkNew<vtkTransformPolyDataFilter> filter;
  filter->SetTransform(move);
  filter->SetInputData(quad);
  filter->Update();
  return filter->GetOutput();
}

/// Mirror symmetry about the image's middle column, over pixels away from the quads' edges.
nmtest::Difference Symmetry(const std::vector<unsigned char>& pixels,
  int width,
  int height,
  int bound)
{
  std::vector<unsigned char> mirrored(pixels.size());
  std::vector<bool> mask(pixels.size() / 3, false);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const size_t p = static_cast<size_t>(y) * width + x;
      const size_t q = static_cast<size_t>(y) * width + (width - 1 - x);
      for (int c = 0; c < 3; ++c)
      {
        mirrored[3 * p + c] = pixels[3 * q + c];
      }
      // Covered on both sides, and not at a quad's border or the middle seam (3 pixels), where
      // the rasterizer's fill rule, not shading, decides.
      const bool covered = pixels[3 * p] && pixels[3 * q];
      mask[p] = covered && std::abs(2 * x + 1 - width) > 6;
    }
  }
  // Drop pixels next to uncovered ones (the quads' outer borders).
  std::vector<bool> inner = mask;
  for (int y = 3; y < height - 3; ++y)
    for (int x = 3; x < width - 3; ++x)
      for (int d = -3; d <= 3; ++d)
        inner[y * width + x] =
          inner[y * width + x] && mask[y * width + x + d] && mask[(y + d) * width + x];
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (y < 3 || y >= height - 3 || x < 3 || x >= width - 3)
        inner[y * width + x] = false;
  return nmtest::Compare(pixels, mirrored, inner, bound);
}
}

int TestNormalMapMirrorSymmetry(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  setup.Width = 320;
  setup.Height = 160;
  setup.CameraDistance = 8.0;
  setup.LightPosition = glm::dvec3(0.0, 1.5, 2.0); // on the mirror plane x = 0
  auto texture = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 128, nmtest::Storage::OpenGL));
  // Left: x in [-2, 0], u along +x. Right: its mirror image, x in [0, 2], u along -x.
  auto left = nmtest::WithTangents(Moved(nmtest::MakeQuad(4, false), -1.0));
  auto right = nmtest::WithTangents(Moved(nmtest::MakeQuad(4, true), 1.0));

  // Mirror images agree up to rasterization and float rounding of the interpolated texture
  // coordinates on each side: 2 levels, on all but 0.1% of the pixels.
  const int bound = 2;
  for (int stock = 0; stock < 2; ++stock)
  {
    for (int frame : { int(vtkNormalMapPolyDataMapper::POINT_TANGENTS),
           int(vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES) })
    {
      if (stock && frame == vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES)
      {
        continue; // VTK's mapper has no derivative frame
      }
      nmtest::FlatActor a, b;
      a.Mesh = left;
      b.Mesh = right;
      a.NormalTexture = b.NormalTexture = texture;
      a.FrameSource = b.FrameSource = frame;
      a.StockMapper = b.StockMapper = stock != 0;
      const auto pixels = nmtest::RenderFlat(setup, { a, b });
      const nmtest::Difference d = Symmetry(pixels, setup.Width, setup.Height, bound);
      const std::string name = stock
        ? "VTK's stock mapper"
        : std::string("ours, ") + vtkNormalMapPolyDataMapper::GetFrameSourceName(frame);
      std::cout << name << ": " << d.Compared << " pixels, " << 100.0 * d.WithinFraction
                << "% symmetric within " << bound << " levels, max difference " << d.MaxChannel
                << std::endl;
      check(d.Compared > 5000, name + ": both quads cover the view"); // 8976 measured
      if (stock)
      {
        // The claim the README makes about VTK 9.1: mirrored UVs shade wrong.
        check(d.WithinFraction < 0.95, name + ": is not mirror-symmetric");
      }
      else
      {
        check(d.WithinFraction >= 0.999, name + ": is mirror-symmetric");
      }
    }
  }
  return check.Result();
}
