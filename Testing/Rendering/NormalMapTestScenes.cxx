// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkNormalMapShading.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLPolyDataMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkRenderingOpenGLConfigure.h" // VTK_USE_X, VTK_OPENGL_HAS_OSMESA, VTK_OPENGL_HAS_EGL
#include "vtkShader.h"
#include "vtkShaderProgram.h"
#include "vtkTexture.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTransform.h"
#include "vtkTransformFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace nmtest
{
namespace
{
const double Pi = 3.14159265358979323846;

/// Height gradient (dh/du, dh/dv) of a pattern, periodic on the unit square.
glm::dvec2 Gradient(Pattern pattern, double u, double v)
{
  u -= std::floor(u);
  v -= std::floor(v);
  switch (pattern)
  {
    case Pattern::SineBump:
    {
      // h = a sin(2 pi f u) sin(2 pi f v); slopes up to a 2 pi f = 0.57.
      const double a = 0.03, w = 2.0 * Pi * 3.0;
      return { a * w * std::cos(w * u) * std::sin(w * v),
        a * w * std::sin(w * u) * std::cos(w * v) };
    }
    case Pattern::Bricks:
    {
      // 4 rows of 2 bricks, odd rows offset by half a brick; within `bevel` of a brick's edge
      // the height falls linearly (slope 0.8) towards the mortar line.
      const double rows = 4.0, columns = 2.0, bevel = 0.025, slope = 0.8;
      const double rowF = v * rows;
      const double row = std::floor(rowF);
      double colF = u * columns + (std::fmod(row, 2.0) == 1.0 ? 0.5 : 0.0);
      colF -= std::floor(colF);
      const double du = colF / columns;              // distance from the brick's left edge
      const double dr = (1.0 - colF) / columns;      // from the right edge
      const double dv = (rowF - row) / rows;         // from the bottom edge
      const double dt = (1.0 - (rowF - row)) / rows; // from the top edge
      const double d = std::min(std::min(du, dr), std::min(dv, dt));
      if (d >= bevel)
      {
        return { 0.0, 0.0 };
      }
      // The height rises away from the nearest edge.
      if (d == du)
        return { slope, 0.0 };
      if (d == dr)
        return { -slope, 0.0 };
      if (d == dv)
        return { 0.0, slope };
      return { 0.0, -slope };
    }
    case Pattern::Rivets:
    {
      // 4 x 4 domes of radius 0.3 cell, h = H cos^2(pi d / (2 r)).
      const double cells = 4.0, r = 0.3 / cells, height = 0.02;
      const double cu = (std::floor(u * cells) + 0.5) / cells;
      const double cv = (std::floor(v * cells) + 0.5) / cells;
      const double x = u - cu, y = v - cv, d = std::sqrt(x * x + y * y);
      if (d >= r || d == 0.0)
      {
        return { 0.0, 0.0 };
      }
      const double dhdd = -height * Pi / (2.0 * r) * std::sin(Pi * d / r);
      return { dhdd * x / d, dhdd * y / d };
    }
  }
  return { 0.0, 0.0 };
}
}

//------------------------------------------------------------------------------
glm::dvec3 PatternNormal(Pattern pattern, double u, double v)
{
  const glm::dvec2 g = Gradient(pattern, u, v);
  return glm::normalize(glm::dvec3(-g.x, -g.y, 1.0));
}

//------------------------------------------------------------------------------
unsigned char Encode(double x)
{
  return static_cast<unsigned char>(std::lround((x * 0.5 + 0.5) * 255.0));
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> MakeRGBNormalImage(int size,
  const std::function<glm::dvec3(double u, double v)>& normalAt)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* texels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const glm::dvec3 n = normalAt((i + 0.5) / size, (j + 0.5) / size);
      unsigned char* t = texels + 3 * (static_cast<size_t>(j) * size + i);
      t[0] = Encode(n.x), t[1] = Encode(n.y), t[2] = Encode(n.z);
    }
  }
  return image;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> MakeNormalMapImage(Pattern pattern, int size, Storage storage)
{
  const int components = storage == Storage::OneChannel                         ? 1
    : (storage == Storage::TwoChannel || storage == Storage::TwoChannelDirectX) ? 2
                                                                                : 3;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size, size, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, components);
  auto* texels = static_cast<unsigned char*>(image->GetScalarPointer());
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const glm::dvec3 n = PatternNormal(pattern, (i + 0.5) / size, (j + 0.5) / size);
      unsigned char* t = texels + (static_cast<size_t>(j) * size + i) * components;
      switch (storage)
      {
        case Storage::OpenGL:
          t[0] = Encode(n.x), t[1] = Encode(n.y), t[2] = Encode(n.z);
          break;
        case Storage::DirectX: // the OpenGL map converted: green inverted
          t[0] = Encode(n.x), t[1] = 255 - Encode(n.y), t[2] = Encode(n.z);
          break;
        case Storage::TwoChannel:
          t[0] = Encode(n.x), t[1] = Encode(n.y);
          break;
        case Storage::TwoChannelDirectX:
          t[0] = Encode(n.x), t[1] = 255 - Encode(n.y);
          break;
        case Storage::OneChannel:
          t[0] = Encode(n.z * 2.0 - 1.0);
          break;
      }
    }
  }
  return image;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTexture> MakeNormalTexture(vtkImageData* image)
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOn();
  texture->MipmapOn(); // trilinear: the maps are minified on the smaller shapes
  texture->RepeatOn();
  return texture;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeQuad(int resolution, bool mirrorU)
{
  const int n = resolution + 1;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const double s = static_cast<double>(i) / resolution, t = static_cast<double>(j) / resolution;
      points->InsertNextPoint(2.0 * s - 1.0, 2.0 * t - 1.0, 0.0);
      normals->InsertNextTuple3(0.0, 0.0, 1.0);
      tcoords->InsertNextTuple2(mirrorU ? 1.0 - s : s, t);
    }
  }
  vtkNew<vtkCellArray> triangles;
  for (int j = 0; j < resolution; ++j)
  {
    for (int i = 0; i < resolution; ++i)
    {
      const vtkIdType a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      const vtkIdType first[3] = { a, b, c }, second[3] = { a, c, d };
      triangles->InsertNextCell(3, first);
      triangles->InsertNextCell(3, second);
    }
  }
  auto quad = vtkSmartPointer<vtkPolyData>::New();
  quad->SetPoints(points);
  quad->SetPolys(triangles);
  quad->GetPointData()->SetNormals(normals);
  quad->GetPointData()->SetTCoords(tcoords);
  return quad;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeSphere(int resolution)
{
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(2 * resolution);
  sphere->SetPhiResolution(resolution);
  sphere->Update();
  return sphere->GetOutput();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> WithTangents(vtkPolyData* mesh)
{
  vtkNew<vtkPolyDataTangentFrames> frames;
  frames->SetInputData(mesh);
  frames->Update();
  return frames->GetOutput();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> WithTangentLayout(vtkPolyData* withTangents, TangentLayout layout)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(withTangents);
  vtkPointData* pd = copy->GetPointData();
  vtkSmartPointer<vtkDataArray> tangents = pd->GetArray("Tangents");
  vtkSmartPointer<vtkDataArray> signs = pd->GetArray("TangentSigns");
  if (layout == TangentLayout::ActiveWithSigns)
  {
    return copy;
  }
  pd->RemoveArray("Tangents");
  pd->RemoveArray("TangentSigns");
  switch (layout)
  {
    case TangentLayout::NamedFloat3WithSigns:
      tangents->SetName("TANGENT");
      pd->AddArray(tangents);
      pd->AddArray(signs);
      break;
    case TangentLayout::NamedDouble4:
    {
      // VTK's Tangents attribute must have 3 components, so a 4-component array goes by name.
      vtkNew<vtkDoubleArray> t4;
      t4->SetName("TANGENT");
      t4->SetNumberOfComponents(4);
      for (vtkIdType i = 0; i < tangents->GetNumberOfTuples(); ++i)
      {
        const double* v = tangents->GetTuple3(i);
        t4->InsertNextTuple4(v[0], v[1], v[2], signs->GetTuple1(i));
      }
      pd->AddArray(t4);
      break;
    }
    case TangentLayout::Unsigned:
      pd->SetTangents(tangents);
      break;
    case TangentLayout::SignsIgnored:
    {
      pd->SetTangents(tangents);
      vtkSmartPointer<vtkDataArray> plusOne = vtk::TakeSmartPointer(signs->NewInstance());
      plusOne->DeepCopy(signs);
      plusOne->Fill(1.0);
      pd->AddArray(plusOne);
      break;
    }
    default:
      break;
  }
  return copy;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Placed(vtkPolyData* mesh, double dx, double dy, double sy)
{
  vtkNew<vtkTransform> place;
  place->Translate(dx, dy, 0.0);
  place->Scale(1.0, sy, 1.0);
  // VTK 9.7's transform filter adds temporary arrays to its input and removes them, which
  // changes the input's modification time: it reads a shallow copy, and the mesh stays as it is.
  vtkNew<vtkPolyData> input;
  input->ShallowCopy(mesh);
  vtkNew<vtkTransformFilter> filter;
  filter->SetTransform(place);
  filter->SetInputData(input);
  filter->Update();
  return filter->GetPolyDataOutput();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Half(vtkPolyData* mesh, bool left)
{
  auto half = vtkSmartPointer<vtkPolyData>::New();
  half->DeepCopy(mesh);
  vtkNew<vtkCellArray> kept;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    double x = 0.0;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      x += mesh->GetPoint(ids->GetId(k))[0];
    }
    if ((x < 0.0) == left)
    {
      kept->InsertNextCell(ids);
    }
  }
  half->SetPolys(kept);
  return half;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> WithoutTCoords(vtkPolyData* mesh)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  copy->GetPointData()->SetTCoords(nullptr);
  copy->GetPointData()->RemoveArray("TCoords");
  return copy;
}

//------------------------------------------------------------------------------
Difference MirrorSymmetry(const std::vector<unsigned char>& pixels,
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
      const bool covered = pixels[3 * p] && pixels[3 * q];
      mask[p] = covered && std::abs(2 * x + 1 - width) > 6;
    }
  }
  // Drop pixels next to uncovered ones (the meshes' outer borders).
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
  return Compare(pixels, mirrored, inner, bound);
}

//------------------------------------------------------------------------------
MirrorScene MakeMirrorScene()
{
  MirrorScene scene;
  scene.Setup.Width = 320;
  scene.Setup.Height = 160;
  scene.Setup.CameraDistance = 8.0;
  scene.Setup.LightPosition = glm::dvec3(0.0, 1.5, 2.0); // on the mirror plane x = 0
  scene.Texture = MakeNormalTexture(MakeNormalMapImage(Pattern::Rivets, 128, Storage::OpenGL));
  scene.Left = WithTangents(Placed(MakeQuad(4, false), -1.0, 0.0));
  scene.Right = WithTangents(Placed(MakeQuad(4, true), 1.0, 0.0));
  return scene;
}

//------------------------------------------------------------------------------
std::string StockCompositeName()
{
  return vtkNew<StockCompositeMapper>()->GetClassName();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkRenderWindow> MakeWindow(int width, int height)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(width, height);
  window->SetOffScreenRendering(1);
  // No multisampling: pixels are then single samples of the shading, comparable to the CPU.
  window->SetMultiSamples(0);
  return window;
}

//------------------------------------------------------------------------------
void ReportRenderPath(vtkRenderWindow* window)
{
  static bool reported = false;
  if (reported)
  {
    return;
  }
  reported = true;
  std::istringstream capabilities(window->ReportCapabilities());
  std::string line;
  std::string renderer = "unknown";
  while (std::getline(capabilities, line))
  {
    if (line.find("OpenGL renderer string") != std::string::npos)
    {
      renderer = line.substr(line.find(':') + 1);
    }
  }
#if defined(VTK_USE_X)
  const char* path = std::getenv("NORMALMAPPING_HEADLESS_PATH")
    ? std::getenv("NORMALMAPPING_HEADLESS_PATH")
    : "X display";
#elif defined(VTK_OPENGL_HAS_OSMESA)
  const char* path = "OSMesa, no X server";
#elif defined(VTK_OPENGL_HAS_EGL)
  const char* path = "EGL, no X server";
#else
  const char* path = "the platform's window system";
#endif
  std::cout << "Rendering path: " << path << "; " << window->GetClassName() << ";" << renderer
            << std::endl;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> GrabImage(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  return grab->GetOutput();
}

//------------------------------------------------------------------------------
std::vector<unsigned char> ReadPixels(vtkRenderWindow* window)
{
  vtkSmartPointer<vtkImageData> image = GrabImage(window);
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  return std::vector<unsigned char>(
    rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues());
}

//------------------------------------------------------------------------------
namespace
{
/// An output window that counts the errors it is given and prints them as VTK's does.
class ErrorCounter : public vtkOutputWindow
{
public:
  static ErrorCounter* New();
  vtkTypeMacro(ErrorCounter, vtkOutputWindow);
  void DisplayErrorText(const char* text) override
  {
    ++this->Errors;
    this->Superclass::DisplayErrorText(text);
  }
  int Errors = 0;
};
vtkStandardNewMacro(ErrorCounter);
}

int CountErrors(const std::function<void()>& run)
{
  vtkNew<ErrorCounter> counter;
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(counter);
  run();
  vtkOutputWindow::SetInstance(previous);
  return counter->Errors;
}

//------------------------------------------------------------------------------
void Checks::operator()(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok:   " : "  FAIL: ") << what << std::endl;
  this->Failures += ok ? 0 : 1;
}

int Checks::Result() const
{
  return this->Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

//------------------------------------------------------------------------------
void AddSceneLight(vtkRenderer* renderer, const glm::dvec3& position)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(position.x, position.y, position.z);
  light->SetFocalPoint(0.0, 0.0, 0.0);
  renderer->AddLight(light);
}

//------------------------------------------------------------------------------
void SetFlatCamera(vtkRenderer* renderer, const FlatSetup& setup)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0.0, 0.0, setup.CameraDistance);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetViewAngle(setup.ViewAngle);
  camera->SetParallelProjection(setup.Parallel);
  camera->SetParallelScale(setup.CameraDistance * std::tan(setup.ViewAngle * Pi / 360.0));
  renderer->ResetCameraClippingRange();
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkRenderWindow> MakeFlatScene(const FlatSetup& setup,
  const std::vector<FlatActor>& actors)
{
  auto window = MakeWindow(setup.Width, setup.Height);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->SetTwoSidedLighting(true);
  AddSceneLight(renderer, setup.LightPosition);
  for (const FlatActor& a : actors)
  {
    vtkSmartPointer<vtkPolyDataMapper> mapper;
    if (a.Blocks && a.StockMapper)
    {
      mapper = vtkSmartPointer<StockCompositeMapper>::New();
    }
    else if (a.Blocks)
    {
      auto ours = vtkSmartPointer<vtkNormalMapCompositePolyDataMapper>::New();
      ours->SetMapEncoding(a.Encoding);
      ours->SetFrameSource(a.FrameSource);
      ours->SetTangentsArrayName(a.TangentsArrayName);
      mapper = ours;
    }
    else if (a.StockMapper)
    {
      mapper = vtkSmartPointer<vtkOpenGLPolyDataMapper>::New();
    }
    else
    {
      auto ours = vtkSmartPointer<vtkNormalMapPolyDataMapper>::New();
      ours->SetMapEncoding(a.Encoding);
      ours->SetFrameSource(a.FrameSource);
      ours->SetTangentsArrayName(a.TangentsArrayName);
      mapper = ours;
    }
    if (a.Blocks)
    {
      mapper->SetInputDataObject(a.Blocks);
    }
    else
    {
      mapper->SetInputData(a.Mesh);
    }
    mapper->SetInterpolateScalarsBeforeMapping(a.InterpolateScalars);
    if (a.Shaders)
    {
      vtkNew<vtkCallbackCommand> capture;
      capture->SetClientData(a.Shaders);
      capture->SetCallback(
        [](vtkObject*, unsigned long, void* clientData, void* callData)
        {
          auto* program = static_cast<vtkShaderProgram*>(callData);
          *static_cast<std::string*>(clientData) =
            std::string(program->GetVertexShader()->GetSource()) + "\n" +
            program->GetFragmentShader()->GetSource();
        });
      mapper->AddObserver(vtkCommand::UpdateShaderEvent, capture);
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetScale(a.Scale[0], a.Scale[1], a.Scale[2]);
    if (a.TextureTransform)
    {
      vtkNew<vtkInformation> keys;
      keys->Set(vtkNormalMapShading::TextureTransformKey(), a.TextureTransform, 16);
      actor->SetPropertyKeys(keys);
    }
    vtkProperty* property = actor->GetProperty();
    property->SetInterpolation(a.Interpolation);
    property->SetColor(setup.Color.x, setup.Color.y, setup.Color.z);
    property->SetAmbient(setup.Ambient);
    property->SetDiffuse(setup.Diffuse);
    property->SetSpecular(setup.Specular);
    property->SetSpecularPower(setup.SpecularPower);
    property->SetSpecularColor(1.0, 1.0, 1.0);
    property->SetBackfaceCulling(!a.TwoSided);
    property->SetEdgeVisibility(a.EdgeVisibility);
    if (a.NormalTexture)
    {
      property->SetNormalTexture(a.NormalTexture);
      property->SetNormalScale(a.NormalScale);
    }
    renderer->AddActor(actor);
  }
  SetFlatCamera(renderer, setup);
  window->AddRenderer(renderer);
  return window;
}

//------------------------------------------------------------------------------
std::vector<unsigned char> RenderFlat(const FlatSetup& setup, const std::vector<FlatActor>& actors)
{
  auto window = MakeFlatScene(setup, actors);
  window->Render();
  ReportRenderPath(window);
  vtkActorCollection* rendered = window->GetRenderers()->GetFirstRenderer()->GetActors();
  rendered->InitTraversal();
  for (const FlatActor& a : actors)
  {
    auto* ours = vtkNormalMapPolyDataMapper::SafeDownCast(rendered->GetNextActor()->GetMapper());
    if (a.AppliedFrame && ours)
    {
      *a.AppliedFrame = ours->GetLastAppliedFrame();
    }
  }
  return ReadPixels(window);
}

//------------------------------------------------------------------------------
glm::dvec3 PixelOnPlane(const FlatSetup& setup, int px, int py)
{
  const double halfHeight = std::tan(setup.ViewAngle * Pi / 360.0);
  const double aspect = static_cast<double>(setup.Width) / setup.Height;
  const double x = ((px + 0.5) / setup.Width * 2.0 - 1.0) * halfHeight * aspect;
  const double y = ((py + 0.5) / setup.Height * 2.0 - 1.0) * halfHeight;
  return { x * setup.CameraDistance, y * setup.CameraDistance, 0.0 };
}

//------------------------------------------------------------------------------
glm::dvec3 ReferenceShade(const FlatSetup& setup, int px, int py, const glm::dvec3& n)
{
  // View coordinates: the camera looks down -z from (0, 0, d), so only a translation.
  const glm::dvec3 p = PixelOnPlane(setup, px, py) - glm::dvec3(0.0, 0.0, setup.CameraDistance);
  const glm::dvec3 lightDirection = glm::normalize(-setup.LightPosition);
  const double df = std::max(0.0, glm::dot(n, -lightDirection));
  const glm::dvec3 reflected = lightDirection - 2.0 * glm::dot(n, lightDirection) * n;
  const double sf = (df > 0.0 ? 1.0 : 0.0) *
    std::pow(std::max(0.0, glm::dot(reflected, glm::normalize(-p))), setup.SpecularPower);
  const glm::dvec3 color = setup.Ambient * setup.Color + setup.Diffuse * df * setup.Color +
    setup.Specular * sf * glm::dvec3(1.0);
  return glm::clamp(color, 0.0, 1.0) * 255.0;
}

//------------------------------------------------------------------------------
Difference CompareWithReferenceShading(const FlatSetup& setup,
  const std::vector<unsigned char>& pixels,
  Pattern pattern,
  int bound,
  glm::dvec2 scale)
{
  std::vector<unsigned char> reference(pixels.size(), 0);
  std::vector<bool> mask(pixels.size() / 3, false);
  // Two pixels in from the quad's edges, where coverage (not shading) decides the colour.
  const double margin =
    2.0 * 2.0 * setup.CameraDistance * std::tan(setup.ViewAngle * Pi / 360.0) / setup.Height;
  for (int py = 0; py < setup.Height; ++py)
  {
    for (int px = 0; px < setup.Width; ++px)
    {
      const glm::dvec3 p = PixelOnPlane(setup, px, py);
      if (std::abs(p.x) > scale.x - margin || std::abs(p.y) > scale.y - margin)
      {
        continue;
      }
      const size_t index = static_cast<size_t>(py) * setup.Width + px;
      mask[index] = true;
      // Texture coordinates of the quad: u = (x + 1) / 2, v = (y + 1) / 2 in its own
      // coordinates; its frame is the model's x, y, z, so the tangent-space normal is the
      // model normal. Scaled by diag(sx, sy, 1), the displaced surface's normals transform by
      // the inverse transpose, diag(1 / sx, 1 / sy, 1): that is the geometric truth.
      const glm::dvec3 model =
        PatternNormal(pattern, (p.x / scale.x + 1.0) / 2.0, (p.y / scale.y + 1.0) / 2.0);
      const glm::dvec3 n =
        glm::normalize(glm::dvec3(model.x / scale.x, model.y / scale.y, model.z));
      const glm::dvec3 color = ReferenceShade(setup, px, py, n);
      for (int c = 0; c < 3; ++c)
      {
        reference[3 * index + c] = static_cast<unsigned char>(std::lround(color[c]));
      }
    }
  }
  return Compare(pixels, reference, mask, bound);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeDisplacedQuad(int resolution)
{
  // The SineBump height field in texture units; its gradient is Gradient(SineBump, u, v).
  const auto height = [](double u, double v)
  {
    const double a = 0.03, w = 2.0 * Pi * 3.0;
    return a * std::sin(w * u) * std::sin(w * v);
  };
  auto grid = MakeQuad(resolution);
  vtkPoints* points = grid->GetPoints();
  vtkDataArray* normals = grid->GetPointData()->GetNormals();
  vtkDataArray* tcoords = grid->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    const double u = tcoords->GetComponent(i, 0), v = tcoords->GetComponent(i, 1);
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0], p[1], 2.0 * height(u, v));
    const glm::dvec3 normal = PatternNormal(Pattern::SineBump, u, v);
    normals->SetTuple3(i, normal.x, normal.y, normal.z);
  }
  return grid;
}

//------------------------------------------------------------------------------
std::vector<bool> InnerPixels(int width, int height, int margin)
{
  std::vector<bool> inner(static_cast<size_t>(width) * height, false);
  for (int y = margin; y < height - margin; ++y)
  {
    for (int x = margin; x < width - margin; ++x)
    {
      inner[static_cast<size_t>(y) * width + x] = true;
    }
  }
  return inner;
}

//------------------------------------------------------------------------------
Difference Compare(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b,
  const std::vector<bool>& mask,
  int bound)
{
  Difference d;
  int within = 0;
  double sum = 0.0;
  for (size_t p = 0; p < mask.size(); ++p)
  {
    if (!mask[p])
    {
      continue;
    }
    int m = 0;
    for (int c = 0; c < 3; ++c)
    {
      m = std::max(m, std::abs(int(a[3 * p + c]) - int(b[3 * p + c])));
    }
    ++d.Compared;
    d.MaxChannel = std::max(d.MaxChannel, m);
    within += m <= bound ? 1 : 0;
    sum += m;
  }
  d.WithinFraction = d.Compared ? static_cast<double>(within) / d.Compared : 0.0;
  d.MeanChannel = d.Compared ? sum / d.Compared : 0.0;
  return d;
}

//------------------------------------------------------------------------------
std::vector<bool> CoveredPixels(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b)
{
  std::vector<bool> mask(a.size() / 3);
  for (size_t p = 0; p < mask.size(); ++p)
  {
    mask[p] = a[3 * p] || a[3 * p + 1] || a[3 * p + 2] || b[3 * p] || b[3 * p + 1] || b[3 * p + 2];
  }
  return mask;
}
}
