// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapImageTest.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCompositeDataIterator.h"
#include "vtkFloatArray.h"
#include "vtkGLTFReader.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkImageExtractComponents.h"
#include "vtkImageShiftScale.h"
#include "vtkLight.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTesting.h"
#include "vtkTexture.h"

#include <vtksys/SystemTools.hxx>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <utility>

namespace nmtest
{
namespace
{
// The image comparison's parameters; NormalMapImageTest.h says why these values.
constexpr int ChannelThreshold = 6;
constexpr double AllowedError = 1.0;

/// What a comparison found.
struct Verdict
{
  bool Compared = false; // false: the images could not be compared (size, missing baseline)
  double Error = 0.0;
  int PixelsOver = 0; // pixels with a channel beyond the threshold
  vtkSmartPointer<vtkImageData> Difference;
  bool Passed() const { return this->Compared && this->Error <= AllowedError; }
  bool Failed() const { return this->Compared && this->Error > AllowedError; }
};

Verdict Compare(vtkImageData* image, vtkImageData* baseline)
{
  Verdict v;
  int a[3], b[3];
  image->GetDimensions(a);
  baseline->GetDimensions(b);
  if (a[0] != b[0] || a[1] != b[1])
  {
    std::cout << "The render is " << a[0] << "x" << a[1] << ", the baseline " << b[0] << "x" << b[1]
              << ": not compared." << std::endl;
    return v;
  }
  vtkNew<vtkImageDifference> difference;
  difference->SetInputData(image);
  difference->SetImageData(baseline);
  difference->SetThreshold(ChannelThreshold);
  difference->AllowShiftOn();
  difference->AveragingOff();
  difference->Update();
  v.Compared = true;
  v.Error = difference->GetThresholdedError();
  v.Difference = difference->GetOutput();
  const auto* excess = static_cast<const unsigned char*>(v.Difference->GetScalarPointer());
  for (vtkIdType p = 0; p < v.Difference->GetNumberOfPoints(); ++p)
  {
    v.PixelsOver += (excess[3 * p] || excess[3 * p + 1] || excess[3 * p + 2]) ? 1 : 0;
  }
  return v;
}

/// Writes a PNG; false (with VTK's error message) when it cannot.
bool WritePng(vtkImageData* image, const std::string& file)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(file.c_str());
  writer->Write();
  return writer->GetErrorCode() == 0;
}

/// The baseline as RGB, or nullptr when it cannot be read.
vtkSmartPointer<vtkImageData> ReadBaseline(const std::string& file)
{
  vtkNew<vtkPNGReader> reader;
  if (!vtksys::SystemTools::FileExists(file) || !reader->CanReadFile(file.c_str()))
  {
    return nullptr;
  }
  reader->SetFileName(file.c_str());
  vtkNew<vtkImageExtractComponents> rgb;
  rgb->SetInputConnection(reader->GetOutputPort());
  rgb->SetComponents(0, 1, 2);
  rgb->Update();
  return rgb->GetOutput();
}

/// Prints a comparison; when it failed, writes the render and the difference (excess x 10,
/// as VTK's harness does) as <folder>/<stem>.png and <stem>.diff.png.
void Report(const Verdict& v,
  vtkImageData* image,
  const std::string& folder,
  const std::string& stem)
{
  std::cout << "<DartMeasurement name=\"ImageError\" type=\"numeric/double\">" << v.Error
            << "</DartMeasurement>" << std::endl;
  std::cout << stem << ": image error " << v.Error << " (allowed " << AllowedError << "), "
            << v.PixelsOver << " pixels beyond " << ChannelThreshold << " levels" << std::endl;
  if (v.Passed() || folder.empty())
  {
    return;
  }
  const std::string picture = folder + "/" + stem + ".png";
  WritePng(image, picture);
  std::cout << "<DartMeasurementFile name=\"TestImage\" type=\"image/png\">" << picture
            << "</DartMeasurementFile>" << std::endl;
  if (v.Difference)
  {
    vtkNew<vtkImageShiftScale> scaled;
    scaled->SetInputData(v.Difference);
    scaled->SetScale(10.0);
    scaled->ClampOverflowOn();
    scaled->SetOutputScalarTypeToUnsignedChar();
    scaled->Update();
    const std::string difference = folder + "/" + stem + ".diff.png";
    WritePng(scaled->GetOutput(), difference);
    std::cout << "<DartMeasurementFile name=\"DifferenceImage\" type=\"image/png\">" << difference
              << "</DartMeasurementFile>" << std::endl;
  }
}

/// A copy of an RGB image with offset(x, y) levels added to every channel, clamped.
template<typename Offset>
vtkSmartPointer<vtkImageData> Offsetted(vtkImageData* image, Offset offset)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(image);
  int d[3];
  copy->GetDimensions(d);
  auto* rgb = static_cast<unsigned char*>(copy->GetScalarPointer());
  for (int y = 0; y < d[1]; ++y)
  {
    for (int x = 0; x < d[0]; ++x)
    {
      unsigned char* pixel = rgb + 3 * (static_cast<size_t>(y) * d[0] + x);
      for (int c = 0; c < 3; ++c)
      {
        pixel[c] = static_cast<unsigned char>(std::clamp(pixel[c] + offset(x, y, d), 0, 255));
      }
    }
  }
  return copy;
}

/// A file-name-friendly form of an alteration's name.
std::string Slug(const std::string& name)
{
  std::string slug;
  for (char c : name)
  {
    const bool word = std::isalnum(static_cast<unsigned char>(c));
    if (word || (!slug.empty() && slug.back() != '-'))
    {
      slug += word ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : '-';
    }
  }
  while (!slug.empty() && slug.back() == '-')
  {
    slug.pop_back();
  }
  return slug;
}
}

//------------------------------------------------------------------------------
int RunImageTest(int argc,
  char* argv[],
  const std::vector<std::string>& alterations,
  const SceneBuilder& build)
{
  vtkNew<vtkTesting> testing;
  testing->AddArguments(argc, argv);
  if (!testing->IsValidImageSpecified())
  {
    std::cout << "An image test needs its baseline: -V <file>.png" << std::endl;
    return EXIT_FAILURE;
  }
  const std::string baselineFile = testing->GetValidImageFileName();
  const std::string folder = testing->GetTempDirectory();
  const std::string stem = vtksys::SystemTools::GetFilenameWithoutLastExtension(baselineFile);
  const auto render = [&](int alteration)
  {
    vtkSmartPointer<vtkRenderWindow> window = build(alteration);
    window->Render();
    ReportRenderPath(window);
    return GrabImage(window);
  };

  if (testing->IsFlagSpecified("--write-baseline"))
  {
    const bool written = WritePng(render(-1), baselineFile);
    std::cout << (written ? "Wrote " : "Could not write ") << baselineFile << std::endl;
    return written ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  vtkSmartPointer<vtkImageData> baseline = ReadBaseline(baselineFile);
  vtkSmartPointer<vtkImageData> scene = render(-1);
  if (!baseline)
  {
    WritePng(scene, folder + "/" + stem + ".png");
    std::cout << "No baseline " << baselineFile << "; the render is in " << folder << "/" << stem
              << ".png (cmake --build <build> --target NormalMappingBaselines writes them all)"
              << std::endl;
    return EXIT_FAILURE;
  }
  if (!testing->IsFlagSpecified("--altered"))
  {
    const Verdict v = Compare(scene, baseline);
    Report(v, scene, folder, stem);
    return v.Passed() ? EXIT_SUCCESS : EXIT_FAILURE;
  }

  // The twin: the comparison must pass what does not matter and fail what does.
  Checks check;
  const auto compareAs = [&](vtkImageData* image, const std::string& what)
  {
    const Verdict v = Compare(image, baseline);
    Report(v, image, folder, stem + ".can-fail." + Slug(what));
    return v;
  };
  const Verdict rounding = compareAs(
    Offsetted(scene, [](int x, int y, const int*) { return (x + y) % 2 ? 2 : -2; }), "rounding");
  check(rounding.Passed(), "the scene with +-2 levels on every pixel passes");
  const Verdict quarter = compareAs(Offsetted(scene,
                                      [](int x, int y, const int* d)
                                      {
                                        const bool inside = 4 * x >= d[0] && 4 * x < 3 * d[0] &&
                                          4 * y >= d[1] && 4 * y < 3 * d[1];
                                        return inside ? 40 : 0;
                                      }),
    "plus 40 levels on the centre quarter");
  check(quarter.Failed(), "the scene with +40 levels over the centre quarter fails");
  for (size_t i = 0; i < alterations.size(); ++i)
  {
    const Verdict v = compareAs(render(static_cast<int>(i)), alterations[i]);
    check(v.Failed(), "altered, " + alterations[i] + ": fails");
  }
  return check.Result();
}

//------------------------------------------------------------------------------
void AddPanel(vtkRenderWindow* window, int columns, int rows, int column, int row, const Panel& p)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(static_cast<double>(column) / columns,
    static_cast<double>(rows - 1 - row) / rows,
    static_cast<double>(column + 1) / columns,
    static_cast<double>(rows - row) / rows);
  renderer->SetBackground(0.1, 0.1, 0.12);
  renderer->SetTwoSidedLighting(true);
  AddSceneLight(renderer, glm::dvec3(-1.0, 1.5, 2.0));
  vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
  if (p.StockMapper)
  {
    mapper = vtkSmartPointer<vtkOpenGLPolyDataMapper>::New();
  }
  else
  {
    auto ours = vtkSmartPointer<vtkNormalMapPolyDataMapper>::New();
    ours->SetMapEncoding(p.Encoding);
    ours->SetFrameSource(p.FrameSource);
    mapper = ours;
  }
  mapper->SetInputData(p.Mesh);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetScale(p.Scale[0], p.Scale[1], p.Scale[2]);
  actor->RotateX(p.RotateX);
  actor->RotateY(p.RotateY);
  vtkProperty* property = actor->GetProperty();
  if (p.Texture)
  {
    property->SetNormalTexture(p.Texture);
    property->SetNormalScale(p.Strength);
  }
  property->SetColor(0.8, 0.55, 0.4);
  property->SetInterpolation(p.Interpolation);
  if (p.Interpolation == VTK_PBR)
  {
    property->SetRoughness(0.4);
    property->SetMetallic(0.1);
  }
  else
  {
    property->SetSpecular(0.4);
    property->SetSpecularPower(30.0);
  }
  renderer->AddActor(actor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(p.Zoom);
  window->AddRenderer(renderer);
}

//------------------------------------------------------------------------------
int RunEncodingTest(int argc, char* argv[], Storage storage, int encoding, int otherGreen)
{
  auto map = MakeNormalTexture(MakeNormalMapImage(Pattern::Rivets, 256, storage));
  auto quad = WithTangents(MakeQuad(4));
  auto sphere = WithTangents(MakeSphere(48));
  return RunImageTest(argc,
    argv,
    { "the other green convention", "the map dropped" },
    [&](int alteration)
    {
      auto window = MakeWindow(400, 200);
      Panel p;
      p.Texture = alteration == 1 ? nullptr : map.Get();
      p.Encoding = alteration == 0 ? otherGreen : encoding;
      p.Mesh = quad;
      AddPanel(window, 2, 1, 0, 0, p);
      p.Mesh = sphere;
      p.RotateX = -60.0;
      AddPanel(window, 2, 1, 1, 0, p);
      return window;
    });
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> LoadKhronosModel(const std::string& file)
{
  vtkNew<vtkGLTFReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkSmartPointer<vtkCompositeDataIterator> it =
    vtk::TakeSmartPointer(reader->GetOutput()->NewIterator());
  it->InitTraversal();
  auto* mesh =
    it->IsDoneWithTraversal() ? nullptr : vtkPolyData::SafeDownCast(it->GetCurrentDataObject());
  if (!mesh)
  {
    return nullptr;
  }
  auto model = vtkSmartPointer<vtkPolyData>::New();
  model->ShallowCopy(mesh);
  vtkPointData* pd = model->GetPointData();
  pd->SetNormals(pd->GetArray("NORMAL"));
  // glTF's v points down the image, VTK's up (vtkPNGReader puts the first row on top).
  vtkDataArray* gltfUV = pd->GetArray("TEXCOORD_0");
  vtkNew<vtkFloatArray> uv;
  uv->SetName("TCoords");
  uv->SetNumberOfComponents(2);
  uv->SetNumberOfTuples(gltfUV->GetNumberOfTuples());
  for (vtkIdType i = 0; i < gltfUV->GetNumberOfTuples(); ++i)
  {
    uv->SetTuple2(i, gltfUV->GetComponent(i, 0), 1.0 - gltfUV->GetComponent(i, 1));
  }
  pd->SetTCoords(uv);
  vtkNew<vtkPolyDataTangentFrames> frames;
  frames->SetMethod(vtkPolyDataTangentFrames::MIKKTSPACE);
  frames->SetInputData(model);
  frames->Update();
  return frames->GetOutput();
}

//------------------------------------------------------------------------------
namespace
{
/// Runs of covered (non-black) pixels along one axis: [begin, end) pairs.
std::vector<std::pair<int, int>> Runs(const std::vector<bool>& covered)
{
  std::vector<std::pair<int, int>> runs;
  for (int i = 0; i < static_cast<int>(covered.size()); ++i)
  {
    if (covered[i] && (i == 0 || !covered[i - 1]))
    {
      runs.emplace_back(i, i);
    }
    if (covered[i])
    {
      runs.back().second = i + 1;
    }
  }
  return runs;
}

}

//------------------------------------------------------------------------------
double WorstCell(const std::vector<unsigned char>& rgb, int size, int bound, int& cells)
{
  auto covered = [&](int x, int y)
  {
    const size_t p = 3 * (static_cast<size_t>(y) * size + x);
    return rgb[p] || rgb[p + 1] || rgb[p + 2];
  };
  std::vector<bool> rowsCovered(size, false);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      rowsCovered[y] = rowsCovered[y] || covered(x, y);
  // Rows of cells; thinner runs are the models' label bars.
  auto rows = Runs(rowsCovered);
  int tallest = 0;
  for (const auto& r : rows)
    tallest = std::max(tallest, r.second - r.first);
  rows.erase(
    std::remove_if(rows.begin(),
      rows.end(),
      [&](const std::pair<int, int>& r) { return 5 * (r.second - r.first) < 4 * tallest; }),
    rows.end());
  std::vector<bool> columnsCovered(size, false);
  for (const auto& r : rows)
    for (int y = r.first; y < r.second; ++y)
      for (int x = 0; x < size; ++x)
        columnsCovered[x] = columnsCovered[x] || covered(x, y);
  const auto columns = Runs(columnsCovered);
  int minGap = size;
  for (size_t c = 1; c < columns.size(); ++c)
    minGap = std::min(minGap, columns[c].first - columns[c - 1].second);
  int width = size, height = size;
  for (const auto& c : columns)
    width = std::min(width, c.second - c.first);
  for (const auto& r : rows)
    height = std::min(height, r.second - r.first);
  // Two pixels in from each cell's border, where coverage, not shading, decides.
  const int margin = 2;
  double worst = 1.0;
  cells = 0;
  for (const auto& r : rows)
  {
    size_t reference = 0;
    for (size_t c = 0; c < columns.size(); ++c)
    {
      if (c > 0 && columns[c].first - columns[c - 1].second > 3 * minGap)
      {
        reference = c; // a wider gap starts a new group; its first column is the geometry
        continue;
      }
      if (c == reference)
        continue;
      int within = 0, total = 0;
      for (int y = margin; y < height - margin; ++y)
      {
        for (int x = margin; x < width - margin; ++x)
        {
          const size_t a = 3 * (static_cast<size_t>(r.first + y) * size + columns[c].first + x);
          const size_t b =
            3 * (static_cast<size_t>(r.first + y) * size + columns[reference].first + x);
          int m = 0;
          for (int k = 0; k < 3; ++k)
            m = std::max(m, std::abs(int(rgb[a + k]) - int(rgb[b + k])));
          within += m <= bound ? 1 : 0;
          ++total;
        }
      }
      worst = std::min(worst, total ? static_cast<double>(within) / total : 0.0);
      ++cells;
    }
  }
  return worst;
}

//------------------------------------------------------------------------------
std::string KhronosModelFolder(const std::string& name)
{
  const char* shared = std::getenv("NORMALMAPPING_SHARED_DATA");
  const std::string folder = std::string(shared ? shared : "") + "/gltf/" + name + "/";
  if (!std::ifstream(folder + name + ".gltf"))
  {
    std::cout << "SKIPPED: " << folder << name
              << ".gltf not found: the shared data (../shared/data, or the CMake variable "
                 "NORMALMAPPING_SHARED_DATA) is absent"
              << std::endl;
    return std::string();
  }
  return folder;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTexture> LoadKhronosNormalMap(const std::string& file)
{
  vtkNew<vtkPNGReader> png;
  png->SetFileName(file.c_str());
  auto texture = MakeNormalTexture(nullptr);
  texture->SetInputConnection(png->GetOutputPort());
  return texture;
}

//------------------------------------------------------------------------------
void AddKhronosView(vtkRenderWindow* window,
  const double viewport[4],
  vtkPolyData* model,
  vtkTexture* normalMap,
  int encoding)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  vtkNew<vtkNormalMapPolyDataMapper> mapper;
  mapper->SetInputData(model);
  mapper->SetMapEncoding(encoding);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetNormalTexture(normalMap);
  actor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  actor->GetProperty()->SetSpecular(0.0);
  renderer->AddActor(actor);
  double bounds[6];
  model->GetBounds(bounds);
  SetKhronosViewpoint(renderer, bounds);
  window->AddRenderer(renderer);
}

//------------------------------------------------------------------------------
void SetKhronosViewpoint(vtkRenderer* renderer, const double bounds[6])
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPosition(-1.0, 1.0, 1.5);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->AddLight(light);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  // Fit the bounds (a square view) with a 3% border.
  const double cx = 0.5 * (bounds[0] + bounds[1]), cy = 0.5 * (bounds[2] + bounds[3]);
  camera->SetPosition(cx, cy, bounds[5] + 5.0);
  camera->SetFocalPoint(cx, cy, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetParallelScale(0.515 * std::max(bounds[1] - bounds[0], bounds[3] - bounds[2]));
  renderer->ResetCameraClippingRange();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> MakeObjectSpaceSphereMap(Pattern pattern, int size)
{
  const double pi = 3.14159265358979323846;
  return MakeRGBNormalImage(size,
    [&](double u, double v)
    {
      // vtkTexturedSphereSource: u = theta / 2 pi around z, v = 1 - phi / pi from the +z pole.
      const double theta = 2.0 * pi * u, phi = pi * (1.0 - v);
      const glm::dvec3 normal(
        std::sin(phi) * std::cos(theta), std::sin(phi) * std::sin(theta), std::cos(phi));
      const glm::dvec3 tangent(-std::sin(theta), std::cos(theta), 0.0);
      const glm::dvec3 bitangent = glm::cross(normal, tangent);
      const glm::dvec3 t = PatternNormal(pattern, u, v);
      return glm::normalize(t.x * tangent + t.y * bitangent + t.z * normal);
    });
}
}
