// SPDX-License-Identifier: BSD-3-Clause
// Rendered pixels against independent answers for what TestNormalMapCPUReference leaves out:
// Flat and Gouraud interpolation and the two-channel DirectX encoding against the CPU
// reference shading; PBR against the displaced geometry it stands for; and an object-space map
// on a curved surface under a rotated, non-uniformly scaled actor against the CPU shading of
// the map's normals transformed by the inverse transpose. Each check has a control that must
// fail it (the map dropped or read with the wrong convention).
#include "NormalMapTestScenes.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkNormalMapPolyDataMapper.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkProperty.h" // VTK_FLAT, VTK_GOURAUD, VTK_PBR
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using Mapper = vtkNormalMapPolyDataMapper;
const double Pi = 3.14159265358979323846;

void Report(const std::string& what, const nmtest::Difference& d, int bound)
{
  std::cout << what << ": " << d.Compared << " pixels, " << 100.0 * d.WithinFraction << "% within "
            << bound << " levels, mean " << d.MeanChannel << ", max " << d.MaxChannel << std::endl;
}

/// An actor of the flat scene with a normal map, a frame source and an interpolation.
nmtest::FlatActor Mapped(vtkPolyData* mesh, vtkTexture* texture, int frame, int interpolation)
{
  nmtest::FlatActor a;
  a.Mesh = mesh;
  a.NormalTexture = texture;
  a.FrameSource = frame;
  a.Interpolation = interpolation;
  return a;
}

std::string FrameName(int frame)
{
  return frame == Mapper::POINT_TANGENTS ? "point tangents" : "screen derivatives";
}

/// A copy of a two-channel (x, y) map image with y negated: the DirectX convention.
vtkSmartPointer<vtkImageData> GreenInverted(vtkImageData* image)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(image);
  auto* texels = static_cast<unsigned char*>(copy->GetScalarPointer());
  const vtkIdType count = copy->GetNumberOfPoints();
  const int components = copy->GetNumberOfScalarComponents();
  for (vtkIdType i = 0; i < count; ++i)
  {
    texels[i * components + 1] = static_cast<unsigned char>(255 - texels[i * components + 1]);
  }
  return copy;
}

// The curved surface of the object-space check: a cap z = H (1 - x^2)(1 - y^2) over the quad
// of MakeQuad (u = (x + 1) / 2, v = (y + 1) / 2), with its analytic normals.
const double CapHeight = 0.4;

glm::dvec3 CapNormal(double x, double y)
{
  const double dzdx = -2.0 * CapHeight * x * (1.0 - y * y);
  const double dzdy = -2.0 * CapHeight * y * (1.0 - x * x);
  return glm::normalize(glm::dvec3(-dzdx, -dzdy, 1.0));
}

vtkSmartPointer<vtkPolyData> MakeCap(int resolution)
{
  auto cap = nmtest::MakeQuad(resolution);
  vtkPoints* points = cap->GetPoints();
  vtkDataArray* normals = cap->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    points->SetPoint(i, p[0], p[1], CapHeight * (1.0 - p[0] * p[0]) * (1.0 - p[1] * p[1]));
    const glm::dvec3 n = CapNormal(p[0], p[1]);
    normals->SetTuple3(i, n.x, n.y, n.z);
  }
  return cap;
}

/// The object-space map's normal at (u, v): the cap's normal tilted by the SineBump pattern
/// (its tangent-space normal applied in the model's x, y, z), so that it differs from the
/// surface normal everywhere the pattern has slope.
glm::dvec3 ObjectSpaceNormal(double u, double v)
{
  const glm::dvec3 bump = nmtest::PatternNormal(nmtest::Pattern::SineBump, u, v);
  const glm::dvec3 cap = CapNormal(2.0 * u - 1.0, 2.0 * v - 1.0);
  return glm::normalize(cap + glm::dvec3(bump.x, bump.y, 0.0));
}

vtkSmartPointer<vtkImageData> MakeObjectSpaceImage(int size)
{
  return nmtest::MakeRGBNormalImage(size, ObjectSpaceNormal);
}
}

int TestNormalMapLightingReference(int, char*[])
{
  nmtest::Checks check;
  nmtest::FlatSetup setup;
  const auto pattern = nmtest::Pattern::SineBump;
  // As in TestNormalMapCPUReference: a 128-texel map magnified over ~190 pixels (bilinear
  // filtering of a smooth field, 0.3% relative error), and its error budget: 8-bit map (under
  // 1 level), filtering (well under 1), float shader arithmetic, final rounding (half a level):
  // 3 levels on 99.5% of the pixels (specular highlights amplify normal error).
  const int bound = 3;
  const double share = 0.995;
  auto openGLImage = nmtest::MakeNormalMapImage(pattern, 128, nmtest::Storage::OpenGL);
  auto openGL = nmtest::MakeNormalTexture(openGLImage);
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(1));

  // Flat and Gouraud: VTK lights both per fragment, Flat with the face normal from screen
  // derivatives (its vertex shader has no point normal), Gouraud with the interpolated point
  // normal. On the flat quad both normals are +z: the same CPU reference as Phong applies.
  for (int interpolation : { VTK_FLAT, VTK_GOURAUD })
  {
    const std::string model = interpolation == VTK_FLAT ? "Flat" : "Gouraud";
    for (int frame : { Mapper::POINT_TANGENTS, Mapper::SCREEN_DERIVATIVES })
    {
      const nmtest::FlatActor a = Mapped(quad, openGL, frame, interpolation);
      const auto d = nmtest::CompareWithReferenceShading(
        setup, nmtest::RenderFlat(setup, { a }), pattern, bound);
      const std::string name = model + ", " + FrameName(frame);
      Report(name, d, bound);
      check(d.Compared > 30000 && d.WithinFraction >= share, name + ": matches the CPU reference");
    }
    nmtest::FlatActor plain; // control: the quad without its map
    plain.Mesh = quad;
    plain.Interpolation = interpolation;
    const auto control = nmtest::CompareWithReferenceShading(
      setup, nmtest::RenderFlat(setup, { plain }), pattern, bound);
    Report(model + " without the map (control)", control, bound);
    check(control.WithinFraction < 0.5, model + ": the control fails the comparison");
  }

  // Two channels, DirectX convention: x and y stored, y negated, z rebuilt. z from 8-bit x and
  // y adds under half a level's worth of angle at these slopes (z >= 0.87): the same budget.
  {
    auto twoChannel = nmtest::MakeNormalMapImage(pattern, 128, nmtest::Storage::TwoChannel);
    auto directX = nmtest::MakeNormalTexture(GreenInverted(twoChannel));
    for (int encoding : { Mapper::TWO_CHANNEL_DIRECTX, Mapper::TWO_CHANNEL_OPENGL })
    {
      nmtest::FlatActor a;
      a.Mesh = quad;
      a.NormalTexture = directX;
      a.Encoding = encoding;
      const auto d = nmtest::CompareWithReferenceShading(
        setup, nmtest::RenderFlat(setup, { a }), pattern, bound);
      if (encoding == Mapper::TWO_CHANNEL_DIRECTX)
      {
        Report("two-channel DirectX map", d, bound);
        check(d.WithinFraction >= share, "two-channel DirectX: matches the CPU reference");
      }
      else
      {
        Report("the same map read as two-channel OpenGL (control)", d, bound);
        check(d.WithinFraction < 0.8, "two-channel DirectX: the wrong convention is detected");
      }
    }
  }

  // PBR: there is no CPU reference of VTK's PBR model here, so the reference is the geometry
  // the map stands for, lit by VTK's own PBR code from analytic normals (parallel projection
  // so displaced points land on the same pixels; see TestNormalMapGeometryTruth for the
  // budget: map quantization, vertex-normal interpolation, the view vector of the relief).
  // 4 levels on 99% of the pixels well inside the quad.
  {
    nmtest::FlatSetup parallel = setup;
    parallel.Parallel = true;
    auto displaced = nmtest::MakeDisplacedQuad(384);
    nmtest::FlatActor geometry;
    geometry.Mesh = displaced;
    geometry.Interpolation = VTK_PBR;
    const auto truth = nmtest::RenderFlat(parallel, { geometry });
    const std::vector<bool> inner = nmtest::InnerPixels(parallel.Width, parallel.Height, 30);
    const int pbrBound = 4;
    for (int frame : { Mapper::POINT_TANGENTS, Mapper::SCREEN_DERIVATIVES })
    {
      const auto d =
        nmtest::Compare(nmtest::RenderFlat(parallel, { Mapped(quad, openGL, frame, VTK_PBR) }),
          truth,
          inner,
          pbrBound);
      const std::string name = "PBR, " + FrameName(frame);
      Report(name + " vs displaced geometry", d, pbrBound);
      check(d.WithinFraction >= 0.99, name + ": lights the quad like the geometry");
    }
    nmtest::FlatActor plain;
    plain.Mesh = quad;
    plain.Interpolation = VTK_PBR;
    const auto control =
      nmtest::Compare(nmtest::RenderFlat(parallel, { plain }), truth, inner, pbrBound);
    Report("PBR without the map (control)", control, pbrBound);
    check(control.WithinFraction < 0.5, "PBR: the control fails the comparison");
  }

  // Object space on a curved surface, actor rotated 30 degrees about z and scaled (1.3, 0.8, 1):
  // the normal at a pixel is the map's model normal times the inverse transpose of R S, that
  // is R S^-1, whatever the surface's own normal and tangent frame. Parallel projection along
  // -z, so a pixel's model (x, y) (hence its texture coordinates) follows from undoing R S in
  // the plane, exactly: the cap's texture coordinates are linear in x and y. No specular term,
  // so the relief's height (which moves the view vector) does not enter. Budget as above: the
  // 8-bit map moves the normal by up to ~0.007 rad, ~1.2 levels of diffuse light.
  {
    nmtest::FlatSetup objectSetup = setup;
    objectSetup.Parallel = true;
    objectSetup.Specular = 0.0;
    auto cap = MakeCap(64);
    auto objectMap = nmtest::MakeNormalTexture(MakeObjectSpaceImage(128));
    const double angle = 30.0 * Pi / 180.0, sx = 1.3, sy = 0.8;
    auto render = [&](int encoding)
    {
      nmtest::FlatActor a;
      a.Mesh = cap;
      a.NormalTexture = objectMap;
      a.Encoding = encoding;
      a.Scale[0] = sx;
      a.Scale[1] = sy;
      auto window = nmtest::MakeFlatScene(objectSetup, { a });
      window->GetRenderers()->GetFirstRenderer()->GetActors()->GetLastActor()->RotateZ(30.0);
      window->Render();
      return nmtest::ReadPixels(window);
    };
    std::vector<unsigned char> reference(objectSetup.Width * objectSetup.Height * 3, 0);
    std::vector<bool> mask(objectSetup.Width * objectSetup.Height, false);
    // Two pixels in from the cap's outline, where coverage decides the colour.
    const double pixel = 2.0 * objectSetup.CameraDistance *
      std::tan(objectSetup.ViewAngle * Pi / 360.0) / objectSetup.Height;
    for (int py = 0; py < objectSetup.Height; ++py)
    {
      for (int px = 0; px < objectSetup.Width; ++px)
      {
        const glm::dvec3 world = nmtest::PixelOnPlane(objectSetup, px, py);
        // Undo the rotation, then the scale.
        const double x = (std::cos(angle) * world.x + std::sin(angle) * world.y) / sx;
        const double y = (-std::sin(angle) * world.x + std::cos(angle) * world.y) / sy;
        if (std::abs(x) > 1.0 - 2.0 * pixel / sy || std::abs(y) > 1.0 - 2.0 * pixel / sy)
        {
          continue;
        }
        const glm::dvec3 model = ObjectSpaceNormal((x + 1.0) / 2.0, (y + 1.0) / 2.0);
        const glm::dvec3 scaled(model.x / sx, model.y / sy, model.z);
        const glm::dvec3 n =
          glm::normalize(glm::dvec3(std::cos(angle) * scaled.x - std::sin(angle) * scaled.y,
            std::sin(angle) * scaled.x + std::cos(angle) * scaled.y,
            scaled.z));
        const glm::dvec3 color = nmtest::ReferenceShade(objectSetup, px, py, n);
        const size_t index = static_cast<size_t>(py) * objectSetup.Width + px;
        mask[index] = true;
        for (int c = 0; c < 3; ++c)
        {
          reference[3 * index + c] = static_cast<unsigned char>(std::lround(color[c]));
        }
      }
    }
    const auto d = nmtest::Compare(render(Mapper::OBJECT_SPACE), reference, mask, bound);
    Report("object space, curved, rotated and scaled", d, bound);
    check(d.Compared > 20000 && d.WithinFraction >= share,
      "object space on a curved surface: matches the CPU reference");
    // Control: the same texels read as a tangent-space map (applied in the cap's own frame).
    const auto control =
      nmtest::Compare(render(Mapper::TANGENT_SPACE_OPENGL), reference, mask, bound);
    Report("the same map read as tangent space (control)", control, bound);
    check(control.WithinFraction < 0.5, "object space: reading it in tangent space is detected");
  }
  return check.Result();
}
