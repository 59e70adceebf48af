// SPDX-License-Identifier: BSD-3-Clause
#include "vtkTangentFrameChecks.h"

#include "vtkNormalMappingPrivate.h"
#include "vtkTangentFrameKernels.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <cmath>

namespace vtkNormalMapping
{
namespace
{
/// Winding bits of a point: it has a usable triangle of positive / negative handedness.
constexpr unsigned char PositiveWinding = 1;
constexpr unsigned char NegativeWinding = 2;

/// The triangles of the polygons and strips (detail::CellTriangle), three point ids each.
std::vector<vtkIdType> ListTriangles(vtkPolyData* mesh)
{
  std::vector<vtkIdType> ids;
  for (int kind = 0; kind < 2; ++kind)
  {
    const bool strip = kind == 1;
    auto it = vtk::TakeSmartPointer((strip ? mesh->GetStrips() : mesh->GetPolys())->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* pts;
      it->GetCurrentCell(n, pts);
      for (vtkIdType j = 0; j + 2 < n; ++j)
      {
        vtkIdType tri[3];
        detail::CellTriangle(pts, j, strip, tri);
        ids.insert(ids.end(), tri, tri + 3);
      }
    }
  }
  return ids;
}

glm::dvec3 Tuple3(vtkDataArray* array, vtkIdType id)
{
  double v[3];
  array->GetTuple(id, v);
  return glm::dvec3(v[0], v[1], v[2]);
}

glm::dvec2 UV(vtkDataArray* uvs, vtkIdType id)
{
  return glm::dvec2(
    uvs->GetComponent(id, 0), uvs->GetNumberOfComponents() > 1 ? uvs->GetComponent(id, 1) : 0.0);
}

/**
 * Per point, the windings (PositiveWinding, NegativeWinding bits) of its usable triangles
 * relative to its normal: the handedness vtkPolyDataTangentFrames gives each corner.
 */
std::vector<unsigned char> PointWindings(vtkPolyData* mesh,
  vtkDataArray* normals,
  vtkDataArray* uvs)
{
  const vtkIdType numPoints = mesh->GetNumberOfPoints();
  const std::vector<vtkIdType> ids = ListTriangles(mesh);
  const vtkIdType numTriangles = static_cast<vtkIdType>(ids.size() / 3);
  vtkDataArray* points = mesh->GetPoints()->GetData();
  const DegeneracyTolerance tol = detail::ToleranceFor(points, uvs);
  std::vector<signed char> sides(ids.size(), 0);
  vtkSMPTools::For(0,
    numTriangles,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType t = begin; t < end; ++t)
      {
        const vtkIdType* tri = &ids[3 * t];
        if (std::any_of(tri, tri + 3, [&](vtkIdType id) { return id < 0 || id >= numPoints; }))
        {
          continue;
        }
        const TriangleFrame f = ComputeTriangleFrame(Tuple3(points, tri[0]),
          Tuple3(points, tri[1]),
          Tuple3(points, tri[2]),
          UV(uvs, tri[0]),
          UV(uvs, tri[1]),
          UV(uvs, tri[2]),
          tol);
        for (int k = 0; f.Orientation != 0 && k < 3; ++k)
        {
          sides[3 * t + k] =
            static_cast<signed char>(CornerSign(f, SafeNormalize(Tuple3(normals, tri[k]))));
        }
      }
    });
  std::vector<unsigned char> windings(static_cast<size_t>(numPoints), 0);
  for (size_t c = 0; c < ids.size(); ++c)
  {
    if (sides[c] != 0)
    {
      windings[ids[c]] |= sides[c] > 0 ? PositiveWinding : NegativeWinding;
    }
  }
  return windings;
}

/// A point's supplied frame measured against its normal; nothing but Finite when the tangent or
/// the sign is not finite, or the tangent longer than the largest length allowed.
struct PointMeasures
{
  bool Finite = false;
  double Sign = 0.0;
  double LengthError = 0.0; ///< | |T| - 1 |
  double Cosine = 0.0;      ///< |T.N| / |T|, 0 for a zero tangent
  bool HasNormal = false;   ///< false: the normal is zero or non-finite, nothing to measure against
};

PointMeasures Measure(const glm::dvec3& normal,
  const glm::dvec3& tangent,
  double sign,
  double largest)
{
  PointMeasures m;
  m.Finite = detail::IsFinite(tangent) && std::isfinite(sign);
  // The length without overflow of the squares, so that a finite tangent up to `largest` passes.
  const double largestComponent = m.Finite ? detail::MaxAbs(tangent) : 0.0;
  const double length =
    largestComponent > 0.0 ? largestComponent * glm::length(tangent / largestComponent) : 0.0;
  m.Finite = m.Finite && length <= largest;
  if (!m.Finite)
  {
    return m;
  }
  const glm::dvec3 n = SafeNormalize(normal);
  m.Sign = sign;
  m.LengthError = std::abs(length - 1.0);
  m.HasNormal = n != glm::dvec3(0.0);
  m.Cosine = m.HasNormal && length > 0.0 ? std::abs(glm::dot(n, tangent)) / length : 0.0;
  return m;
}

/// The FrameDefect bits of one point.
unsigned char PointDefects(const PointMeasures& m,
  unsigned char winding,
  bool vDown,
  const FrameCheckTolerances& tol)
{
  if (!m.Finite)
  {
    return DefectNonFinite;
  }
  const double sign = m.Sign;
  unsigned char defects = 0;
  defects |= m.LengthError > tol.Unit ? DefectNotUnit : 0;
  defects |= !m.HasNormal || m.Cosine > tol.Perpendicular ? DefectNotPerpendicular : 0;
  defects |= std::abs(std::abs(sign) - 1.0) > tol.Sign ? DefectSignNotUnit : 0;
  if (winding == (PositiveWinding | NegativeWinding))
  {
    defects |= DefectMixedWinding;
  }
  else if (winding != 0)
  {
    const bool positiveWinding = (winding == PositiveWinding) != vDown;
    defects |= positiveWinding != (sign > 0.0) ? DefectSignAgainstWinding : 0;
  }
  return defects;
}

/// The counts of a check, from its points' defects and measures.
FrameCheckCounts CountDefects(const std::vector<unsigned char>& defects,
  const std::vector<unsigned char>& windings,
  const std::vector<PointMeasures>& measures)
{
  FrameCheckCounts counts;
  counts.Points = static_cast<vtkIdType>(defects.size());
  for (vtkIdType p = 0; p < counts.Points; ++p)
  {
    const unsigned char d = defects[p];
    counts.Failed += d != 0 ? 1 : 0;
    counts.NonFinite += (d & DefectNonFinite) ? 1 : 0;
    counts.NotUnit += (d & DefectNotUnit) ? 1 : 0;
    counts.NotPerpendicular += (d & DefectNotPerpendicular) ? 1 : 0;
    counts.SignNotUnit += (d & DefectSignNotUnit) ? 1 : 0;
    counts.SignAgainstWinding += (d & DefectSignAgainstWinding) ? 1 : 0;
    counts.MixedWinding += (d & DefectMixedWinding) ? 1 : 0;
    const bool noWinding = windings.empty() || windings[p] == 0;
    counts.NoWinding += noWinding ? 1 : 0;
    counts.SignAgreesWithWinding +=
      !noWinding && !(d & (DefectNonFinite | DefectSignAgainstWinding | DefectMixedWinding)) ? 1
                                                                                             : 0;
    const PointMeasures& m = measures[p];
    if (!m.Finite)
    {
      continue;
    }
    counts.PositiveSigns += m.Sign > 0.0 ? 1 : 0;
    counts.MaxLengthError = std::max(counts.MaxLengthError, m.LengthError);
    counts.MaxCosineToNormal = std::max(counts.MaxCosineToNormal, m.Cosine);
  }
  return counts;
}

} // namespace

SuppliedFrameArrays FindSuppliedFrames(vtkPolyData* mesh,
  const std::string& name,
  std::string& problem)
{
  SuppliedFrameArrays result;
  vtkPointData* pd = mesh->GetPointData();
  vtkDataArray* tangents = nullptr;
  if (!name.empty())
  {
    tangents = pd->GetArray(name.c_str());
    problem = pd->GetAbstractArray(name.c_str()) && !tangents
      ? "the point array '" + name + "' is not numeric"
      : "there is no point array '" + name + "'";
  }
  else
  {
    tangents = pd->GetTangents() ? pd->GetTangents() : pd->GetArray("Tangents");
    problem = "there are no point tangents (no active tangents, no point array 'Tangents')";
  }
  if (!tangents)
  {
    return result;
  }
  const int components = tangents->GetNumberOfComponents();
  if (components != 3 && components != 4)
  {
    problem = "the supplied tangent array '" +
      std::string(tangents->GetName() ? tangents->GetName() : "") + "' has " +
      std::to_string(components) + " components instead of 3 or 4";
    return result;
  }
  tangents = detail::PointArray(mesh, tangents, "the supplied tangent", components, problem);
  if (!tangents)
  {
    return result;
  }
  vtkDataArray* signs = nullptr;
  if (components == 3)
  {
    problem = "the supplied tangents have 3 components and there is no point array 'TangentSigns'";
    signs = detail::PointArray(mesh, pd->GetArray("TangentSigns"), "the supplied sign", 1, problem);
    if (!signs)
    {
      return result;
    }
  }
  problem.clear();
  result.Tangents = tangents;
  result.Signs = signs;
  return result;
}

void SuppliedFrame(const SuppliedFrameArrays& supplied,
  vtkIdType id,
  double tangent[3],
  double& sign)
{
  for (int c = 0; c < 3; ++c)
  {
    tangent[c] = supplied.Tangents->GetComponent(id, c);
  }
  sign =
    supplied.Signs ? supplied.Signs->GetComponent(id, 0) : supplied.Tangents->GetComponent(id, 3);
}

FrameCheck CheckSuppliedFrames(vtkPolyData* mesh,
  vtkDataArray* normals,
  vtkDataArray* uvs,
  const SuppliedFrameArrays& supplied,
  bool vDown,
  const FrameCheckTolerances& tolerances,
  double largest)
{
  FrameCheck check;
  const vtkIdType numPoints = mesh->GetNumberOfPoints();
  const std::vector<unsigned char> windings =
    uvs ? PointWindings(mesh, normals, uvs) : std::vector<unsigned char>();
  check.Defects.assign(static_cast<size_t>(numPoints), 0);
  std::vector<PointMeasures> measures(static_cast<size_t>(numPoints));
  vtkSMPTools::For(0,
    numPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType p = begin; p < end; ++p)
      {
        double t[3], sign;
        SuppliedFrame(supplied, p, t, sign);
        measures[p] = Measure(Tuple3(normals, p), glm::dvec3(t[0], t[1], t[2]), sign, largest);
        check.Defects[p] =
          PointDefects(measures[p], windings.empty() ? 0 : windings[p], vDown, tolerances);
      }
    });
  check.Counts = CountDefects(check.Defects, windings, measures);
  return check;
}
}
