// SPDX-License-Identifier: BSD-3-Clause
// Rendering cost and accuracy of normal mapping on the software rasterizer (Mesa llvmpipe):
// VTK's stock mapper without and with its own normal mapping (with the texture as given, and
// with its mipmaps on: trilinear filtering), and
// vtkNormalMapPolyDataMapper with each frame source (point tangents, screen-space derivatives),
// each under Phong and PBR.
//
//   BenchNormalMapRendering [--out DIR] [--smoke] [--window PIXELS] [--quads N] [--frames N]
//   (under Testing/Rendering/RunHeadless.sh)
//
// Writes DIR/rendering.md (its section of docs/benchmarks.md), DIR/rendering.tsv (for BenchChart)
// and DIR/rendering.env (renderer and versions). Defaults: a 512 x 512 window, a quad of
// 512 x 512 cells, 30 timed frames; --smoke: 128, 16 and 2.
//
// The scene is the mapper tests' flat scene (NormalMapTestScenes): a finely tessellated flat
// quad with the SineBump normal map, one directional light, a fixed camera and window. Per
// configuration: one frame to build shaders and buffers (timed on its own), two warm-up frames,
// then N timed frames, round-robin over the configurations, each Render() followed by glFinish
// (WaitForCompletion); the median ms/frame is reported. Image error: against the CPU reference
// shading of the mapper tests (ReferenceShade, VTK's Phong model in double from the analytic
// normals; Phong only), also under the non-uniform actor scale (1.6, 0.7, 1); and, for both
// lighting models, against the geometry the map stands for (the quad displaced by the height field,
// with its analytic normals, rendered with the same lighting in parallel projection).
#include "BenchCommon.h"
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLVertexBufferObject.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkTexture.h"
#include "vtkVersionMacros.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;

struct Configuration
{
  std::string Name;
  bool Stock = false;
  bool Mapped = true;
  int FrameSource = Mapper::AUTOMATIC;
  bool WithTangents = true; // the mesh has point Tangents and TangentSigns
  bool PBR = false;
  bool Mipmapped = false; // the texture's own mipmaps on (trilinear filtering)
  bool Unsigned = false;  // the mesh's Tangents without TangentSigns
};

std::vector<Configuration> Configurations()
{
  std::vector<Configuration> all;
  for (bool pbr : { false, true })
  {
    all.push_back({ "VTK mapper, no normal map", true, false, Mapper::AUTOMATIC, false, pbr });
    all.push_back({ "VTK mapper, its normal mapping", true, true, Mapper::AUTOMATIC, true, pbr });
    all.push_back({ "VTK mapper, its normal mapping, mipmapped texture",
      true,
      true,
      Mapper::AUTOMATIC,
      true,
      pbr,
      true });
    all.push_back({ "ours, point tangents", false, true, Mapper::POINT_TANGENTS, true, pbr });
    all.push_back({ "ours, point tangents without signs",
      false,
      true,
      Mapper::POINT_TANGENTS,
      true,
      pbr,
      false,
      true });
    all.push_back(
      { "ours, screen derivatives", false, true, Mapper::SCREEN_DERIVATIVES, false, pbr });
  }
  return all;
}

/// Vertex buffer bytes per vertex of the mapper's attributes (a buffer shared by two
/// attributes counted once), and which attributes they are.
std::pair<int, std::string> VertexBytes(vtkOpenGLPolyDataMapper* mapper)
{
  std::set<vtkOpenGLVertexBufferObject*> seen;
  int bytes = 0;
  std::string names;
  for (const char* attribute : { "vertexMC",
         "normalMC",
         "tcoord",
         "scalarColor",
         "tangentMC",
         "nmTangentMC",
         "nmTangentSignMC" })
  {
    vtkOpenGLVertexBufferObject* vbo = mapper->GetVBOs()->GetVBO(attribute);
    if (!vbo)
    {
      continue;
    }
    names += (names.empty() ? "" : " + ") + std::string(attribute) + " " +
      std::to_string(vbo->GetStride());
    if (seen.insert(vbo).second)
    {
      bytes += static_cast<int>(vbo->GetStride());
    }
    else
    {
      names += " (shared)";
    }
  }
  return { bytes, names };
}

/// A line of the window's capabilities report ("OpenGL renderer string: llvmpipe ...").
std::string Capability(vtkRenderWindow* window, const std::string& key)
{
  std::istringstream report(window->ReportCapabilities());
  for (std::string line; std::getline(report, line);)
  {
    if (line.find(key) != std::string::npos)
    {
      const size_t value = line.find_first_not_of(' ', line.find(':') + 1);
      return value == std::string::npos ? std::string() : line.substr(value);
    }
  }
  return "unknown";
}

double Milliseconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
    .count();
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

std::string ErrorCell(const nmtest::Difference& d, int bound)
{
  char share[32];
  std::snprintf(share, sizeof(share), "%.2f%%", 100.0 * d.WithinFraction);
  return share + std::string(" within ") + std::to_string(bound) + "; mean " +
    Bench::Format(d.MeanChannel, 2) + ", max " + std::to_string(d.MaxChannel);
}
}

int main(int argc, char* argv[])
{
  std::string out = ".";
  int windowSize = 512, quadResolution = 512, frames = 30; // quads per side: 2 r^2 triangles
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool value = i + 1 < argc;
    if (arg == "--out" && value)
    {
      out = argv[++i];
    }
    else if (arg == "--smoke")
    {
      windowSize = 128, quadResolution = 16, frames = 2;
    }
    else if (arg == "--window" && value)
    {
      windowSize = std::max(64, std::atoi(argv[++i]));
    }
    else if (arg == "--quads" && value)
    {
      quadResolution = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--frames" && value)
    {
      frames = std::max(1, std::atoi(argv[++i]));
    }
    else
    {
      std::cerr << "usage: BenchNormalMapRendering [--out DIR] [--smoke] [--window PIXELS] "
                   "[--quads N] [--frames N]"
                << std::endl;
      return 2;
    }
  }
  nmtest::FlatSetup setup;
  setup.Width = setup.Height = windowSize;
  const int truthResolution = 3 * setup.Width / 2; // ~1.5 quads per pixel, as in the test
  // The mapper tests' bounds: 3 levels against the CPU reference (8-bit map, bilinear
  // filtering, rounding; see TestNormalMapCPUReference), 4 against the displaced geometry
  // (also the vertex-normal interpolation and the view vector; TestNormalMapGeometryTruth).
  const int referenceBound = 3, geometryBound = 4;
  const auto pattern = nmtest::Pattern::SineBump;
  // 128 texels over ~380 pixels: magnified, so the map is bilinearly filtered, as the CPU
  // reference assumes (see TestNormalMapCPUReference).
  auto normalMap = nmtest::MakeNormalMapImage(pattern, 128, nmtest::Storage::OpenGL);
  auto bare = nmtest::MakeQuad(quadResolution);
  auto withTangents = nmtest::WithTangents(bare);
  auto unsignedTangents = nmtest::WithTangentLayout(withTangents, nmtest::TangentLayout::Unsigned);

  // The geometry the map stands for, per lighting model, in parallel projection.
  nmtest::FlatSetup parallel = setup;
  parallel.Parallel = true;
  auto displaced = nmtest::MakeDisplacedQuad(truthResolution);
  std::vector<unsigned char> truth[2];
  for (int pbr : { 0, 1 })
  {
    nmtest::FlatActor geometry;
    geometry.Mesh = displaced;
    geometry.Interpolation = pbr ? VTK_PBR : VTK_PHONG;
    truth[pbr] = nmtest::RenderFlat(parallel, { geometry });
  }
  // Pixels well inside the quad (the displaced silhouette differs from the flat one at the
  // border), the test's 30 of 256 pixels.
  std::vector<bool> inner(truth[0].size() / 3, false);
  const int border = 30 * setup.Width / 256;
  for (int y = border; y < setup.Height - border; ++y)
  {
    for (int x = border; x < setup.Width - border; ++x)
    {
      inner[static_cast<size_t>(y) * setup.Width + x] = true;
    }
  }

  // Every configuration's window stays open: its first frame (shaders, buffers) and two
  // warm-up frames, then the timed frames round-robin over the configurations, so that load
  // from other processes spreads over all of them instead of hitting one.
  struct Scene
  {
    Configuration What;
    vtkSmartPointer<vtkTexture> Texture; // its own: a texture holds one window's GL resources
    vtkSmartPointer<vtkRenderWindow> Window;
    double FirstFrame = 0.0;
    std::vector<double> Times;
  };
  std::vector<Scene> scenes;
  for (const Configuration& c : Configurations())
  {
    Scene scene;
    scene.What = c;
    scene.Texture = nmtest::MakeNormalTexture(normalMap);
    scene.Texture->SetMipmap(c.Mipmapped);
    nmtest::FlatActor a;
    a.Mesh = c.Unsigned ? unsignedTangents : (c.WithTangents ? withTangents : bare);
    a.NormalTexture = c.Mapped ? scene.Texture.Get() : nullptr;
    a.StockMapper = c.Stock;
    a.FrameSource = c.FrameSource;
    a.Interpolation = c.PBR ? VTK_PBR : VTK_PHONG;
    scene.Window = nmtest::MakeFlatScene(setup, { a });
    const auto start = std::chrono::steady_clock::now();
    scene.Window->Render();
    scene.Window->WaitForCompletion();
    scene.FirstFrame = Milliseconds(start);
    nmtest::ReportRenderPath(scene.Window);
    for (int warm = 0; warm < 2; ++warm)
    {
      scene.Window->Render();
    }
    scene.Window->WaitForCompletion();
    scenes.push_back(scene);
  }
  for (int f = 0; f < frames; ++f)
  {
    for (Scene& scene : scenes)
    {
      scene.Window->MakeCurrent();
      const auto start = std::chrono::steady_clock::now();
      scene.Window->Render();
      scene.Window->WaitForCompletion();
      scene.Times.push_back(Milliseconds(start));
    }
  }

  std::ostringstream rows, tsv;
  tsv << "configuration\tlighting\tms_per_frame\tfirst_frame_ms\tgeometry_mean_error\t"
         "reference_mean_error\tvertex_bytes\n";
  const std::string renderer = Capability(scenes.front().Window, "OpenGL renderer string");
  const std::string version = Capability(scenes.front().Window, "OpenGL version string");
  for (Scene& scene : scenes)
  {
    const Configuration& c = scene.What;
    vtkRenderWindow* window = scene.Window;
    vtkRenderer* ren = window->GetRenderers()->GetFirstRenderer();
    vtkActor* actor = ren->GetActors()->GetLastActor();
    auto* mapper = vtkOpenGLPolyDataMapper::SafeDownCast(actor->GetMapper());
    const double msPerFrame = Median(scene.Times);
    window->Render();
    const auto pixels = nmtest::ReadPixels(window);
    const auto vertex = VertexBytes(mapper);
    auto* ours = Mapper::SafeDownCast(mapper);
    const std::string applied =
      ours ? Mapper::GetAppliedFrameName(ours->GetLastAppliedFrame()) : std::string("-");

    std::string referenceCell = "n/a (the CPU reference is Phong)", scaledCell = referenceCell;
    double referenceMean = -1.0;
    if (!c.PBR)
    {
      const auto d = nmtest::CompareWithReferenceShading(setup, pixels, pattern, referenceBound);
      referenceMean = d.MeanChannel;
      referenceCell = ErrorCell(d, referenceBound);
      actor->SetScale(1.6, 0.7, 1.0);
      window->Render();
      const auto scaled = nmtest::CompareWithReferenceShading(
        setup, nmtest::ReadPixels(window), pattern, referenceBound, glm::dvec2(1.6, 0.7));
      scaledCell = ErrorCell(scaled, referenceBound);
      actor->SetScale(1.0, 1.0, 1.0);
    }
    nmtest::SetFlatCamera(ren, parallel);
    window->Render();
    const auto geometry =
      nmtest::Compare(nmtest::ReadPixels(window), truth[c.PBR ? 1 : 0], inner, geometryBound);

    const char* lighting = c.PBR ? "PBR" : "Phong";
    rows << "| " << c.Name << " | " << lighting << " | " << Bench::Format(msPerFrame) << " | "
         << Bench::Format(scene.FirstFrame) << " | " << referenceCell << " | " << scaledCell
         << " | " << ErrorCell(geometry, geometryBound) << " | " << vertex.first << " ("
         << vertex.second << ") | " << applied << " |\n";
    tsv << c.Name << "\t" << lighting << "\t" << msPerFrame << "\t" << scene.FirstFrame << "\t"
        << geometry.MeanChannel << "\t" << referenceMean << "\t" << vertex.first << "\n";
    std::cout << c.Name << ", " << lighting << ": " << msPerFrame << " ms/frame, first frame "
              << scene.FirstFrame << " ms; vs geometry: mean " << geometry.MeanChannel << std::endl;
  }

  // The quad's 2 units against the 2 d tan(view angle / 2) the window's height shows.
  const int quadPixels = static_cast<int>(
    setup.Height / (setup.CameraDistance * std::tan(setup.ViewAngle * 3.14159265358979 / 360.0)));
  const char* path = std::getenv("NORMALMAPPING_HEADLESS_PATH");
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::ostringstream md;
  md << "## Rendering: frame time and image error\n\n"
     << "Mesa llvmpipe (OpenGL renderer `" << renderer << "`, version `" << version << "`), "
     << (path ? path : "an X display") << ", VTK " << VTK_VERSION << "; llvmpipe rasterizes on "
     << (threads ? std::string(threads) : std::string("one thread per core (LP_NUM_THREADS unset)"))
     << ". The mapper tests' flat scene: a " << setup.Width << " x " << setup.Height
     << " window, no multisampling, a flat quad of "
     << Bench::Count(2LL * quadResolution * quadResolution) << " triangles ("
     << Bench::Count((quadResolution + 1LL) * (quadResolution + 1LL)) << " points) covering "
     << quadPixels << " x " << quadPixels
     << " pixels, a 128 x 128 SineBump normal map (magnified), one directional light, "
        "perspective camera. Every mapper samples the same texture as it is given (bilinear); "
        "the \"mipmapped texture\" row shows what trilinear filtering costs VTK's mapper "
        "(on llvmpipe, even where the map is magnified). The point tangents are "
        "`vtkPolyDataTangentFrames`' (AngleWeighted; VTK's mapper uses the same float "
        "`Tangents`); the rows without signs render them without `TangentSigns` (the mapper takes "
        "each triangle's handedness from screen-space derivatives), the rows without tangents "
        "the mesh without tangent arrays.\n\n"
     << "- **ms/frame**: median of " << frames
     << " frames, each `Render()` then `glFinish`, after one frame that builds the shaders and "
        "buffers (**first frame**) and two warm-up frames. All configurations' windows stay "
        "open and the timed frames go round-robin over them, so that load from other processes "
        "spreads over all of them.\n"
     << "- **vs CPU reference**: the rendered quad against the mapper tests' CPU reference "
        "shading (`ReferenceShade`: VTK's Phong model in double precision from the height "
        "field's analytic normals), share of pixels whose largest channel error is within "
     << referenceBound
     << " levels of 255, the mean and maximum of that error; also with the actor scaled "
        "(1.6, 0.7, 1), where the reference is the scaled displaced surface.\n"
     << "- **vs displaced geometry**: the same quad in parallel projection against a "
     << truthResolution << " x " << truthResolution
     << " grid displaced by the height field with its analytic normals, rendered with the same "
        "lighting model (for PBR, the only reference there is), within "
     << geometryBound << " levels, over the pixels " << border << " pixels in from the border.\n"
     << "- **VBO bytes per vertex**: the vertex buffers the mapper built, read back from its "
        "`vtkOpenGLVertexBufferObjectGroup` (stride of each attribute's buffer; a buffer that two "
        "attributes share counted once); the index buffer (the same for all) is not counted.\n\n"
     << "| mapper, frame source | lighting | ms/frame | first frame, ms | vs CPU reference | "
        "scaled (1.6, 0.7, 1) vs CPU reference | vs displaced geometry | VBO bytes per vertex "
        "(attribute stride) | frame the shader applied |\n"
     << "|---|---|---:|---:|---:|---:|---:|---|---|\n"
     << rows.str() << "\n";
  const bool written = Bench::WriteText(out + "/rendering.md", md.str()) &&
    Bench::WriteText(out + "/rendering.tsv", tsv.str()) &&
    Bench::WriteText(
      out + "/rendering.env", "OpenGL renderer " + renderer + ", version " + version + "\n");
  return written ? 0 : 1;
}
