// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapRender.h"

#include "NormalMapFiles.h"
#include "NormalMapImages.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkMapper.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkNormalMapCompositePolyDataMapper.h>
#include <vtkNormalMapPolyDataMapper.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRenderingOpenGLConfigure.h> // VTK_USE_X
#include <vtkTexture.h>
#include <vtkWindowToImageFilter.h>

#if defined(VTK_USE_X) && defined(NORMALMAP_HAVE_X11)
#include <X11/Xlib.h>
#endif

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

namespace NormalMapRender
{
namespace
{
double MillisecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
    .count();
}

std::string RendererString(vtkRenderWindow* window)
{
  std::istringstream capabilities(window->ReportCapabilities());
  std::string line;
  const std::string key = "OpenGL renderer string:";
  while (std::getline(capabilities, line))
  {
    const size_t at = line.find(key);
    if (at != std::string::npos)
    {
      const size_t begin = line.find_first_not_of(' ', at + key.size());
      return begin == std::string::npos ? std::string() : line.substr(begin);
    }
  }
  return "unknown";
}

// An actor for `mapper` with the scene's material and this normal map.
void AddActor(vtkRenderer* renderer,
  vtkMapper* mapper,
  const Scene& scene,
  vtkTexture* normalMap,
  double strength)
{
  mapper->ScalarVisibilityOff();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  vtkProperty* property = actor->GetProperty();
  property->SetColor(scene.Color[0], scene.Color[1], scene.Color[2]);
  if (scene.PBR)
  {
    property->SetInterpolationToPBR();
    property->SetMetallic(0.0);
    property->SetRoughness(0.45);
  }
  else
  {
    property->SetInterpolationToPhong();
    property->SetAmbient(0.08);
    property->SetDiffuse(0.85);
    property->SetSpecular(0.35);
    property->SetSpecularPower(30.0);
  }
  if (normalMap)
  {
    property->SetNormalTexture(normalMap);
    property->SetNormalScale(strength);
  }
  renderer->AddActor(actor);
}

// The X display for VTK's X window, opened here: VTK 9.1 calls abort() when it cannot open one.
class DisplayConnection
{
public:
  ~DisplayConnection()
  {
#if defined(VTK_USE_X) && defined(NORMALMAP_HAVE_X11)
    if (this->Display)
    {
      XCloseDisplay(static_cast<::Display*>(this->Display));
    }
#endif
  }
  bool Attach(vtkRenderWindow* window, std::string& name, std::string& error)
  {
    if (std::strcmp(window->GetClassName(), "vtkXOpenGLRenderWindow") != 0)
    {
      name = "no X server";
      return true;
    }
    const char* variable = std::getenv("DISPLAY");
    name = std::string("X display ") + (variable && *variable ? variable : "(DISPLAY not set)");
#if defined(VTK_USE_X) && defined(NORMALMAP_HAVE_X11)
    this->Display = XOpenDisplay(nullptr);
    if (!this->Display)
    {
      error = "cannot open the " + name +
        ": this VTK renders through X only, even offscreen (run under Xvfb, e.g. "
        "xvfb-run -a normalmap ...)";
      return false;
    }
    window->SetDisplayId(this->Display);
#else
    if (!variable || !*variable)
    {
      error = "DISPLAY is not set: this VTK renders through X only, even offscreen";
      return false;
    }
#endif
    return true;
  }

private:
  void* Display = nullptr;
};
}

bool Render(const Scene& scene, Rendered& result, std::string& error)
{
  NormalMapFiles::VTKMessageCapture messages;
  DisplayConnection display;
  {
    vtkNew<vtkRenderWindow> window;
    std::string displayName;
    if (!display.Attach(window, displayName, error))
    {
      return false;
    }
    window->SetOffScreenRendering(1);
    window->SetSize(scene.Width, scene.Height);
    window->SetMultiSamples(8);

    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(Background[0], Background[1], Background[2]);
    renderer->SetTwoSidedLighting(true);
    renderer->AutomaticLightCreationOff();
    vtkNew<vtkLight> light;
    if (scene.LightInScene)
    {
      light->SetLightTypeToSceneLight();
    }
    else
    {
      light->SetLightTypeToCameraLight();
    }
    light->SetPositional(false);
    light->SetPosition(scene.LightPosition[0], scene.LightPosition[1], scene.LightPosition[2]);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    renderer->AddLight(light);

    vtkNew<vtkNormalMapPolyDataMapper> mapper;
    std::vector<vtkSmartPointer<vtkNormalMapCompositePolyDataMapper>> composites;
    if (scene.Parts.empty())
    {
      mapper->SetInputData(scene.Mesh);
      mapper->SetMapEncoding(scene.Encoding);
      mapper->SetFrameSource(scene.FrameSource);
      AddActor(renderer, mapper, scene, scene.NormalMap, scene.Strength);
    }
    for (const Part& part : scene.Parts)
    {
      auto composite = vtkSmartPointer<vtkNormalMapCompositePolyDataMapper>::New();
      composite->SetInputDataObject(part.Blocks);
      composite->SetMapEncoding(scene.Encoding);
      composite->SetFrameSource(scene.FrameSource);
      AddActor(renderer, composite, scene, part.NormalMap, part.Strength);
      composites.push_back(composite);
    }

    vtkCamera* camera = renderer->GetActiveCamera();
    if (scene.PlaceCamera)
    {
      camera->SetPosition(scene.CameraPosition);
      camera->SetFocalPoint(scene.FocalPoint);
      camera->SetViewUp(scene.ViewUp);
      camera->OrthogonalizeViewUp();
      renderer->ResetCameraClippingRange();
    }
    else
    {
      renderer->ResetCamera();
      camera->Azimuth(scene.Azimuth);
      camera->Elevation(scene.Elevation);
      camera->OrthogonalizeViewUp();
      camera->Zoom(scene.Zoom);
      renderer->ResetCameraClippingRange();
    }
    window->AddRenderer(renderer);

    auto start = std::chrono::steady_clock::now();
    window->Render();
    result.FirstFrameMs = MillisecondsSince(start);
    if (!messages.Errors().empty())
    {
      error = "rendering failed: " + messages.Errors().front();
      return false;
    }
    start = std::chrono::steady_clock::now();
    window->Render();
    result.NextFrameMs = MillisecondsSince(start);

    result.Renderer = RendererString(window);
    result.Window = std::string(window->GetClassName()) + ", " + displayName;
    if (scene.Parts.empty())
    {
      result.AppliedFrame =
        vtkNormalMapPolyDataMapper::GetAppliedFrameName(mapper->GetLastAppliedFrame());
    }
    for (size_t p = 0; p < scene.Parts.size(); ++p)
    {
      const std::vector<std::string>& names = scene.Parts[p].BlockNames;
      for (unsigned int b = 0; b < names.size(); ++b)
      {
        // A multiblock's leaves have flat indices 1, 2, ... (0 is the dataset itself).
        result.AppliedFrame += (result.AppliedFrame.empty() ? "" : "; ") + names[b] + ": " +
          vtkNormalMapPolyDataMapper::GetAppliedFrameName(
            composites[p]->GetLastAppliedFrame(b + 1));
      }
    }

    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->Update();
    result.Image = vtkSmartPointer<vtkImageData>::New();
    result.Image->DeepCopy(grab->GetOutput());
    // The window goes before the display connection it uses.
    window->Finalize();
  }
  if (!messages.Errors().empty())
  {
    error = "rendering failed: " + messages.Errors().front();
    return false;
  }
  result.Warnings = messages.Warnings();
  return true;
}

vtkSmartPointer<vtkTexture> MakeTexture(vtkImageData* image)
{
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(image);
  texture->InterpolateOn();
  texture->MipmapOn(); // trilinear: a minified normal map does not alias
  texture->RepeatOn();
  return texture;
}

vtkSmartPointer<vtkImageData> ReadImage(const std::string& path, std::string& error)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    error = "cannot open '" + path + "': no such file or not readable";
    return nullptr;
  }
  const std::vector<unsigned char> bytes(
    (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad())
  {
    error = "cannot read '" + path + "'";
    return nullptr;
  }
  // Not vtkPNGReader / vtkJPEGReader: VTK 9.1's PNG reader crashes on a corrupt file (see
  // NormalMapImages.h).
  vtkSmartPointer<vtkImageData> image = NormalMapImages::Decode(bytes.data(), bytes.size(), error);
  if (!image)
  {
    error = "cannot read the image '" + path + "': " + error;
  }
  return image;
}

bool WritePNG(vtkImageData* image, NormalMapFiles::OutputTransaction& output, std::string& error)
{
  NormalMapFiles::VTKMessageCapture messages;
  const std::string path = output.MainPath();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !messages.Errors().empty())
  {
    error = "cannot write '" + output.FinalPath() + "'" +
      (messages.Errors().empty() ? std::string() : ": " + messages.Errors().front());
    return false;
  }
  return true;
}

bool ParseSize(const std::string& text, int& width, int& height)
{
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos || x == 0 || x + 1 >= text.size())
  {
    return false;
  }
  const std::string w = text.substr(0, x), h = text.substr(x + 1);
  if (w.find_first_not_of("0123456789") != std::string::npos ||
    h.find_first_not_of("0123456789") != std::string::npos || w.size() > 5 || h.size() > 5)
  {
    return false;
  }
  width = std::stoi(w);
  height = std::stoi(h);
  return width >= 16 && width <= 8192 && height >= 16 && height <= 8192;
}
}
