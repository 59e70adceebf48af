// SPDX-License-Identifier: BSD-3-Clause
/**
 * Scenes for the mapper's tests: procedural normal maps with analytic normals, meshes with
 * tangent frames, a headless render window, pixel read-back and a small check recorder.
 */
#ifndef NormalMapTestScenes_h
#define NormalMapTestScenes_h

#include "vtkImageData.h"                        // For vtkSmartPointer<vtkImageData>
#include "vtkNormalMapCompositePolyDataMapper.h" // For StockCompositeMapper
#include "vtkPolyData.h"                         // For vtkSmartPointer<vtkPolyData>
#include "vtkRenderWindow.h"                     // For vtkSmartPointer<vtkRenderWindow>
#include "vtkSmartPointer.h"
#include "vtkTexture.h" // For vtkSmartPointer<vtkTexture>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <functional>
#include <string>
#include <vector>

class vtkActor;
class vtkDataObject;
class vtkImageData;
class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;
class vtkTexture;

namespace nmtest
{
/// VTK's own composite mapper, the superclass of ours: vtkCompositePolyDataMapper2 up to VTK 9.2,
/// vtkCompositePolyDataMapper from 9.3.
using StockCompositeMapper = vtkNormalMapCompositePolyDataMapper::Superclass;
/// Its class name, for messages.
std::string StockCompositeName();

/// Height fields whose normal maps the tests render; h and its gradient are analytic.
enum class Pattern
{
  SineBump, // a smooth egg-crate bump, 3 periods each way
  Bricks,   // bricks with bevelled mortar grooves
  Rivets    // hemispherical domes on a grid
};

/// How the generated texture stores the normal.
enum class Storage
{
  OpenGL,            // RGB, green = +v
  DirectX,           // RGB, green = -v
  TwoChannel,        // RG (2 components), green = +v
  TwoChannelDirectX, // RG (2 components), green = -v
  OneChannel         // the height only (not a normal map: for bad-input tests)
};

/// Unit tangent-space normal of a pattern at (u, v) in [0, 1]^2 (x along +u, y along +v).
glm::dvec3 PatternNormal(Pattern pattern, double u, double v);

/// A unit vector component in [-1, 1] as a texel value (0..255).
unsigned char Encode(double x);

/// A size x size texture image of the pattern (texel centres at (i + 0.5) / size).
vtkSmartPointer<vtkImageData> MakeNormalMapImage(Pattern pattern, int size, Storage storage);
/// A size x size RGB map (Encode per channel) of the unit normals normalAt(u, v), sampled at
/// texel centres: for maps whose normals are not a pattern's tangent-space ones.
vtkSmartPointer<vtkImageData> MakeRGBNormalImage(int size,
  const std::function<glm::dvec3(double u, double v)>& normalAt);

/// A texture for a normal map: repeat, linear interpolation (mipmaps follow from the mapper).
vtkSmartPointer<vtkTexture> MakeNormalTexture(vtkImageData* image);

/// A flat quad in the z = 0 plane, [-1, 1]^2, u along +x and v along +y (or -x when
/// mirrored), with normals +z, split into resolution^2 quads of two triangles.
vtkSmartPointer<vtkPolyData> MakeQuad(int resolution, bool mirrorU = false);

/// A UV sphere (u around, v from pole to pole) with normals.
vtkSmartPointer<vtkPolyData> MakeSphere(int resolution);

/// Adds point Tangents and TangentSigns with vtkPolyDataTangentFrames (angle-weighted).
vtkSmartPointer<vtkPolyData> WithTangents(vtkPolyData* mesh);

/// How a mesh from WithTangents stores its tangents (for the mappers' array handling).
enum class TangentLayout
{
  ActiveWithSigns,      // as WithTangents writes them: active float Tangents, TangentSigns
  NamedFloat3WithSigns, // float "TANGENT" (3 components, not active) and TangentSigns
  NamedDouble4,         // double "TANGENT", 4 components, the sign in w (glTF)
  Unsigned,             // active float Tangents, no signs (VTK's vtkPolyDataTangents)
  SignsIgnored,         // active float Tangents, TangentSigns all +1: mirroring ignored
  None                  // no tangents
};

/// A copy of a mesh with tangents and signs (WithTangents) in the given layout.
vtkSmartPointer<vtkPolyData> WithTangentLayout(vtkPolyData* withTangents, TangentLayout layout);

/// A copy of a mesh moved by (dx, dy) after scaling y by sy.
vtkSmartPointer<vtkPolyData> Placed(vtkPolyData* mesh, double dx, double dy, double sy = 1.0);

/// A copy of a mesh with only the triangles whose centroid is left (or right) of x = 0.
vtkSmartPointer<vtkPolyData> Half(vtkPolyData* mesh, bool left);

/// A copy of a mesh without texture coordinates.
vtkSmartPointer<vtkPolyData> WithoutTCoords(vtkPolyData* mesh);

/// An offscreen render window of the given size, ready for a renderer.
vtkSmartPointer<vtkRenderWindow> MakeWindow(int width, int height);

/// Prints once which headless path rendering took (OSMesa or X/Xvfb, and the GL renderer).
void ReportRenderPath(vtkRenderWindow* window);

/// The window's RGB image as last rendered (back buffer), bottom row first.
vtkSmartPointer<vtkImageData> GrabImage(vtkRenderWindow* window);

/// The window's RGB pixels, bottom row first.
std::vector<unsigned char> ReadPixels(vtkRenderWindow* window);

/// The errors VTK reports while run() runs (shader compile errors, say), counted by an output
/// window installed for that time; they are still printed as VTK prints them.
int CountErrors(const std::function<void()>& run);

/// Keeps checking after a failure and reports every failed check.
class Checks
{
public:
  void operator()(bool ok, const std::string& what);
  int Result() const; // EXIT_SUCCESS or EXIT_FAILURE
private:
  int Failures = 0;
};

/// Pixel statistics of two equally sized RGB images over the pixels where mask is true.
struct Difference
{
  int Compared = 0;
  int MaxChannel = 0;        // largest channel difference, 0..255
  double WithinFraction = 0; // share of compared pixels whose max channel difference <= bound
  double MeanChannel = 0;    // mean over compared pixels of their largest channel difference
};
Difference Compare(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b,
  const std::vector<bool>& mask,
  int bound);

/// A mask (for Compare) of the pixels of a width x height image at least `margin` from its edges.
std::vector<bool> InnerPixels(int width, int height, int margin);

/**
 * Mirror symmetry of an image about its middle column, over the pixels covered on both sides
 * and at least 3 pixels from uncovered ones and from the middle seam (where the rasterizer's
 * fill rule, not shading, decides).
 */
Difference MirrorSymmetry(const std::vector<unsigned char>& pixels,
  int width,
  int height,
  int bound);

/// One actor of a flat scene.
struct FlatActor
{
  vtkPolyData* Mesh = nullptr;
  vtkTexture* NormalTexture = nullptr; // none: no normal map
  double NormalScale = 1.0;
  int Encoding = 0;         // vtkNormalMapPolyDataMapper::MapEncodings
  int FrameSource = 0;      // vtkNormalMapPolyDataMapper::FrameSources
  bool StockMapper = false; // VTK's vtkOpenGLPolyDataMapper instead of ours
  int Interpolation = 2;    // VTK_PHONG
  bool TwoSided = true;
  double Scale[3] = { 1.0, 1.0, 1.0 };
  std::string* Shaders = nullptr; // when set: receives the vertex + fragment shader source
  int* AppliedFrame = nullptr;    // when set (our mapper): receives GetLastAppliedFrame()
  /// When set, drawn instead of Mesh through a composite mapper: ours
  /// (vtkNormalMapCompositePolyDataMapper), or VTK's (StockCompositeMapper, with StockMapper).
  vtkDataObject* Blocks = nullptr;
  std::string TangentsArrayName; // our mappers' setting (empty: the active tangents)
  /// When set, the actor's vtkProp::GeneralTextureTransform: 16 values, a row-major 4x4
  /// matrix that VTK applies to the texture coordinates (ParaView's Flip Textures sets one).
  const double* TextureTransform = nullptr;
  /// The mapper's InterpolateScalarsBeforeMapping (ParaView's default is on): whether point
  /// scalars, which color the mesh when it has them, go through the color map as a texture.
  bool InterpolateScalars = false;
  /// Edges drawn over the surface, which VTK draws through a geometry shader.
  bool EdgeVisibility = false;
};

/// The fixed camera and light of the flat scenes, shared with the CPU reference.
struct FlatSetup
{
  int Width = 256;
  int Height = 256;
  double CameraDistance = 5.0;                // camera at (0, 0, d) looking at the origin, y up
  double ViewAngle = 30.0;                    // vertical, degrees
  bool Parallel = false;                      // parallel projection with the same framing at z = 0
  glm::dvec3 LightPosition{ -1.0, 1.5, 2.0 }; // a directional scene light towards the origin
  double Ambient = 0.1, Diffuse = 0.7, Specular = 0.3, SpecularPower = 20.0;
  glm::dvec3 Color{ 1.0, 0.8, 0.6 };
};

/**
 * The offscreen window of a flat scene, not rendered yet: one renderer (black background,
 * two-sided lighting, the setup's scene light and camera) with one actor per FlatActor, in
 * order. Render it as often as needed (benchmarks time it).
 */
vtkSmartPointer<vtkRenderWindow> MakeFlatScene(const FlatSetup& setup,
  const std::vector<FlatActor>& actors);

/**
 * The mirror-symmetry scene: a Rivets-mapped quad with tangents at x in [-2, 0] (u along +x)
 * and its mirror image at x in [0, 2] (u along -x), under a light on the mirror plane x = 0.
 */
struct MirrorScene
{
  FlatSetup Setup;
  vtkSmartPointer<vtkTexture> Texture;
  vtkSmartPointer<vtkPolyData> Left, Right;
};
MirrorScene MakeMirrorScene();

/// Adds a directional scene light from `position` towards the origin.
void AddSceneLight(vtkRenderer* renderer, const glm::dvec3& position);

/// Points the renderer's camera as the setup says (perspective, or parallel with the same framing).
void SetFlatCamera(vtkRenderer* renderer, const FlatSetup& setup);

/// Renders the actors with the setup and returns the pixels (black background).
std::vector<unsigned char> RenderFlat(const FlatSetup& setup, const std::vector<FlatActor>& actors);

/**
 * VTK's Phong shading (its non-PBR fragment code for directional scene lights), in double
 * precision, of a surface point seen at pixel (px, py) with world normal n: 0..255 per channel.
 */
glm::dvec3 ReferenceShade(const FlatSetup& setup, int px, int py, const glm::dvec3& n);

/// Where the pixel centre's view ray meets the plane z = 0.
glm::dvec3 PixelOnPlane(const FlatSetup& setup, int px, int py);

/**
 * Rendered pixels of the flat quad of MakeQuad (perspective setup, actor scale (sx, sy, 1))
 * against ReferenceShade of the pattern's analytic normals, over the quad's pixels two pixels
 * in from its edges (where coverage, not shading, decides the colour).
 */
Difference CompareWithReferenceShading(const FlatSetup& setup,
  const std::vector<unsigned char>& pixels,
  Pattern pattern,
  int bound,
  glm::dvec2 scale = glm::dvec2(1.0));

/**
 * The quad of MakeQuad(resolution) displaced along z by the SineBump height field (2 h(u, v):
 * a texture unit is 2 world units, so slopes match the map's), with the field's analytic
 * normals: the geometry a SineBump normal map stands for.
 */
vtkSmartPointer<vtkPolyData> MakeDisplacedQuad(int resolution);

/// Pixels that differ from the background colour (0 0 0) in either image.
std::vector<bool> CoveredPixels(const std::vector<unsigned char>& a,
  const std::vector<unsigned char>& b);
}

#endif
