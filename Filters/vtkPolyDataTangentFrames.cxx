#include "vtkPolyDataTangentFrames.h"

#include "vtkTangentFrameKernels.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cfloat>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkPolyDataTangentFrames);

namespace
{
using namespace vtkNormalMapping;

/// Items processed between two progress reports / abort checks (on the calling thread).
constexpr vtkIdType BatchSize = 1 << 17;

/// Runs f(begin, end) over [0, n) with vtkSMPTools, in batches; between batches it reports
/// progress in [p0, p1] and checks AbortExecute, on the calling thread only. False if aborted.
template<typename F>
bool BatchedFor(vtkAlgorithm* algo, vtkIdType n, double p0, double p1, const F& f)
{
  for (vtkIdType begin = 0; begin < n; begin += BatchSize)
  {
    if (algo->GetAbortExecute())
    {
      return false;
    }
    const vtkIdType end = std::min(n, begin + BatchSize);
    vtkSMPTools::For(begin, end, [&](vtkIdType b, vtkIdType e) { f(b, e); });
    algo->UpdateProgress(p0 + (p1 - p0) * static_cast<double>(end) / static_cast<double>(n));
  }
  return !algo->GetAbortExecute();
}

/// Sum of thread-local counters (integer: the order does not matter).
vtkIdType Total(vtkSMPThreadLocal<vtkIdType>& counter)
{
  vtkIdType total = 0;
  for (vtkIdType c : counter)
  {
    total += c;
  }
  return total;
}

/// Thread-local lists concatenated and sorted, so that the result does not depend on threads.
template<typename T, typename Less>
std::vector<T> Merge(vtkSMPThreadLocal<std::vector<T>>& lists, Less less)
{
  std::vector<T> all;
  for (auto& list : lists)
  {
    all.insert(all.end(), list.begin(), list.end());
  }
  std::sort(all.begin(), all.end(), less);
  return all;
}

/// The triangles of the polygon and strip cells, each with its corners in winding order.
struct SurfaceTriangles
{
  std::vector<vtkIdType> Ids;          // 3 per triangle
  std::vector<vtkIdType> PolyOffsets;  // first triangle of each polygon cell, + end
  std::vector<vtkIdType> StripOffsets; // first triangle of each strip cell (after polygons), + end
  vtkIdType NumberOfTriangles() const { return static_cast<vtkIdType>(this->Ids.size() / 3); }
};

/// Number of triangles per cell (n - 2 for n >= 3) prefix-summed from `first`.
template<typename IdT>
void CountTriangles(const IdT* offsets,
  vtkIdType numCells,
  vtkIdType first,
  std::vector<vtkIdType>& triOffsets,
  vtkIdType& shortCells)
{
  triOffsets.resize(numCells + 1);
  vtkIdType running = first;
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    triOffsets[c] = running;
    const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
    if (n < 3)
    {
      ++shortCells;
    }
    running += std::max<vtkIdType>(n - 2, 0);
  }
  triOffsets[numCells] = running;
}

/// Writes the triangles of cells [begin, end); false when a point id is out of range.
/// Polygons fan from corner 0; strip triangle j is (j, j+1, j+2) with every odd one reversed,
/// so that all triangles of a strip share its winding.
template<typename IdT>
bool FillTriangles(const IdT* offsets,
  const IdT* conn,
  bool strip,
  vtkIdType begin,
  vtkIdType end,
  vtkIdType numPoints,
  const vtkIdType* triOffsets,
  vtkIdType* out)
{
  for (vtkIdType c = begin; c < end; ++c)
  {
    const IdT* pts = conn + offsets[c];
    const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
    for (vtkIdType k = 0; k < n; ++k)
    {
      if (pts[k] < 0 || static_cast<vtkIdType>(pts[k]) >= numPoints)
      {
        return false;
      }
    }
    vtkIdType* tri = out + 3 * triOffsets[c];
    for (vtkIdType j = 0; j + 2 < n; ++j, tri += 3)
    {
      if (!strip)
      {
        tri[0] = pts[0];
        tri[1] = pts[j + 1];
        tri[2] = pts[j + 2];
      }
      else
      {
        const bool odd = (j & 1) != 0;
        tri[0] = pts[odd ? j + 1 : j];
        tri[1] = pts[odd ? j : j + 1];
        tri[2] = pts[j + 2];
      }
    }
  }
  return true;
}

/// Calls f(offsets, connectivity) with the typed raw storage of a cell array.
template<typename F>
void WithCellStorage(vtkCellArray* cells, F&& f)
{
  if (cells->IsStorage64Bit())
  {
    f(cells->GetOffsetsArray64()->GetPointer(0), cells->GetConnectivityArray64()->GetPointer(0));
  }
  else
  {
    f(cells->GetOffsetsArray32()->GetPointer(0), cells->GetConnectivityArray32()->GetPointer(0));
  }
}

/// Calls f(array) with the array down-cast to its concrete float or double type when it is
/// one, so that tuple ranges compile to plain loads; other types go through vtkDataArray.
template<typename F>
void WithRealArray(vtkDataArray* array, F&& f)
{
  if (auto* fa = vtkFloatArray::FastDownCast(array))
  {
    f(fa);
  }
  else if (auto* da = vtkDoubleArray::FastDownCast(array))
  {
    f(da);
  }
  else
  {
    f(array);
  }
}

template<typename RangeT>
glm::dvec3 Load3(const RangeT& range, vtkIdType id)
{
  const auto t = range[id];
  return glm::dvec3(t[0], t[1], t[2]);
}

/// One point-to-triangle table: the corners (3 * triangle + corner) of each point, in triangle
/// order, which fixes the order of every per-point sum.
struct PointCorners
{
  std::vector<vtkIdType> Offsets; // numPoints + 1
  std::vector<vtkIdType> Corners;

  void Build(const SurfaceTriangles& tris, vtkIdType numPoints)
  {
    this->Offsets.assign(numPoints + 1, 0);
    const vtkIdType numCorners = static_cast<vtkIdType>(tris.Ids.size());
    for (vtkIdType c = 0; c < numCorners; ++c)
    {
      ++this->Offsets[tris.Ids[c] + 1];
    }
    for (vtkIdType p = 0; p < numPoints; ++p)
    {
      this->Offsets[p + 1] += this->Offsets[p];
    }
    this->Corners.resize(numCorners);
    std::vector<vtkIdType> cursor(this->Offsets.begin(), this->Offsets.end() - 1);
    for (vtkIdType c = 0; c < numCorners; ++c)
    {
      this->Corners[cursor[tris.Ids[c]]++] = c;
    }
  }
};

/// A point on a mirror seam: its normal, and the frame of its mirrored (-1) side, which goes
/// to the point's copy when splitting.
struct SplitPoint
{
  vtkIdType Id;
  glm::dvec3 Normal;
  glm::dvec3 Tangent;
};

struct FallbackPoint
{
  vtkIdType Id;
  glm::dvec3 Normal;
};

/// Everything one execution shares between its passes.
struct Execution
{
  vtkPolyDataTangentFrames* Filter = nullptr;
  TangentMethod Method = TangentMethod::AngleWeighted;
  bool Splitting = true;
  vtkIdType NumberOfPoints = 0;
  SurfaceTriangles Triangles;
  std::vector<TriangleFrame> Frames;
  std::vector<std::array<double, 3>> Angles; // only for AngleWeighted
  PointCorners Table;

  vtkIdType DegenerateTriangles = 0;
  vtkIdType InvalidNormals = 0;
  vtkIdType Conflicts = 0;
  std::vector<SplitPoint> Splits;
  std::vector<FallbackPoint> Fallbacks;

  double Weight(vtkIdType corner) const
  {
    const vtkIdType t = corner / 3;
    return CornerWeight(this->Method,
      this->Frames[t],
      this->Angles.empty() ? nullptr : this->Angles[t].data(),
      static_cast<int>(corner % 3));
  }

  /// The geometric normal of a point: area-weighted mean of its triangles' normals.
  glm::dvec3 GeometricNormal(vtkIdType p) const
  {
    glm::dvec3 sum(0.0);
    for (vtkIdType i = this->Table.Offsets[p]; i < this->Table.Offsets[p + 1]; ++i)
    {
      const TriangleFrame& f = this->Frames[this->Table.Corners[i] / 3];
      sum += f.Area * f.UnitNormal;
    }
    return SafeNormalize(sum);
  }
};

/// Per-triangle frames (and corner angles), in parallel.
struct ComputeFrames
{
  template<typename PointsT, typename UVT>
  bool operator()(PointsT* points, UVT* uvs, Execution& ex, const DegeneracyTolerance& tol)
  {
    const auto pts = vtk::DataArrayTupleRange<3>(points);
    const auto uv = vtk::DataArrayTupleRange(uvs);
    const bool twoComponents = uvs->GetNumberOfComponents() >= 2;
    const vtkIdType* ids = ex.Triangles.Ids.data();
    const bool angles = ex.Method == TangentMethod::AngleWeighted;
    vtkSMPThreadLocal<vtkIdType> degenerate;
    const bool done = BatchedFor(ex.Filter,
      ex.Triangles.NumberOfTriangles(),
      0.10,
      0.35,
      [&](vtkIdType begin, vtkIdType end)
      {
        vtkIdType& count = degenerate.Local();
        for (vtkIdType t = begin; t < end; ++t)
        {
          const vtkIdType* tri = ids + 3 * t;
          glm::dvec3 p[3];
          glm::dvec2 u[3];
          for (int k = 0; k < 3; ++k)
          {
            p[k] = Load3(pts, tri[k]);
            const auto tc = uv[tri[k]];
            u[k] = glm::dvec2(tc[0], twoComponents ? static_cast<double>(tc[1]) : 0.0);
          }
          ex.Frames[t] = ComputeTriangleFrame(p[0], p[1], p[2], u[0], u[1], u[2], tol);
          count += ex.Frames[t].Orientation == 0 ? 1 : 0;
          if (angles)
          {
            ComputeCornerAngles(p[0], p[1], p[2], ex.Angles[t].data());
          }
        }
      });
    ex.DegenerateTriangles = Total(degenerate);
    return done;
  }
};

/// Smooth point normals for input that has none: area-weighted triangle normals, or the input
/// cell normals averaged with the same weights. Points with no area get (0, 0, 1).
template<typename OutT>
bool ComputePointNormals(Execution& ex,
  vtkDataArray* cellNormals,
  vtkIdType firstPolyCell,
  vtkIdType firstStripCell,
  vtkAOSDataArrayTemplate<OutT>* out)
{
  const SurfaceTriangles& tris = ex.Triangles;
  const vtkIdType numPolyTris = tris.PolyOffsets.back();
  const auto cellOfTriangle = [&](vtkIdType t)
  {
    if (t < numPolyTris)
    {
      const auto it = std::upper_bound(tris.PolyOffsets.begin(), tris.PolyOffsets.end(), t);
      return firstPolyCell + static_cast<vtkIdType>(it - tris.PolyOffsets.begin()) - 1;
    }
    const auto it = std::upper_bound(tris.StripOffsets.begin(), tris.StripOffsets.end(), t);
    return firstStripCell + static_cast<vtkIdType>(it - tris.StripOffsets.begin()) - 1;
  };
  OutT* n = out->GetPointer(0);
  return BatchedFor(ex.Filter,
    ex.NumberOfPoints,
    0.45,
    0.50,
    [&](vtkIdType begin, vtkIdType end)
    {
      double cellNormal[3];
      for (vtkIdType p = begin; p < end; ++p)
      {
        glm::dvec3 sum(0.0);
        for (vtkIdType i = ex.Table.Offsets[p]; i < ex.Table.Offsets[p + 1]; ++i)
        {
          const vtkIdType t = ex.Table.Corners[i] / 3;
          const TriangleFrame& f = ex.Frames[t];
          if (cellNormals)
          {
            cellNormals->GetTuple(cellOfTriangle(t), cellNormal);
            sum += f.Area * SafeNormalize(glm::dvec3(cellNormal[0], cellNormal[1], cellNormal[2]));
          }
          else
          {
            sum += f.Area * f.UnitNormal;
          }
        }
        glm::dvec3 unit = SafeNormalize(sum);
        if (unit == glm::dvec3(0.0))
        {
          unit = glm::dvec3(0.0, 0.0, 1.0);
        }
        for (int c = 0; c < 3; ++c)
        {
          n[3 * p + c] = static_cast<OutT>(unit[c]);
        }
      }
    });
}

/// The per-point pass: sums each point's triangles by handedness, picks or splits, and writes
/// tangent, sign and bitangent of the first numPoints points.
struct GatherFrames
{
  template<typename NormalsT, typename OutT>
  bool operator()(NormalsT* normals,
    Execution& ex,
    vtkAOSDataArrayTemplate<OutT>* tangents,
    vtkAOSDataArrayTemplate<OutT>* signs,
    vtkAOSDataArrayTemplate<OutT>* bitangents)
  {
    const auto nrm = vtk::DataArrayTupleRange<3>(normals);
    OutT* tOut = tangents->GetPointer(0);
    OutT* sOut = signs->GetPointer(0);
    OutT* bOut = bitangents ? bitangents->GetPointer(0) : nullptr;
    vtkSMPThreadLocal<vtkIdType> invalidNormals, conflicts;
    vtkSMPThreadLocal<std::vector<SplitPoint>> splits;
    vtkSMPThreadLocal<std::vector<FallbackPoint>> fallbacks;

    const bool done = BatchedFor(ex.Filter,
      ex.NumberOfPoints,
      0.50,
      0.85,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType p = begin; p < end; ++p)
        {
          glm::dvec3 n = SafeNormalize(Load3(nrm, p));
          if (n == glm::dvec3(0.0))
          {
            ++invalidNormals.Local();
            n = ex.GeometricNormal(p);
          }
          // Index 0: the +1 side, 1: the -1 side.
          glm::dvec3 sum[2] = { glm::dvec3(0.0), glm::dvec3(0.0) };
          double weight[2] = { 0.0, 0.0 };
          vtkIdType count[2] = { 0, 0 };
          for (vtkIdType i = ex.Table.Offsets[p]; i < ex.Table.Offsets[p + 1]; ++i)
          {
            const vtkIdType corner = ex.Table.Corners[i];
            const TriangleFrame& f = ex.Frames[corner / 3];
            if (f.Orientation == 0)
            {
              continue;
            }
            const int side = CornerSign(f, n) > 0 ? 0 : 1;
            const double w = ex.Weight(corner);
            sum[side] += w * f.Tangent;
            weight[side] += w;
            ++count[side];
          }
          if (count[0] + count[1] == 0)
          {
            fallbacks.Local().push_back({ p, n });
            continue;
          }
          int side = weight[1] > weight[0] ? 1 : 0;
          if (count[0] > 0 && count[1] > 0)
          {
            ++conflicts.Local();
            if (ex.Splitting)
            {
              side = 0;
              glm::dvec3 mirrored;
              if (!OrthonormalizeTangent(n, sum[1], mirrored))
              {
                mirrored = FallbackTangent(n);
              }
              splits.Local().push_back({ p, n, mirrored });
            }
          }
          glm::dvec3 t;
          if (!OrthonormalizeTangent(n, sum[side], t))
          {
            t = FallbackTangent(n);
          }
          WriteFrame(p, n, t, side == 0 ? 1.0 : -1.0, tOut, sOut, bOut);
        }
      });
    ex.InvalidNormals = Total(invalidNormals);
    ex.Conflicts = Total(conflicts);
    ex.Splits = Merge(splits, [](const SplitPoint& a, const SplitPoint& b) { return a.Id < b.Id; });
    ex.Fallbacks =
      Merge(fallbacks, [](const FallbackPoint& a, const FallbackPoint& b) { return a.Id < b.Id; });
    return done;
  }

  template<typename OutT>
  static void WriteFrame(vtkIdType p,
    const glm::dvec3& n,
    const glm::dvec3& t,
    double sign,
    OutT* tOut,
    OutT* sOut,
    OutT* bOut)
  {
    for (int c = 0; c < 3; ++c)
    {
      tOut[3 * p + c] = static_cast<OutT>(t[c]);
    }
    sOut[p] = static_cast<OutT>(sign);
    if (bOut)
    {
      const glm::dvec3 b = sign * glm::cross(n, t);
      for (int c = 0; c < 3; ++c)
      {
        bOut[3 * p + c] = static_cast<OutT>(b[c]);
      }
    }
  }
};

/// Points with no usable triangle: the mean of their non-fallback neighbours' tangents on their
/// own tangent plane, and their neighbours' majority sign; the fixed rule where that fails.
template<typename OutT>
void FillFallbacks(Execution& ex, OutT* tOut, OutT* sOut, OutT* bOut)
{
  std::vector<vtkIdType> fallbackIds(ex.Fallbacks.size());
  std::transform(ex.Fallbacks.begin(),
    ex.Fallbacks.end(),
    fallbackIds.begin(),
    [](const FallbackPoint& fp) { return fp.Id; });
  const auto isFallback = [&](vtkIdType q)
  { return std::binary_search(fallbackIds.begin(), fallbackIds.end(), q); };
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(ex.Fallbacks.size()),
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType i = b; i < e; ++i)
      {
        const FallbackPoint& fp = ex.Fallbacks[i];
        glm::dvec3 sum(0.0);
        double signSum = 0.0;
        for (vtkIdType j = ex.Table.Offsets[fp.Id]; j < ex.Table.Offsets[fp.Id + 1]; ++j)
        {
          const vtkIdType corner = ex.Table.Corners[j];
          const vtkIdType* tri = ex.Triangles.Ids.data() + 3 * (corner / 3);
          for (int k = 0; k < 3; ++k)
          {
            const vtkIdType q = tri[k];
            if (q != fp.Id && !isFallback(q))
            {
              sum += glm::dvec3(tOut[3 * q], tOut[3 * q + 1], tOut[3 * q + 2]);
              signSum += sOut[q];
            }
          }
        }
        glm::dvec3 t;
        if (!OrthonormalizeTangent(fp.Normal, sum, t))
        {
          t = FallbackTangent(fp.Normal);
        }
        GatherFrames::WriteFrame(fp.Id, fp.Normal, t, signSum < 0.0 ? -1.0 : 1.0, tOut, sOut, bOut);
      }
    });
}

/// Re-points the corners on the mirrored side of split points to the points' copies.
/// A corner's side is the majority of the handedness of the cell's triangles that hold it.
template<typename IdT>
void RepointCells(const Execution& ex,
  IdT* offsets,
  IdT* conn,
  vtkIdType numCells,
  bool strip,
  const std::vector<vtkIdType>& triOffsets)
{
  const auto& splits = ex.Splits;
  const vtkIdType firstNew = ex.NumberOfPoints;
  vtkSMPTools::For(0,
    numCells,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        IdT* pts = conn + offsets[c];
        const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
        const vtkIdType t0 = triOffsets[c];
        for (vtkIdType k = 0; k < n; ++k)
        {
          const auto it = std::lower_bound(splits.begin(),
            splits.end(),
            pts[k],
            [](const SplitPoint& s, IdT id) { return s.Id < static_cast<vtkIdType>(id); });
          if (it == splits.end() || it->Id != static_cast<vtkIdType>(pts[k]))
          {
            continue;
          }
          // Triangles of this cell that hold corner k.
          vtkIdType first = 0, last = -1;
          if (strip)
          {
            first = std::max<vtkIdType>(k - 2, 0);
            last = std::min<vtkIdType>(k, n - 3);
          }
          else if (k == 0)
          {
            last = n - 3;
          }
          else
          {
            first = std::max<vtkIdType>(k - 2, 0);
            last = std::min<vtkIdType>(k - 1, n - 3);
          }
          int vote = 0;
          for (vtkIdType j = first; j <= last; ++j)
          {
            const TriangleFrame& f = ex.Frames[t0 + j];
            vote += f.Orientation == 0 ? 0 : CornerSign(f, it->Normal);
          }
          if (vote < 0)
          {
            pts[k] = static_cast<IdT>(firstNew + (it - splits.begin()));
          }
        }
      }
    });
}

/// Per-cell tangents of polygons and strips: area-weighted triangle tangents on the cell's
/// plane. Vertex and line cells get (0, 0, 0).
template<typename OutT>
void ComputeCellTangentArray(const Execution& ex,
  vtkIdType firstSurfaceCell,
  vtkAOSDataArrayTemplate<OutT>* out)
{
  OutT* cOut = out->GetPointer(0);
  std::fill(cOut, cOut + 3 * out->GetNumberOfTuples(), OutT(0));
  const SurfaceTriangles& tris = ex.Triangles;
  const vtkIdType numPolys = static_cast<vtkIdType>(tris.PolyOffsets.size()) - 1;
  const vtkIdType numStrips = static_cast<vtkIdType>(tris.StripOffsets.size()) - 1;
  vtkSMPTools::For(0,
    numPolys + numStrips,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        const bool strip = c >= numPolys;
        const auto& offsets = strip ? tris.StripOffsets : tris.PolyOffsets;
        const vtkIdType local = strip ? c - numPolys : c;
        glm::dvec3 t(0.0), n(0.0);
        for (vtkIdType j = offsets[local]; j < offsets[local + 1]; ++j)
        {
          const TriangleFrame& f = ex.Frames[j];
          t += f.Area * f.Tangent;
          n += f.Area * f.UnitNormal;
        }
        n = SafeNormalize(n);
        glm::dvec3 unit;
        if (!OrthonormalizeTangent(n, t, unit))
        {
          unit = FallbackTangent(n);
        }
        for (int k = 0; k < 3; ++k)
        {
          cOut[3 * (firstSurfaceCell + c) + k] = static_cast<OutT>(unit[k]);
        }
      }
    });
}

/// A copy of `array` with `extra` more tuples, tuple numPoints + i copied from ids[i].
vtkSmartPointer<vtkAbstractArray> Extend(vtkAbstractArray* array, vtkIdList* src, vtkIdList* dst)
{
  vtkSmartPointer<vtkAbstractArray> copy = vtk::TakeSmartPointer(array->NewInstance());
  copy->DeepCopy(array);
  copy->Resize(array->GetNumberOfTuples() + src->GetNumberOfIds());
  copy->InsertTuples(dst, src, array);
  return copy;
}

/// Checks a numeric point array: exists, numeric, long enough.
vtkDataArray* NumericPointArray(vtkPolyData* input,
  const char* name,
  vtkAbstractArray* abstract,
  std::string& problem)
{
  if (!abstract)
  {
    problem = std::string("no point array ") + name;
    return nullptr;
  }
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  if (!array)
  {
    problem = std::string("point array '") + (abstract->GetName() ? abstract->GetName() : "") +
      "' is not numeric (" + abstract->GetClassName() + ")";
    return nullptr;
  }
  if (array->GetNumberOfTuples() < input->GetNumberOfPoints())
  {
    problem = std::string("point array '") + (array->GetName() ? array->GetName() : "") + "' has " +
      std::to_string(array->GetNumberOfTuples()) + " tuples for " +
      std::to_string(input->GetNumberOfPoints()) + " points";
    return nullptr;
  }
  return array;
}
} // namespace

struct vtkPolyDataTangentFrames::Internals
{
  template<typename OutT>
  static int Run(vtkPolyDataTangentFrames* self,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkDataArray* uvs,
    vtkDataArray* normals,
    vtkDataArray* cellNormals);
};

vtkPolyDataTangentFrames::vtkPolyDataTangentFrames() = default;
vtkPolyDataTangentFrames::~vtkPolyDataTangentFrames() = default;

const char* vtkPolyDataTangentFrames::GetMethodName(int method)
{
  switch (method)
  {
    case UNWEIGHTED:
      return "Unweighted";
    case AREA_WEIGHTED:
      return "AreaWeighted";
    case ANGLE_WEIGHTED:
      return "AngleWeighted";
    default:
      return "Unknown";
  }
}

void vtkPolyDataTangentFrames::SetTCoordsArrayName(const std::string& name)
{
  if (name != this->TCoordsArrayName)
  {
    this->TCoordsArrayName = name;
    this->Modified();
  }
}

int vtkPolyDataTangentFrames::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->NumberOfDegenerateTriangles = 0;
  this->NumberOfFallbackPoints = 0;
  this->NumberOfHandednessConflicts = 0;
  this->NumberOfSplitPoints = 0;
  this->NumberOfInvalidNormals = 0;
  if (!input || !output)
  {
    return 0;
  }
  const auto passThrough = [&]()
  {
    output->ShallowCopy(input);
    return 1;
  };
  if (input->GetNumberOfPoints() == 0 ||
    input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    // Nothing to give frames to; not an error (vertices and lines only, or empty input).
    return passThrough();
  }

  // Texture coordinates.
  vtkPointData* pd = input->GetPointData();
  std::string problem;
  vtkAbstractArray* uvAbstract = this->TCoordsArrayName.empty()
    ? pd->GetTCoords()
    : pd->GetAbstractArray(this->TCoordsArrayName.c_str());
  const std::string uvLabel = this->TCoordsArrayName.empty()
    ? std::string("texture coordinates (no active TCoords)")
    : "texture coordinates '" + this->TCoordsArrayName + "'";
  vtkDataArray* uvs = NumericPointArray(input, uvLabel.c_str(), uvAbstract, problem);
  if (!uvs)
  {
    vtkErrorMacro("Cannot compute tangent frames: " << problem << "; passing the input through.");
    return passThrough();
  }
  if (uvs->GetNumberOfComponents() == 1)
  {
    vtkWarningMacro("Texture coordinates '"
      << (uvs->GetName() ? uvs->GetName() : "")
      << "' have 1 component; using (u, 0), so every "
         "triangle has zero UV area and gets a fallback frame.");
  }
  else if (uvs->GetNumberOfComponents() > 2)
  {
    vtkWarningMacro("Texture coordinates '" << (uvs->GetName() ? uvs->GetName() : "") << "' have "
                                            << uvs->GetNumberOfComponents()
                                            << " components; using the first two.");
  }

  // Normals: point normals, else cell normals, else computed.
  vtkDataArray* normals = pd->GetNormals();
  vtkDataArray* cellNormals = nullptr;
  if (normals)
  {
    normals = NumericPointArray(input, "Normals", normals, problem);
    if (normals && normals->GetNumberOfComponents() != 3)
    {
      problem = "point normals have " + std::to_string(normals->GetNumberOfComponents()) +
        " components instead of 3";
      normals = nullptr;
    }
    if (!normals)
    {
      vtkWarningMacro("Ignoring the point normals: " << problem << ".");
    }
  }
  if (!normals)
  {
    vtkDataArray* cn = input->GetCellData()->GetNormals();
    if (cn && cn->GetNumberOfComponents() == 3 &&
      cn->GetNumberOfTuples() >= input->GetNumberOfCells())
    {
      cellNormals = cn;
      vtkWarningMacro("The input has cell normals but no point normals; averaging the cell "
                      "normals to points (area-weighted) and adding them as point 'Normals'.");
    }
    else
    {
      vtkWarningMacro("The input has no point normals; computing smooth area-weighted point "
                      "normals (without splitting) and adding them as point 'Normals'.");
    }
  }

  const bool doublePrecision = this->OutputPrecision == DOUBLE_PRECISION ||
    (this->OutputPrecision == DEFAULT_PRECISION && input->GetPoints()->GetDataType() == VTK_DOUBLE);
  return doublePrecision ? Internals::Run<double>(this, input, output, uvs, normals, cellNormals)
                         : Internals::Run<float>(this, input, output, uvs, normals, cellNormals);
}

template<typename OutT>
int vtkPolyDataTangentFrames::Internals::Run(vtkPolyDataTangentFrames* self,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkDataArray* uvs,
  vtkDataArray* normals,
  vtkDataArray* cellNormals)
{
  // The concrete vtkFloatArray / vtkDoubleArray, so that users' SafeDownCasts work.
  using OutArray = typename std::
    conditional<std::is_same<OutT, float>::value, vtkFloatArray, vtkDoubleArray>::type;
  Execution ex;
  ex.Filter = self;
  ex.Method = static_cast<TangentMethod>(self->Method);
  ex.Splitting = self->Splitting;
  ex.NumberOfPoints = input->GetNumberOfPoints();
  const vtkIdType numPoints = ex.NumberOfPoints;
  const auto aborted = [&]()
  {
    output->Initialize();
    return 1;
  };

  // 1. Triangles of polygons and strips, with point ids checked.
  vtkCellArray* polys = input->GetPolys();
  vtkCellArray* strips = input->GetStrips();
  vtkIdType shortCells = 0;
  WithCellStorage(polys,
    [&](const auto* offsets, const auto*) {
      CountTriangles(offsets, polys->GetNumberOfCells(), 0, ex.Triangles.PolyOffsets, shortCells);
    });
  WithCellStorage(strips,
    [&](const auto* offsets, const auto*)
    {
      CountTriangles(offsets,
        strips->GetNumberOfCells(),
        ex.Triangles.PolyOffsets.back(),
        ex.Triangles.StripOffsets,
        shortCells);
    });
  ex.Triangles.Ids.resize(3 * ex.Triangles.StripOffsets.back());
  std::atomic<bool> idsInRange(true);
  for (vtkCellArray* cells : { polys, strips })
  {
    const bool strip = cells == strips;
    const auto& triOffsets = strip ? ex.Triangles.StripOffsets : ex.Triangles.PolyOffsets;
    WithCellStorage(cells,
      [&](const auto* offsets, const auto* conn)
      {
        vtkSMPTools::For(0,
          cells->GetNumberOfCells(),
          [&](vtkIdType b, vtkIdType e)
          {
            if (!FillTriangles(offsets,
                  conn,
                  strip,
                  b,
                  e,
                  numPoints,
                  triOffsets.data(),
                  ex.Triangles.Ids.data()))
            {
              idsInRange = false;
            }
          });
      });
  }
  if (!idsInRange)
  {
    vtkErrorWithObjectMacro(self,
      "Cannot compute tangent frames: a polygon or strip refers to a "
      "point id outside [0, "
        << numPoints << "); passing the input through.");
    output->ShallowCopy(input);
    return 1;
  }
  if (shortCells > 0)
  {
    vtkWarningWithObjectMacro(self,
      << shortCells
      << " polygon or strip cells have fewer than 3 points; they "
         "pass through and give no frames.");
  }
  self->UpdateProgress(0.10);

  // 2. Per-triangle frames, with a degeneracy tolerance from the stored precisions.
  const vtkIdType numTris = ex.Triangles.NumberOfTriangles();
  ex.Frames.resize(numTris);
  if (ex.Method == TangentMethod::AngleWeighted)
  {
    ex.Angles.resize(numTris);
  }
  const auto epsilon = [](vtkDataArray* a)
  { return a->GetDataType() == VTK_DOUBLE ? DBL_EPSILON : static_cast<double>(FLT_EPSILON); };
  const DegeneracyTolerance tol =
    DegeneracyTolerance::ForEpsilons(epsilon(input->GetPoints()->GetData()), epsilon(uvs));
  bool done = true;
  WithRealArray(input->GetPoints()->GetData(),
    [&](auto* points)
    { WithRealArray(uvs, [&](auto* uv) { done = ComputeFrames()(points, uv, ex, tol); }); });
  if (!done)
  {
    return aborted();
  }

  // 3. The point-to-triangle table.
  ex.Table.Build(ex.Triangles, numPoints);
  self->UpdateProgress(0.45);

  // 4. Normals, computed when the input has no point normals.
  vtkSmartPointer<OutArray> computedNormals;
  if (!normals)
  {
    computedNormals = vtkSmartPointer<OutArray>::New();
    computedNormals->SetName("Normals");
    computedNormals->SetNumberOfComponents(3);
    computedNormals->SetNumberOfTuples(numPoints);
    const vtkIdType firstPoly = input->GetNumberOfVerts() + input->GetNumberOfLines();
    if (!ComputePointNormals(
          ex, cellNormals, firstPoly, firstPoly + input->GetNumberOfPolys(), computedNormals.Get()))
    {
      return aborted();
    }
    normals = computedNormals;
  }

  // 5. Per-point frames.
  const auto makeArray = [&](const char* name, int components, vtkIdType tuples)
  {
    auto array = vtkSmartPointer<OutArray>::New();
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(tuples);
    return array;
  };
  auto tangents = makeArray(TangentsArrayName(), 3, numPoints);
  auto signs = makeArray(SignsArrayName(), 1, numPoints);
  vtkSmartPointer<OutArray> bitangents;
  if (self->ComputeBitangents)
  {
    bitangents = makeArray(BitangentsArrayName(), 3, numPoints);
  }
  WithRealArray(normals,
    [&](auto* n) { done = GatherFrames()(n, ex, tangents.Get(), signs.Get(), bitangents.Get()); });
  if (!done)
  {
    return aborted();
  }
  FillFallbacks(ex,
    tangents->GetPointer(0),
    signs->GetPointer(0),
    bitangents ? bitangents->GetPointer(0) : nullptr);
  self->UpdateProgress(0.90);

  // 6. Split points: copies appended after the input points, cells re-pointed.
  const vtkIdType numSplits = ex.Splitting ? static_cast<vtkIdType>(ex.Splits.size()) : 0;
  vtkNew<vtkIdList> splitSource, splitTarget;
  splitSource->SetNumberOfIds(numSplits);
  splitTarget->SetNumberOfIds(numSplits);
  for (vtkIdType i = 0; i < numSplits; ++i)
  {
    splitSource->SetId(i, ex.Splits[i].Id);
    splitTarget->SetId(i, numPoints + i);
  }
  output->CopyStructure(input);
  output->GetCellData()->PassData(input->GetCellData());
  if (numSplits == 0)
  {
    output->GetPointData()->PassData(input->GetPointData());
  }
  else
  {
    vtkNew<vtkPoints> points;
    points->SetData(
      vtkDataArray::SafeDownCast(Extend(input->GetPoints()->GetData(), splitSource, splitTarget)));
    output->SetPoints(points);
    vtkPointData* inPD = input->GetPointData();
    vtkPointData* outPD = output->GetPointData();
    outPD->Initialize();
    for (int a = 0; a < inPD->GetNumberOfArrays(); ++a)
    {
      vtkAbstractArray* array = inPD->GetAbstractArray(a);
      auto extended = Extend(array, splitSource, splitTarget);
      outPD->AddArray(extended);
      const int attribute = inPD->IsArrayAnAttribute(a);
      if (attribute >= 0)
      {
        outPD->SetActiveAttribute(outPD->GetNumberOfArrays() - 1, attribute);
      }
    }
    if (computedNormals)
    {
      computedNormals =
        OutArray::SafeDownCast(Extend(computedNormals, splitSource, splitTarget).GetPointer());
    }
    tangents->Resize(numPoints + numSplits);
    tangents->SetNumberOfTuples(numPoints + numSplits);
    signs->Resize(numPoints + numSplits);
    signs->SetNumberOfTuples(numPoints + numSplits);
    if (bitangents)
    {
      bitangents->Resize(numPoints + numSplits);
      bitangents->SetNumberOfTuples(numPoints + numSplits);
    }
    for (vtkIdType i = 0; i < numSplits; ++i)
    {
      const SplitPoint& s = ex.Splits[i];
      GatherFrames::WriteFrame(numPoints + i,
        s.Normal,
        s.Tangent,
        -1.0,
        tangents->GetPointer(0),
        signs->GetPointer(0),
        bitangents ? bitangents->GetPointer(0) : nullptr);
    }
    for (vtkCellArray* cells : { polys, strips })
    {
      const bool strip = cells == strips;
      vtkNew<vtkCellArray> copy;
      copy->DeepCopy(cells);
      WithCellStorage(copy,
        [&](auto* offsets, auto* conn)
        {
          RepointCells(ex,
            offsets,
            conn,
            copy->GetNumberOfCells(),
            strip,
            strip ? ex.Triangles.StripOffsets : ex.Triangles.PolyOffsets);
        });
      if (strip)
      {
        output->SetStrips(copy);
      }
      else
      {
        output->SetPolys(copy);
      }
    }
  }
  vtkPointData* outPD = output->GetPointData();
  if (computedNormals)
  {
    outPD->SetNormals(computedNormals);
  }
  outPD->SetTangents(tangents);
  outPD->AddArray(signs);
  if (bitangents)
  {
    outPD->AddArray(bitangents);
  }
  if (self->ComputeCellTangents)
  {
    auto cellTangents = makeArray(TangentsArrayName(), 3, input->GetNumberOfCells());
    ComputeCellTangentArray(
      ex, input->GetNumberOfVerts() + input->GetNumberOfLines(), cellTangents.Get());
    output->GetCellData()->SetTangents(cellTangents);
  }

  self->NumberOfDegenerateTriangles = ex.DegenerateTriangles;
  self->NumberOfFallbackPoints = static_cast<vtkIdType>(ex.Fallbacks.size());
  self->NumberOfHandednessConflicts = ex.Conflicts;
  self->NumberOfSplitPoints = numSplits;
  self->NumberOfInvalidNormals = ex.InvalidNormals;
  self->UpdateProgress(1.0);
  return 1;
}

void vtkPolyDataTangentFrames::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << GetMethodName(this->Method) << "\n";
  os << indent << "TCoordsArrayName: "
     << (this->TCoordsArrayName.empty() ? "(active TCoords)" : this->TCoordsArrayName) << "\n";
  os << indent << "Splitting: " << (this->Splitting ? "On" : "Off") << "\n";
  os << indent << "ComputeBitangents: " << (this->ComputeBitangents ? "On" : "Off") << "\n";
  os << indent << "ComputeCellTangents: " << (this->ComputeCellTangents ? "On" : "Off") << "\n";
  os << indent << "OutputPrecision: " << this->OutputPrecision << "\n";
  os << indent << "NumberOfDegenerateTriangles: " << this->NumberOfDegenerateTriangles << "\n";
  os << indent << "NumberOfFallbackPoints: " << this->NumberOfFallbackPoints << "\n";
  os << indent << "NumberOfHandednessConflicts: " << this->NumberOfHandednessConflicts << "\n";
  os << indent << "NumberOfSplitPoints: " << this->NumberOfSplitPoints << "\n";
  os << indent << "NumberOfInvalidNormals: " << this->NumberOfInvalidNormals << "\n";
}
