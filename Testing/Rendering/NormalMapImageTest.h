// SPDX-License-Identifier: BSD-3-Clause
/**
 * The image tests' harness: a scene compared with its baseline in Testing/Data/Baseline, and
 * the proof that the comparison sees the regressions the scene is there to catch.
 *
 * The comparison is VTK 9.1's vtkImageDifference, driven by vtkTesting's arguments (-V
 * baseline, -T temporary folder; a failure writes <test>.png and <test>.diff.png there). For
 * each pixel it takes the best match (smallest sum of channel differences) among the other
 * image's pixels within +-2 pixels, in both directions, and keeps the worse direction; each
 * channel's difference beyond a threshold is the pixel's excess; the image error is the summed
 * excess in units of 3 x 255 (one pixel wrong by 255 levels in every channel beyond the
 * threshold counts 1). vtkRegressionTestImage uses a threshold of 105 levels, accepts a match of
 * 3x3 means too, and allows an error of 0.15: every shading change below 105 levels passes with
 * an error of 0 (the strength-1 rivets drawn flat, the map dropped, +40 levels over a quarter
 * of the picture). The image tests use instead:
 * - No 3x3 averaging: a pixel must match a pixel, not a neighbourhood's mean.
 * - The +-2 pixel shift stays: it forgives an edge one rasterizer puts a pixel off, and it
 *   cannot hide shading: a region wider than 2 pixels that changed has no match inside it.
 * - ChannelThreshold = 6 levels: driver rounding is 1 or 2 levels (each test's twin checks that
 *   +-2 levels on every pixel passes, with 3x margin); a regression that matters moves shading
 *   by tens of levels.
 * - AllowedError = 1.0: one pixel totally wrong passes, as do about 36 pixels 7 levels beyond
 *   the threshold in every channel; a 10 x 10 pixel region 20 levels off (error 100 x 14 / 255
 *   = 5.5) fails.
 * llvmpipe through Xvfb (Debian's VTK) and through OSMesa render every baseline bit-identically,
 * so the two paths need no allowance of their own.
 *
 * A test program calls RunImageTest with a function that builds its scene, or, given an
 * alteration index, the same scene with one deliberate regression (the map dropped, the sign
 * or green flipped, ...). Run as
 *   NormalMappingRenderingTests TestX -V <dir>/TestX.png -T <temporary dir>
 * it compares the scene with the baseline. With --altered (the ctest twin TestX.CanFail) it
 * passes only when every alteration FAILS the comparison, the scene plus 40 levels over the
 * centre quarter of the picture fails, and the scene plus or minus 2 levels on every pixel
 * passes. With --write-baseline it writes the scene's render to the -V file (what
 * `cmake --build <build> --target NormalMappingBaselines` does for every image test).
 */
#ifndef NormalMapImageTest_h
#define NormalMapImageTest_h

#include "NormalMapTestScenes.h" // For Pattern
#include "vtkPolyData.h"         // For vtkSmartPointer<vtkPolyData>
#include "vtkRenderWindow.h"     // For vtkSmartPointer<vtkRenderWindow>
#include "vtkSmartPointer.h"
#include "vtkTexture.h" // For vtkSmartPointer<vtkTexture>

#include <functional>
#include <string>
#include <vector>

class vtkImageData;

namespace nmtest
{
/// Builds the test's scene (alteration -1) or the scene with one deliberate regression.
using SceneBuilder = std::function<vtkSmartPointer<vtkRenderWindow>(int alteration)>;

/**
 * Runs an image test (see the file comment). `alterations` names each deliberate regression
 * the scene must show, in the order of the builder's alteration index.
 */
int RunImageTest(int argc,
  char* argv[],
  const std::vector<std::string>& alterations,
  const SceneBuilder& build);

/// One view of a grid of views: a mesh, its normal map and the mapper's settings.
struct Panel
{
  vtkPolyData* Mesh = nullptr;
  vtkTexture* Texture = nullptr; // none: no normal map
  int Encoding = 0;              // vtkNormalMapPolyDataMapper::MapEncodings
  int FrameSource = 0;           // vtkNormalMapPolyDataMapper::FrameSources
  double Strength = 1.0;
  double Scale[3] = { 1.0, 1.0, 1.0 };
  double RotateX = 0.0, RotateY = 0.0; // degrees, applied after the scale
  int Interpolation = 2;               // VTK_FLAT, VTK_GOURAUD, VTK_PHONG or VTK_PBR
  bool StockMapper = false;            // VTK's vtkOpenGLPolyDataMapper instead of ours
  double Zoom = 1.4;
};

/**
 * Adds a renderer at (column, row) of a grid of columns x rows views (row 0 on top): dark
 * background, two-sided lighting, a scene light from the upper left, the panel's actor, the
 * camera fit to it.
 */
void AddPanel(vtkRenderWindow* window, int columns, int rows, int column, int row, const Panel& p);

/**
 * The map encoding tests: a rivets map stored as `storage` on a quad and on a sphere (both with
 * point tangents), read as `encoding`; each dome is lit from the upper left, like the light.
 * Alterations: the map read as `otherGreen` (the other green convention: domes lit from the
 * lower left), and the map dropped.
 */
int RunEncodingTest(int argc, char* argv[], Storage storage, int encoding, int otherGreen);

/**
 * A Khronos glTF test model's first mesh with VTK-convention texture coordinates (v up) and
 * MikkTSpace tangent frames from vtkPolyDataTangentFrames, or nullptr when it cannot be read.
 */
vtkSmartPointer<vtkPolyData> LoadKhronosModel(const std::string& file);

/**
 * The folder of a Khronos test model (NormalTangentTest, NormalTangentMirrorTest) in the shared
 * data, $NORMALMAPPING_SHARED_DATA/gltf/<name>/, with <name>.gltf and <name>_Normal.png; or ""
 * after printing why a test that needs it skips (the shared data is absent).
 */
std::string KhronosModelFolder(const std::string& name);

/**
 * A Khronos model's view in `renderer`: one scene light from the upper left, and a head-on
 * parallel camera fit to `bounds` (xmin, xmax, ymin, ymax, zmin, zmax).
 */
void SetKhronosViewpoint(vtkRenderer* renderer, const double bounds[6]);

/**
 * The worst cell of a Khronos test model's grid in a size x size RGB image on black: each cell
 * compared with the first (real-geometry) cell of its group of columns in the same row. Returns
 * the smallest share of a cell's pixels within `bound` levels of its reference, and counts the
 * cells compared.
 */
double WorstCell(const std::vector<unsigned char>& rgb, int size, int bound, int& cells);

/// A Khronos model's normal map (PNG) as a normal texture.
vtkSmartPointer<vtkTexture> LoadKhronosNormalMap(const std::string& file);

/**
 * Adds a renderer over `viewport` (xmin, ymin, xmax, ymax) showing a Khronos model head-on
 * with a parallel camera fit to its bounds, lit from the upper left, black background.
 */
void AddKhronosView(vtkRenderWindow* window,
  const double viewport[4],
  vtkPolyData* model,
  vtkTexture* normalMap,
  int encoding);

/**
 * An object-space normal map of a pattern for the sphere of MakeSphere: each texel holds the
 * pattern's tangent-space normal turned into the sphere's frame at that (u, v) (tangent along
 * +u around the z axis, bitangent along +v towards the +z pole), so the object-space render
 * matches the tangent-space one.
 */
vtkSmartPointer<vtkImageData> MakeObjectSpaceSphereMap(Pattern pattern, int size);
}

#endif
