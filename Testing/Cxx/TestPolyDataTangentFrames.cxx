// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkPolyDataTangentFrames through the pipeline.
#include "NormalMappingGrid.h"
#include "NormalMappingMessages.h"
#include "NormalMappingProgress.h"
#include "NormalMappingShuffle.h"
#include "NormalMappingThreads.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCubeSource.h"
#include "vtkCylinderSource.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkLookupTable.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkPolyDataTangents.h"
#include "vtkSMPTools.h"
#include "vtkShortArray.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkStripper.h"
#include "vtkTextureMapToCylinder.h"
#include "vtkTextureMapToPlane.h"
#include "vtkTextureMapToSphere.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkVersionMacros.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
const double Pi = std::acos(-1.0);
using Vec = std::array<double, 3>;

Vec Get3(vtkDataArray* a, vtkIdType i)
{
  Vec v;
  a->GetTuple(i, v.data());
  return v;
}
double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
double Norm(const Vec& a)
{
  return std::sqrt(Dot(a, a));
}
Vec Minus(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec Scaled(double s, const Vec& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
double AngleDeg(const Vec& a, const Vec& b)
{
  return std::atan2(Norm(Cross(a, b)), Dot(a, b)) * 180.0 / Pi;
}

/// The invariants every output must meet: finite unit tangents perpendicular to the normals,
/// signs of exactly +1 or -1, and bitangents (when present) equal to sign * cross(N, T).
/// Output arrays are float unless asked otherwise: a unit vector rounded to float has length
/// 1 within 2^-23 per component, so 1e-6 bounds both |T| - 1 and T.N (N is float too).
void ExpectValidFrames(vtkPolyData* out, double tolerance = 1e-6)
{
  vtkPointData* pd = out->GetPointData();
  vtkDataArray* t = pd->GetTangents();
  vtkDataArray* s = pd->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  vtkDataArray* n = pd->GetNormals();
  vtkDataArray* b = pd->GetArray(vtkPolyDataTangentFrames::BitangentsArrayName());
  ASSERT_NE(t, nullptr);
  ASSERT_NE(s, nullptr);
  ASSERT_EQ(t->GetNumberOfTuples(), out->GetNumberOfPoints());
  ASSERT_EQ(s->GetNumberOfTuples(), out->GetNumberOfPoints());
  vtkIdType bad = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints() && bad < 10; ++p)
  {
    const Vec tv = Get3(t, p);
    const double sign = s->GetComponent(p, 0);
    const bool finite = std::isfinite(tv[0]) && std::isfinite(tv[1]) && std::isfinite(tv[2]);
    EXPECT_TRUE(finite) << "point " << p;
    EXPECT_NEAR(Norm(tv), 1.0, tolerance) << "point " << p;
    EXPECT_TRUE(sign == 1.0 || sign == -1.0) << "point " << p << " sign " << sign;
    if (n)
    {
      Vec nv = Get3(n, p);
      const double len = Norm(nv);
      if (std::isfinite(len) && len > 0)
      {
        EXPECT_NEAR(Dot(tv, nv) / len, 0.0, tolerance) << "point " << p;
        if (b)
        {
          const Vec c = Cross(nv, tv);
          const Vec bv = Get3(b, p);
          // The filter rounds its double cross product once; the test crosses the rounded T
          // and N, whose roundings add about two more: 4 tolerances bound the three.
          for (int k = 0; k < 3; ++k)
          {
            EXPECT_NEAR(bv[k], sign * c[k] / len, 4 * tolerance) << "point " << p;
          }
        }
      }
    }
    bad += (finite && std::abs(Norm(tv) - 1.0) <= tolerance) ? 0 : 1;
  }
}

vtkSmartPointer<vtkPolyData> RunFrames(vtkPolyData* input,
  const std::function<void(vtkPolyDataTangentFrames*)>& configure = {})
{
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  if (configure)
  {
    configure(filter);
  }
  filter->Update();
  return filter->GetOutput();
}

using NormalMappingTesting::MakeGrid;

struct ErrorStats
{
  double Mean = 0, Max = 0;
};

/// Angle between each output tangent and the analytic dP/du projected on the tangent plane.
ErrorStats CompareToAnalytic(vtkPolyData* out,
  const std::function<Vec(const Vec&)>& dPdu,
  const std::function<bool(const Vec&)>& include = {})
{
  ErrorStats stats;
  vtkDataArray* t = out->GetPointData()->GetTangents();
  vtkDataArray* n = out->GetPointData()->GetNormals();
  vtkIdType count = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    Vec x;
    out->GetPoint(p, x.data());
    if (include && !include(x))
    {
      continue;
    }
    const Vec nv = Get3(n, p);
    Vec d = dPdu(x);
    const double dn = Dot(d, nv);
    for (int k = 0; k < 3; ++k)
    {
      d[k] -= dn * nv[k];
    }
    const double e = AngleDeg(Get3(t, p), d);
    stats.Mean += e;
    stats.Max = std::max(stats.Max, e);
    ++count;
  }
  stats.Mean /= std::max<vtkIdType>(count, 1);
  return stats;
}

const int AllMethods[] = { vtkPolyDataTangentFrames::UNWEIGHTED,
  vtkPolyDataTangentFrames::AREA_WEIGHTED,
  vtkPolyDataTangentFrames::ANGLE_WEIGHTED };
} // namespace

// ------------------------------------------------------------------ analytic surfaces

TEST(PolyDataTangentFrames, PlaneWithRotatedUVIsExact)
{
  const double a = 0.7; // u = cos(a) x + sin(a) y  =>  dP/du = (cos a, sin a, 0)
  auto mesh = MakeGrid(
    16,
    16,
    [](double s, double t) {
      return Vec{ s, t, 0.0 };
    },
    [](double, double) {
      return Vec{ 0, 0, 1 };
    },
    [a](double x, double y)
    {
      return std::array<double, 2>{ std::cos(a) * x + std::sin(a) * y,
        -std::sin(a) * x + std::cos(a) * y };
    });
  for (int method : AllMethods)
  {
    auto out = RunFrames(mesh, [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); });
    ExpectValidFrames(out);
    const ErrorStats e = CompareToAnalytic(out,
      [a](const Vec&) {
        return Vec{ std::cos(a), std::sin(a), 0 };
      });
    // Every triangle has the exact frame; only the float output rounding remains: 2^-24 per
    // component is ~3.4e-6 degrees, bounded with margin by 1e-5.
    EXPECT_LT(e.Max, 1e-5) << vtkPolyDataTangentFrames::GetMethodName(method);
    EXPECT_EQ(out->GetPointData()->GetArray("TangentSigns")->GetRange()[0], 1.0);
  }
}

namespace
{
// Analytic surfaces, parametrized over [0,1]^2 with uv = (s, t).
struct Surface
{
  const char* Name;
  std::function<Vec(double, double)> P, N;
  std::function<Vec(const Vec&)> dPdu;     // from the position
  std::function<bool(const Vec&)> Include; // points where the analytic frame is defined
  double AngularStep(int n) const { return 2.0 * Pi / n; }
};

std::vector<Surface> AnalyticSurfaces()
{
  const double R = 1.0, r = 0.4;
  return {
    { "cylinder",
      [](double s, double t) {
        return Vec{ std::cos(2 * Pi * s), std::sin(2 * Pi * s), 2.0 * t };
      },
      [](double s, double) {
        return Vec{ std::cos(2 * Pi * s), std::sin(2 * Pi * s), 0 };
      },
      [](const Vec& x) {
        return Vec{ -x[1], x[0], 0 };
      },
      {} },
    { "sphere (latitudes within 60 degrees)",
      [](double s, double t)
      {
        const double th = Pi * (0.1 + 0.8 * t), ph = 2 * Pi * s;
        return Vec{ std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th) };
      },
      [](double s, double t)
      {
        const double th = Pi * (0.1 + 0.8 * t), ph = 2 * Pi * s;
        return Vec{ std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), -std::cos(th) };
      },
      [](const Vec& x) {
        return Vec{ -x[1], x[0], 0 };
      },
      [](const Vec& x) { return std::abs(x[2]) < std::sin(Pi / 3); } },
    { "torus",
      [=](double s, double t)
      {
        const double ph = 2 * Pi * s, th = 2 * Pi * t, ring = R + r * std::cos(th);
        return Vec{ ring * std::cos(ph), ring * std::sin(ph), r * std::sin(th) };
      },
      [](double s, double t)
      {
        const double ph = 2 * Pi * s, th = 2 * Pi * t;
        return Vec{ std::cos(th) * std::cos(ph), std::cos(th) * std::sin(ph), std::sin(th) };
      },
      [](const Vec& x) {
        return Vec{ -x[1], x[0], 0 };
      },
      {} },
  };
}
}

TEST(PolyDataTangentFrames, AnalyticSurfacesConvergeUnderRefinement)
{
  for (const Surface& surface : AnalyticSurfaces())
  {
    for (int method : AllMethods)
    {
      std::vector<ErrorStats> errors;
      for (int n : { 16, 32, 64 })
      {
        auto mesh = MakeGrid(n,
          n,
          surface.P,
          surface.N,
          [](double s, double t) {
            return std::array<double, 2>{ s, t };
          });
        auto out = RunFrames(mesh,
          [&](vtkPolyDataTangentFrames* f)
          {
            f->SetMethod(method);
            f->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
          });
        ExpectValidFrames(out, 1e-12);
        errors.push_back(CompareToAnalytic(out, surface.dPdu, surface.Include));
        // A triangle's dP/du is the direction of a chord of the u-curve through its corner,
        // which turns by half the angular step (2 pi / n) across one cell: no weighting of
        // chords on either side can be further from the true tangent than that. Points on the
        // u seam see one side only and reach the bound exactly where the normal is
        // perpendicular to the plane the chord turns in (the top and bottom of the torus), so
        // the bound holds with equality up to rounding (1e-12 relative).
        const double bound = 0.5 * 360.0 / n * (1 + 1e-12);
        EXPECT_LE(errors.back().Max, bound)
          << surface.Name << " " << vtkPolyDataTangentFrames::GetMethodName(method) << " n=" << n;
      }
      for (size_t i = 1; i < errors.size(); ++i)
      {
        // Halving the cell size at least halves the error (first order, the chord argument);
        // symmetric fans cancel the first-order term and usually do much better.
        EXPECT_LT(errors[i].Max, 0.55 * errors[i - 1].Max + 1e-9)
          << surface.Name << " " << vtkPolyDataTangentFrames::GetMethodName(method);
        EXPECT_LT(errors[i].Mean, 0.55 * errors[i - 1].Mean + 1e-9)
          << surface.Name << " " << vtkPolyDataTangentFrames::GetMethodName(method);
      }
      std::cout << surface.Name << " " << vtkPolyDataTangentFrames::GetMethodName(method)
                << ": max angle (deg) at n=16,32,64: " << errors[0].Max << " " << errors[1].Max
                << " " << errors[2].Max << "; mean " << errors[0].Mean << " " << errors[1].Mean
                << " " << errors[2].Mean << "\n";
    }
  }
}

// ------------------------------------------------------------------ mirrored UVs

namespace
{
/// MakeTorus' options for a u x v torus with the mirrored half.
vtkNormalMapping::TorusOptions MirroredTorusOptions(int u, int v)
{
  vtkNormalMapping::TorusOptions options;
  options.U = u;
  options.V = v;
  options.MirrorU = true;
  return options;
}

void CheckMirroredTorus(int u, int v)
{
  const vtkNormalMapping::TorusOptions options = MirroredTorusOptions(u, v);
  auto mesh = vtkNormalMapping::MakeTorus(options);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->ComputeBitangentsOn();
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  ExpectValidFrames(out);

  // Two mirror seams (s = 0 and s = 1/2), each a column of V + 1 points.
  const vtkIdType seamPoints = 2 * (options.V + 1);
  EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), seamPoints);
  EXPECT_EQ(filter->GetNumberOfSplitPoints(), seamPoints);
  EXPECT_EQ(out->GetNumberOfPoints(), mesh->GetNumberOfPoints() + seamPoints);
  EXPECT_EQ(out->GetNumberOfPolys(), mesh->GetNumberOfPolys());
  EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 0);
  EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 0);

  // Every point, including both copies of the seam points: the tangent is sign * the analytic
  // direction (-sin phi, cos phi, 0), and the sign is the side's handedness.
  vtkDataArray* t = out->GetPointData()->GetTangents();
  vtkDataArray* s = out->GetPointData()->GetArray("TangentSigns");
  vtkDataArray* tc = out->GetPointData()->GetTCoords();
  int negative = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    Vec x;
    out->GetPoint(p, x.data());
    const double phi = std::atan2(x[1], x[0]);
    const double sign = s->GetComponent(p, 0);
    const Vec expected{ -sign * std::sin(phi), sign * std::cos(phi), 0 };
    // Chord error bound as in the analytic test: half of 360/U degrees, reached on the seams
    // where each copy's frame comes from one side only; plus the float rounding of the points:
    // each coordinate (|x| < 2) is off by at most 2^-23, an edge's direction then by at most
    // 2 sqrt(3) 2^-23 / L < 2^-20 / L radians, L the shortest edge along u, 2 pi (R - r) / U.
    const double shortest = 2 * Pi * (options.RingRadius - options.TubeRadius) / options.U;
    EXPECT_LE(AngleDeg(Get3(t, p), expected),
      0.5 * 360.0 / options.U + std::ldexp(1.0, -20) / shortest * 180.0 / Pi)
      << "point " << p;
    const double frac = std::fmod(phi / (2 * Pi) + 1.0, 1.0);
    const bool onSeam = std::min({ frac, std::abs(frac - 0.5), 1 - frac }) < 1e-6;
    if (!onSeam)
    {
      EXPECT_EQ(sign, frac < 0.5 ? 1.0 : -1.0) << "point " << p;
    }
    negative += sign < 0 ? 1 : 0;
    (void)tc;
  }
  // The copies are the -1 side: the mirrored half has as many points as the other.
  EXPECT_EQ(negative, out->GetNumberOfPoints() / 2);

  // Each triangle's corners carry its handedness: no triangle mixes the two frames.
  vtkIdType npts;
  const vtkIdType* pts;
  vtkCellArray* polys = out->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    const double s0 = s->GetComponent(pts[0], 0);
    EXPECT_EQ(s->GetComponent(pts[1], 0), s0);
    EXPECT_EQ(s->GetComponent(pts[2], 0), s0);
  }
}
}

TEST(PolyDataTangentFrames, MirroredTorusSplitsSeamsAndSignsMirroredHalf)
{
  CheckMirroredTorus(64, 16);
  // 267,537 points: several chunks of triangles, so that two threads share the sums.
  CheckMirroredTorus(1040, 256);
}

/// Calls f(a, b, c) for every triangle of the polygons (fans from corner 0) and strips (every
/// odd triangle reversed) of `mesh`, with its point ids.
void ForEachTriangle(vtkPolyData* mesh,
  const std::function<void(vtkIdType, vtkIdType, vtkIdType)>& f)
{
  vtkIdType n;
  const vtkIdType* pts;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, pts);)
  {
    for (vtkIdType j = 1; j + 1 < n; ++j)
    {
      f(pts[0], pts[j], pts[j + 1]);
    }
  }
  vtkCellArray* strips = mesh->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(n, pts);)
  {
    for (vtkIdType j = 0; j + 2 < n; ++j)
    {
      if (j % 2 == 0)
      {
        f(pts[j], pts[j + 1], pts[j + 2]);
      }
      else
      {
        f(pts[j + 1], pts[j], pts[j + 2]);
      }
    }
  }
}

/**
 * For a mesh in the xy plane (winding normal +z up to the triangles' orientation): at each corner
 * of each triangle, the tangent is along the triangle's own dP/du and the sign is that of its UV
 * winding. Returns the number of triangles.
 */
int ExpectEachTriangleSeesItsOwnFrame(vtkPolyData* out)
{
  vtkDataArray* t = out->GetPointData()->GetTangents();
  vtkDataArray* sign = out->GetPointData()->GetArray("TangentSigns");
  vtkDataArray* tc = out->GetPointData()->GetTCoords();
  int triangleCount = 0;
  ForEachTriangle(out,
    [&](vtkIdType a, vtkIdType b, vtkIdType c)
    {
      ++triangleCount;
      Vec pa, pb, pc;
      out->GetPoint(a, pa.data());
      out->GetPoint(b, pb.data());
      out->GetPoint(c, pc.data());
      const Vec e1{ pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
      const Vec e2{ pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2] };
      const double du1 = tc->GetComponent(b, 0) - tc->GetComponent(a, 0);
      const double dv1 = tc->GetComponent(b, 1) - tc->GetComponent(a, 1);
      const double du2 = tc->GetComponent(c, 0) - tc->GetComponent(a, 0);
      const double dv2 = tc->GetComponent(c, 1) - tc->GetComponent(a, 1);
      const double det = du1 * dv2 - du2 * dv1;
      // dP/du = (dv2 e1 - dv1 e2) / det; the winding normal is +z.
      const Vec dPdu{ (dv2 * e1[0] - dv1 * e2[0]) / det, (dv2 * e1[1] - dv1 * e2[1]) / det, 0 };
      const double winding = Cross(e1, e2)[2] > 0 ? 1.0 : -1.0;
      for (vtkIdType p : { a, b, c })
      {
        // The frames are exact up to float rounding of the output.
        EXPECT_LT(AngleDeg(Get3(t, p), dPdu), 1e-4) << "point " << p;
        EXPECT_EQ(sign->GetComponent(p, 0), det * winding > 0 ? 1.0 : -1.0) << "point " << p;
      }
    });
  return triangleCount;
}

TEST(PolyDataTangentFrames, SplitCornersOfPolygonsAndStripsSeeTheirOwnFrame)
{
  // A plane over [-0.5, 0.5]^2 whose texture is mirrored at x = 0 (u = |2x|): u grows towards -x
  // on the left half and towards +x on the right one. Stored as quads, as triangles and as strips,
  // every triangle must find at each of its corners its own frame: the tangent along its dP/du and
  // the sign of its UV winding, also at the seam points, whose copies take the right half; with
  // the weighted methods and with MikkTSpace, which share the re-pointing of split corners.
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(8, 4);
  plane->Update();
  vtkNew<vtkPolyData> quads;
  quads->DeepCopy(plane->GetOutput());
  vtkDataArray* uv = quads->GetPointData()->GetTCoords();
  for (vtkIdType p = 0; p < quads->GetNumberOfPoints(); ++p)
  {
    uv->SetComponent(p, 0, std::abs(2.0 * quads->GetPoint(p)[0]));
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(quads);
  vtkNew<vtkStripper> strips;
  strips->SetInputConnection(triangles->GetOutputPort());
  strips->Update();
  ASSERT_GT(strips->GetOutput()->GetNumberOfStrips(), 0);
  ASSERT_EQ(strips->GetOutput()->GetNumberOfPolys(), 0);

  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
    for (vtkPolyData* mesh :
      { static_cast<vtkPolyData*>(quads), triangles->GetOutput(), strips->GetOutput() })
    {
      SCOPED_TRACE(mesh->GetNumberOfStrips() > 0
          ? "strips"
          : (mesh->GetPolys()->IsHomogeneous() == 4 ? "quads" : "triangles"));
      SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
      vtkSmartPointer<vtkPolyData> out =
        RunFrames(mesh, [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); });
      EXPECT_EQ(out->GetNumberOfPoints(), mesh->GetNumberOfPoints() + 5); // the seam column
      EXPECT_EQ(ExpectEachTriangleSeesItsOwnFrame(out), 64);
    }
}

/// The values of a point or cell array, as doubles, for exact comparison.
std::vector<double> ValuesOf(vtkDataArray* array)
{
  std::vector<double> values;
  for (vtkIdType i = 0; array && i < array->GetNumberOfValues(); ++i)
  {
    values.push_back(array->GetVariantValue(i).ToDouble());
  }
  return values;
}

/// The point ids of every polygon, then every strip, each cell prefixed by its size.
std::vector<vtkIdType> ConnectivityOf(vtkPolyData* mesh)
{
  std::vector<vtkIdType> ids;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    vtkIdType n;
    const vtkIdType* pts;
    for (cells->InitTraversal(); cells->GetNextCell(n, pts);)
    {
      ids.push_back(n);
      ids.insert(ids.end(), pts, pts + n);
    }
  }
  return ids;
}

TEST(PolyDataTangentFrames, CellsWhoseCornersNeedBothSidesAreCutIntoTriangles)
{
  // 1. One strip across a mirror seam (u = |x - 2|, points in pairs along x), with a cell array:
  //    at the seam points, strip triangles of both handednesses share a strip corner, which has
  //    one point id. The strip winds counterclockwise about its normals (+z). With splitting, every
  //    method cuts the strip into its 8 triangles, as one-triangle strips in strip order, and
  //    splits the 2 seam points, so that each triangle sees its own frame at each corner. The
  //    output is the one for those one-triangle strips given as input, bit for bit; each takes the
  //    strip's cell data but for its global id. Without splitting the strip stays whole (its seam
  //    points take one side's frame, as conflicts).
  const auto makeStrip = [](bool cut)
  {
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> uv, normals;
    uv->SetNumberOfComponents(2);
    normals->SetNumberOfComponents(3);
    std::vector<vtkIdType> ids;
    for (int i = 0; i <= 4; ++i)
    {
      for (int j : { 1, 0 })
      {
        ids.push_back(points->InsertNextPoint(i, j, 0));
        uv->InsertNextTuple2(std::abs(i - 2.0), j);
        normals->InsertNextTuple3(0, 0, 1);
      }
    }
    vtkNew<vtkCellArray> strips;
    vtkNew<vtkIntArray> tag;
    tag->SetName("Tag");
    if (!cut)
    {
      strips->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
      tag->InsertNextValue(7);
    }
    for (vtkIdType j = 0; cut && j + 2 < static_cast<vtkIdType>(ids.size()); ++j)
    {
      // Strip triangle j as a strip of its own, every odd one reversed to keep the winding.
      const vtkIdType tri[3] = { ids[j % 2 ? j + 1 : j], ids[j % 2 ? j : j + 1], ids[j + 2] };
      strips->InsertNextCell(3, tri);
      tag->InsertNextValue(7);
    }
    vtkNew<vtkPolyData> strip;
    strip->SetPoints(points);
    strip->SetStrips(strips);
    strip->GetPointData()->SetTCoords(uv);
    strip->GetPointData()->SetNormals(normals);
    strip->GetCellData()->AddArray(tag);
    vtkNew<vtkIdTypeArray> globalIds; // one id per cell
    globalIds->SetName("GlobalIds");
    for (vtkIdType c = 0; c < strips->GetNumberOfCells(); ++c)
    {
      globalIds->InsertNextValue(100 + c);
    }
    strip->GetCellData()->SetGlobalIds(globalIds);
    vtkNew<vtkIntArray> empty; // shorter than the cells
    empty->SetName("Empty");
    strip->GetCellData()->AddArray(empty);
    return vtkSmartPointer<vtkPolyData>(strip);
  };
  const vtkSmartPointer<vtkPolyData> strip = makeStrip(false);
  const vtkSmartPointer<vtkPolyData> triangles = makeStrip(true);
  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    for (bool splitting : { true, false })
    {
      SCOPED_TRACE(splitting ? "splitting" : "no splitting");
      const auto run = [&](vtkPolyData* input)
      {
        vtkNew<vtkPolyDataTangentFrames> filter;
        Messages messages(filter);
        filter->SetInputData(input);
        filter->SetMethod(method);
        filter->SetSplitting(splitting);
        filter->ComputeCellTangentsOn();
        filter->Update();
        EXPECT_TRUE(messages.Warnings.empty()) << messages.Warnings.front();
        EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), 2);
        EXPECT_EQ(filter->GetNumberOfSplitPoints(), splitting ? 2 : 0);
        vtkSmartPointer<vtkPolyData> out = filter->GetOutput();
        ExpectValidFrames(out);
        return out;
      };
      vtkSmartPointer<vtkPolyData> out = run(strip);
      EXPECT_EQ(out->GetNumberOfStrips(), splitting ? 8 : 1);
      EXPECT_EQ(out->GetCellData()->GetTangents()->GetNumberOfTuples(), splitting ? 8 : 1);
      EXPECT_EQ(
        ValuesOf(out->GetCellData()->GetArray("Tag")), std::vector<double>(splitting ? 8 : 1, 7.0));
      // The triangles of a cut cell would repeat its global id: dropped. An array shorter than
      // the cells cannot follow them and passes as it is.
      EXPECT_EQ(ValuesOf(out->GetCellData()->GetGlobalIds()),
        splitting ? std::vector<double>() : std::vector<double>{ 100 });
      ASSERT_NE(out->GetCellData()->GetArray("Empty"), nullptr);
      EXPECT_EQ(out->GetCellData()->GetArray("Empty")->GetNumberOfTuples(), 0);
      if (!splitting)
      {
        continue;
      }
      EXPECT_EQ(ExpectEachTriangleSeesItsOwnFrame(out), 8);
      vtkSmartPointer<vtkPolyData> expected = run(triangles);
      EXPECT_EQ(ConnectivityOf(out), ConnectivityOf(expected));
      for (const char* name : { "Tangents", "TangentSigns", "Normals" })
      {
        EXPECT_EQ(ValuesOf(out->GetPointData()->GetArray(name)),
          ValuesOf(expected->GetPointData()->GetArray(name)))
          << name;
      }
      EXPECT_EQ(ValuesOf(out->GetCellData()->GetTangents()),
        ValuesOf(expected->GetCellData()->GetTangents()));
    }
  }

  // 2. A quad folded in UV: its fan triangles (0, 1, 2) and (0, 2, 3) have opposite handedness
  //    and tie at corners 0 and 2. With splitting (the default) the quad becomes those two
  //    triangles, and points 0 and 2 are split between them.
  vtkNew<vtkPolyData> quad;
  {
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> uv, normals;
    uv->SetNumberOfComponents(2);
    normals->SetNumberOfComponents(3);
    const double corners[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
    const double uvs[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 1.5, 0.2 } };
    for (int i = 0; i < 4; ++i)
    {
      points->InsertNextPoint(corners[i][0], corners[i][1], 0);
      uv->InsertNextTuple(uvs[i]);
      normals->InsertNextTuple3(0, 0, 1);
    }
    vtkNew<vtkCellArray> polys;
    const vtkIdType ids[4] = { 0, 1, 2, 3 };
    polys->InsertNextCell(4, ids);
    quad->SetPoints(points);
    quad->SetPolys(polys);
    quad->GetPointData()->SetTCoords(uv);
    quad->GetPointData()->SetNormals(normals);
  }
  vtkNew<vtkPolyDataTangentFrames> filter;
  Messages messages(filter);
  filter->SetInputData(quad);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  ExpectValidFrames(out);
  EXPECT_TRUE(messages.Warnings.empty());
  EXPECT_EQ(out->GetNumberOfPolys(), 2);
  EXPECT_EQ(out->GetNumberOfPoints(), 6);
  EXPECT_EQ(filter->GetNumberOfSplitPoints(), 2);
  EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), 2);
  EXPECT_EQ(ExpectEachTriangleSeesItsOwnFrame(out), 2);
}

TEST(PolyDataTangentFrames, SplitPointsTakeEveryPointArrayWithItsMetadata)
{
  // Extra point data of two kinds (numeric with component names, an information key, a lookup
  // table and the scalars attribute; strings) on a mesh whose mirror seams split: the input
  // points keep their tuples, each appended point copies those of the point it splits from,
  // and the arrays hold just their tuples.
  auto mesh = vtkNormalMapping::MakeTorus(MirroredTorusOptions(16, 4));
  const vtkIdType numIn = mesh->GetNumberOfPoints();
  vtkNew<vtkIntArray> tag; // (source id, -source id)
  tag->SetName("Tag");
  tag->SetNumberOfComponents(2);
  tag->SetComponentName(0, "id");
  tag->SetComponentName(1, "minus id");
  tag->GetInformation()->Set(vtkAbstractArray::GUI_HIDE(), 1);
  vtkNew<vtkLookupTable> table;
  tag->SetLookupTable(table);
  vtkNew<vtkStringArray> label;
  label->SetName("Label");
  for (vtkIdType p = 0; p < numIn; ++p)
  {
    tag->InsertNextTuple2(static_cast<double>(p), -static_cast<double>(p));
    label->InsertNextValue("point " + std::to_string(p));
  }
  mesh->GetPointData()->SetScalars(tag);
  mesh->GetPointData()->AddArray(label);

  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkSmartPointer<vtkPolyData> out =
      RunFrames(mesh, [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); });
    ASSERT_GT(out->GetNumberOfPoints(), numIn); // the seams split
    auto* outTag = vtkIntArray::SafeDownCast(out->GetPointData()->GetScalars());
    auto* outLabel = vtkStringArray::SafeDownCast(out->GetPointData()->GetAbstractArray("Label"));
    ASSERT_NE(outTag, nullptr);
    ASSERT_NE(outLabel, nullptr);
    EXPECT_STREQ(outTag->GetName(), "Tag");
    EXPECT_STREQ(outTag->GetComponentName(1), "minus id");
    EXPECT_TRUE(
      outTag->HasInformation() && outTag->GetInformation()->Has(vtkAbstractArray::GUI_HIDE()));
    EXPECT_NE(outTag->GetLookupTable(), nullptr);
    EXPECT_EQ(outTag->GetNumberOfTuples(), out->GetNumberOfPoints());
    EXPECT_EQ(outLabel->GetNumberOfValues(), out->GetNumberOfPoints());
    // No spare capacity: an output that keeps twice its arrays' memory costs a pipeline that
    // holds it that much more.
    for (vtkAbstractArray* array : { static_cast<vtkAbstractArray*>(outTag),
           static_cast<vtkAbstractArray*>(outLabel),
           static_cast<vtkAbstractArray*>(out->GetPoints()->GetData()) })
    {
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 7, 0)
      const vtkIdType capacity = array->GetCapacity();
#else
      const vtkIdType capacity = array->GetSize();
#endif
      EXPECT_EQ(capacity, array->GetNumberOfValues()) << array->GetName();
    }
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      const vtkIdType source = outTag->GetValue(2 * p);
      ASSERT_EQ(source, p < numIn ? p : source) << "point " << p;
      ASSERT_TRUE(source >= 0 && source < numIn) << "point " << p;
      EXPECT_EQ(outTag->GetValue(2 * p + 1), -source) << "point " << p;
      EXPECT_EQ(outLabel->GetValue(p), "point " + std::to_string(source)) << "point " << p;
      Vec x, y;
      out->GetPoint(p, x.data());
      mesh->GetPoint(source, y.data());
      EXPECT_EQ(x, y) << "point " << p;
    }
  }
}

TEST(PolyDataTangentFrames, SplitOutputPutsItsFrameArraysWhereTheUnsplitOutputDoes)
{
  // The input already has arrays of the names the filter writes (a glTF file's tangents read
  // back, say), one of them the active scalars. Splitting does not copy them (the filter's own
  // arrays replace them), yet the output must list the same arrays in the same order, with the
  // same attributes, as without splitting, where the input's arrays pass through and are
  // replaced in place.
  auto mesh = vtkNormalMapping::MakeTorus(MirroredTorusOptions(16, 4));
  const vtkIdType numIn = mesh->GetNumberOfPoints();
  const auto named = [numIn](const char* name, int components)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(numIn);
    array->Fill(7.0);
    return vtkSmartPointer<vtkFloatArray>(array);
  };
  vtkPointData* pd = mesh->GetPointData();
  pd->AddArray(named("Before", 1));
  pd->AddArray(named(vtkPolyDataTangentFrames::TangentsArrayName(), 3));
  pd->SetScalars(named(vtkPolyDataTangentFrames::SignsArrayName(), 1));
  pd->AddArray(named(vtkPolyDataTangentFrames::BitangentsArrayName(), 3));
  pd->AddArray(named("After", 1));

  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    for (bool bitangents : { false, true })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (bitangents ? ", bitangents" : ""));
      std::vector<std::string> layout[2]; // array names, then the scalars' name
      for (bool splitting : { false, true })
      {
        vtkSmartPointer<vtkPolyData> out = RunFrames(mesh,
          [&](vtkPolyDataTangentFrames* f)
          {
            f->SetMethod(method);
            f->SetSplitting(splitting);
            f->SetComputeBitangents(bitangents);
          });
        ASSERT_EQ(out->GetNumberOfPoints() > numIn, splitting);
        vtkPointData* outPD = out->GetPointData();
        for (int k = 0; k < outPD->GetNumberOfArrays(); ++k)
        {
          vtkAbstractArray* array = outPD->GetAbstractArray(k);
          layout[splitting].emplace_back(array->GetName());
          EXPECT_EQ(array->GetNumberOfTuples(), out->GetNumberOfPoints()) << array->GetName();
        }
        ASSERT_NE(outPD->GetScalars(), nullptr);
        layout[splitting].emplace_back(outPD->GetScalars()->GetName());
        // The frame arrays are the filter's: a sign is +1 or -1, never the input's 7.
        auto* signs = outPD->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
        ASSERT_NE(signs, nullptr);
        EXPECT_EQ(std::abs(signs->GetComponent(out->GetNumberOfPoints() - 1, 0)), 1.0);
        // Without bitangents the input's array of that name is point data like any other.
        auto* b = outPD->GetArray(vtkPolyDataTangentFrames::BitangentsArrayName());
        ASSERT_NE(b, nullptr);
        EXPECT_EQ(b->GetComponent(out->GetNumberOfPoints() - 1, 0) == 7.0, !bitangents);
      }
      EXPECT_EQ(layout[1], layout[0]);
    }
  }
}

TEST(PolyDataTangentFrames, InputTangentsOfAnotherNamePassThrough)
{
  // A reader's tangents under a name of their own (glTF's TANGENT) hold the TANGENTS attribute.
  // The output's Tangents take the attribute, and the input's array stays point data like any
  // other, split with the points, for every method.
  auto mesh = vtkNormalMapping::MakeTorus(MirroredTorusOptions(16, 4));
  vtkFloatArray* supplied = NormalMappingTesting::AddFilledArray(
    mesh->GetPointData(), mesh->GetNumberOfPoints(), "TANGENT", 3, 7.0);
  mesh->GetPointData()->SetTangents(supplied);
  for (int method = vtkPolyDataTangentFrames::UNWEIGHTED;
       method <= vtkPolyDataTangentFrames::MIKKTSPACE;
       ++method)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    auto out = RunFrames(mesh, [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); });
    ASSERT_GT(out->GetNumberOfPoints(), mesh->GetNumberOfPoints()); // the seams split
    vtkDataArray* active = out->GetPointData()->GetTangents();
    ASSERT_NE(active, nullptr);
    EXPECT_STREQ(active->GetName(), vtkPolyDataTangentFrames::TangentsArrayName());
    vtkDataArray* passed = out->GetPointData()->GetArray("TANGENT");
    ASSERT_NE(passed, nullptr) << "the input's tangents are gone";
    ASSERT_EQ(passed->GetNumberOfTuples(), out->GetNumberOfPoints());
    EXPECT_EQ(passed->GetComponent(out->GetNumberOfPoints() - 1, 2), 7.0);
  }
}

TEST(PolyDataTangentFrames, AttributesNamedLikeFrameArraysAreReplacedWithAWarning)
{
  // The input's normals or texture coordinates named like an output frame array: the frame
  // array replaces them (as it replaces any array of its name), with a warning, and the output's
  // attribute is gone rather than naming frame data. With and without split points, for every
  // method.
  for (int method = vtkPolyDataTangentFrames::UNWEIGHTED;
       method <= vtkPolyDataTangentFrames::MIKKTSPACE;
       ++method)
  {
    for (const bool mirrored : { false, true })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (mirrored ? ", mirrored" : ""));
      vtkNormalMapping::TorusOptions options = MirroredTorusOptions(16, 4);
      options.MirrorU = mirrored;
      auto mesh = vtkNormalMapping::MakeTorus(options);
      mesh->GetPointData()->GetNormals()->SetName("Bitangents");
      mesh->GetPointData()->GetTCoords()->SetName("TangentSigns");
      mesh->GetCellData()->SetNormals(NormalMappingTesting::AddFilledArray(
        mesh->GetCellData(), mesh->GetNumberOfCells(), "Tangents", 3, 0.0));

      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetInputData(mesh);
      filter->SetMethod(method);
      filter->ComputeBitangentsOn();
      filter->ComputeCellTangentsOn();
      Messages messages(filter);
      filter->Update();
      vtkPolyData* out = filter->GetOutput();
      EXPECT_TRUE(messages.Has(messages.Warnings, "point normals are named 'Bitangents'"));
      EXPECT_TRUE(messages.Has(messages.Warnings, "texture coordinates are named 'TangentSigns'"));
      EXPECT_TRUE(messages.Has(messages.Warnings, "cell normals are named 'Tangents'"));
      EXPECT_EQ(out->GetPointData()->GetNormals(), nullptr);
      EXPECT_EQ(out->GetPointData()->GetTCoords(), nullptr);
      EXPECT_EQ(out->GetCellData()->GetNormals(), nullptr);
      EXPECT_EQ(out->GetPointData()->GetTangents(), out->GetPointData()->GetArray("Tangents"));
      EXPECT_EQ(out->GetCellData()->GetTangents(), out->GetCellData()->GetArray("Tangents"));
      vtkDataArray* signs = out->GetPointData()->GetArray("TangentSigns");
      ASSERT_NE(signs, nullptr);
      ASSERT_EQ(signs->GetNumberOfComponents(), 1);
    }
  }
}

TEST(PolyDataTangentFrames, SplitPointsCopyNoGlobalIds)
{
  // Global ids name each point once (VTK's parallel filters match points by them). Split copies
  // would repeat their source's, so an output with split points has none, as
  // vtkPolyDataNormals' has none; without split points the ids pass through.
  auto mesh = vtkNormalMapping::MakeTorus(MirroredTorusOptions(16, 4));
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GlobalIds");
  ids->SetNumberOfTuples(mesh->GetNumberOfPoints());
  std::iota(ids->GetPointer(0), ids->GetPointer(0) + mesh->GetNumberOfPoints(), 100);
  mesh->GetPointData()->SetGlobalIds(ids);
  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    for (bool splitting : { true, false })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (splitting ? ", splitting" : ", no splitting"));
      auto out = RunFrames(mesh,
        [&](vtkPolyDataTangentFrames* f)
        {
          f->SetMethod(method);
          f->SetSplitting(splitting);
        });
      ASSERT_EQ(out->GetNumberOfPoints() > mesh->GetNumberOfPoints(), splitting);
      vtkPointData* pd = out->GetPointData();
      if (splitting)
      {
        EXPECT_EQ(pd->GetGlobalIds(), nullptr);
        EXPECT_EQ(pd->GetAbstractArray("GlobalIds"), nullptr);
      }
      else
      {
        EXPECT_EQ(pd->GetGlobalIds(), ids.Get());
      }
    }
  }
}

TEST(PolyDataTangentFrames, RepeatedUpdatesGiveTheSameBits)
{
  // Re-executing reuses memory the previous execution freed (glibc hands the per-point sums'
  // block back from the second or third execution on): every execution must start from zero
  // sums and give the first one's bits.
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(vtkNormalMapping::MakeTorus(MirroredTorusOptions(1040, 256)));
  std::vector<float> first;
  for (int run = 0; run < 4; ++run)
  {
    filter->Modified();
    filter->Update();
    auto* t = vtkFloatArray::SafeDownCast(filter->GetOutput()->GetPointData()->GetTangents());
    ASSERT_NE(t, nullptr);
    std::vector<float> bits(t->GetPointer(0), t->GetPointer(0) + t->GetDataSize());
    if (run == 0)
    {
      first = bits;
      continue;
    }
    ASSERT_EQ(bits.size(), first.size());
    EXPECT_EQ(0, std::memcmp(bits.data(), first.data(), 4 * bits.size())) << "run " << run;
  }
}

TEST(PolyDataTangentFrames, MirroredTorusWithoutSplittingCountsConflicts)
{
  const vtkNormalMapping::TorusOptions options = MirroredTorusOptions(64, 16);
  auto mesh = vtkNormalMapping::MakeTorus(options);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->SplittingOff();
  filter->Update();
  ExpectValidFrames(filter->GetOutput());
  EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), 2 * (options.V + 1));
  EXPECT_EQ(filter->GetNumberOfSplitPoints(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), mesh->GetNumberOfPoints());
}

// ------------------------------------------------------------------ degenerate, hostile

namespace
{
vtkSmartPointer<vtkPolyData> MakeTriangles(const std::vector<Vec>& points,
  const std::vector<std::array<double, 2>>& uvs,
  const std::vector<std::vector<vtkIdType>>& cells,
  const std::vector<Vec>& normals = {})
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (const Vec& p : points)
  {
    pts->InsertNextPoint(p.data());
  }
  vtkNew<vtkFloatArray> tc;
  tc->SetNumberOfComponents(2);
  tc->SetName("TCoords");
  for (const auto& uv : uvs)
  {
    tc->InsertNextTuple(uv.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& c : cells)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(c.size()), c.data());
  }
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetTCoords(tc);
  if (!normals.empty())
  {
    vtkNew<vtkFloatArray> n;
    n->SetNumberOfComponents(3);
    n->SetName("Normals");
    for (const Vec& v : normals)
    {
      n->InsertNextTuple(v.data());
    }
    mesh->GetPointData()->SetNormals(n);
  }
  return mesh;
}
}

TEST(PolyDataTangentFrames, SingleTriangle)
{
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 0, 1, 2 } },
    { { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 } });
  auto out = RunFrames(mesh);
  ExpectValidFrames(out);
  for (vtkIdType p = 0; p < 3; ++p)
  {
    EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), p), (Vec{ 1, 0, 0 }));
  }
}

TEST(PolyDataTangentFrames, ZeroUVAreaTriangleFallsBackToNeighbours)
{
  // Two good triangles and a third whose own point 4 has the UVs of point 1: triangle (1,3,4)
  // has zero UV area, so point 4 has no usable triangle and follows its neighbours: their
  // tangent (u, 0, 0) and their majority sign u, with u = 1 and with u mirrored (u = -1, where
  // every good triangle has handedness -1).
  for (const double u : { 1.0, -1.0 })
  {
    SCOPED_TRACE(u);
    auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 2, 0.5, 0 } },
      { { 0, 0 }, { u, 0 }, { 0, 1 }, { u, 1 }, { u, 0 } },
      { { 0, 1, 2 }, { 1, 3, 2 }, { 1, 4, 3 } },
      std::vector<Vec>(5, Vec{ 0, 0, 1 }));
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(mesh);
    filter->Update();
    auto out = filter->GetOutput();
    ExpectValidFrames(out);
    EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 1);
    ASSERT_EQ(filter->GetNumberOfFallbackPoints(), 1);
    vtkDataArray* signs = out->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
    for (vtkIdType p = 0; p < 5; ++p)
    {
      EXPECT_EQ(signs->GetComponent(p, 0), u) << "point " << p;
    }
    const Vec t4 = Get3(out->GetPointData()->GetTangents(), 4);
    EXPECT_LT(AngleDeg(t4, { u, 0, 0 }), 1e-5); // float output rounding, as above
  }
}

TEST(PolyDataTangentFrames, AFallbackPointBetweenOppositeSignsTakesThePositiveSign)
{
  // Point 0's only triangle (0, 1, 2) has zero UV area. Its neighbours: point 1, in a +1
  // triangle with tangent +x, and point 2, in a mirrored (-1) triangle with tangent -x. The
  // vote is a tie, which goes to +1; the neighbours' tangents cancel, which leaves Duff et al.'s
  // basis of the normal +z: +x.
  auto mesh = MakeTriangles(
    { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 2, 0, 0 }, { 1, 1, 0 }, { 1, 1, 0 }, { 0, 2, 0 } },
    { { 0, 0 }, { 0, 0 }, { 0, 0 }, { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, 1 } },
    { { 0, 1, 2 }, { 1, 3, 4 }, { 2, 5, 6 } },
    std::vector<Vec>(7, Vec{ 0, 0, 1 }));
  for (int method : AllMethods)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(mesh);
    filter->SetMethod(method);
    filter->Update();
    auto out = filter->GetOutput();
    ExpectValidFrames(out);
    ASSERT_EQ(filter->GetNumberOfFallbackPoints(), 1);
    vtkDataArray* signs = out->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
    ASSERT_EQ(signs->GetComponent(1, 0), 1.0);
    ASSERT_EQ(signs->GetComponent(2, 0), -1.0);
    EXPECT_EQ(signs->GetComponent(0, 0), 1.0);
    EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), 0), (Vec{ 1, 0, 0 }));
  }
}

TEST(PolyDataTangentFrames, WithoutSplittingATieGoesToThePositiveSide)
{
  // Two triangles mirrored across x = 0 with u = |x|: the seam points 0 and 1 get the same
  // weight from both sides, bit for bit (the mirrored edges give the same dot and cross
  // products). Without splitting they take the +1 side: sign +1 and the right triangle's
  // tangent (1, 0, 0).
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 0, 1, 0 }, { 1, 0, 0 }, { -1, 0, 0 } },
    { { 0, 0 }, { 0, 1 }, { 1, 0 }, { 1, 0 } },
    { { 0, 2, 1 }, { 0, 1, 3 } },
    std::vector<Vec>(4, Vec{ 0, 0, 1 }));
  for (int method : { vtkPolyDataTangentFrames::UNWEIGHTED,
         vtkPolyDataTangentFrames::AREA_WEIGHTED,
         vtkPolyDataTangentFrames::ANGLE_WEIGHTED })
  {
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(mesh);
    filter->SetMethod(method);
    filter->SplittingOff();
    filter->Update();
    auto out = filter->GetOutput();
    ExpectValidFrames(out);
    EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), 2);
    vtkDataArray* signs = out->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
    for (vtkIdType p = 0; p < 2; ++p)
    {
      EXPECT_EQ(signs->GetComponent(p, 0), 1.0) << "method " << method << " point " << p;
      EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), p), (Vec{ 1, 0, 0 }))
        << "method " << method << " point " << p;
    }
  }
}

TEST(PolyDataTangentFrames, OnlyDegenerateTrianglesUseTheFixedRule)
{
  // All triangles zero-area or zero-UV-area: every point falls back to the fixed rule.
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 0, 0 } },
    { { 0, 1, 2 }, { 0, 1, 3 } },
    std::vector<Vec>(4, Vec{ 0, 0, 1 }));
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->Update();
  ExpectValidFrames(filter->GetOutput());
  EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 2);
  EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 4);
  // The fixed rule for n = +z is (1, 0, 0).
  EXPECT_EQ(Get3(filter->GetOutput()->GetPointData()->GetTangents(), 0), (Vec{ 1, 0, 0 }));
}

TEST(PolyDataTangentFrames, NonFiniteInputGivesFiniteOutput)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int where = 0; where < 6; ++where)
  {
    std::vector<Vec> pts = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } };
    std::vector<std::array<double, 2>> uvs = { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } };
    std::vector<Vec> normals(4, Vec{ 0, 0, 1 });
    const double bad = where % 2 ? inf : nan;
    if (where < 2)
    {
      pts[3][0] = bad;
    }
    else if (where < 4)
    {
      uvs[3][1] = bad;
    }
    else
    {
      normals[3][2] = bad;
    }
    auto mesh = MakeTriangles(pts, uvs, { { 0, 1, 2 }, { 1, 3, 2 } }, normals);
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(mesh);
    filter->ComputeBitangentsOn();
    filter->Update();
    auto out = filter->GetOutput();
    SCOPED_TRACE("case " + std::to_string(where));
    // Finite unit tangents everywhere; the normal check skips the non-finite input normal.
    ExpectValidFrames(out);
    EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), where < 4 ? 1 : 0);
    EXPECT_EQ(filter->GetNumberOfInvalidNormals(), where >= 4 ? 1 : 0);
    vtkDataArray* b = out->GetPointData()->GetArray("Bitangents");
    for (vtkIdType p = 0; p < 4; ++p)
    {
      const Vec bv = Get3(b, p);
      EXPECT_TRUE(std::isfinite(bv[0]) && std::isfinite(bv[1]) && std::isfinite(bv[2]));
    }
  }
}

TEST(PolyDataTangentFrames, ZeroAndUnnormalizedNormals)
{
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 0, 1, 2 } },
    { { 0, 0, 0 }, { 0, 0, 1e-30 }, { 0.3, 0, 5 } });
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfInvalidNormals(), 1); // only the zero one; tiny is a direction
  vtkDataArray* t = filter->GetOutput()->GetPointData()->GetTangents();
  EXPECT_LT(AngleDeg(Get3(t, 0), { 1, 0, 0 }), 1e-5); // zero normal: the face normal is used
  EXPECT_LT(AngleDeg(Get3(t, 1), { 1, 0, 0 }), 1e-5);
  // Point 2: T perpendicular to the normalized (0.3, 0, 5).
  const Vec n2{ 0.3 / std::hypot(0.3, 5.0), 0, 5 / std::hypot(0.3, 5.0) };
  EXPECT_NEAR(Dot(Get3(t, 2), n2), 0.0, 1e-6);
}

TEST(PolyDataTangentFrames, EmptyInputAndNoSurfaceCells)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPolyDataTangentFrames> filter;
  Messages messages(filter);
  filter->SetInputData(empty);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_TRUE(messages.Errors.empty());

  // Points with texture coordinates, but only vertex and line cells: passed through without
  // frames (nothing to give them to), without a message.
  vtkNew<vtkPolyData> wire;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> uv;
  uv->SetNumberOfComponents(2);
  for (int i = 0; i < 3; ++i)
  {
    points->InsertNextPoint(i, 0, 0);
    uv->InsertNextTuple2(0.5 * i, 0.0);
  }
  wire->SetPoints(points);
  wire->GetPointData()->SetTCoords(uv);
  vtkNew<vtkCellArray> verts, lines;
  const vtkIdType vertex[1] = { 0 }, line[3] = { 0, 1, 2 };
  verts->InsertNextCell(1, vertex);
  lines->InsertNextCell(3, line);
  wire->SetVerts(verts);
  wire->SetLines(lines);
  filter->SetInputData(wire);
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  EXPECT_EQ(out->GetNumberOfPoints(), 3);
  EXPECT_EQ(out->GetNumberOfVerts(), 1);
  EXPECT_EQ(out->GetNumberOfLines(), 1);
  EXPECT_EQ(out->GetPointData()->GetTCoords(), uv.Get());
  EXPECT_EQ(out->GetPointData()->GetArray(vtkPolyDataTangentFrames::TangentsArrayName()), nullptr);
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.Warnings.empty());
}

TEST(PolyDataTangentFrames, VerticesLinesPolygonsAndStripsTogether)
{
  // A strip of 4 triangles, a quad, a hexagon, plus vertex and line cells on the same points.
  vtkNew<vtkPoints> pts;
  vtkNew<vtkFloatArray> tc;
  tc->SetNumberOfComponents(2);
  vtkNew<vtkFloatArray> n;
  n->SetNumberOfComponents(3);
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      pts->InsertNextPoint(i, j, 0);
      tc->InsertNextTuple2(0.1 * i, 0.5 * j);
      n->InsertNextTuple3(0, 0, 1);
    }
  }
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  const vtkIdType v[2] = { 0, 5 }, l[3] = { 0, 2, 4 }, quad[4] = { 0, 2, 3, 1 };
  // Fanned from corner 0, (3,0): starting at (2,0) would give a collinear (degenerate) triangle.
  const vtkIdType hexagon[6] = { 6, 8, 9, 7, 5, 4 };
  const vtkIdType strip[6] = { 0, 1, 2, 3, 4, 5 };
  verts->InsertNextCell(2, v);
  lines->InsertNextCell(3, l);
  polys->InsertNextCell(4, quad);
  polys->InsertNextCell(6, hexagon);
  strips->InsertNextCell(6, strip);
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(pts);
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  mesh->SetStrips(strips);
  mesh->GetPointData()->SetTCoords(tc);
  mesh->GetPointData()->SetNormals(n);

  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->ComputeCellTangentsOn();
  filter->Update();
  vtkPolyData* out = filter->GetOutput();
  ExpectValidFrames(out);
  EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 0);
  // u grows along +x everywhere: every point's tangent is +x, sign +1 (strip triangles
  // alternate their corner order but keep the strip's winding).
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    if (p == 10 || p == 11)
    {
      // Not in any polygon or strip: fallback points without neighbours, sign +1.
      EXPECT_EQ(out->GetPointData()->GetArray("TangentSigns")->GetComponent(p, 0), 1.0);
      continue;
    }
    EXPECT_LT(AngleDeg(Get3(out->GetPointData()->GetTangents(), p), { 1, 0, 0 }), 1e-5) << p;
    EXPECT_EQ(out->GetPointData()->GetArray("TangentSigns")->GetComponent(p, 0), 1.0);
  }
  EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 2);
  // Vertex and line cells pass through untouched.
  EXPECT_EQ(out->GetNumberOfVerts(), 1);
  EXPECT_EQ(out->GetNumberOfLines(), 1);
  EXPECT_EQ(out->GetNumberOfPolys(), 2);
  EXPECT_EQ(out->GetNumberOfStrips(), 1);
  // Cell tangents: zero for the vertex and line cells, +x for the polygons and the strip.
  vtkDataArray* ct = out->GetCellData()->GetTangents();
  ASSERT_NE(ct, nullptr);
  EXPECT_EQ(Get3(ct, 0), (Vec{ 0, 0, 0 }));
  EXPECT_EQ(Get3(ct, 1), (Vec{ 0, 0, 0 }));
  for (vtkIdType c = 2; c < 5; ++c)
  {
    EXPECT_LT(AngleDeg(Get3(ct, c), { 1, 0, 0 }), 1e-5) << c;
  }
}

TEST(PolyDataTangentFrames, CellTangentsAreAreaWeightedOverTheCellsTriangles)
{
  // A quad folded along its diagonal (0, 2): triangle (0, 1, 2) of area 2 in z = 0 with
  // dP/du = +x, and triangle (0, 2, 3), of another area and plane, whose texture coordinates
  // give dP/du = (1, 0.25, -0.125). The cell tangent (docs/filter.md) is the area-weighted sum
  // of the triangles' unit tangents, made perpendicular to the sum of their cross products,
  // normalised: computed here from those two triangles, for every weighted method.
  const std::vector<Vec> p = { { 0, 0, 0 }, { 4, 0, 0 }, { 2, 1, 0 }, { 0, 1, 0.5 } };
  auto mesh = MakeTriangles(p, { { 0, 0 }, { 4, 0 }, { 2, 1 }, { 0, 2 } }, { { 0, 1, 2, 3 } });
  const Vec cross1 = Cross(Minus(p[1], p[0]), Minus(p[2], p[0]));
  const Vec cross2 = Cross(Minus(p[2], p[0]), Minus(p[3], p[0]));
  const Vec tangent1 = { 1, 0, 0 };
  const Vec tangent2 = Scaled(1.0 / Norm({ 1, 0.25, -0.125 }), { 1, 0.25, -0.125 });
  const double area1 = 0.5 * Norm(cross1), area2 = 0.5 * Norm(cross2);
  Vec t, n;
  for (int k = 0; k < 3; ++k)
  {
    t[k] = area1 * tangent1[k] + area2 * tangent2[k];
    n[k] = cross1[k] + cross2[k];
  }
  n = Scaled(1.0 / Norm(n), n);
  const Vec perpendicular = Minus(t, Scaled(Dot(t, n), n));
  const Vec expected = Scaled(1.0 / Norm(perpendicular), perpendicular);
  for (int method : AllMethods)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    auto out = RunFrames(mesh,
      [&](vtkPolyDataTangentFrames* f)
      {
        f->SetMethod(method);
        f->ComputeCellTangentsOn();
      });
    vtkDataArray* ct = out->GetCellData()->GetTangents();
    ASSERT_NE(ct, nullptr);
    const Vec actual = Get3(ct, 0);
    for (int k = 0; k < 3; ++k)
    {
      // Float output: a unit vector rounded once (6e-8 per component).
      EXPECT_NEAR(actual[k], expected[k], 1e-6) << "component " << k;
    }
  }
}

TEST(PolyDataTangentFrames, OutOfRangeIdsAreAnErrorAndPassThrough)
{
  auto mesh = MakeTriangles(
    { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 0 }, { 1, 0 }, { 0, 1 } }, { { 0, 1, 7 } });
  vtkNew<vtkPolyDataTangentFrames> filter;
  Messages messages(filter);
  filter->SetInputData(mesh);
  filter->Update();
  EXPECT_TRUE(messages.Has(messages.Errors, "point id outside")) << messages.Errors.size();
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetTangents(), nullptr);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPolys(), 1);
}

namespace
{
const int EveryMethod[] = { vtkPolyDataTangentFrames::UNWEIGHTED,
  vtkPolyDataTangentFrames::AREA_WEIGHTED,
  vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
  vtkPolyDataTangentFrames::MIKKTSPACE };

/// Two triangles in z = 0 sharing the edge 0-2, the second with mirrored texture coordinates:
/// points 0 and 2 are on a mirror seam, so splitting adds two points.
vtkSmartPointer<vtkPolyData> MirroredPair()
{
  return MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { -1, 0, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 0 } },
    { { 0, 1, 2 }, { 0, 2, 3 } },
    std::vector<Vec>(4, Vec{ 0, 0, 1 }));
}

/// A copy of mesh with one more polygon (strip = false) or strip.
vtkSmartPointer<vtkPolyData> WithCell(vtkPolyData* mesh, std::vector<vtkIdType> ids, bool strip)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  // A cell array of its own: a polydata without strips (or polygons) hands out VTK's one empty
  // array, shared by every such polydata, which must not get the cell.
  vtkNew<vtkCellArray> cells;
  cells->DeepCopy(strip ? copy->GetStrips() : copy->GetPolys());
  cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  if (strip)
  {
    copy->SetStrips(cells);
  }
  else
  {
    copy->SetPolys(cells);
  }
  return copy;
}
}

TEST(PolyDataTangentFrames, OutOfRangeIdsInAnyCellAreAnErrorForEveryMethod)
{
  // Polygons and strips of every size, with an id just past the end or negative: the same
  // error and a pass-through from every method. Cells with fewer than 3 points give no frames,
  // but a bad id in them is still an error (MikkTSpace read out of bounds here before).
  auto mesh = MirroredPair();
  const std::vector<std::pair<std::vector<vtkIdType>, bool>> cells = { { { 0, 1, 4 }, false },
    { { -1, 1, 2, 3 }, false },
    { { 0, 4 }, false },
    { { -1 }, false },
    { { 0, 1, 2, 4 }, true },
    { { 2, -1 }, true },
    { { 9 }, true } };
  for (const auto& [ids, strip] : cells)
  {
    auto bad = WithCell(mesh, ids, strip);
    for (int method : EveryMethod)
    {
      SCOPED_TRACE(std::string(strip ? "strip" : "polygon") + " of " + std::to_string(ids.size()) +
        " " + vtkPolyDataTangentFrames::GetMethodName(method));
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      filter->SetInputData(bad);
      filter->SetMethod(method);
      filter->Update();
      vtkPolyData* out = filter->GetOutput();
      ASSERT_EQ(messages.Errors.size(), 1u);
      EXPECT_TRUE(messages.Has(messages.Errors, "outside [0, 4)")) << messages.Errors[0];
      EXPECT_EQ(out->GetPoints(), bad->GetPoints()); // passed through, not copied
      EXPECT_EQ(out->GetPolys(), bad->GetPolys());
      EXPECT_EQ(out->GetStrips(), bad->GetStrips());
      EXPECT_EQ(out->GetPointData()->GetTangents(), nullptr);
    }
  }
}

TEST(PolyDataTangentFrames, OutOfRangeIdsInLargeTriangleMeshesForAnyNumberOfThreads)
{
  // A bad id anywhere, first or last triangle or in the middle, with one thread or several,
  // must give the error and the pass-through.
  vtkNormalMapping::TorusOptions options;
  // 145,162 triangles, 72,581 points.
  options.U = 401;
  options.V = 181;
  const auto torus = vtkNormalMapping::MakeTorus(options);
  const vtkIdType numCells = torus->GetNumberOfPolys();
  for (const vtkIdType cell : { vtkIdType(0), vtkIdType(1000), numCells / 2 + 7, numCells - 1 })
  {
    for (const vtkIdType id : { torus->GetNumberOfPoints(), vtkIdType(-1) })
    {
      auto bad = vtkSmartPointer<vtkPolyData>::New();
      bad->DeepCopy(torus);
      bad->GetPolys()->GetConnectivityArray()->SetComponent(
        3 * cell + 1, 0, static_cast<double>(id));
      for (int threads : { 1, 2, 8 })
      {
        SCOPED_TRACE("cell " + std::to_string(cell) + " id " + std::to_string(id) + ", " +
          std::to_string(threads) + " threads");
        NormalMappingTesting::WithThreads(threads,
          [&]()
          {
            vtkNew<vtkPolyDataTangentFrames> filter;
            Messages messages(filter);
            filter->SetInputData(bad);
            filter->Update();
            ASSERT_EQ(messages.Errors.size(), 1u);
            EXPECT_TRUE(messages.Has(messages.Errors, "point id outside")) << messages.Errors[0];
            EXPECT_EQ(filter->GetOutput()->GetPointData()->GetTangents(), nullptr);
          });
      }
    }
  }
}

TEST(PolyDataTangentFrames, OutOfRangeIdsAnywhereAreAnErrorOnEveryPath)
{
  // One bad id (first, middle or last corner; equal to the number of points, negative, or
  // huge) on every path that reads ids: each method, with input normals, without normals (point
  // links), with an unusable normal (links too), with cell tangents, on one thread and on two
  // (18,432 triangles: more than one chunk of the two-thread sums). Each run must report the
  // error, pass the input through and count nothing; under AddressSanitizer a read outside the
  // arrays fails the run.
  const auto clean = vtkNormalMapping::MakeTorus(MirroredTorusOptions(96, 96));
  const vtkIdType numPoints = clean->GetNumberOfPoints();
  const vtkIdType numIds = clean->GetPolys()->GetNumberOfConnectivityIds();
  enum NormalsMode
  {
    Given,
    None,
    OneUnusable,
    CellTangents
  };
  for (int method : EveryMethod)
  {
    for (NormalsMode mode : { Given, None, OneUnusable, CellTangents })
    {
      for (vtkIdType position : { vtkIdType(0), numIds / 2 + 1, numIds - 1 })
      {
        for (double bad : { double(numPoints), -1.0, std::ldexp(1.0, 40) })
        {
          for (int threads : { 1, 2 })
          {
            SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
              ", normals mode " + std::to_string(mode) + ", corner " + std::to_string(position) +
              ", id " + std::to_string(bad) + ", " + std::to_string(threads) + " threads");
            vtkNew<vtkPolyData> mesh;
            mesh->DeepCopy(clean);
            mesh->GetPolys()->GetConnectivityArray()->SetComponent(position, 0, bad);
            if (mode == None)
            {
              mesh->GetPointData()->SetNormals(nullptr);
            }
            if (mode == OneUnusable)
            {
              mesh->GetPointData()->GetNormals()->SetTuple3(numPoints / 3, 0.0, 0.0, 0.0);
            }
            vtkNew<vtkPolyDataTangentFrames> filter;
            Messages messages(filter);
            filter->SetInputData(mesh);
            filter->SetMethod(method);
            filter->SetComputeCellTangents(mode == CellTangents);
            NormalMappingTesting::WithThreads(threads, [&]() { filter->Update(); });
            vtkPolyData* out = filter->GetOutput();
            EXPECT_TRUE(
              messages.Has(messages.Errors, "outside [0, " + std::to_string(numPoints) + ")"));
            EXPECT_EQ(out->GetPointData()->GetArray("Tangents"), nullptr);
            EXPECT_EQ(out->GetNumberOfPoints(), numPoints);
            EXPECT_EQ(out->GetPolys(), mesh->GetPolys());
            EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 0);
            EXPECT_EQ(filter->GetNumberOfSplitPoints(), 0);
          }
        }
      }
    }
  }
}

TEST(PolyDataTangentFrames, CellsWithFewerThanThreePointsPassThrough)
{
  // Polygons with 0, 1 and 2 points and strips of 0, 1 and 2 points beside a mirrored pair:
  // a warning, the cells unchanged (even where their point is split), the other frames as
  // without them.
  auto mesh = MirroredPair();
  auto input = mesh;
  for (const auto& ids : std::vector<std::vector<vtkIdType>>{ {}, { 0 }, { 0, 2 } })
  {
    input = WithCell(WithCell(input, ids, false), ids, true);
  }
  for (int method : EveryMethod)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    const auto configure = [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); };
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(input);
    configure(filter);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    EXPECT_TRUE(messages.Errors.empty());
    EXPECT_TRUE(messages.Has(messages.Warnings, "6 polygon or strip cells have fewer than 3"));
    ExpectValidFrames(out);
    auto reference = RunFrames(mesh, configure);
    ASSERT_EQ(out->GetNumberOfPoints(), reference->GetNumberOfPoints());
    EXPECT_EQ(out->GetNumberOfPoints(), 6); // the two seam points split
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), p),
        Get3(reference->GetPointData()->GetTangents(), p))
        << "point " << p;
    }
    for (vtkCellArray* cells : { out->GetPolys(), out->GetStrips() })
    {
      vtkCellArray* in = cells == out->GetPolys() ? input->GetPolys() : input->GetStrips();
      ASSERT_EQ(cells->GetNumberOfCells(), in->GetNumberOfCells());
      const vtkIdType first = cells == out->GetPolys() ? 2 : 0; // the short cells
      for (vtkIdType c = first; c < cells->GetNumberOfCells(); ++c)
      {
        vtkNew<vtkIdList> a, b;
        in->GetCellAtId(c, a);
        cells->GetCellAtId(c, b);
        ASSERT_EQ(a->GetNumberOfIds(), b->GetNumberOfIds());
        for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k)
        {
          EXPECT_EQ(a->GetId(k), b->GetId(k));
        }
      }
    }
  }
}

TEST(PolyDataTangentFrames, SplitCornersAfterCellsWithoutPointsFindTheirCells)
{
  // A mirrored torus as polygons and as strips, with a cell of two points and a cell of no points
  // before each of its cells. The corners of split points are found among the connectivity
  // entries and traced back to their cell, which must pass over the cells without points (they
  // start where the next cell does). Every method gives the points, the frames and the
  // re-pointed cells of the mesh without the short cells (strips across the seams cut into
  // triangles in both).
  auto polygons = vtkNormalMapping::MakeTorus(MirroredTorusOptions(16, 4));
  vtkNew<vtkStripper> stripper;
  stripper->SetInputData(polygons);
  stripper->Update();
  ASSERT_GT(stripper->GetOutput()->GetNumberOfStrips(), 0);
  for (vtkPolyData* mesh : { polygons.Get(), stripper->GetOutput() })
  {
    const bool strips = mesh->GetNumberOfStrips() > 0;
    SCOPED_TRACE(strips ? "strips" : "polygons");
    vtkCellArray* original = strips ? mesh->GetStrips() : mesh->GetPolys();
    vtkNew<vtkCellArray> padded;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < original->GetNumberOfCells(); ++c)
    {
      original->GetCellAtId(c, ids);
      padded->InsertNextCell(2, ids->GetPointer(0));
      padded->InsertNextCell(0, ids->GetPointer(0));
      padded->InsertNextCell(ids);
    }
    vtkNew<vtkPolyData> input;
    input->ShallowCopy(mesh);
    if (strips)
    {
      input->SetStrips(padded);
    }
    else
    {
      input->SetPolys(padded);
    }
    for (int method : EveryMethod)
    {
      SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
      const auto configure = [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); };
      auto reference = RunFrames(mesh, configure);
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      filter->SetInputData(input);
      configure(filter);
      filter->Update();
      vtkPolyData* out = filter->GetOutput();
      EXPECT_TRUE(messages.Errors.empty());
      ASSERT_GT(reference->GetNumberOfPoints(), mesh->GetNumberOfPoints()); // the seams split
      ASSERT_EQ(out->GetNumberOfPoints(), reference->GetNumberOfPoints());
      for (const char* name : { "Tangents", "TangentSigns" })
      {
        vtkDataArray* got = out->GetPointData()->GetArray(name);
        vtkDataArray* want = reference->GetPointData()->GetArray(name);
        ASSERT_NE(got, nullptr);
        for (vtkIdType i = 0; i < want->GetNumberOfValues(); ++i)
        {
          ASSERT_EQ(got->GetVariantValue(i), want->GetVariantValue(i)) << name << " value " << i;
        }
      }
      // The short cells pass through, two before each cell of the reference's (or before the
      // triangles a cut cell became).
      vtkCellArray* got = strips ? out->GetStrips() : out->GetPolys();
      vtkCellArray* want = strips ? reference->GetStrips() : reference->GetPolys();
      std::vector<std::vector<vtkIdType>> gotCells;
      vtkIdType shortCells = 0;
      vtkNew<vtkIdList> a, b;
      for (vtkIdType c = 0; c < got->GetNumberOfCells(); ++c)
      {
        got->GetCellAtId(c, b);
        if (b->GetNumberOfIds() < 3)
        {
          ++shortCells;
          continue;
        }
        gotCells.emplace_back(b->begin(), b->end());
      }
      EXPECT_EQ(shortCells, 2 * original->GetNumberOfCells());
      ASSERT_EQ(static_cast<vtkIdType>(gotCells.size()), want->GetNumberOfCells());
      for (vtkIdType c = 0; c < want->GetNumberOfCells(); ++c)
      {
        want->GetCellAtId(c, a);
        EXPECT_EQ(std::vector<vtkIdType>(a->begin(), a->end()), gotCells[c]) << "cell " << c;
      }
    }
  }
}

TEST(PolyDataTangentFrames, OnlyEmptyPolygonsAndStrips)
{
  // Points, but every polygon and strip without points: a warning and a pass-through of the
  // cells, no error (MikkTSpace called them out-of-range ids before, and its cell tangents read
  // the first corner of an empty polygon).
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(MirroredPair());
  mesh->SetPolys(vtkNew<vtkCellArray>());
  auto input = WithCell(WithCell(mesh, {}, false), {}, true);
  for (int method : EveryMethod)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(input);
    filter->SetMethod(method);
    filter->ComputeCellTangentsOn();
    filter->Update();
    EXPECT_TRUE(messages.Errors.empty()) << messages.Errors.front();
    EXPECT_TRUE(messages.Has(messages.Warnings, "2 polygon or strip cells have fewer than 3"));
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPolys(), 1);
    EXPECT_EQ(filter->GetOutput()->GetNumberOfStrips(), 1);
    ExpectValidFrames(filter->GetOutput()); // every point a fallback point
    vtkDataArray* cellTangents = filter->GetOutput()->GetCellData()->GetTangents();
    ASSERT_NE(cellTangents, nullptr);
    for (vtkIdType c = 0; c < 2; ++c)
    {
      // No triangle: the fixed rule's tangent for a zero normal.
      EXPECT_EQ(Get3(cellTangents, c), (Vec{ 1, 0, 0 })) << "cell " << c;
    }
  }
}

TEST(PolyDataTangentFrames, PolygonsWithRepeatedIds)
{
  // A quad (0, 1, 1, 2) fans into (0, 1, 1), degenerate, and (0, 1, 2); a triangle (2, 2, 2) and
  // a strip (0, 1, 0, 1) are degenerate throughout. The good triangle gives the frames.
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 0, 1, 1, 2 }, { 2, 2, 2 } },
    std::vector<Vec>(3, Vec{ 0, 0, 1 }));
  mesh = WithCell(mesh, { 0, 1, 0, 1 }, true);
  for (int method : EveryMethod)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(mesh);
    filter->SetMethod(method);
    filter->Update();
    EXPECT_TRUE(messages.Errors.empty());
    ExpectValidFrames(filter->GetOutput());
    for (vtkIdType p = 0; p < 3; ++p)
    {
      EXPECT_LT(AngleDeg(Get3(filter->GetOutput()->GetPointData()->GetTangents(), p), { 1, 0, 0 }),
        1e-5); // float output rounding, as above
    }
    if (method != vtkPolyDataTangentFrames::MIKKTSPACE) // it counts by its own rules
    {
      EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 4); // (0,1,1), (2,2,2), 2 in the strip
    }
  }
}

TEST(PolyDataTangentFrames, PointArraysShorterOrLongerThanThePoints)
{
  auto mesh = MirroredPair();
  for (int method : EveryMethod)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    const auto run = [&](vtkPolyDataTangentFrames* filter, vtkPolyData* input)
    {
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->SetTCoordsArrayName(input->GetPointData()->GetArray("UV2") ? "UV2" : "");
      filter->Update();
      return filter->GetOutput();
    };
    // Texture coordinates, active or named, one tuple short: an error and a pass-through.
    for (bool named : { false, true })
    {
      vtkNew<vtkPolyData> shortUV;
      shortUV->DeepCopy(mesh);
      vtkDataArray* uv = shortUV->GetPointData()->GetTCoords();
      uv->SetNumberOfTuples(3);
      if (named)
      {
        uv->SetName("UV2");
        shortUV->GetPointData()->SetActiveTCoords(nullptr);
      }
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      vtkPolyData* out = run(filter, shortUV);
      EXPECT_TRUE(messages.Has(messages.Errors, "has 3 tuples for 4 points"));
      EXPECT_EQ(out->GetPoints(), shortUV->GetPoints());
      EXPECT_EQ(out->GetPointData()->GetTangents(), nullptr);
    }
    // Point normals one short: ignored with a warning and computed instead.
    {
      vtkNew<vtkPolyData> shortNormals;
      shortNormals->DeepCopy(mesh);
      shortNormals->GetPointData()->GetNormals()->SetNumberOfTuples(3);
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      vtkPolyData* out = run(filter, shortNormals);
      EXPECT_TRUE(messages.Errors.empty());
      EXPECT_TRUE(messages.Has(messages.Warnings, "has 3 tuples for 4 points"));
      vtkDataArray* n = out->GetPointData()->GetNormals();
      ASSERT_EQ(n->GetNumberOfTuples(), out->GetNumberOfPoints());
      EXPECT_EQ(Get3(n, 3), (Vec{ 0, 0, 1 })); // computed
      ExpectValidFrames(out);
    }
    // Cell normals one short (and no point normals): not used; normals computed.
    {
      vtkNew<vtkPolyData> shortCellNormals;
      shortCellNormals->DeepCopy(mesh);
      shortCellNormals->GetPointData()->SetNormals(nullptr);
      vtkNew<vtkFloatArray> cn;
      cn->SetNumberOfComponents(3);
      cn->InsertNextTuple3(0, 0, 1);
      shortCellNormals->GetCellData()->SetNormals(cn);
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      vtkPolyData* out = run(filter, shortCellNormals);
      EXPECT_TRUE(messages.Errors.empty());
      EXPECT_TRUE(messages.Has(messages.Warnings, "no point normals; computing"));
      ExpectValidFrames(out);
    }
    // Unrelated point arrays shorter and longer than the points, with points split: the short
    // one passes as it is; the long one gets one tuple per output point, the copies' tuples
    // from their sources (the weighted methods read past the short one's end before).
    {
      vtkNew<vtkPolyData> extra;
      extra->DeepCopy(mesh);
      vtkNew<vtkDoubleArray> shorter, longer;
      shorter->SetName("Shorter");
      longer->SetName("Longer");
      for (int i = 0; i < 8; ++i)
      {
        longer->InsertNextValue(10 + i);
        if (i < 2)
        {
          shorter->InsertNextValue(i);
        }
      }
      extra->GetPointData()->AddArray(shorter);
      extra->GetPointData()->AddArray(longer);
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      vtkPolyData* out = run(filter, extra);
      EXPECT_TRUE(messages.Errors.empty());
      ASSERT_EQ(out->GetNumberOfPoints(), 6); // points 0 and 2 split, copies 4 and 5
      EXPECT_EQ(out->GetPointData()->GetArray("Shorter")->GetNumberOfTuples(), 2);
      vtkDataArray* l = out->GetPointData()->GetArray("Longer");
      ASSERT_EQ(l->GetNumberOfTuples(), 6);
      for (vtkIdType p = 0; p < 4; ++p)
      {
        EXPECT_EQ(l->GetComponent(p, 0), 10 + p);
      }
      EXPECT_EQ(l->GetComponent(4, 0), 10); // copy of point 0
      EXPECT_EQ(l->GetComponent(5, 0), 12); // copy of point 2
    }
  }
}

TEST(PolyDataTangentFrames, IntegerTextureCoordinatesAreConverted)
{
  // Texture coordinates stored as short integers are read through a double copy (which a
  // pointer outlived before: a use after free). The frames equal those from float storage.
  auto mesh = MirroredPair();
  vtkNew<vtkPolyData> integers;
  integers->DeepCopy(mesh);
  vtkNew<vtkShortArray> uv;
  uv->DeepCopy(mesh->GetPointData()->GetTCoords());
  integers->GetPointData()->SetTCoords(uv);
  for (int method : EveryMethod)
  {
    const auto configure = [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); };
    auto expected = RunFrames(mesh, configure);
    auto out = RunFrames(integers, configure);
    ASSERT_EQ(out->GetNumberOfPoints(), expected->GetNumberOfPoints());
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), p),
        Get3(expected->GetPointData()->GetTangents(), p));
    }
  }
}

TEST(PolyDataTangentFrames, MissingAndBadTextureCoordinates)
{
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 0, 1, 2 } },
    std::vector<Vec>(3, Vec{ 0, 0, 1 }));
  {
    vtkNew<vtkPolyData> noUV;
    noUV->DeepCopy(mesh);
    noUV->GetPointData()->SetTCoords(nullptr);
    noUV->GetPointData()->RemoveArray("TCoords");
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(noUV);
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Errors, "no active TCoords"));
    EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 3); // passed through
    EXPECT_EQ(filter->GetOutput()->GetPointData()->GetTangents(), nullptr);
  }
  {
    vtkNew<vtkPolyData> named;
    named->DeepCopy(mesh);
    vtkNew<vtkStringArray> text;
    text->SetName("UV2");
    text->SetNumberOfValues(3);
    named->GetPointData()->AddArray(text);
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(named);
    filter->SetTCoordsArrayName("UV2");
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Errors, "is not numeric"));
    filter->SetTCoordsArrayName("NoSuchArray");
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Errors, "NoSuchArray"));
  }
  {
    vtkNew<vtkPolyData> threeComponents;
    threeComponents->DeepCopy(mesh);
    vtkNew<vtkDoubleArray> uvw;
    uvw->SetNumberOfComponents(3);
    uvw->InsertNextTuple3(0, 0, 9);
    uvw->InsertNextTuple3(1, 0, 9);
    uvw->InsertNextTuple3(0, 1, 9);
    threeComponents->GetPointData()->SetTCoords(uvw);
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(threeComponents);
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Warnings, "using the first two"));
    EXPECT_EQ(Get3(filter->GetOutput()->GetPointData()->GetTangents(), 0), (Vec{ 1, 0, 0 }));
  }
  {
    vtkNew<vtkPolyData> shortArray;
    shortArray->DeepCopy(mesh);
    shortArray->GetPointData()->GetTCoords()->SetNumberOfTuples(2);
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(shortArray);
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Errors, "has 2 tuples for 3 points"));
  }
}

TEST(PolyDataTangentFrames, SecondUVSetByName)
{
  // TCoords map u along +x; a second set "UV2" maps u along +y.
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 } },
    { { 0, 1, 2 } },
    std::vector<Vec>(3, Vec{ 0, 0, 1 }));
  vtkNew<vtkFloatArray> uv2;
  uv2->SetName("UV2");
  uv2->SetNumberOfComponents(2);
  uv2->InsertNextTuple2(0, 0);
  uv2->InsertNextTuple2(0, 1);
  uv2->InsertNextTuple2(1, 0);
  mesh->GetPointData()->AddArray(uv2);
  auto out = RunFrames(mesh, [](vtkPolyDataTangentFrames* f) { f->SetTCoordsArrayName("UV2"); });
  EXPECT_EQ(Get3(out->GetPointData()->GetTangents(), 0), (Vec{ 0, 1, 0 }));
  // UV2 is a mirror image of TCoords' layout: handedness -1.
  EXPECT_EQ(out->GetPointData()->GetArray("TangentSigns")->GetComponent(0, 0), -1.0);
}

TEST(PolyDataTangentFrames, MissingNormalsAreComputedAndCellNormalsUsed)
{
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } },
    { { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } },
    { { 0, 1, 2 }, { 1, 3, 2 } });
  {
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(mesh);
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Warnings, "no point normals; computing"));
    vtkDataArray* n = filter->GetOutput()->GetPointData()->GetNormals();
    ASSERT_NE(n, nullptr);
    EXPECT_EQ(Get3(n, 3), (Vec{ 0, 0, 1 }));
    ExpectValidFrames(filter->GetOutput());
  }
  {
    vtkNew<vtkPolyData> withCellNormals;
    withCellNormals->DeepCopy(mesh);
    vtkNew<vtkFloatArray> cn;
    cn->SetNumberOfComponents(3);
    cn->InsertNextTuple3(0, 0, 2); // unnormalized on purpose
    cn->InsertNextTuple3(0, 0, 1);
    withCellNormals->GetCellData()->SetNormals(cn);
    vtkNew<vtkPolyDataTangentFrames> filter;
    Messages messages(filter);
    filter->SetInputData(withCellNormals);
    filter->Update();
    EXPECT_TRUE(messages.Has(messages.Warnings, "cell normals but no point normals"));
    EXPECT_EQ(Get3(filter->GetOutput()->GetPointData()->GetNormals(), 0), (Vec{ 0, 0, 1 }));
    ExpectValidFrames(filter->GetOutput());
  }
}

TEST(PolyDataTangentFrames, ComputedNormalsAreAreaWeighted)
{
  // Point 0 is in triangle (0, 1, 2), cross product (0, 0, 2), and triangle (0, 2, 3), cross
  // product (1, 0, 1): of other areas and planes. Point 4 is in no triangle. Computed normals
  // (docs/filter.md) are the area-weighted sums of the triangles' unit normals, or of the given
  // cell normals, normalized; +z for a point in no triangle.
  auto mesh = MakeTriangles({ { 0, 0, 0 }, { 2, 0, 0 }, { 0, 1, 0 }, { -1, 0, 1 }, { 5, 5, 5 } },
    { { 0, 0 }, { 2, 0 }, { 0, 1 }, { -1, 0 }, { 0, 0 } },
    { { 0, 1, 2 }, { 0, 2, 3 } });
  const double area0 = 1.0, area1 = std::sqrt(2.0) / 2;
  // Float output: unit vectors rounded once (6e-8 per component).
  const auto expectNear = [](const Vec& actual, const Vec& expected, const char* what)
  {
    const double length = Norm(expected);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(actual[k], expected[k] / length, 1e-6) << what << ", component " << k;
    }
  };
  {
    const auto out = RunFrames(mesh);
    vtkDataArray* n = out->GetPointData()->GetNormals();
    ASSERT_NE(n, nullptr);
    // area0 (0, 0, 1) + area1 (1, 0, 1) / sqrt(2)
    expectNear(
      Get3(n, 0), { area1 / std::sqrt(2.0), 0, area0 + area1 / std::sqrt(2.0) }, "point 0");
    expectNear(Get3(n, 4), { 0, 0, 1 }, "point 4");
  }
  {
    // Cell normals that are not the triangles' own, the first one unnormalized.
    vtkNew<vtkPolyData> withCellNormals;
    withCellNormals->DeepCopy(mesh);
    vtkNew<vtkFloatArray> cn;
    cn->SetNumberOfComponents(3);
    cn->InsertNextTuple3(0, 0, 2);
    cn->InsertNextTuple3(1, 0, 0);
    withCellNormals->GetCellData()->SetNormals(cn);
    const auto out = RunFrames(withCellNormals);
    vtkDataArray* n = out->GetPointData()->GetNormals();
    ASSERT_NE(n, nullptr);
    expectNear(Get3(n, 0), { area1, 0, area0 }, "point 0, cell normals");
    expectNear(Get3(n, 4), { 0, 0, 1 }, "point 4, cell normals");
  }
}

TEST(PolyDataTangentFrames, AZeroNormalIsReplacedByTheGeometricNormal)
{
  // A coarse torus, so that the sum of a point's triangle tangents leaves its tangent plane by
  // far more than the rounding; one point's normal zeroed. Its tangent is made perpendicular to
  // the area-weighted normal of its triangles (the sum of their cross products), computed here.
  vtkNormalMapping::TorusOptions options;
  options.U = 12;
  options.V = 6;
  auto mesh = vtkNormalMapping::MakeTorus(options);
  const vtkIdType zeroed = 7;
  mesh->GetPointData()->GetNormals()->SetTuple3(zeroed, 0, 0, 0);
  Vec geometric{ 0, 0, 0 };
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfPolys(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    if (ids->IsId(zeroed) < 0)
    {
      continue;
    }
    Vec p[3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids->GetId(k), p[k].data());
    }
    const Vec cross = Cross(Minus(p[1], p[0]), Minus(p[2], p[0]));
    for (int k = 0; k < 3; ++k)
    {
      geometric[k] += cross[k];
    }
  }
  for (int method : AllMethods)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    auto out = RunFrames(mesh, [&](vtkPolyDataTangentFrames* f) { f->SetMethod(method); });
    const Vec t = Get3(out->GetPointData()->GetTangents(), zeroed);
    // Float output: |T.N| of a unit vector rounded once, a few 1e-8.
    EXPECT_NEAR(Dot(t, geometric) / Norm(geometric), 0.0, 1e-6);
  }
}

// ------------------------------------------------------------------ VTK's sources

TEST(PolyDataTangentFrames, VTKSourcesAndTextureMappersGoThroughCleanly)
{
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> inputs;
  const auto add = [&](const std::string& name, vtkAlgorithm* source)
  {
    source->Update();
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->DeepCopy(vtkPolyData::SafeDownCast(source->GetOutputDataObject(0)));
    inputs.emplace_back(name, copy);
  };
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(8, 5);
  add("plane", plane);
  vtkNew<vtkCubeSource> cube;
  add("cube", cube);
  vtkNew<vtkTexturedSphereSource> texturedSphere;
  texturedSphere->SetThetaResolution(24);
  texturedSphere->SetPhiResolution(12);
  add("textured sphere", texturedSphere);
  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetResolution(16);
  add("cylinder", cylinder);
  vtkNew<vtkParametricTorus> torus;
  vtkNew<vtkParametricFunctionSource> parametric;
  parametric->SetParametricFunction(torus);
  parametric->GenerateTextureCoordinatesOn();
  parametric->SetUResolution(24);
  parametric->SetVResolution(12);
  add("parametric torus", parametric);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  vtkNew<vtkTextureMapToPlane> toPlane;
  toPlane->SetInputConnection(sphere->GetOutputPort());
  add("sphere + vtkTextureMapToPlane", toPlane);
  vtkNew<vtkTextureMapToSphere> toSphere;
  toSphere->SetInputConnection(sphere->GetOutputPort());
  add("sphere + vtkTextureMapToSphere", toSphere);
  vtkNew<vtkTextureMapToCylinder> toCylinder;
  toCylinder->SetInputConnection(sphere->GetOutputPort());
  add("sphere + vtkTextureMapToCylinder", toCylinder);

  for (auto& [name, input] : inputs)
  {
    SCOPED_TRACE(name);
    for (int method : AllMethods)
    {
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->ComputeBitangentsOn();
      filter->Update();
      EXPECT_TRUE(messages.Errors.empty()) << messages.Errors.front();
      vtkPolyData* out = filter->GetOutput();
      ASSERT_NE(out->GetPointData()->GetTangents(), nullptr);
      ExpectValidFrames(out);
      EXPECT_EQ(out->GetNumberOfCells(), input->GetNumberOfCells());
      EXPECT_EQ(
        out->GetNumberOfPoints(), input->GetNumberOfPoints() + filter->GetNumberOfSplitPoints());
    }
  }
}

// ------------------------------------------------------------------ determinism, settings

TEST(PolyDataTangentFrames, BitIdenticalForAnyNumberOfThreads)
{
  // The weighted methods sum the points in ranges (chunks) of point ids, as many as the threads
  // or more; each chunk adds the triangles of the tiles that reach its points. One, two and
  // eight threads must give the same bits, and the same counts. Two mirrored tori of different
  // sizes: the first fits one chunk on one thread, the second needs several. The first again
  // with its quads written as quads, strips and triangle pairs in turn, so that cells that are
  // not all triangles take every path too; and the second with its points in a random order, so
  // that every tile reaches every chunk (fewer chunks are then used), and with triangles that
  // have no frame.
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  for (int u : { 300, 521 })
  {
    vtkNormalMapping::TorusOptions options;
    options.U = u;
    options.V = u == 300 ? 120 : 257;
    options.MirrorU = true;
    meshes.push_back(vtkNormalMapping::MakeTorus(options));
  }
  {
    // MakeTorus writes each quad (a, b, c, d) as the triangles (a, b, c) and (a, c, d).
    vtkPolyData* torus = meshes[0];
    vtkNew<vtkCellArray> polys, strips;
    vtkNew<vtkIdList> tri0, tri1;
    for (vtkIdType q = 0; 2 * q + 1 < torus->GetNumberOfPolys(); ++q)
    {
      torus->GetCellPoints(2 * q, tri0);
      torus->GetCellPoints(2 * q + 1, tri1);
      const vtkIdType a = tri0->GetId(0), b = tri0->GetId(1), c = tri0->GetId(2),
                      d = tri1->GetId(2);
      if (q % 3 == 0)
      {
        const vtkIdType quad[4] = { a, b, c, d };
        polys->InsertNextCell(4, quad);
      }
      else if (q % 3 == 1)
      {
        const vtkIdType strip[4] = { b, c, a, d }; // (b, c, a) and (a, c, d)
        strips->InsertNextCell(4, strip);
      }
      else
      {
        polys->InsertNextCell(tri0);
        polys->InsertNextCell(tri1);
      }
    }
    auto mixed = vtkSmartPointer<vtkPolyData>::New();
    mixed->SetPoints(torus->GetPoints());
    mixed->GetPointData()->ShallowCopy(torus->GetPointData());
    mixed->SetPolys(polys);
    mixed->SetStrips(strips);
    meshes.push_back(mixed);
  }
  {
    // The second torus with shuffled points, whose first tenth of ids take one texture
    // coordinate: the triangles with all three points among them have no frame.
    auto shuffled = NormalMappingTesting::ShuffledPoints(meshes[1], 7);
    for (vtkIdType p = 0; p < shuffled->GetNumberOfPoints() / 10; ++p)
    {
      shuffled->GetPointData()->GetTCoords()->SetTuple2(p, 0.5, 0.5);
    }
    meshes.push_back(shuffled);
  }
  ASSERT_EQ(meshes[0]->GetNumberOfPoints(), 36300);
  ASSERT_EQ(meshes[1]->GetNumberOfPoints(), 134418);
  std::map<int, vtkIdType> torusDegenerate; // per method
  for (const auto& mesh : meshes)
    for (int method : AllMethods)
    {
      SCOPED_TRACE(std::to_string(mesh->GetNumberOfPoints()) + " points, " +
        std::to_string(mesh->GetNumberOfStrips()) + " strips");
      std::vector<std::vector<float>> results;
      std::vector<std::array<vtkIdType, 4>> counts;
      for (int threads : { 1, 2, 8 })
      {
        NormalMappingTesting::WithThreads(threads,
          [&]()
          {
            // A backend may grant fewer threads than asked (VTK's STDThread backend caps the
            // count at the core count), but a run asked for several must get several, so that
            // chunks summed on several threads are compared with those of one.
            const int granted = vtkSMPTools::GetEstimatedNumberOfThreads();
            EXPECT_LE(granted, threads);
            EXPECT_EQ(granted > 1, threads > 1);
            vtkNew<vtkPolyDataTangentFrames> f;
            f->SetInputData(mesh);
            f->SetMethod(method);
            f->ComputeBitangentsOn();
            f->ComputeCellTangentsOn();
            f->Update();
            vtkPolyData* out = f->GetOutput();
            std::vector<float> bits;
            for (vtkDataArray* array : { out->GetPointData()->GetArray("Tangents"),
                   out->GetPointData()->GetArray("TangentSigns"),
                   out->GetPointData()->GetArray("Bitangents"),
                   out->GetCellData()->GetTangents() })
            {
              auto* a = vtkFloatArray::SafeDownCast(array);
              bits.insert(bits.end(), a->GetPointer(0), a->GetPointer(0) + a->GetDataSize());
            }
            results.push_back(bits);
            counts.push_back({ f->GetNumberOfDegenerateTriangles(),
              f->GetNumberOfFallbackPoints(),
              f->GetNumberOfHandednessConflicts(),
              f->GetNumberOfSplitPoints() });
          });
      }
      ASSERT_EQ(results.size(), 3u);
      EXPECT_EQ(0, std::memcmp(results[0].data(), results[1].data(), results[0].size() * 4));
      EXPECT_EQ(0, std::memcmp(results[0].data(), results[2].data(), results[0].size() * 4));
      EXPECT_EQ(counts[0], counts[1]);
      EXPECT_EQ(counts[0], counts[2]);
      // The shuffled mesh has more triangles without a frame than the torus it comes from.
      if (mesh == meshes[1])
      {
        torusDegenerate[method] = counts[0][0];
      }
      if (mesh == meshes.back())
      {
        EXPECT_GT(counts[0][0], torusDegenerate[method]);
      }
    }
}

namespace
{
/// The storages besides 64-bit ids a vtkCellArray of triangles can take: 32-bit ids, and from
/// VTK 9.6 fixed-size cells (no offsets array), each as a conversion of the cell array.
std::vector<std::pair<std::string, bool (*)(vtkCellArray*)>> OtherCellStorages()
{
  std::vector<std::pair<std::string, bool (*)(vtkCellArray*)>> storages = { { "32-bit ids",
    [](vtkCellArray* c) { return c->ConvertTo32BitStorage() && !c->IsStorage64Bit(); } } };
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  storages.emplace_back("fixed-size cells, 64-bit ids",
    [](vtkCellArray* c)
    {
      return c->ConvertToStorageType(vtkCellArray::StorageTypes::FixedSizeInt64) &&
        c->IsStorageFixedSize64Bit();
    });
  storages.emplace_back("fixed-size cells, 32-bit ids",
    [](vtkCellArray* c)
    {
      return c->ConvertToStorageType(vtkCellArray::StorageTypes::FixedSizeInt32) &&
        c->IsStorageFixedSize32Bit();
    });
#endif
  return storages;
}
} // namespace

TEST(PolyDataTangentFrames, EveryCellStorageGivesTheSameFrames)
{
  // Triangles whose ids are stored in 32 bits are converted to vtkIdType first, a path of their
  // own, and fixed-size cells (VTK 9.6 and later) are read from a 64-bit copy: a mirrored torus
  // (split points re-point cells) must give the same bits in every output with any storage, for
  // every method, with cell tangents; an out-of-range id is still an error.
  vtkNormalMapping::TorusOptions options;
  options.U = 48;
  options.V = 24;
  options.MirrorU = true;
  auto wide = vtkNormalMapping::MakeTorus(options);
  const auto run = [](vtkPolyData* mesh, int method)
  {
    return RunFrames(mesh,
      [&](vtkPolyDataTangentFrames* f)
      {
        f->SetMethod(method);
        f->ComputeBitangentsOn();
        f->ComputeCellTangentsOn();
      });
  };
  for (const auto& storage : OtherCellStorages())
  {
    SCOPED_TRACE(storage.first);
    auto narrow = vtkSmartPointer<vtkPolyData>::New();
    narrow->DeepCopy(wide);
    ASSERT_TRUE(storage.second(narrow->GetPolys()));
    for (int method : EveryMethod)
    {
      SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
      auto a = run(wide, method);
      auto b = run(narrow, method);
      ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
      EXPECT_GT(a->GetNumberOfPoints(), wide->GetNumberOfPoints()); // the seams are split
      for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(a->GetPointData()),
             static_cast<vtkDataSetAttributes*>(a->GetCellData()) })
      {
        vtkDataSetAttributes* other = data == a->GetPointData()
          ? static_cast<vtkDataSetAttributes*>(b->GetPointData())
          : static_cast<vtkDataSetAttributes*>(b->GetCellData());
        for (const char* name : { "Tangents", "TangentSigns", "Bitangents" })
        {
          auto* x = vtkFloatArray::SafeDownCast(data->GetArray(name));
          auto* y = vtkFloatArray::SafeDownCast(other->GetArray(name));
          if (!x)
          {
            EXPECT_EQ(y, nullptr) << name;
            continue;
          }
          ASSERT_NE(y, nullptr) << name;
          ASSERT_EQ(x->GetDataSize(), y->GetDataSize()) << name;
          EXPECT_EQ(0, std::memcmp(x->GetPointer(0), y->GetPointer(0), 4 * x->GetDataSize()))
            << name;
        }
      }
      vtkNew<vtkIdList> pa, pb;
      for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c)
      {
        a->GetCellPoints(c, pa);
        b->GetCellPoints(c, pb);
        ASSERT_EQ(pa->GetNumberOfIds(), pb->GetNumberOfIds());
        for (vtkIdType k = 0; k < pa->GetNumberOfIds(); ++k)
        {
          ASSERT_EQ(pa->GetId(k), pb->GetId(k)) << "cell " << c;
        }
      }
    }
  }
  auto narrow = vtkSmartPointer<vtkPolyData>::New();
  narrow->DeepCopy(wide);
  ASSERT_TRUE(narrow->GetPolys()->ConvertTo32BitStorage());
  const vtkIdType bad[3] = { 0, 1, narrow->GetNumberOfPoints() };
  narrow->GetPolys()->InsertNextCell(3, bad);
  ASSERT_FALSE(narrow->GetPolys()->IsStorage64Bit());
  vtkNew<vtkPolyDataTangentFrames> filter;
  Messages messages(filter);
  filter->SetInputData(narrow);
  filter->Update();
  EXPECT_TRUE(messages.Has(messages.Errors, "point id outside"));
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetTangents(), nullptr);
}

TEST(PolyDataTangentFrames, OutputPrecision)
{
  vtkNormalMapping::TorusOptions options;
  options.U = 8;
  options.V = 4;
  auto floatMesh = vtkNormalMapping::MakeTorus(options);
  options.DoublePrecision = true;
  auto doubleMesh = vtkNormalMapping::MakeTorus(options);
  EXPECT_EQ(RunFrames(floatMesh)->GetPointData()->GetTangents()->GetDataType(), VTK_FLOAT);
  EXPECT_EQ(RunFrames(doubleMesh)->GetPointData()->GetTangents()->GetDataType(), VTK_DOUBLE);
  auto out = RunFrames(floatMesh,
    [](vtkPolyDataTangentFrames* f)
    {
      f->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
      f->ComputeBitangentsOn();
    });
  EXPECT_EQ(out->GetPointData()->GetTangents()->GetDataType(), VTK_DOUBLE);
  EXPECT_EQ(out->GetPointData()->GetArray("Bitangents")->GetDataType(), VTK_DOUBLE);
  out = RunFrames(doubleMesh,
    [](vtkPolyDataTangentFrames* f) { f->SetOutputPrecision(vtkAlgorithm::SINGLE_PRECISION); });
  EXPECT_EQ(out->GetPointData()->GetTangents()->GetDataType(), VTK_FLOAT);
}

TEST(PolyDataTangentFrames, ProgressAndAbort)
{
  vtkNormalMapping::TorusOptions options;
  options.U = 512;
  options.V = 256; // 262,144 triangles: more than one batch
  auto mesh = vtkNormalMapping::MakeTorus(options);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  NormalMappingTesting::ProgressRecorder recorder(filter);
  filter->Update();
  recorder.ExpectRisesToOne(5);

  // Abort at the first progress report: a valid, empty output.
  vtkNew<vtkCallbackCommand> abortNow;
  abortNow->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
    { static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn(); });
  filter->AddObserver(vtkCommand::ProgressEvent, abortNow);
  filter->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
}

TEST(PolyDataTangentFrames, PrintSelfListsEverySetting)
{
  vtkNew<vtkPolyDataTangentFrames> filter;
  std::ostringstream os;
  filter->Print(os);
  for (const char* setting : { "Method: AngleWeighted",
         "TCoordsArrayName",
         "Splitting: On",
         "GLTFSignConvention: Off",
         "ComputeBitangents: Off",
         "ComputeCellTangents: Off",
         "OutputPrecision",
         "NumberOfDegenerateTriangles",
         "NumberOfFallbackPoints",
         "NumberOfHandednessConflicts",
         "NumberOfSplitPoints",
         "NumberOfInvalidNormals" })
  {
    EXPECT_NE(os.str().find(setting), std::string::npos) << setting;
  }
}

// ------------------------------------------------------------------ against VTK's filter

TEST(PolyDataTangentFrames, AgreesWithVTKWhereVTKIsRightAndNotWhereItIsWrong)
{
  vtkNormalMapping::TorusOptions options;
  options.U = 64;
  options.V = 32;
  auto plain = vtkNormalMapping::MakeTorus(options);
  vtkNew<vtkPolyDataTangents> vtkFilter;
  vtkFilter->SetInputData(plain);
  vtkFilter->Update();
  auto ours = RunFrames(plain);
  vtkDataArray* theirs = vtkFilter->GetOutput()->GetPointData()->GetTangents();
  vtkDataArray* mine = ours->GetPointData()->GetTangents();
  vtkDataArray* n = ours->GetPointData()->GetNormals();
  double maxAngle = 0;
  for (vtkIdType p = 0; p < plain->GetNumberOfPoints(); ++p)
  {
    Vec t = Get3(theirs, p);
    const Vec nv = Get3(n, p);
    const double d = Dot(t, nv);
    for (int k = 0; k < 3; ++k)
    {
      t[k] -= d * nv[k]; // VTK's is not orthogonalized; compare directions in the tangent plane
    }
    maxAngle = std::max(maxAngle, AngleDeg(t, Get3(mine, p)));
  }
  // Both are within half a cell's turn (360/64/2 degrees) of the truth (see the analytic test).
  EXPECT_LT(maxAngle, 360.0 / options.U);

  // Mirrored UVs: VTK 9.1 has no sign, so its bitangent cross(N, T) points against dP/dv on the
  // mirrored half; ours, sign * cross(N, T), points along it. dP/dv on this torus is the
  // direction around the tube, (-sin theta cos phi, -sin theta sin phi, cos theta).
  options.MirrorU = true;
  auto mirrored = vtkNormalMapping::MakeTorus(options);
  vtkFilter->SetInputData(mirrored);
  vtkFilter->Update();
  auto oursMirrored = RunFrames(mirrored);
  const auto countWrongBitangents = [&](vtkPolyData* out, vtkDataArray* t, vtkDataArray* s)
  {
    int wrong = 0, total = 0;
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      Vec x;
      out->GetPoint(p, x.data());
      const Vec nv = Get3(out->GetPointData()->GetNormals(), p);
      const double phi = std::atan2(x[1], x[0]);
      const double theta = std::atan2(nv[2], nv[0] * std::cos(phi) + nv[1] * std::sin(phi));
      const Vec dPdv{
        -std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), std::cos(theta)
      };
      const double sign = s ? s->GetComponent(p, 0) : 1.0;
      Vec b = Cross(nv, Get3(t, p));
      wrong += Dot(b, dPdv) * sign > 0 ? 0 : 1;
      ++total;
    }
    return std::make_pair(wrong, total);
  };
  const auto [oursWrong, oursTotal] = countWrongBitangents(oursMirrored,
    oursMirrored->GetPointData()->GetTangents(),
    oursMirrored->GetPointData()->GetArray("TangentSigns"));
  EXPECT_EQ(oursWrong, 0);
  const auto [vtkWrong, vtkTotal] = countWrongBitangents(
    vtkFilter->GetOutput(), vtkFilter->GetOutput()->GetPointData()->GetTangents(), nullptr);
  // Roughly the mirrored half of VTK's points shade with a flipped bitangent.
  EXPECT_GT(vtkWrong, vtkTotal / 3) << "VTK's filter unexpectedly handles mirrored UVs";
  std::cout << "mirrored torus: bitangents against dP/dv: ours " << oursWrong << "/" << oursTotal
            << ", vtkPolyDataTangents " << vtkWrong << "/" << vtkTotal << "\n";

  // Degenerate UVs (all texture coordinates equal): ours gives finite fallback frames.
  vtkNew<vtkPolyData> collapsed;
  collapsed->DeepCopy(plain);
  collapsed->GetPointData()->GetTCoords()->Fill(0.25);
  auto oursCollapsed = RunFrames(collapsed);
  ExpectValidFrames(oursCollapsed);
  vtkFilter->SetInputData(collapsed);
  vtkFilter->Update();
  vtkDataArray* vtkCollapsed = vtkFilter->GetOutput()->GetPointData()->GetTangents();
  int vtkNonFinite = 0;
  for (vtkIdType p = 0; p < collapsed->GetNumberOfPoints(); ++p)
  {
    const Vec t = Get3(vtkCollapsed, p);
    vtkNonFinite += (std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2])) ? 0 : 1;
  }
  std::cout << "collapsed UVs: vtkPolyDataTangents gives " << vtkNonFinite << " of "
            << collapsed->GetNumberOfPoints() << " non-finite tangents; ours 0\n";
  // docs/filter.md: VTK's filter divides by the zero UV determinant on every point.
  EXPECT_EQ(vtkNonFinite, collapsed->GetNumberOfPoints());
}

TEST(PolyDataTangentFrames, MikkTSpaceWithoutNormalsUsesComputedNormals)
{
  // No point normals: the filter computes them first and MikkTSpace uses (and outputs) them.
  vtkNormalMapping::TorusOptions options;
  options.U = 16;
  options.V = 8;
  auto mesh = vtkNormalMapping::MakeTorus(options);
  mesh->GetPointData()->SetNormals(nullptr);
  mesh->GetPointData()->RemoveArray("Normals");
  vtkNew<vtkPolyDataTangentFrames> filter;
  Messages messages(filter);
  filter->SetInputData(mesh);
  filter->SetMethodToMikkTSpace();
  filter->Update();
  EXPECT_TRUE(messages.Errors.empty());
  EXPECT_TRUE(messages.Has(messages.Warnings, "no point normals; computing"));
  vtkPolyData* out = filter->GetOutput();
  ASSERT_NE(out->GetPointData()->GetNormals(), nullptr);
  EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 0); // no corner left at MikkTSpace's default
  ExpectValidFrames(out);
}

// ------------------------------------------------------------------ bad input, table-driven

namespace
{
/// MirroredPair with one cell of every kind: a vertex, a line and a strip beside the polygons.
vtkSmartPointer<vtkPolyData> EveryCellKind()
{
  auto mesh = WithCell(MirroredPair(), { 0, 1, 2 }, true);
  mesh->SetVerts(vtkNew<vtkCellArray>());
  mesh->SetLines(vtkNew<vtkCellArray>());
  const vtkIdType vertex = 3, line[2] = { 0, 3 };
  mesh->GetVerts()->InsertNextCell(1, &vertex);
  mesh->GetLines()->InsertNextCell(2, line);
  return mesh;
}

/// A copy of `mesh` whose cell array `kind` (0 vertices, 1 lines, 2 polygons, 3 strips) has the
/// given offsets over a connectivity of `size` ids (valid point ids if there are points), in 32- or
/// 64-bit storage. vtkCellArray::SetData takes such arrays without a check.
vtkSmartPointer<vtkPolyData> WithMalformedCells(vtkPolyData* mesh,
  int kind,
  const std::vector<long long>& offsets,
  vtkIdType size,
  bool storage64)
{
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(mesh);
  vtkNew<vtkCellArray> cells;
  const auto fill = [&](auto* o, auto* c)
  {
    using T = typename std::remove_pointer_t<decltype(o)>::ValueType;
    for (long long v : offsets)
    {
      o->InsertNextValue(static_cast<T>(v));
    }
    for (vtkIdType i = 0; i < size; ++i)
    {
      c->InsertNextValue(static_cast<T>(i % std::max<vtkIdType>(mesh->GetNumberOfPoints(), 1)));
    }
    cells->SetData(o, c);
  };
  if (storage64)
  {
    fill(vtkNew<vtkTypeInt64Array>().GetPointer(), vtkNew<vtkTypeInt64Array>().GetPointer());
  }
  else
  {
    fill(vtkNew<vtkTypeInt32Array>().GetPointer(), vtkNew<vtkTypeInt32Array>().GetPointer());
  }
  switch (kind)
  {
    case 0:
      copy->SetVerts(cells);
      break;
    case 1:
      copy->SetLines(cells);
      break;
    case 2:
      copy->SetPolys(cells);
      break;
    default:
      copy->SetStrips(cells);
  }
  return copy;
}

/// One run of every method, with and without splitting; `check` sees each output.
void ForEveryConfiguration(vtkPolyData* input,
  const std::function<void(vtkPolyDataTangentFrames*, const Messages&)>& check,
  const std::string& tcoordsName = std::string())
{
  for (int method : EveryMethod)
  {
    for (bool splitting : { true, false })
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (splitting ? ", splitting" : ", no splitting"));
      vtkNew<vtkPolyDataTangentFrames> filter;
      Messages messages(filter);
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->SetSplitting(splitting);
      filter->SetTCoordsArrayName(tcoordsName);
      filter->ComputeBitangentsOn();
      filter->ComputeCellTangentsOn();
      filter->Update();
      check(filter, messages);
    }
  }
}

/// The documented result of an error: exactly one error containing `text`, and the input passed
/// through (the same points and cell arrays, no frames).
void ExpectErrorAndPassThrough(vtkPolyDataTangentFrames* filter,
  const Messages& messages,
  vtkPolyData* input,
  const std::string& text)
{
  vtkPolyData* out = filter->GetOutput();
  ASSERT_EQ(messages.Errors.size(), 1u);
  EXPECT_NE(messages.Errors[0].find(text), std::string::npos) << messages.Errors[0];
  EXPECT_EQ(out->GetPoints(), input->GetPoints());
  EXPECT_EQ(out->GetVerts(), input->GetVerts());
  EXPECT_EQ(out->GetLines(), input->GetLines());
  EXPECT_EQ(out->GetPolys(), input->GetPolys());
  EXPECT_EQ(out->GetStrips(), input->GetStrips());
  EXPECT_EQ(out->GetPointData()->GetTangents(), nullptr);
}
} // namespace

TEST(PolyDataTangentFrames, MalformedCellArraysAreAnErrorForEveryMethod)
{
  // Offsets that do not start at 0, end before or past the connectivity (6 ids), decrease (a
  // cell of negative size, also where the sizes wrap around), are negative, lie far past the
  // connectivity, or are missing altogether, in each of the four cell arrays, 32- and 64-bit: one
  // error naming the array and the input passed through, from every method with and without
  // splitting, instead of reads and writes outside the arrays.
  auto mesh = EveryCellKind();
  const char* names[4] = { "vertex", "line", "polygon", "triangle strip" };
  for (bool storage64 : { false, true })
  {
    const long long far = storage64 ? (1LL << 40) : VTK_TYPE_INT32_MAX;
    const long long top = storage64 ? VTK_TYPE_INT64_MAX : VTK_TYPE_INT32_MAX;
    const std::vector<std::pair<std::vector<long long>, std::string>> cases = {
      { { 1, 3, 6 }, "its first offset is 1, not 0" },
      { { 0, 3, 5 }, "its last offset is 5 but the connectivity holds 6 ids" },
      { { 0, 3, 7 }, "its last offset is 7 but the connectivity holds 6 ids" },
      { { 0, 4, 2, 6 }, "the offsets decrease at cell 1 (4, then 2)" },
      { { 0, -3, 6 }, "the offsets decrease at cell 0 (0, then -3)" },
      { { 0, far, 6 }, "the offsets decrease at cell 1" },
      // Differences that wrap around in the offsets' type are all positive here.
      { { 0, top, -2, 6 }, "the offsets decrease at cell 1" },
      { { 0, 3, far }, "its last offset is " + std::to_string(far) },
      { {}, "it has no offsets" },
    };
    for (int kind = 0; kind < 4; ++kind)
    {
      for (const auto& entry : cases)
      {
        const std::vector<long long>& offsets = entry.first;
        const std::string& problem = entry.second; // (clang 14 cannot capture a structured binding)
        SCOPED_TRACE(std::string(names[kind]) + (storage64 ? " 64-bit: " : " 32-bit: ") + problem);
        auto bad = WithMalformedCells(mesh, kind, offsets, 6, storage64);
        ForEveryConfiguration(bad,
          [&](vtkPolyDataTangentFrames* filter, const Messages& messages)
          {
            ExpectErrorAndPassThrough(filter,
              messages,
              bad,
              "the " + std::string(names[kind]) + " cell array is malformed: " + problem);
          });
      }
    }
  }
  // Also without points, where a well-formed input has nothing to do.
  vtkNew<vtkPolyData> noPoints;
  noPoints->SetPoints(vtkNew<vtkPoints>());
  auto bad = WithMalformedCells(noPoints, 2, { 0, 3, 7 }, 6, true);
  ForEveryConfiguration(bad,
    [&](vtkPolyDataTangentFrames* filter, const Messages& messages)
    { ExpectErrorAndPassThrough(filter, messages, bad, "polygon cell array is malformed"); });
}

TEST(PolyDataTangentFrames, EveryBadInputEveryMethodWithAndWithoutSplitting)
{
  // The bad inputs of the README's "Error messages" table, each run through every method with
  // and without splitting (bitangents and cell tangents on, so every output path runs): errors
  // pass the input through; warnings and silent cases give valid frames (finite unit tangents
  // perpendicular to the normals, signs of +1 or -1). Under AddressSanitizer (scripts/
  // sanitize.sh) this is also the proof that none of them reads or writes out of bounds.
  auto base = EveryCellKind();
  struct Case
  {
    std::string Name;
    std::function<void(vtkPolyData*)> Change;
    std::string Error;   // expected error text (empty: none)
    std::string Warning; // expected warning text (empty: none)
    std::string TCoordsName = std::string();
    // The warning comes from the weighted methods only: MikkTSpace classifies triangles as the
    // reference does and does not count every one of these as degenerate, so it does not warn.
    bool WeightedMethodsOnly = false;
  };
  const auto removeTCoords = [](vtkPolyData* m)
  {
    m->GetPointData()->SetTCoords(nullptr);
    m->GetPointData()->RemoveArray("TCoords");
  };
  const auto removeNormals = [](vtkPolyData* m)
  {
    m->GetPointData()->SetNormals(nullptr);
    m->GetPointData()->RemoveArray("Normals");
  };
  const auto addCell = [](vtkPolyData* m, std::vector<vtkIdType> ids, bool strip)
  { (strip ? m->GetStrips() : m->GetPolys())->InsertNextCell(ids.size(), ids.data()); };
  const auto setTCoords = [](vtkPolyData* m, vtkDataArray* uv, int components)
  {
    uv->SetName("TCoords");
    uv->SetNumberOfComponents(components);
    uv->SetNumberOfTuples(m->GetNumberOfPoints());
    for (vtkIdType p = 0; p < m->GetNumberOfPoints(); ++p)
    {
      for (int k = 0; k < components; ++k)
      {
        uv->SetComponent(p, k, m->GetPointData()->GetTCoords()->GetComponent(p, k % 2));
      }
    }
    m->GetPointData()->SetTCoords(uv);
  };
  const std::vector<Case> cases = {
    { "no texture coordinates", removeTCoords, "no active TCoords", "" },
    { "texture coordinates named but missing",
      [](vtkPolyData*) {},
      "no point array texture coordinates 'UV2'",
      "",
      "UV2" },
    { "texture coordinates named, a string array",
      [&](vtkPolyData* m)
      {
        vtkNew<vtkStringArray> text;
        text->SetName("UV2");
        text->SetNumberOfValues(m->GetNumberOfPoints());
        m->GetPointData()->AddArray(text);
      },
      "point array 'UV2' is not numeric (vtkStringArray)",
      "",
      "UV2" },
    { "texture coordinates one short",
      [](vtkPolyData* m) { m->GetPointData()->GetTCoords()->SetNumberOfTuples(3); },
      "has 3 tuples for 4 points",
      "" },
    // Every method says "a polygon or strip refers to a point id outside [0, 4)".
    { "polygon id past the end",
      [&](vtkPolyData* m) {
        addCell(m, { 0, 1, 4 }, false);
      },
      "outside [0, 4); passing the input through",
      "" },
    { "negative id in a 1-point polygon",
      [&](vtkPolyData* m) { addCell(m, { -1 }, false); },
      "outside [0, 4); passing the input through",
      "" },
    { "bad id in a strip of 2",
      [&](vtkPolyData* m) {
        addCell(m, { 2, 9 }, true);
      },
      "outside [0, 4); passing the input through",
      "" },
    { "polygons and strips with 0, 1 and 2 points",
      [&](vtkPolyData* m)
      {
        for (const std::vector<vtkIdType>& ids : { std::vector<vtkIdType>{}, { 0 }, { 0, 2 } })
        {
          addCell(m, ids, false);
          addCell(m, ids, true);
        }
      },
      "",
      "6 polygon or strip cells have fewer than 3 points" },
    { "polygons and strips with repeated ids",
      [&](vtkPolyData* m)
      {
        addCell(m, { 0, 1, 1, 2 }, false);
        addCell(m, { 3, 3, 3 }, false);
        addCell(m, { 0, 1, 0, 1 }, true);
      },
      "",
      "" },
    { "point normals one short",
      [](vtkPolyData* m) { m->GetPointData()->GetNormals()->SetNumberOfTuples(3); },
      "",
      "Ignoring the point normals: point array 'Normals' has 3 tuples for 4 points" },
    // vtkDataSetAttributes refuses normals of other than 3 components, but an array can be
    // changed after it is set.
    { "point normals of 2 components",
      [](vtkPolyData* m)
      {
        vtkDataArray* normals = m->GetPointData()->GetNormals();
        normals->SetNumberOfComponents(2);
        normals->SetNumberOfTuples(m->GetNumberOfPoints());
        normals->Fill(0.5);
      },
      "",
      "Ignoring the point normals: point normals have 2 components instead of 3" },
    { "no normals", removeNormals, "", "no point normals; computing" },
    { "cell normals of 2 components only",
      [&](vtkPolyData* m)
      {
        removeNormals(m);
        vtkNew<vtkFloatArray> cn;
        cn->SetNumberOfComponents(3);
        cn->SetNumberOfTuples(m->GetNumberOfCells());
        m->GetCellData()->SetNormals(cn);
        cn->SetNumberOfComponents(2);
        cn->SetNumberOfTuples(m->GetNumberOfCells());
        cn->Fill(0.5);
      },
      "",
      "The input has no point normals; computing" },
    { "cell normals only",
      [&](vtkPolyData* m)
      {
        removeNormals(m);
        vtkNew<vtkFloatArray> cn;
        cn->SetNumberOfComponents(3);
        for (vtkIdType c = 0; c < m->GetNumberOfCells(); ++c)
        {
          cn->InsertNextTuple3(0, 0, 1);
        }
        m->GetCellData()->SetNormals(cn);
      },
      "",
      "cell normals but no point normals" },
    { "zero and NaN normals",
      [](vtkPolyData* m)
      {
        m->GetPointData()->GetNormals()->SetTuple3(0, 0, 0, 0);
        m->GetPointData()->GetNormals()->SetTuple3(1, std::nan(""), 0, 1);
      },
      "",
      "" },
    { "1-component texture coordinates",
      [&](vtkPolyData* m) { setTCoords(m, vtkNew<vtkDoubleArray>(), 1); },
      "",
      "have 1 component; using (u, 0)" },
    { "3-component texture coordinates",
      [&](vtkPolyData* m) { setTCoords(m, vtkNew<vtkDoubleArray>(), 3); },
      "",
      "have 3 components; using the first two" },
    { "integer texture coordinates",
      [&](vtkPolyData* m) { setTCoords(m, vtkNew<vtkShortArray>(), 2); },
      "",
      "" },
    { "NaN and infinite coordinates",
      [](vtkPolyData* m)
      {
        m->GetPoints()->SetPoint(1, std::nan(""), 0, 0);
        m->GetPointData()->GetTCoords()->SetTuple2(3, INFINITY, 0);
      },
      "",
      "None of the 3 triangles has a usable frame",
      "",
      true },
    { "other point arrays shorter and longer",
      [](vtkPolyData* m)
      {
        vtkNew<vtkDoubleArray> shorter, longer;
        shorter->SetName("Shorter");
        shorter->SetNumberOfTuples(2);
        shorter->Fill(1);
        longer->SetName("Longer");
        longer->SetNumberOfTuples(9);
        longer->Fill(2);
        m->GetPointData()->AddArray(shorter);
        m->GetPointData()->AddArray(longer);
      },
      "",
      "" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Name);
    vtkNew<vtkPolyData> input;
    input->DeepCopy(base);
    c.Change(input);
    ForEveryConfiguration(
      input,
      [&](vtkPolyDataTangentFrames* filter, const Messages& messages)
      {
        if (!c.Error.empty())
        {
          ExpectErrorAndPassThrough(filter, messages, input, c.Error);
          return;
        }
        EXPECT_TRUE(messages.Errors.empty()) << messages.Errors.front();
        if (c.Warning.empty() ||
          (c.WeightedMethodsOnly && filter->GetMethod() == vtkPolyDataTangentFrames::MIKKTSPACE))
        {
          EXPECT_TRUE(messages.Warnings.empty()) << messages.Warnings.front();
        }
        else
        {
          EXPECT_TRUE(messages.Has(messages.Warnings, c.Warning))
            << (messages.Warnings.empty() ? std::string("no warning") : messages.Warnings[0]);
        }
        vtkPolyData* out = filter->GetOutput();
        EXPECT_EQ(
          out->GetNumberOfPoints(), input->GetNumberOfPoints() + filter->GetNumberOfSplitPoints());
        EXPECT_EQ(out->GetNumberOfCells(), input->GetNumberOfCells());
        ExpectValidFrames(out);
      },
      c.TCoordsName);
  }
}
