// SPDX-License-Identifier: BSD-3-Clause
// Numerical stability of vtkPolyDataTangentFrames at the extremes: scaled, translated and
// near-degenerate input, a vertex of very high valence, and meshes of degenerate triangles.
#include "NormalMappingTestData.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkTangentFrameKernels.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkParametricEllipsoid.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTexturedSphereSource.h"
#include "vtkXMLPolyDataReader.h"

#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const double Pi = std::acos(-1.0);
using Vec = std::array<double, 3>;

const int WeightedMethods[] = { vtkPolyDataTangentFrames::UNWEIGHTED,
  vtkPolyDataTangentFrames::AREA_WEIGHTED,
  vtkPolyDataTangentFrames::ANGLE_WEIGHTED };

Vec Get3(vtkDataArray* a, vtkIdType i)
{
  Vec v;
  a->GetTuple(i, v.data());
  return v;
}

double AngleDeg(const Vec& a, const Vec& b)
{
  const Vec c{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
           a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) *
    180.0 / Pi;
}

/// The filter's output on one input, with its counts.
struct FilterRun
{
  vtkSmartPointer<vtkPolyData> Output;
  vtkIdType Degenerate;
  vtkIdType Splits;
};

FilterRun RunFilter(vtkPolyData* input, int method, int precision)
{
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  filter->SetMethod(method);
  filter->SetOutputPrecision(precision);
  filter->Update();
  return {
    filter->GetOutput(), filter->GetNumberOfDegenerateTriangles(), filter->GetNumberOfSplitPoints()
  };
}

vtkSmartPointer<vtkPolyData> Frames(vtkPolyData* input, int method, int precision)
{
  return RunFilter(input, method, precision).Output;
}

/// Every tangent finite, unit and perpendicular to its (normalized) normal within `tol`, every
/// sign +1 or -1.
void ExpectValid(vtkPolyData* out, double tol)
{
  vtkDataArray* t = out->GetPointData()->GetTangents();
  vtkDataArray* n = out->GetPointData()->GetNormals();
  vtkDataArray* s = out->GetPointData()->GetArray("TangentSigns");
  ASSERT_NE(t, nullptr);
  int reported = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints() && reported < 5; ++p)
  {
    const Vec tv = Get3(t, p);
    const Vec nv = Get3(n, p);
    const double len = std::sqrt(tv[0] * tv[0] + tv[1] * tv[1] + tv[2] * tv[2]);
    const double nlen = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    const double dot = (tv[0] * nv[0] + tv[1] * nv[1] + tv[2] * nv[2]) / nlen;
    const double sign = s->GetComponent(p, 0);
    const bool ok = std::abs(len - 1.0) <= tol && (!(nlen > 0) || std::abs(dot) <= tol) &&
      (sign == 1.0 || sign == -1.0);
    EXPECT_TRUE(ok) << "point " << p << " |T|=" << len << " T.N=" << dot << " sign=" << sign;
    reported += ok ? 0 : 1;
  }
}

/// A copy of mesh with points p -> scale * p + offset and texture coordinates uv -> uvScale * uv,
/// stored in the given precision (the transform is applied in double, then rounded once).
vtkSmartPointer<vtkPolyData> Transformed(vtkPolyData* mesh,
  double scale,
  double offset,
  double uvScale,
  bool doublePrecision)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  const int type = doublePrecision ? VTK_DOUBLE : VTK_FLOAT;
  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  points->SetNumberOfPoints(mesh->GetNumberOfPoints());
  auto uv = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  uv->SetNumberOfComponents(2);
  uv->SetNumberOfTuples(mesh->GetNumberOfPoints());
  uv->SetName("TCoords");
  vtkDataArray* inUV = mesh->GetPointData()->GetTCoords();
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    points->SetPoint(p, scale * x[0] + offset, scale * x[1] + offset, scale * x[2] + offset);
    uv->SetTuple2(p, uvScale * inUV->GetComponent(p, 0), uvScale * inUV->GetComponent(p, 1));
  }
  out->SetPoints(points);
  out->GetPointData()->SetTCoords(uv);
  return out;
}

vtkSmartPointer<vtkPolyData> Torus(bool mirror)
{
  vtkNormalMapping::TorusOptions options;
  options.U = 32;
  options.V = 16;
  options.MirrorU = mirror;
  options.DoublePrecision = true; // exact reference geometry; Transformed() stores it
  return vtkNormalMapping::MakeTorus(options);
}

double MaxAngleBetween(vtkPolyData* a, vtkPolyData* b)
{
  double worst = 0.0;
  vtkDataArray* ta = a->GetPointData()->GetTangents();
  vtkDataArray* tb = b->GetPointData()->GetTangents();
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    worst = std::max(worst, AngleDeg(Get3(ta, p), Get3(tb, p)));
  }
  return worst;
}
}

TEST(TangentFramesStability, ScaledPositionsAndTextureCoordinates)
{
  // The frame does not depend on the scale of positions or texture coordinates. Double input:
  // the scaled coordinates are rounded once (relative 2^-53) and the kernels rescale by exact
  // powers of two, so the frames agree to ~1e-12 degrees. Float input: rounding the scaled
  // coordinates to float (relative 2^-24 = 6e-8) moves an edge of this torus (length >= 0.07,
  // coordinates <= 1.35) by up to 1.35/0.07 * 6e-8 relative, about 1.2e-6 rad = 7e-5 degrees;
  // the float output adds 3.4e-6 degrees. Bounds: 1e-9 (double), 2e-4 (float) degrees.
  for (bool mirror : { false, true })
  {
    auto mesh = Torus(mirror);
    for (bool dbl : { false, true })
    {
      for (int method : WeightedMethods)
      {
        const int precision = vtkAlgorithm::DOUBLE_PRECISION;
        auto reference = Frames(Transformed(mesh, 1.0, 0.0, 1.0, dbl), method, precision);
        for (double scale : { 1e-30, 1e-20, 1e-10, 1e10, 1e20, 1e30 })
        {
          for (double uvScale : { 1e-10, 1.0, 1e10 })
          {
            auto out = Frames(Transformed(mesh, scale, 0.0, uvScale, dbl), method, precision);
            SCOPED_TRACE(std::string(dbl ? "double" : "float") + " method " +
              vtkPolyDataTangentFrames::GetMethodName(method) + " scale " + std::to_string(scale) +
              " uv " + std::to_string(uvScale));
            ASSERT_EQ(out->GetNumberOfPoints(), reference->GetNumberOfPoints());
            ExpectValid(out, 1e-12);
            EXPECT_LE(MaxAngleBetween(out, reference), dbl ? 1e-9 : 2e-4);
            vtkDataArray* s0 = reference->GetPointData()->GetArray("TangentSigns");
            vtkDataArray* s1 = out->GetPointData()->GetArray("TangentSigns");
            for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
            {
              ASSERT_EQ(s0->GetComponent(p, 0), s1->GetComponent(p, 0)) << "point " << p;
            }
          }
        }
      }
    }
  }
}

TEST(TangentFramesStability, AreaWeightsAtTheExtremesOfDouble)
{
  // Beyond the documented scales, double positions scaled by 1e-300 ... 1e300: the edges are
  // rescaled exactly, but the areas that weigh the tangents of AREA_WEIGHTED overflow or vanish
  // in the input's units. They are clamped to one range, where they weigh alike, so that
  // AREA_WEIGHTED gives the unit mesh's UNWEIGHTED frames (every area of this torus lies beyond
  // the clamp at these scales) and no point falls back; UNWEIGHTED and ANGLE_WEIGHTED give the
  // unit mesh's own. Bound: 1e-9 degrees, as for the documented scales.
  auto mesh = Torus(true);
  const int precision = vtkAlgorithm::DOUBLE_PRECISION;
  auto unit = Transformed(mesh, 1.0, 0.0, 1.0, true);
  for (double scale : { 1e-300, 1e-200, 1e154, 1e200, 1e300 })
  {
    for (int method : WeightedMethods)
    {
      SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method) + std::string(" scale ") +
        std::to_string(scale));
      const int referenceMethod = method == vtkPolyDataTangentFrames::AREA_WEIGHTED
        ? vtkPolyDataTangentFrames::UNWEIGHTED
        : method;
      auto reference = Frames(unit, referenceMethod, precision);
      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetInputData(Transformed(mesh, scale, 0.0, 1.0, true));
      filter->SetMethod(method);
      filter->SetOutputPrecision(precision);
      filter->Update();
      vtkPolyData* out = filter->GetOutput();
      ASSERT_EQ(out->GetNumberOfPoints(), reference->GetNumberOfPoints());
      ExpectValid(out, 1e-12);
      EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 0);
      EXPECT_LE(MaxAngleBetween(out, reference), 1e-9);
    }
  }
}

TEST(TangentFramesStability, TranslatedFarFromTheOrigin)
{
  // Translating by T rounds float coordinates to ulp(T) = T * 2^-24 (about 6e-4 at 1e4, 0.5 at
  // 1e7): edges of length h lose relative accuracy ulp(T)/h, and the tangent (a combination of
  // two edges) turns by up to a few times that. This torus has h >= 0.07, so the bound is
  // min(180, 4 * ulp(T) / 0.07 rad). Double input keeps ulp(T) = T * 2^-53 (2e-9 at 1e7).
  // Where 64 epsilon (T + 1.35) exceeds the longest edge (0.27 < 0.3) every triangle is within
  // the rounding noise of its coordinates (vtkNormalMapping::IsRoundingNoise): all degenerate,
  // every point a fallback point with a valid frame.
  auto mesh = Torus(false);
  std::cout << "translation | float input max angle (deg) | double input max angle (deg)\n";
  for (int method : WeightedMethods)
  {
    auto reference =
      Frames(Transformed(mesh, 1.0, 0.0, 1.0, true), method, vtkAlgorithm::DOUBLE_PRECISION);
    for (double offset : { 1e4, 1e5, 1e6, 1e7 })
    {
      double worst[2];
      for (bool dbl : { false, true })
      {
        const FilterRun run = RunFilter(
          Transformed(mesh, 1.0, offset, 1.0, dbl), method, vtkAlgorithm::DOUBLE_PRECISION);
        SCOPED_TRACE(std::to_string(offset) + (dbl ? " double" : " float"));
        ExpectValid(run.Output, 1e-12); // always a valid frame, however wrong its direction
        worst[dbl] = MaxAngleBetween(run.Output, reference);
        const double epsilon = dbl ? DBL_EPSILON : FLT_EPSILON;
        if (64.0 * epsilon * (offset + 1.35) > 0.3)
        {
          EXPECT_EQ(run.Degenerate, mesh->GetNumberOfPolys());
          continue;
        }
        EXPECT_EQ(run.Degenerate, 0);
        const double ulp = offset * std::ldexp(1.0, dbl ? -53 : -24);
        const double bound = std::min(180.0, 4.0 * ulp / 0.07 * 180.0 / Pi);
        EXPECT_LE(worst[dbl], bound);
      }
      if (method == vtkPolyDataTangentFrames::ANGLE_WEIGHTED)
      {
        std::cout << offset << " | " << worst[0] << " | " << worst[1] << "\n";
      }
    }
  }
}

namespace
{
using TexCoord = std::array<double, 2>;

/// A mesh of double points xyz[k] with texture coordinates uv[k] and point normals (0, 0, 1),
/// whose triangles are the consecutive triples of `ids`.
vtkSmartPointer<vtkPolyData> FacingUp(const std::vector<Vec>& xyz,
  const std::vector<TexCoord>& uv,
  const std::vector<vtkIdType>& ids)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> tc, normals;
  tc->SetNumberOfComponents(2);
  tc->SetName("TCoords");
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  for (size_t k = 0; k < xyz.size(); ++k)
  {
    points->InsertNextPoint(xyz[k].data());
    tc->InsertNextTuple(uv[k].data());
    normals->InsertNextTuple3(0, 0, 1);
  }
  vtkNew<vtkCellArray> polys;
  for (size_t t = 0; t + 2 < ids.size(); t += 3)
  {
    polys->InsertNextCell(3, &ids[t]);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetTCoords(tc);
  mesh->GetPointData()->SetNormals(normals);
  return mesh;
}

/// Two triangles sharing the edge (0,1)-(1,0) plus one test triangle (0, 1, 2) given by its
/// points and texture coordinates.
vtkSmartPointer<vtkPolyData> WithTestTriangle(const std::array<Vec, 3>& p,
  const std::array<TexCoord, 3>& uv)
{
  // A well-shaped neighbour so that the test triangle's points are not all fallback points.
  return FacingUp({ p[0], p[1], p[2], { 0.0, -1.0, 0.0 } },
    { uv[0], uv[1], uv[2], { 0.0, -1.0 } },
    { 0, 1, 2, 0, 3, 1 });
}
}

TEST(TangentFramesStability, NearDegenerateSliversAndNeedles)
{
  struct Case
  {
    const char* Name;
    std::array<Vec, 3> P;
    std::array<std::array<double, 2>, 3> UV;
    bool Degenerate; // expected classification of the test triangle
  };
  const double d = 1e-20;
  const std::vector<Case> cases = {
    { "UV determinant 1e-20 relative",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0.5, d } } },
      true },
    { "UV determinant 1e-3 relative",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0.5, 1e-3 } } },
      false },
    { "position sliver 1e-20",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, d, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0, 1 } } },
      true },
    { "needle (one edge 1e-20)",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 1, d, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0, 1 } } },
      true },
    { "zero area, good UVs",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0, 1 } } },
      true },
    { "good area, zero UV area",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } },
      { { { 0, 0 }, { 1, 1 }, { 2, 2 } } },
      true },
    { "thin but honest (shape 1e-3)",
      { { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, 1e-3, 0 } } },
      { { { 0, 0 }, { 1, 0 }, { 0.5, 1e-3 } } },
      false },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Name);
    for (int method : WeightedMethods)
    {
      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetInputData(WithTestTriangle(c.P, c.UV));
      filter->SetMethod(method);
      filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
      filter->Update();
      ExpectValid(filter->GetOutput(), 1e-12);
      EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), c.Degenerate ? 1 : 0);
    }
  }
}

TEST(TangentFramesStability, TheUVThresholdFollowsTheUVPrecision)
{
  // A UV triangle of shape ratio 1e-10: below 4 float epsilon (4.8e-7), far above 4 double
  // epsilon (8.9e-16). Stored in double it is a real (thin) UV triangle; stored in float its
  // shape is within the rounding of its coordinates, and it is degenerate.
  const auto mesh = WithTestTriangle(
    { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } }, { { { 0, 0 }, { 1, 0 }, { 0.5, 1e-10 } } });
  vtkNew<vtkFloatArray> floatUV;
  floatUV->DeepCopy(mesh->GetPointData()->GetTCoords());
  auto withFloatUV = vtkSmartPointer<vtkPolyData>::New();
  withFloatUV->DeepCopy(mesh);
  withFloatUV->GetPointData()->SetTCoords(floatUV);
  for (int method : WeightedMethods)
  {
    for (const bool doubleUV : { true, false })
    {
      SCOPED_TRACE(doubleUV ? "double UVs" : "float UVs");
      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetInputData(doubleUV ? mesh.Get() : withFloatUV.Get());
      filter->SetMethod(method);
      filter->Update();
      EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), doubleUV ? 0 : 1);
    }
  }
}

TEST(TangentFramesStability, VertexSharedByHundredThousandTriangles)
{
  // A disk fanned around its centre with 100,000 triangles and a planar map u = x: the centre's
  // tangent is (1, 0, 0) for every weighting (the fan is symmetric), up to the rounding of
  // 100,000 summands (relative 1e5 * 2^-53 ~ 1e-11): bound 1e-8 degrees.
  const int n = 100000;
  std::vector<Vec> xyz{ { 0, 0, 0 } };
  std::vector<TexCoord> uv{ { 0, 0 } };
  std::vector<vtkIdType> ids;
  for (int i = 0; i < n; ++i)
  {
    const double a = 2 * Pi * i / n;
    xyz.push_back({ std::cos(a), std::sin(a), 0 });
    uv.push_back({ std::cos(a), std::sin(a) });
    ids.insert(ids.end(), { 0, 1 + i, 1 + (i + 1) % n });
  }
  const auto disk = FacingUp(xyz, uv, ids);
  for (int method : WeightedMethods)
  {
    auto out = Frames(disk, method, vtkAlgorithm::DOUBLE_PRECISION);
    ExpectValid(out, 1e-12);
    EXPECT_LT(AngleDeg(Get3(out->GetPointData()->GetTangents(), 0), { 1, 0, 0 }), 1e-8);
  }
}

TEST(TangentFramesStability, MeshOfOnlyDegenerateTriangles)
{
  // 10,000 triangles, each with zero area or zero UV area: every point is a fallback point with
  // the fixed rule's frame, and the counts say so.
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> tc;
  tc->SetNumberOfComponents(2);
  vtkNew<vtkCellArray> polys;
  for (int i = 0; i < 10000; ++i)
  {
    const vtkIdType base = points->GetNumberOfPoints();
    if (i % 2)
    {
      // Collinear points with good UVs.
      points->InsertNextPoint(i, 0, 0);
      points->InsertNextPoint(i + 1, 0, 0);
      points->InsertNextPoint(i + 2, 0, 0);
      tc->InsertNextTuple2(0, 0);
      tc->InsertNextTuple2(1, 0);
      tc->InsertNextTuple2(0, 1);
    }
    else
    {
      // A good triangle with every UV equal.
      points->InsertNextPoint(i, 0, 0);
      points->InsertNextPoint(i + 1, 0, 0);
      points->InsertNextPoint(i, 1, 0);
      tc->InsertNextTuple2(0.5, 0.5);
      tc->InsertNextTuple2(0.5, 0.5);
      tc->InsertNextTuple2(0.5, 0.5);
    }
    const vtkIdType tri[3] = { base, base + 1, base + 2 };
    polys->InsertNextCell(3, tri);
  }
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetTCoords(tc);
  for (int method : WeightedMethods)
  {
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(mesh);
    filter->SetMethod(method);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    // Normals were computed (collinear triangles have none: (0, 0, 1) there).
    ExpectValid(out, 1e-6); // float output: 2^-23 per component
    EXPECT_EQ(filter->GetNumberOfDegenerateTriangles(), 10000);
    EXPECT_EQ(filter->GetNumberOfFallbackPoints(), 30000);
  }
}

namespace
{
struct NamedMesh
{
  const char* Name;
  vtkSmartPointer<vtkPolyData> Mesh;
};

vtkSmartPointer<vtkPolyData> ParametricSurface(vtkParametricFunction* function, int u, int v)
{
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(function);
  source->SetUResolution(u);
  source->SetVResolution(v);
  source->GenerateTextureCoordinatesOn();
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  return source->GetOutput();
}

/**
 * Triangulated surfaces with seams and poles as VTK's sources make them, points in double. Their
 * seam and pole points are computed more than once and differ by rounding: the parametric torus
 * has seam slivers about 30 epsilon * (largest coordinate) high, the ellipsoid and the sphere
 * pole triangles below one such unit, next to triangles about 1e14 units high.
 */
std::vector<NamedMesh> SeamAndPoleSurfaces()
{
  vtkNew<vtkParametricTorus> torus; // ring radius 1, tube radius 0.5
  vtkNew<vtkParametricEllipsoid> ellipsoid;
  ellipsoid->SetXRadius(1.0);
  ellipsoid->SetYRadius(0.7);
  ellipsoid->SetZRadius(0.5);
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  return { { "vtkParametricTorus 64x32", ParametricSurface(torus, 64, 32) },
    { "vtkParametricEllipsoid 48x24", ParametricSurface(ellipsoid, 48, 24) },
    { "vtkTexturedSphereSource 48x24", sphere->GetOutput() } };
}

/// A copy of a mesh made by Transformed(mesh, Scale, Offset, 1, Double).
struct Variant
{
  const char* Name;
  double Scale;
  double Offset;
  bool Double;
};

/// The largest coordinate magnitude of a mesh, and the smallest height (2 area / longest edge)
/// of its triangles that are more than 1e-6 of that high (the rest are rounding noise).
void Extent(vtkPolyData* mesh, double& largest, double& smallestHeight)
{
  largest = 0.0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const Vec x = Get3(mesh->GetPoints()->GetData(), p);
    largest = std::max({ largest, std::abs(x[0]), std::abs(x[1]), std::abs(x[2]) });
  }
  smallestHeight = largest;
  vtkIdType n;
  const vtkIdType* ids;
  mesh->GetPolys()->InitTraversal();
  while (mesh->GetPolys()->GetNextCell(n, ids))
  {
    ASSERT_EQ(n, 3);
    const Vec a = Get3(mesh->GetPoints()->GetData(), ids[0]);
    const Vec b = Get3(mesh->GetPoints()->GetData(), ids[1]);
    const Vec c = Get3(mesh->GetPoints()->GetData(), ids[2]);
    const Vec e1{ b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const Vec e2{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const Vec e3{ c[0] - b[0], c[1] - b[1], c[2] - b[2] };
    const Vec cr{
      e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]
    };
    const auto length = [](const Vec& v)
    { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); };
    const double h = length(cr) / std::max({ length(e1), length(e2), length(e3) });
    if (h > 1e-6 * largest)
    {
      smallestHeight = std::min(smallestHeight, h);
    }
  }
}
}

TEST(TangentFramesStability, SliverAtTheRoundingNoiseIsDegenerate)
{
  // The seam sliver of vtkParametricTorus: two points 31 epsilon * M apart (M = 1.5, the largest
  // coordinate) joined to a third 0.1 away, with full-size UVs. Its shape ratio (1e-13) is far
  // above 4 epsilon; its height is within 64 epsilon * M, so it has no frame. The same sliver
  // 128 epsilon * M high is a real (thin) triangle, and with the noise bound at 0 the seam
  // sliver would get a frame: the height rule classifies it.
  using vtkNormalMapping::ComputeTriangleFrame;
  using vtkNormalMapping::DegeneracyTolerance;
  const DegeneracyTolerance tol = DegeneracyTolerance::ForEpsilons(DBL_EPSILON, FLT_EPSILON);
  DegeneracyTolerance withoutNoise = tol;
  withoutNoise.PositionNoise = 0.0;
  const double unit = DBL_EPSILON * 1.5;
  const glm::dvec2 uv0(0.0, 1.0), uv1(1.0, 1.0), uv2(1.0, 0.9677);
  for (double height : { 31.0, 128.0 })
  {
    const glm::dvec3 p0(0.0, 1.5, 0.0), p1(height * unit, 1.5, 0.0),
      p2(height * unit, 1.4898, 0.1006);
    const bool noise = height < 64.0;
    EXPECT_EQ(ComputeTriangleFrame(p0, p1, p2, uv0, uv1, uv2, tol).Orientation == 0, noise)
      << height;
    EXPECT_NE(ComputeTriangleFrame(p0, p1, p2, uv0, uv1, uv2, withoutNoise).Orientation, 0)
      << height;
  }
}

TEST(TangentFramesStability, SeamAndPoleNoiseIsDegenerateAtAnyScaleAndPrecision)
{
  // The same surface stored in float, translated by 1e4 in double, and scaled in double and in
  // float gives the frames, signs, split points and degenerate counts of the unit double one.
  // Frames: rounding the stored coordinates moves a corner by up to epsilon * (M + T) (M the
  // largest coordinate of the unit mesh, T the translation), which turns a triangle whose height
  // is h by about that over h; a point's frame is a weighted mean of such directions, then made
  // perpendicular to the same normal. Bound: 8 epsilon (M + T) / h_min radians (h_min the
  // smallest height of a real triangle), a factor 8 for the two edges a tangent combines and
  // the UV distortion of these surfaces.
  const Variant variants[] = { { "float", 1.0, 0.0, false },
    { "double +1e4", 1.0, 1e4, true },
    { "double x1e-30", 1e-30, 0.0, true },
    { "double x1e30", 1e30, 0.0, true },
    { "float x1e-20", 1e-20, 0.0, false },
    { "float x1e20", 1e20, 0.0, false } };
  for (const NamedMesh& surface : SeamAndPoleSurfaces())
  {
    double largest = 0.0, smallestHeight = 0.0;
    Extent(surface.Mesh, largest, smallestHeight);
    for (int method : WeightedMethods)
    {
      const int precision = vtkAlgorithm::DOUBLE_PRECISION;
      const FilterRun reference =
        RunFilter(Transformed(surface.Mesh, 1.0, 0.0, 1.0, true), method, precision);
      for (const Variant& v : variants)
      {
        SCOPED_TRACE(std::string(surface.Name) + " " + v.Name + " method " +
          vtkPolyDataTangentFrames::GetMethodName(method));
        const FilterRun run =
          RunFilter(Transformed(surface.Mesh, v.Scale, v.Offset, 1.0, v.Double), method, precision);
        EXPECT_EQ(run.Degenerate, reference.Degenerate);
        ExpectValid(run.Output, 1e-12);
        EXPECT_EQ(run.Splits, reference.Splits);
        if (run.Splits != reference.Splits)
        {
          continue; // the points differ: nothing to compare them with
        }
        const double epsilon = v.Double ? DBL_EPSILON : FLT_EPSILON;
        const double bound = 8.0 * epsilon * (largest + v.Offset) / smallestHeight * 180.0 / Pi;
        const double worst = MaxAngleBetween(run.Output, reference.Output);
        std::cout << surface.Name << " " << v.Name << " "
                  << vtkPolyDataTangentFrames::GetMethodName(method) << ": degenerate "
                  << run.Degenerate << " splits " << run.Splits << " max " << worst
                  << " deg (bound " << bound << ")\n";
        EXPECT_LE(worst, bound);
        vtkDataArray* s0 = reference.Output->GetPointData()->GetArray("TangentSigns");
        vtkDataArray* s1 = run.Output->GetPointData()->GetArray("TangentSigns");
        for (vtkIdType p = 0; p < run.Output->GetNumberOfPoints(); ++p)
        {
          ASSERT_EQ(s0->GetComponent(p, 0), s1->GetComponent(p, 0)) << "point " << p;
        }
      }
    }
  }
}

namespace
{
/// Whether two outputs have the same points and bit-identical tangents and signs.
void ExpectSameBits(vtkPolyData* a, vtkPolyData* b)
{
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  vtkDataArray* ta = a->GetPointData()->GetTangents();
  vtkDataArray* tb = b->GetPointData()->GetTangents();
  vtkDataArray* sa = a->GetPointData()->GetArray("TangentSigns");
  vtkDataArray* sb = b->GetPointData()->GetArray("TangentSigns");
  vtkIdType differing = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    differing += Get3(ta, p) != Get3(tb, p) || sa->GetComponent(p, 0) != sb->GetComponent(p, 0);
  }
  EXPECT_EQ(differing, 0);
}
}

TEST(TangentFramesStability, MikkTSpaceScaledByPowersOfTwoKeepsEveryBit)
{
  // The MikkTSpace reference meshes (float) scaled by 2^-40 and 2^100, exactly (checked): the
  // kernel computes in float, where products of such coordinates under- or overflow; brought
  // back to unit extent by a power of two, the kernel gets the unit mesh's floats times a power
  // of two and gives the unit mesh's frames bit for bit.
  REQUIRE_SHARED_DATA(dataDir);
  for (const char* name : { "torus", "mirror_grid", "cylinder_seam", "noisy", "NormalTangentTest" })
  {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((dataDir + "/mikktspace/" + name + ".vtp").c_str());
    reader->Update();
    vtkPolyData* mesh = reader->GetOutput();
    ASSERT_GT(mesh->GetNumberOfPoints(), 0) << name;
    ASSERT_EQ(mesh->GetPoints()->GetDataType(), VTK_FLOAT) << name;
    const auto unit =
      Frames(mesh, vtkPolyDataTangentFrames::MIKKTSPACE, vtkAlgorithm::DOUBLE_PRECISION);
    for (int exponent : { -40, 100 })
    {
      SCOPED_TRACE(std::string(name) + " x 2^" + std::to_string(exponent));
      const double scale = std::ldexp(1.0, exponent);
      auto scaled = Transformed(mesh, scale, 0.0, 1.0, false);
      for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
      {
        const Vec a = Get3(mesh->GetPoints()->GetData(), p);
        const Vec b = Get3(scaled->GetPoints()->GetData(), p);
        ASSERT_EQ(a, Vec({ b[0] / scale, b[1] / scale, b[2] / scale })) << "point " << p;
      }
      ExpectSameBits(
        Frames(scaled, vtkPolyDataTangentFrames::MIKKTSPACE, vtkAlgorithm::DOUBLE_PRECISION), unit);
    }
    // Double input near the origin is the float input, rounded as the reference rounds it.
    ExpectSameBits(Frames(Transformed(mesh, 1.0, 0.0, 1.0, true),
                     vtkPolyDataTangentFrames::MIKKTSPACE,
                     vtkAlgorithm::DOUBLE_PRECISION),
      unit);
  }
}

TEST(TangentFramesStability, MikkTSpaceAtAnyScaleAndFarFromTheOrigin)
{
  // MikkTSpace computes in float: a double mesh scaled by 1e-30 ... 1e30 (or a float one by
  // 1e-20 ... 1e20) goes into the kernel at unit extent, rounded to float from a value that
  // differs from the unit mesh's by a factor that is not a power of two; a double mesh
  // translated by 1e4 goes in centred. Either way the kernel's floats differ from the unit
  // mesh's by their rounding, FLT_EPSILON * M (M the largest coordinate), which turns a frame
  // by about that over the smallest real triangle height h_min: bound 8 FLT_EPSILON M / h_min
  // radians, as in SeamAndPoleNoiseIsDegenerateAtAnyScaleAndPrecision. Split points: the same.
  const Variant variants[] = { { "double +1e4", 1.0, 1e4, true },
    { "double x1e-30", 1e-30, 0.0, true },
    { "double x1e30", 1e30, 0.0, true },
    { "float x1e-20", 1e-20, 0.0, false },
    { "float x1e20", 1e20, 0.0, false } };
  // The meshes are tori without rounding noise: MikkTSpace, like the reference, takes every
  // triangle of non-zero area as real, so where a translation makes noise-separated points
  // coincide (the seams and poles of SeamAndPoleSurfaces) its frames change there by design.
  for (bool mirror : { false, true })
  {
    const auto mesh = Torus(mirror);
    double largest = 0.0, smallestHeight = 0.0;
    Extent(mesh, largest, smallestHeight);
    const double bound = 8.0 * FLT_EPSILON * largest / smallestHeight * 180.0 / Pi;
    for (bool dbl : { false, true })
    {
      const FilterRun unit = RunFilter(Transformed(mesh, 1.0, 0.0, 1.0, dbl),
        vtkPolyDataTangentFrames::MIKKTSPACE,
        vtkAlgorithm::DOUBLE_PRECISION);
      for (const Variant& v : variants)
      {
        if (v.Double != dbl)
        {
          continue;
        }
        SCOPED_TRACE(std::string(mirror ? "mirrored torus " : "torus ") + v.Name);
        const FilterRun run = RunFilter(Transformed(mesh, v.Scale, v.Offset, 1.0, dbl),
          vtkPolyDataTangentFrames::MIKKTSPACE,
          vtkAlgorithm::DOUBLE_PRECISION);
        ExpectValid(run.Output, 1e-4);
        EXPECT_EQ(run.Splits, unit.Splits);
        if (run.Splits != unit.Splits)
        {
          continue;
        }
        const double worst = MaxAngleBetween(run.Output, unit.Output);
        std::cout << (mirror ? "mirrored torus" : "torus") << " MikkTSpace " << v.Name
                  << ": splits " << run.Splits << " max " << worst << " deg (bound " << bound
                  << ")\n";
        EXPECT_LE(worst, bound);
      }
    }
  }
}

TEST(TangentFramesStability, MikkTSpaceTinyFloatMeshFarAlongOneAxis)
{
  // A float torus squashed to 2^-16.1 across in x and z, at y = 0 and at y = 2^113 (float
  // input is not centred: the reference rounds nothing, so neither does the filter). The kernel
  // brings a mesh this small to unit extent (x 2^16), which would take the second's y past
  // float's largest value and make every frame the default; it scales that one by 2^13 only,
  // which leaves y below 2^127. y is the same at every point, so the edges, and with them every
  // frame, are those of the mesh at y = 0, bit for bit: the two scales differ by a power of two
  // and leave the edges far inside float's range. A smaller scale would not do: below an extent
  // of about 2^-16 the kernel's own products of edges underflow and change frames.
  vtkNormalMapping::TorusOptions options;
  options.U = 16;
  options.V = 8;
  options.DoublePrecision = true;
  const auto torus = vtkNormalMapping::MakeTorus(options);
  const double squash = std::ldexp(1.0, -16) / 2.7 / 1.08; // the torus is 2.7 across
  const auto place = [&](float y)
  {
    auto out = vtkSmartPointer<vtkPolyData>::New();
    out->DeepCopy(torus);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(torus->GetNumberOfPoints());
    for (vtkIdType p = 0; p < torus->GetNumberOfPoints(); ++p)
    {
      double x[3];
      torus->GetPoint(p, x);
      points->SetPoint(p, squash * x[0], y, squash * x[2]);
    }
    out->SetPoints(points);
    return out;
  };
  vtkNew<vtkPolyDataTangentFrames> near, far;
  near->SetInputData(place(0.0f));
  far->SetInputData(place(std::ldexp(1.0f, 113)));
  for (vtkPolyDataTangentFrames* f : { near.Get(), far.Get() })
  {
    f->SetMethodToMikkTSpace();
    f->Update();
  }
  vtkPolyData* a = near->GetOutput();
  vtkPolyData* b = far->GetOutput();
  ExpectValid(b, 1e-4);
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  EXPECT_LT(far->GetNumberOfFallbackPoints(), b->GetNumberOfPoints() / 10);
  EXPECT_EQ(far->GetNumberOfFallbackPoints(), near->GetNumberOfFallbackPoints());
  vtkDataArray* ta = a->GetPointData()->GetTangents();
  vtkDataArray* tb = b->GetPointData()->GetTangents();
  vtkIdType differing = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    differing += Get3(ta, p) == Get3(tb, p) ? 0 : 1;
  }
  EXPECT_EQ(differing, 0);
}

TEST(TangentFramesStability, TriangleFacingAwayFromTheNormalKeepsTheTextureHandedness)
{
  // A flat 2 x 2 grid, u = x / 2, v = y / 2, point normals +z, with one triangle wound the
  // other way (its winding normal is -z; its texture map is that of its neighbours). A renderer
  // computes B = sign * cross(N, T) with the point normal: B must be dP/dv = +y everywhere, so
  // the sign is +1 at every point, the flipped triangle agrees with its neighbours and nothing
  // splits. MikkTSpace keeps the reference's sign, that of the UV winding: -1 at the flipped
  // triangle's corners, whose points it splits (what tools that bake normal maps expect).
  std::vector<Vec> xyz;
  std::vector<TexCoord> uv;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      xyz.push_back({ double(i), double(j), 0.0 });
      uv.push_back({ 0.5 * i, 0.5 * j });
    }
  }
  std::vector<vtkIdType> ids;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      const vtkIdType a = 3 * j + i, b = a + 1, c = a + 4, d = a + 3;
      const bool flipped = i == 0 && j == 0;
      ids.insert(ids.end(), { a, flipped ? c : b, flipped ? b : c, a, c, d });
    }
  }
  const auto grid = FacingUp(xyz, uv, ids);
  for (int method : WeightedMethods)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(grid);
    filter->SetMethod(method);
    filter->ComputeBitangentsOn();
    filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
    filter->Update();
    vtkPolyData* out = filter->GetOutput();
    EXPECT_EQ(filter->GetNumberOfHandednessConflicts(), 0);
    ASSERT_EQ(out->GetNumberOfPoints(), 9);
    for (vtkIdType p = 0; p < 9; ++p)
    {
      // Exact input, one tangent direction: only the rounding of a normalization (1e-12 deg).
      EXPECT_EQ(out->GetPointData()->GetArray("TangentSigns")->GetComponent(p, 0), 1.0) << p;
      EXPECT_LT(AngleDeg(Get3(out->GetPointData()->GetTangents(), p), { 1, 0, 0 }), 1e-12) << p;
      EXPECT_LT(AngleDeg(Get3(out->GetPointData()->GetArray("Bitangents"), p), { 0, 1, 0 }), 1e-12)
        << p;
    }
  }
  vtkNew<vtkPolyDataTangentFrames> mikk;
  mikk->SetInputData(grid);
  mikk->SetMethodToMikkTSpace();
  mikk->Update();
  vtkPolyData* out = mikk->GetOutput();
  // Points 0, 1 and 4 are the flipped triangle's, the first cell: they keep its frame (their
  // first corner's), and their copies, appended in that order, the +1 frame of the others.
  EXPECT_EQ(mikk->GetNumberOfSplitPoints(), 3);
  ASSERT_EQ(out->GetNumberOfPoints(), 12);
  vtkDataArray* signs = out->GetPointData()->GetArray("TangentSigns");
  for (vtkIdType p : { 0, 1, 4 })
  {
    EXPECT_EQ(signs->GetComponent(p, 0), -1.0) << p;
  }
  for (vtkIdType p = 9; p < 12; ++p)
  {
    EXPECT_EQ(signs->GetComponent(p, 0), 1.0) << p;
  }
}
