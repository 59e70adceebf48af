// SPDX-License-Identifier: BSD-3-Clause
// normalmap demo: the built-in scene. A torus whose two halves use the same texture mirrored,
// a procedural normal map, tangent frames from vtkPolyDataTangentFrames, a picture from
// vtkNormalMapPolyDataMapper, and what it measured on the way (see UsageText below).
#include "NormalMapFiles.h"
#include "NormalMapPatterns.h"
#include "NormalMapRender.h"
#include "NormalMapTangents.h"
#include "NormalMapTool.h"

#include <vtkImageData.h>
#include <vtkNormalMapPolyDataMapper.h>
#include <vtkNormalMappingMeshes.h>
#include <vtkPolyData.h>
#include <vtkPolyDataTangentFrames.h>
#include <vtkTexture.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr const char* Name = "demo";

const char* UsageText =
  R"(usage: normalmap demo [-o OUT.png] [--size WxH]

Renders the built-in scene and prints what it measured: a torus (vtkNormalMapping::MakeTorus)
whose two halves use the same texture mirrored, a procedural normal map (bricks with rivets),
angle-weighted tangent frames from vtkPolyDataTangentFrames (mirror-seam points split), drawn
by vtkNormalMapPolyDataMapper with a light in the mirror plane, so the two halves must shade
as mirror images of each other: the demo measures how closely they do.

options:
  -o, --output OUT.png   the picture (default: normalmap-demo.png in the current folder)
  --size WxH             picture size in pixels, 16..8192 each (default 1200x800)
  -h, --help             this text
)";

double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

// How closely the picture matches its own left-right mirror image, over the pixels where
// either side shows the surface (the camera and the light lie in the torus' mirror plane).
struct Symmetry
{
  long Compared = 0;
  long Within = 0; // max channel difference <= Bound
  int MaxDifference = 0;
  static constexpr int Bound = 8;
};

Symmetry MeasureSymmetry(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  const int components = image->GetNumberOfScalarComponents();
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  unsigned char background[3];
  for (int c = 0; c < 3; ++c)
  {
    background[c] = static_cast<unsigned char>(NormalMapRender::Background[c] * 255.0 + 0.5);
  }
  auto isBackground = [&](const unsigned char* p)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(int(p[c]) - int(background[c])) > 2)
        return false;
    }
    return true;
  };
  Symmetry s;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0] / 2; ++x)
    {
      const unsigned char* left = pixels + (static_cast<size_t>(y) * dims[0] + x) * components;
      const unsigned char* right =
        pixels + (static_cast<size_t>(y) * dims[0] + (dims[0] - 1 - x)) * components;
      if (isBackground(left) && isBackground(right))
      {
        continue;
      }
      int difference = 0;
      for (int c = 0; c < 3; ++c)
      {
        difference = std::max(difference, std::abs(int(left[c]) - int(right[c])));
      }
      ++s.Compared;
      s.Within += difference <= Symmetry::Bound ? 1 : 0;
      s.MaxDifference = std::max(s.MaxDifference, difference);
    }
  }
  return s;
}
}

int NormalMapTool::DemoCommand(int argc, char* argv[])
{
  std::string outputPath = "normalmap-demo.png";
  int width = 1200, height = 800;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      std::cout << UsageText;
      return Success;
    }
    if (arg != "-o" && arg != "--output" && arg != "--size")
    {
      return Fail(Name, "unknown argument '" + arg + "' (see normalmap demo --help)", Usage);
    }
    if (i + 1 >= argc)
    {
      return Fail(Name, arg + " needs a value (see normalmap demo --help)", Usage);
    }
    const std::string value = argv[++i];
    if (arg == "--size")
    {
      if (!NormalMapRender::ParseSize(value, width, height))
      {
        return Fail(Name,
          "bad --size '" + value +
            "' (WxH, each 16..8192, e.g. 1200x800) (see normalmap demo --help)",
          Usage);
      }
    }
    else
    {
      outputPath = value;
    }
  }
  if (NormalMapFiles::Extension(outputPath) != ".png")
  {
    return Fail(Name, "'" + outputPath + "': the output must be a .png file", Usage);
  }
  std::string error;
  NormalMapFiles::OutputTransaction output;
  if (!output.Begin(outputPath, error))
  {
    return Fail(Name, error);
  }

  // The mesh: 256 x 128 quads, u mirrored at the ring's angles 0 and 180 degrees.
  vtkNormalMapping::TorusOptions torus;
  torus.MirrorU = true;
  vtkSmartPointer<vtkPolyData> mesh = vtkNormalMapping::MakeTorus(torus);

  // Tangent frames: angle-weighted, the filter's default (the map is procedural, not baked
  // against MikkTSpace frames).
  NormalMapTangents::Options options;
  options.Method = vtkPolyDataTangentFrames::ANGLE_WEIGHTED;
  NormalMapTangents::Counts counts;
  std::vector<std::string> warnings;
  const auto tangentStart = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkPolyData> framed =
    NormalMapTangents::Compute(mesh, options, counts, warnings, error);
  const double tangentMs = MillisecondsSince(tangentStart);
  if (!framed)
  {
    return Fail(Name, error);
  }

  const int mapSize = 512;
  vtkSmartPointer<vtkTexture> texture =
    NormalMapRender::MakeTexture(NormalMapPatterns::MakeBrickNormalMap(
      NormalMapPatterns::Bricks(), mapSize, NormalMapPatterns::Encoding::OpenGL));

  // The torus lies in z = 0 around the z axis; its texture is mirrored across the plane y = 0.
  // Camera and light both lie in that plane, so the picture is its own left-right mirror image
  // when the mirrored half shades right.
  NormalMapRender::Scene scene;
  scene.Mesh = framed;
  scene.NormalMap = texture;
  scene.Encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
  scene.FrameSource = vtkNormalMapPolyDataMapper::POINT_TANGENTS;
  scene.Width = width;
  scene.Height = height;
  scene.PlaceCamera = true;
  const double camera[3] = { 3.6, 0.0, 2.8 }, up[3] = { 0.0, 0.0, 1.0 };
  std::copy(camera, camera + 3, scene.CameraPosition);
  std::copy(up, up + 3, scene.ViewUp);
  scene.LightInScene = true;
  const double light[3] = { 0.6, 0.0, 1.0 };
  std::copy(light, light + 3, scene.LightPosition);
  NormalMapRender::Rendered rendered;
  if (!NormalMapRender::Render(scene, rendered, error))
  {
    return Fail(Name, error);
  }
  const Symmetry symmetry = MeasureSymmetry(rendered.Image);
  if (!NormalMapRender::WritePNG(rendered.Image, output, error) || !output.Commit(error))
  {
    return Fail(Name, error);
  }

  for (const std::string& w : warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
  for (const std::string& w : rendered.Warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
  std::error_code ec;
  const std::filesystem::path written = std::filesystem::absolute(outputPath, ec);
  std::cout << std::fixed << std::setprecision(1)
            << "normalmap demo: a torus whose two halves use one texture, mirrored\n"
            << "  points           " << counts.InputPoints << " in, " << counts.OutputPoints
            << " after tangents\n"
            << "  triangles        " << counts.Triangles << "\n"
            << "  points split     " << counts.SplitPoints << " (on the two mirror seams)\n"
            << "  tangents         angle-weighted (vtkPolyDataTangentFrames), " << tangentMs
            << " ms\n"
            << "  normal map       procedural bricks with rivets, " << mapSize << "x" << mapSize
            << ", OpenGL encoding\n"
            << "  render           " << rendered.FirstFrameMs
            << " ms first frame (shaders, upload), " << rendered.NextFrameMs << " ms the next; "
            << width << "x" << height << ", frame: " << rendered.AppliedFrame << "\n"
            << "  rendering path   " << rendered.Window << "; OpenGL renderer string "
            << rendered.Renderer << "\n"
            << "  mirror symmetry  " << std::setprecision(2)
            << (symmetry.Compared ? 100.0 * symmetry.Within / symmetry.Compared : 0.0) << "% of "
            << symmetry.Compared << " surface pixel pairs within " << Symmetry::Bound
            << "/255 of their mirror image (max " << symmetry.MaxDifference << ")\n"
            << "  wrote            " << (ec ? outputPath : written.string()) << "\n";
  return Success;
}
