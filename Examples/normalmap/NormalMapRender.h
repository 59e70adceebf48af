// SPDX-License-Identifier: BSD-3-Clause
// Offscreen rendering for the normalmap tool's render and demo commands: one mesh drawn with
// vtkNormalMapPolyDataMapper, or groups of meshes (a glTF file's primitives, one group per
// normal map) drawn with vtkNormalMapCompositePolyDataMapper, into an offscreen window, read
// back as an RGB image, and written as PNG all-or-nothing.
//
// Debian's VTK 9.1 renders through X only (no OSMesa, no EGL), and VTK aborts the process when
// it cannot open the display; Render() opens the display itself first, so a missing X server
// is one error line instead of a crash.
#ifndef NormalMapRender_h
#define NormalMapRender_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkImageData;
class vtkMultiBlockDataSet;
class vtkPolyData;
class vtkTexture;

namespace NormalMapFiles
{
class OutputTransaction;
}

namespace NormalMapRender
{
/// The window's background (RGB, 0..1).
constexpr double Background[3] = { 0.1, 0.1, 0.12 };

/// Meshes drawn by one actor through vtkNormalMapCompositePolyDataMapper, with one normal map.
struct Part
{
  vtkMultiBlockDataSet* Blocks = nullptr;
  std::vector<std::string> BlockNames; // for the report, in block order
  vtkTexture* NormalMap = nullptr;     // none: drawn without a map
  double Strength = 1.0;
};

struct Scene
{
  vtkPolyData* Mesh = nullptr;
  vtkTexture* NormalMap = nullptr; // none: drawn without a map
  double Strength = 1.0;
  /// Instead of Mesh, NormalMap and Strength: one actor per part.
  std::vector<Part> Parts;
  int Encoding = 0;    // vtkNormalMapPolyDataMapper::MapEncodings
  int FrameSource = 0; // vtkNormalMapPolyDataMapper::FrameSources
  bool PBR = false;    // PBR interpolation (metallic 0, roughness 0.45) instead of Phong
  int Width = 800;
  int Height = 600;
  double Color[3] = { 0.85, 0.62, 0.48 };

  /// The camera: fitted to the mesh, then turned and zoomed; or placed when PlaceCamera.
  double Azimuth = 0.0;
  double Elevation = 0.0;
  double Zoom = 1.0;
  bool PlaceCamera = false;
  double CameraPosition[3] = { 0.0, 0.0, 1.0 };
  double FocalPoint[3] = { 0.0, 0.0, 0.0 };
  double ViewUp[3] = { 0.0, 1.0, 0.0 };

  /// One directional light, from LightPosition towards the focal point; in camera
  /// coordinates (it turns with the camera) unless LightInScene.
  double LightPosition[3] = { -0.6, 0.8, 1.0 };
  bool LightInScene = false;
};

struct Rendered
{
  vtkSmartPointer<vtkImageData> Image; // RGB, bottom row first
  double FirstFrameMs = 0.0;           // includes building the shaders and uploading the data
  double NextFrameMs = 0.0;            // the same frame again
  std::string Renderer;                // GL_RENDERER, from ReportCapabilities
  std::string Window;                  // the render window class and the display it used
  std::string AppliedFrame;            // the mappers' GetLastAppliedFrame(): the frame's name, or
                                       // "<block name>: <frame>; ..." for parts
  std::vector<std::string> Warnings;   // VTK's warnings during the render, one line each
};

/// Renders the scene offscreen; false with `error` (one line) when no window can be made.
bool Render(const Scene& scene, Rendered& result, std::string& error);

/// A repeating, interpolated texture for a normal map image.
vtkSmartPointer<vtkTexture> MakeTexture(vtkImageData* image);

/// Reads a PNG or JPEG image (NormalMapImages: safe on corrupt files); nullptr with `error`
/// (one line) when it cannot.
vtkSmartPointer<vtkImageData> ReadImage(const std::string& path, std::string& error);

/// Writes `image` as PNG into the transaction's folder (Commit() publishes it).
bool WritePNG(vtkImageData* image, NormalMapFiles::OutputTransaction& output, std::string& error);

/// "WxH" with both in [16, 8192].
bool ParseSize(const std::string& text, int& width, int& height);
}

#endif
