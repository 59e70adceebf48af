// SPDX-License-Identifier: BSD-3-Clause
// The three weightings of vtkPolyDataTangentFrames told apart: a planar fan around one point
// whose triangles carry two different tangents, split into triangles in two ways. Each method's
// tangent at the fan's centre has a closed form, and the three differ.
#include "vtkPolyDataTangentFrames.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
const double Pi = std::acos(-1.0);
const double Degree = Pi / 180.0;

/**
 * A fan around the origin in the z = 0 plane (normals +z), radius 1. Sector A, from 0 to 90
 * degrees, is split at the angles `splitA` and textured with (u, v) = (x, y): its triangles'
 * tangent dP/du is +x. Sector B, from 90 to 180 degrees, is one triangle textured with
 * (u, v) = (y, -x), a rotation (no mirroring): its tangent is +y. Each triangle has its own rim
 * points, so the centre (point 0, where both maps give (0, 0)) is the only shared point.
 */
vtkSmartPointer<vtkPolyData> Fan(const std::vector<double>& splitA)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  vtkNew<vtkDoubleArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkCellArray> triangles;
  const auto add = [&](double x, double y, bool sectorB)
  {
    normals->InsertNextTuple3(0.0, 0.0, 1.0);
    tcoords->InsertNextTuple2(sectorB ? y : x, sectorB ? -x : y);
    return points->InsertNextPoint(x, y, 0.0);
  };
  add(0.0, 0.0, false);
  const auto wedge = [&](double from, double to, bool sectorB)
  {
    const vtkIdType a = add(std::cos(from), std::sin(from), sectorB);
    const vtkIdType b = add(std::cos(to), std::sin(to), sectorB);
    const vtkIdType ids[3] = { 0, a, b }; // counter-clockwise: normal +z
    triangles->InsertNextCell(3, ids);
  };
  for (size_t i = 0; i + 1 < splitA.size(); ++i)
  {
    wedge(splitA[i], splitA[i + 1], false);
  }
  wedge(90.0 * Degree, 180.0 * Degree, true);
  auto fan = vtkSmartPointer<vtkPolyData>::New();
  fan->SetPoints(points);
  fan->SetPolys(triangles);
  fan->GetPointData()->SetNormals(normals);
  fan->GetPointData()->SetTCoords(tcoords);
  return fan;
}

/// Direction of the centre's tangent in the plane, in degrees from +x.
double CentreTangentDegrees(vtkPolyData* fan, int method)
{
  vtkNew<vtkPolyDataTangentFrames> frames;
  frames->SetInputData(fan);
  frames->SetMethod(method);
  frames->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  frames->Update();
  vtkPolyData* out = frames->GetOutput();
  EXPECT_EQ(out->GetNumberOfPoints(), fan->GetNumberOfPoints()) << "no mirroring: no splitting";
  double t[3];
  out->GetPointData()->GetTangents()->GetTuple(0, t);
  EXPECT_NEAR(t[2], 0.0, 1e-12);
  return std::atan2(t[1], t[0]) / Degree;
}

/// The weights of sectors A and B for a method, in closed form.
struct SectorWeights
{
  double A = 0.0, B = 0.0;
  /// The direction of A's weight times +x plus B's weight times +y, in degrees.
  double Degrees() const { return std::atan2(this->B, this->A) / Degree; }
};

SectorWeights Expected(const std::vector<double>& splitA, int method)
{
  SectorWeights w;
  for (size_t i = 0; i + 1 < splitA.size(); ++i)
  {
    const double angle = splitA[i + 1] - splitA[i];
    w.A += method == vtkPolyDataTangentFrames::UNWEIGHTED
      ? 1.0
      : (method == vtkPolyDataTangentFrames::AREA_WEIGHTED ? 0.5 * std::sin(angle) : angle);
  }
  // Sector B: one right-angled wedge of area 1/2.
  w.B = method == vtkPolyDataTangentFrames::UNWEIGHTED
    ? 1.0
    : (method == vtkPolyDataTangentFrames::AREA_WEIGHTED ? 0.5 : 90.0 * Degree);
  return w;
}

const int WeightedMethods[] = { vtkPolyDataTangentFrames::UNWEIGHTED,
  vtkPolyDataTangentFrames::AREA_WEIGHTED,
  vtkPolyDataTangentFrames::ANGLE_WEIGHTED };

// Two ways to split sector A: three even wedges, and two uneven ones.
const std::vector<std::vector<double>> Splits = {
  { 0.0, 30.0 * Degree, 60.0 * Degree, 90.0 * Degree },
  { 0.0, 10.0 * Degree, 90.0 * Degree }
};
}

TEST(TangentFramesWeighting, EachMethodGivesItsOwnClosedFormAnswer)
{
  // Every input is exact or within an ulp of double (the rim's sines and cosines), each
  // triangle's tangent is +x or +y to rounding, and the weights (counts, areas from cross
  // products, angles within about an ulp of atan2) have relative errors near 1e-16: the
  // direction is right to ~1e-13 degrees. 1e-9 degrees leaves room for that and is far below
  // the separation of the methods' answers (checked first, so the test can tell them apart).
  const double tolerance = 1e-9;
  for (const auto& split : Splits)
  {
    const double unweighted = Expected(split, vtkPolyDataTangentFrames::UNWEIGHTED).Degrees();
    const double area = Expected(split, vtkPolyDataTangentFrames::AREA_WEIGHTED).Degrees();
    const double angle = Expected(split, vtkPolyDataTangentFrames::ANGLE_WEIGHTED).Degrees();
    ASSERT_GT(std::abs(unweighted - area), 5.0);
    ASSERT_GT(std::abs(area - angle), 4.0);
    ASSERT_GT(std::abs(unweighted - angle), 15.0);

    auto fan = Fan(split);
    for (int method : WeightedMethods)
    {
      SCOPED_TRACE(std::string(vtkPolyDataTangentFrames::GetMethodName(method)) + ", " +
        std::to_string(split.size() - 1) + " wedges in sector A");
      EXPECT_NEAR(CentreTangentDegrees(fan, method), Expected(split, method).Degrees(), tolerance);
    }
  }
}

TEST(TangentFramesWeighting, OnlyAngleWeightingIgnoresHowTheFanIsSplit)
{
  // Sectors A and B both span 90 degrees: angle weighting gives the bisector, 45 degrees, for
  // any split of A; the other two move with the split (by 8 and 7 degrees here).
  const double tolerance = 1e-9; // as above
  auto even = Fan(Splits[0]);
  auto uneven = Fan(Splits[1]);
  EXPECT_NEAR(
    CentreTangentDegrees(even, vtkPolyDataTangentFrames::ANGLE_WEIGHTED), 45.0, tolerance);
  EXPECT_NEAR(
    CentreTangentDegrees(uneven, vtkPolyDataTangentFrames::ANGLE_WEIGHTED), 45.0, tolerance);
  for (int method :
    { vtkPolyDataTangentFrames::UNWEIGHTED, vtkPolyDataTangentFrames::AREA_WEIGHTED })
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    EXPECT_GT(
      std::abs(CentreTangentDegrees(even, method) - CentreTangentDegrees(uneven, method)), 5.0);
  }
}
