// SPDX-License-Identifier: BSD-3-Clause
// The MikkTSpace method of vtkPolyDataTangentFrames: input polydata -> kernel faces
// (BuildSurface, KernelPositions) -> per-corner frames (vtkMikkTSpaceKernel.h) -> per-point output
// (Assign: points split where their corners disagree; WritePointFrames: the filter's contract).
// docs/mikktspace.md, "Through the filter", lists the rules.
#include "vtkPolyDataTangentFrames.h"

#include "vtkNormalMappingPrivate.h"

#include "vtkMikkTSpaceKernel.h"
#include "vtkTangentFrameKernels.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vtkNormalMapping
{
namespace detail
{
namespace
{
using mikk::CornerFrame;
using mikk::IsCancelled;
static_assert(std::is_same<vtkTypeInt64, long long>::value,
  "64-bit cell storage is passed to the kernel without a copy");

/// Bitwise equality, as two 64-bit compares (this runs once per corner).
bool SameFrame(const CornerFrame& a, const CornerFrame& b)
{
  static_assert(sizeof(CornerFrame) == 16, "four floats");
  std::uint64_t x[2], y[2];
  std::memcpy(x, &a, sizeof(x));
  std::memcpy(y, &b, sizeof(y));
  return x[0] == y[0] && x[1] == y[1];
}

/// |T.N| (unit N) allowed before a kernel tangent is made perpendicular: it keeps the
/// reference's tangents where real files' normals are off unit length by more than float rounding,
/// and corrects the default (1,0,0) and clearly non-unit normals (docs/mikktspace.md).
constexpr double kPerpendicularTolerance = 1e-4;

/**
 * The kernel frame `f` of a point with normal `n` (as given, any length; zero or non-finite:
 * none) made to meet the filter's contract (finite unit tangents perpendicular to the normal),
 * keeping the kernel's bits where they meet it already: a cancelled tangent (mikk::IsCancelled)
 * becomes (1,0,0) made perpendicular to the normal, its sign kept; a tangent with |T.N| above
 * kPerpendicularTolerance is made perpendicular in double (both PerpendicularTangent). The
 * common case is decided without a square root or a normalisation.
 */
CornerFrame ContractFrame(const CornerFrame& f, const glm::dvec3& n)
{
  const glm::dvec3 t(f.Tangent[0], f.Tangent[1], f.Tangent[2]);
  const bool cancelled = IsCancelled(f);
  const double nn = glm::dot(n, n);
  if (!cancelled && nn > 1e-200 && nn < 1e200)
  {
    // |T.N| / |N| <= tolerance, squared (no overflow or underflow in this range).
    const double d = glm::dot(t, n);
    if (d * d <= kPerpendicularTolerance * kPerpendicularTolerance * nn)
    {
      return f;
    }
  }
  const glm::dvec3 unit = SafeNormalize(n);
  if (!cancelled && std::abs(glm::dot(t, unit)) <= kPerpendicularTolerance)
  {
    return f; // a normal of extreme magnitude, or none
  }
  const glm::dvec3 u = PerpendicularTangent(unit, cancelled ? glm::dvec3(1.0, 0.0, 0.0) : t);
  CornerFrame out = f;
  for (int k = 0; k < 3; ++k)
  {
    out.Tangent[k] = static_cast<float>(u[k]);
  }
  return out;
}

/// Copies the first `outComps` components of the first n tuples to OutT (missing ones: 0),
/// each value rounded as a static_cast would (to float: as the reference's float interface).
template<typename OutT>
struct ConvertTuples
{
  template<typename ArrayT>
  void operator()(ArrayT* array, vtkIdType n, int outComps, OutT* out) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array, 0, n);
    const int copy = std::min(array->GetNumberOfComponents(), outComps);
    vtkSMPTools::For(0,
      n,
      [&](vtkIdType b, vtkIdType e)
      {
        for (vtkIdType i = b; i < e; ++i)
        {
          const auto tuple = tuples[i];
          OutT* o = out + static_cast<size_t>(i) * outComps;
          for (int k = 0; k < copy; ++k)
          {
            o[k] = static_cast<OutT>(tuple[k]);
          }
          for (int k = copy; k < outComps; ++k)
          {
            o[k] = OutT(0);
          }
        }
      });
  }
};

/// The first n tuples of `array` as `outComps` floats each: the array's own storage when it is a
/// float array with exactly that many components (no copy), else a converted copy kept in
/// `storage`.
const float* FloatData(vtkDataArray* array, vtkIdType n, int outComps, std::vector<float>& storage)
{
  vtkFloatArray* floats = vtkFloatArray::FastDownCast(array);
  if (floats && floats->GetNumberOfComponents() == outComps)
  {
    return floats->GetPointer(0);
  }
  storage.resize(static_cast<size_t>(n) * outComps);
  DispatchArray(array, ConvertTuples<float>(), n, outComps, storage.data());
  return storage.data();
}

/// Positions as the kernel's floats: (x - centre) * scale for each coordinate, computed in
/// double, then rounded to float.
struct ConvertPositions
{
  template<typename ArrayT>
  void operator()(ArrayT* array, vtkIdType n, const double centre[3], double scale, float* out)
    const
  {
    const auto tuples = vtk::DataArrayTupleRange<3>(array, 0, n);
    vtkSMPTools::For(0,
      n,
      [&](vtkIdType b, vtkIdType e)
      {
        for (vtkIdType i = b; i < e; ++i)
        {
          const auto tuple = tuples[i];
          for (int k = 0; k < 3; ++k)
          {
            out[3 * i + k] =
              static_cast<float>((static_cast<double>(tuple[k]) - centre[k]) * scale);
          }
        }
      });
  }
};

/**
 * The positions the kernel gets, as floats like the reference's (docs/numerics.md, "Scale" and
 * "Far from the origin"): multiplied by the power of two that brings the mesh's extent (the
 * largest side of its bounding box) into [0.5, 1) when it lies outside [2^-16, 2^16] or the mesh
 * is centred; a mesh stored in another type than float whose largest coordinate exceeds 16 times
 * its extent is first moved, in double, to its bounding box's centre (float input never is: the
 * reference rounds nothing, so neither does this). Scaling changes no bit of the reference's
 * frames wherever they neither under- nor overflow. A mesh without a finite, non-zero extent goes
 * in unchanged.
 */
const float* KernelPositions(vtkPoints* points, vtkIdType n, std::vector<float>& storage)
{
  vtkDataArray* array = points->GetData();
  double bounds[6];
  points->GetBounds(bounds);
  const double extent =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const double largest = std::max({ std::abs(bounds[0]),
    std::abs(bounds[1]),
    std::abs(bounds[2]),
    std::abs(bounds[3]),
    std::abs(bounds[4]),
    std::abs(bounds[5]) });
  if (n == 0 || !(extent > 0.0) || !std::isfinite(extent) || !std::isfinite(largest))
  {
    return FloatData(array, n, 3, storage);
  }
  const bool centred = array->GetDataType() != VTK_FLOAT && largest > 16.0 * extent;
  double centre[3] = { 0.0, 0.0, 0.0 };
  double reach = largest; // the largest coordinate magnitude after centring
  if (centred)
  {
    for (int k = 0; k < 3; ++k)
    {
      centre[k] = 0.5 * (bounds[2 * k] + bounds[2 * k + 1]);
    }
    reach = extent;
  }
  // The exponent for the extent, limited so that no coordinate reaches 2^127, float's largest
  // power of two (coordinate differences stay within the scaled extent). Within [2^-16, 2^16]
  // scaling could not change a bit and is skipped (float input is then read without a copy).
  const bool ordinary = extent >= 0x1p-16 && extent <= 0x1p16;
  const int k =
    centred || !ordinary ? std::min(UnitExponent(extent), UnitExponent(reach) + 127) : 0;
  if (k == 0 && !centred)
  {
    return FloatData(array, n, 3, storage);
  }
  storage.resize(static_cast<size_t>(n) * 3);
  const double scale = ScaleByPowerOfTwo(1.0, k);
  DispatchArray(array, ConvertPositions(), n, centre, scale, storage.data());
  return storage.data();
}

/// The normals the contract is checked against: the input's own values, in double.
/// Float normals are read from the kernel's copy; any other type is kept in double (rounding a
/// double normal to float can make it zero or infinite, or turn its direction a little).
struct ContractNormals
{
  const float* Float = nullptr;
  std::vector<double> Wide;

  ContractNormals(vtkDataArray* normals, vtkIdType n, const float* asFloat)
  {
    if (normals->GetDataType() == VTK_FLOAT)
    {
      this->Float = asFloat;
    }
    else
    {
      this->Wide.resize(static_cast<size_t>(n) * 3);
      DispatchArray(normals, ConvertTuples<double>(), n, 3, this->Wide.data());
    }
  }
  glm::dvec3 operator[](vtkIdType p) const
  {
    const size_t i = 3 * static_cast<size_t>(p);
    return this->Float ? glm::dvec3(this->Float[i], this->Float[i + 1], this->Float[i + 2])
                       : glm::dvec3(this->Wide[i], this->Wide[i + 1], this->Wide[i + 2]);
  }
};

/// The kernel's faces built from the polygons and strips (polygon c is face c, the strip
/// triangles follow), and the strips' layout.
struct Surface
{
  vtkIdType NumPolys = 0;
  vtkIdType NumStrips = 0;
  long long PolyCorners = 0;
  long long NumFaces = 0;
  const long long* FaceOffsets = nullptr;
  const long long* FaceConnectivity = nullptr;
  std::vector<long long> OffsetStore, ConnectivityStore; // when the storage cannot be shared
  std::vector<long long> StripFirstTriangle;             // per strip + 1: first strip triangle
  std::vector<long long> StripCornerStart;               // per strip + 1: first strip corner
};

/// The strips' corner and triangle layout (s.StripCornerStart, s.StripFirstTriangle).
void LayOutStrips(vtkCellArray* strips, Surface& s)
{
  WithCellStorage(strips,
    [&](const auto* off, const auto*) { s.StripCornerStart.assign(off, off + s.NumStrips + 1); });
  s.StripFirstTriangle.assign(static_cast<size_t>(s.NumStrips) + 1, 0);
  CellTriangleStarts(strips, s.StripFirstTriangle.data());
}

/// The polygons as the first faces: their offsets and ids copied to 64-bit storage.
void CopyPolygons(vtkCellArray* polys, vtkIdType numPolys, long long* offsets, long long* conn)
{
  WithCellStorage(polys,
    [&](auto* off, auto* ids)
    {
      vtkSMPTools::For(0,
        numPolys,
        [&](vtkIdType b, vtkIdType e)
        {
          for (vtkIdType k = b; k < e; ++k)
          {
            offsets[k + 1] = off[k + 1];
          }
          for (long long k = off[b]; k < static_cast<long long>(off[e]); ++k)
          {
            conn[k] = ids[k];
          }
        });
    });
}

/// The strip triangles as faces after the polygons, each with the strip's winding.
void UnrollStrips(vtkCellArray* strips, const Surface& s, long long* offsets, long long* conn)
{
  WithCellStorage(strips,
    [&](auto*, auto* ids)
    {
      vtkSMPTools::For(0,
        s.NumStrips,
        [&](vtkIdType b, vtkIdType e)
        {
          for (vtkIdType k = b; k < e; ++k)
          {
            const long long first = s.StripCornerStart[k];
            const long long n = s.StripCornerStart[k + 1] - first;
            const long long t0 = s.StripFirstTriangle[k];
            for (long long j = 0; j + 2 < n; ++j)
            {
              const long long base = s.PolyCorners + 3 * (t0 + j);
              offsets[s.NumPolys + t0 + j + 1] = base + 3;
              CellTriangle(ids + first, j, true, conn + base);
            }
          }
        });
    });
}

/// Fills `s` from cell arrays ExecuteBlock has checked (CellArrayProblem, PointIdsInRange): every
/// read of the offsets, and of the ids between them, relies on it.
void BuildSurface(vtkCellArray* polys, vtkCellArray* strips, Surface& s)
{
  s.NumPolys = polys->GetNumberOfCells();
  s.NumStrips = strips->GetNumberOfCells();
  s.PolyCorners = s.NumPolys > 0 ? polys->GetNumberOfConnectivityIds() : 0;
  LayOutStrips(strips, s);
  const long long numStripTriangles = s.StripFirstTriangle.back();
  s.NumFaces = s.NumPolys + numStripTriangles;
  if (s.NumStrips == 0 && s.NumPolys > 0 && polys->IsStorage64Bit())
  {
    // Shared: the kernel reads the polygon storage directly.
    WithCellStorage(polys,
      [&](const auto* offsets, const auto* conn)
      {
        if constexpr (std::is_same<std::decay_t<decltype(*conn)>, long long>::value)
        {
          s.FaceOffsets = offsets;
          s.FaceConnectivity = conn;
        }
      });
    return;
  }
  s.OffsetStore.resize(static_cast<size_t>(s.NumFaces) + 1);
  s.ConnectivityStore.resize(static_cast<size_t>(s.PolyCorners + 3 * numStripTriangles));
  s.OffsetStore[0] = 0;
  if (s.NumPolys > 0)
  {
    CopyPolygons(polys, s.NumPolys, s.OffsetStore.data(), s.ConnectivityStore.data());
  }
  if (s.NumStrips > 0)
  {
    UnrollStrips(strips, s, s.OffsetStore.data(), s.ConnectivityStore.data());
  }
  s.FaceOffsets = s.OffsetStore.data();
  s.FaceConnectivity = s.ConnectivityStore.data();
}

/// Which point each output corner uses and which frame each output point gets.
struct Assignment
{
  std::vector<CornerFrame> PointFrame; // per input point: frame of its first corner (Sign 0: none)
  std::vector<vtkIdType> SplitSource;  // per new point: the input point it copies
  std::vector<CornerFrame> SplitFrame; // per new point: its frame
  std::vector<std::pair<vtkIdType, vtkIdType>> Repoint; // (output corner, new point id)
  vtkIdType Conflicts = 0;
  /// With splitting: the strips (numbered after the polygons) with a corner whose strip
  /// triangles carry different frames, which its one point cannot all take (kept points left
  /// out).
  std::vector<vtkIdType> MixedCells;
};

/**
 * The new point of point p that carries frame f: one of p's new points so far (`mine`), or a new
 * one appended after them all.
 */
vtkIdType SplitPointOf(long long p,
  const CornerFrame& f,
  std::vector<vtkIdType>& mine,
  vtkIdType numPoints,
  Assignment& a)
{
  for (vtkIdType candidate : mine)
  {
    if (SameFrame(a.SplitFrame[static_cast<size_t>(candidate - numPoints)], f))
    {
      return candidate;
    }
  }
  const vtkIdType id = numPoints + static_cast<vtkIdType>(a.SplitSource.size());
  a.SplitSource.push_back(static_cast<vtkIdType>(p));
  a.SplitFrame.push_back(f);
  mine.push_back(id);
  return id;
}

/**
 * One ascending pass over the output corners with a frame, polygon corners then strip corners:
 * every point's frame is that of its first corner (a.PointFrame). A point is a conflict when
 * another of its corners carries a different frame, or when one of its strip corners has strip
 * triangles that disagree. With `splitting` each other frame of a point becomes a new point, in
 * the order of the corners, and the corners carrying it are re-pointed to it. Points of `kept`
 * (non-zero per point whose frame the caller keeps, or null) are neither. The point keeps a
 * copy of its frame (kernel frames have Sign +1 or -1, so Sign 0 marks a point not reached yet):
 * each corner then reads one entry per point instead of a point entry and a corner entry.
 */
void Assign(const Surface& s,
  const std::vector<CornerFrame>& frames,
  vtkIdType numPoints,
  bool splitting,
  const unsigned char* kept,
  Assignment& a)
{
  a.PointFrame.assign(static_cast<size_t>(numPoints), CornerFrame{ { 0.0f, 0.0f, 0.0f }, 0.0f });
  std::vector<unsigned char> conflict;
  const auto markConflict = [&](long long p)
  {
    if (kept && kept[p])
    {
      return;
    }
    if (conflict.empty())
    {
      conflict.assign(static_cast<size_t>(numPoints), 0);
    }
    if (!conflict[static_cast<size_t>(p)])
    {
      conflict[static_cast<size_t>(p)] = 1;
      ++a.Conflicts;
    }
  };
  // Raw pointers, so that the corner loops keep them in registers across push_back calls.
  const long long* off = s.FaceOffsets;
  const long long* conn = s.FaceConnectivity;
  const CornerFrame* kernelFrames = frames.data();
  CornerFrame* pointFrames = a.PointFrame.data();
  std::vector<std::pair<long long, long long>> differing; // (output corner, kernel corner)
  // Output corner c, which takes the frame of kernel corner `slot`.
  const auto visit = [&](long long c, long long slot)
  {
    CornerFrame& first = pointFrames[conn[slot]];
    if (first.Sign == 0.0f)
    {
      first = kernelFrames[slot];
    }
    else if (!SameFrame(kernelFrames[slot], first))
    {
      differing.emplace_back(c, slot);
    }
  };
  // A polygon corner is its own kernel corner; polygons with fewer than 3 points have no frame.
  for (vtkIdType k = 0, numPolys = s.NumPolys; k < numPolys; ++k)
  {
    const long long b = off[k], e = off[k + 1];
    if (e - b < 3)
    {
      continue;
    }
    for (long long c = b; c < e; ++c)
    {
      visit(c, c);
    }
  }
  // A strip corner takes the frame of the first strip triangle containing it.
  for (vtkIdType k = 0; k < s.NumStrips; ++k)
  {
    const long long first = s.StripCornerStart[k];
    const long long n = s.StripCornerStart[k + 1] - first;
    const long long t0 = s.StripFirstTriangle[k];
    if (n < 3)
    {
      continue;
    }
    for (long long i = 0; i < n; ++i)
    {
      // the kernel corner of strip corner i in strip triangle j, which contains it
      const auto slotIn = [&](long long j)
      { return s.PolyCorners + 3 * (t0 + j) + PositionInStripTriangle(i, j); };
      vtkIdType j, last;
      TrianglesAtCorner(i, n, true, j, last);
      const long long slot = slotIn(j);
      visit(s.PolyCorners + first + i, slot);
      for (long long later = j + 1; later <= last; ++later)
      {
        if (!SameFrame(kernelFrames[slotIn(later)], kernelFrames[slot]))
        {
          markConflict(conn[slot]);
          const vtkIdType cell = s.NumPolys + k;
          if (splitting && !(kept && kept[conn[slot]]) &&
            (a.MixedCells.empty() || a.MixedCells.back() != cell))
          {
            a.MixedCells.push_back(cell);
          }
          break;
        }
      }
    }
  }
  std::unordered_map<long long, std::vector<vtkIdType>> extra; // point -> its new points
  for (const auto& [c, slot] : differing)
  {
    const long long p = conn[slot];
    markConflict(p);
    if (splitting && !(kept && kept[p]))
    {
      a.Repoint.emplace_back(c, SplitPointOf(p, kernelFrames[slot], extra[p], numPoints, a));
    }
  }
}

/**
 * Cell c's sums for NewCellTangents (polygons, then strips) from the kernel's corner frames: the
 * tangents of its faces' corners of CornerKind::Computed (neither left at the default nor
 * cancelled, whatever their bits), and its faces' area vectors (the cross products of their fan
 * triangles).
 */
void CellSums(const Surface& s,
  const mikk::Result& kernel,
  const float* positions,
  vtkIdType cell,
  glm::dvec3& t,
  glm::dvec3& n)
{
  // Kernel faces of this cell: polygon c is face c; strip k its strip triangles.
  long long fb = cell, fe = cell + 1;
  if (cell >= s.NumPolys)
  {
    const vtkIdType k = cell - s.NumPolys;
    fb = s.NumPolys + s.StripFirstTriangle[k];
    fe = s.NumPolys + s.StripFirstTriangle[k + 1];
  }
  const auto position = [&](long long c)
  {
    const float* p = positions + 3 * s.FaceConnectivity[c];
    return glm::dvec3(p[0], p[1], p[2]);
  };
  for (long long f = fb; f < fe; ++f)
  {
    const long long cb = s.FaceOffsets[f], ce = s.FaceOffsets[f + 1];
    if (ce - cb < 3)
    {
      continue; // no frame (and an empty polygon has no first corner to read)
    }
    for (long long c = cb; c < ce; ++c)
    {
      if (kernel.CornerKinds[static_cast<size_t>(c)] == mikk::CornerKind::Computed)
      {
        const CornerFrame& cf = kernel.Corners[static_cast<size_t>(c)];
        t += glm::dvec3(cf.Tangent[0], cf.Tangent[1], cf.Tangent[2]);
      }
    }
    const glm::dvec3 o = position(cb);
    for (long long c = cb + 1; c + 1 < ce; ++c)
    {
      n += glm::cross(position(c) - o, position(c + 1) - o);
    }
  }
}

/**
 * The kernel corners that get the fallback frame: those the kernel counts as left at its default
 * or cancelled, less the corners of polygons of fewer than 3 points (which give no frame: the
 * kernel leaves them at its default) and those of kept points (non-zero in `kept`; null: none),
 * which keep their supplied frames.
 */
vtkIdType FallbackCorners(const Surface& s, const mikk::Result& kernel, const unsigned char* kept)
{
  const auto size = [&](long long f) { return s.FaceOffsets[f + 1] - s.FaceOffsets[f]; };
  // Only polygons can be short faces (a short strip gives no face); the kernel counts them.
  long long shortCorners = 0;
  for (long long f = 0; kernel.NumberOfSkippedFaces > 0 && f < s.NumPolys; ++f)
  {
    shortCorners += size(f) < 3 ? size(f) : 0;
  }
  vtkIdType count = kernel.NumberOfDefaultCorners + kernel.NumberOfCancelledCorners - shortCorners;
  for (long long f = 0; kept && f < s.NumFaces; ++f)
  {
    for (long long c = s.FaceOffsets[f]; size(f) >= 3 && c < s.FaceOffsets[f + 1]; ++c)
    {
      const bool keptFallback =
        kernel.CornerKinds[static_cast<size_t>(c)] != mikk::CornerKind::Computed &&
        kept[s.FaceConnectivity[c]];
      count -= keptFallback ? 1 : 0;
    }
  }
  return count;
}

/**
 * Every output point's frame: the kernel frame Assignment gives it (the default for points no
 * corner with a frame reaches), made to meet the contract with the normal of the input point it
 * comes from (ContractFrame), its sign times `signFactor` (-1 for glTF's convention), and its
 * bitangent. Points are assigned and split on the kernel's frames before: the contract depends
 * only on the frame and the point's normal, so corners that share a frame share the result.
 */
template<typename OutArray>
void WritePointFrames(float signFactor,
  const ContractNormals& contractNormals,
  const Assignment& a,
  vtkIdType numIn,
  const OutputFrames<OutArray>& arrays)
{
  const auto pointFrame = [&](vtkIdType p) -> const CornerFrame&
  {
    if (p >= numIn)
    {
      return a.SplitFrame[static_cast<size_t>(p - numIn)];
    }
    const CornerFrame& first = a.PointFrame[static_cast<size_t>(p)];
    return first.Sign != 0.0f ? first : mikk::DefaultCornerFrame;
  };
  const auto sourceOf = [&](vtkIdType p)
  { return p < numIn ? p : a.SplitSource[static_cast<size_t>(p - numIn)]; };
  const auto out = arrays.Storage();
  vtkSMPTools::For(0,
    arrays.Tangents->GetNumberOfTuples(),
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType p = b; p < e; ++p)
      {
        const glm::dvec3 normal = contractNormals[sourceOf(p)];
        const CornerFrame f = ContractFrame(pointFrame(p), normal);
        // For the bitangent, the unit normal the tangent was made perpendicular to; a zero or
        // non-finite normal gives a zero bitangent (SafeNormalize), never NaN.
        const glm::dvec3 n = out.Bitangents ? SafeNormalize(normal) : glm::dvec3(0.0);
        out.Write(p,
          n,
          glm::dvec3(f.Tangent[0], f.Tangent[1], f.Tangent[2]),
          static_cast<double>(signFactor * f.Sign));
      }
    });
}

/**
 * The output, with the filter's settings: the input with the split points appended (their point
 * data copied, the computed normals too) and the corners of their frames re-pointed, the point
 * frames, and the cell tangents when asked for. The kernel's corners are freed once the cell
 * tangents are made, before the point data is copied, so that their memory can hold the copies.
 */
template<typename OutArray>
void WriteOutput(vtkPolyDataTangentFrames* filter,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkDataArray* computedNormals,
  const Surface& s,
  mikk::Result& kernel,
  const float* positions,
  const ContractNormals& contractNormals,
  const Assignment& a)
{
  const vtkIdType numIn = input->GetNumberOfPoints();
  const vtkIdType numSplits = static_cast<vtkIdType>(a.SplitSource.size());
  vtkSmartPointer<OutArray> cellTangents;
  if (filter->GetComputeCellTangents())
  {
    cellTangents = NewCellTangents<OutArray>(input,
      [&](vtkIdType c, glm::dvec3& t, glm::dvec3& n) { CellSums(s, kernel, positions, c, t, n); });
  }
  std::vector<CornerFrame>().swap(kernel.Corners);
  std::vector<mikk::CornerKind>().swap(kernel.CornerKinds);
  const OutputFrames<OutArray> arrays(numIn + numSplits, filter->GetComputeBitangents());
  WritePointFrames(
    filter->GetGLTFSignConvention() ? -1.0f : 1.0f, contractNormals, a, numIn, arrays);
  WriteSplitOutput(input, output, a.SplitSource, a.Repoint, arrays, computedNormals);
  if (cellTangents)
  {
    AddActiveTangents(output->GetCellData(), cellTangents);
  }
}
} // namespace
} // namespace detail
} // namespace vtkNormalMapping

//------------------------------------------------------------------------------
vtkIdType vtkPolyDataTangentFrames::ComputeMikkTSpace(const BlockInput& block,
  vtkDataArray* normalArray,
  bool computedNormals)
{
  using namespace vtkNormalMapping::detail;
  namespace mikk = vtkNormalMapping::mikk;
  vtkPolyData* input = block.Input;
  const vtkIdType numPoints = input->GetNumberOfPoints();
  Surface surface;
  BuildSurface(input->GetPolys(), input->GetStrips(), surface);
  std::vector<float> positionStore, normalStore, tcoordStore;
  const float* positions = KernelPositions(input->GetPoints(), numPoints, positionStore);
  const float* normals = FloatData(normalArray, numPoints, 3, normalStore);
  const float* tcoords = FloatData(block.UVs, numPoints, 2, tcoordStore);
  if (!this->ContinueBlock(block, 0.05))
  {
    return 0;
  }

  // The kernel's corner frames, with progress from 0.05 to 0.85.
  const mikk::MeshInput kernelInput{ surface.NumFaces,
    surface.FaceOffsets,
    surface.FaceConnectivity,
    numPoints,
    positions,
    normals,
    tcoords };
  mikk::Result result = mikk::ComputeMikkTSpace(kernelInput,
    [&](double progress) { return !this->ContinueBlock(block, 0.05 + 0.8 * progress); });
  if (result.Aborted)
  {
    return 0;
  }
  if (result.TooLarge)
  {
    vtkErrorMacro("Cannot compute MikkTSpace frames: the input exceeds the kernel's 32-bit index "
                  "limits; passing the input through.");
    block.Output->ShallowCopy(input);
    return 0;
  }
  this->NumberOfDegenerateTriangles += result.NumberOfDegenerateTriangles;
  this->NumberOfFallbackPoints += FallbackCorners(surface, result, block.KeptPoints);
  const ContractNormals contractNormals(normalArray, numPoints, normals);
  Assignment assignment;
  Assign(surface, result.Corners, numPoints, this->Splitting, block.KeptPoints, assignment);
  this->NumberOfHandednessConflicts += assignment.Conflicts;
  if (block.MixedCells && !assignment.MixedCells.empty())
  {
    *block.MixedCells = std::move(assignment.MixedCells);
    return result.NumberOfTriangles;
  }
  this->NumberOfSplitPoints += static_cast<vtkIdType>(assignment.SplitSource.size());
  if (!this->ContinueBlock(block, 0.9))
  {
    return 0;
  }

  const auto write =
    this->DoubleOutput(input) ? WriteOutput<vtkDoubleArray> : WriteOutput<vtkFloatArray>;
  write(this,
    input,
    block.Output,
    computedNormals ? normalArray : nullptr,
    surface,
    result,
    positions,
    contractNormals,
    assignment);
  if (block.SplitSources)
  {
    *block.SplitSources = std::move(assignment.SplitSource);
  }
  this->ContinueBlock(block, 1.0);
  return result.NumberOfTriangles;
}
