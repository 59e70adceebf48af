// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames::ComputeBlock: the shading normals, then the MikkTSpace method
// (ComputeMikkTSpace, vtkPolyDataTangentFramesMikkTSpace.cxx) or the weighted methods, which
// this file holds.
#include "vtkPolyDataTangentFrames.h"

#include "vtkNormalMappingPrivate.h"
#include "vtkTangentFrameKernels.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <numeric>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

/*
 * How the weighted methods run (everything in double, the passes on vtkSMPTools::For):
 * 1. The polygons (fans from corner 0) and strips are listed as triangles, in cell order; where
 *    normals are computed or replaced, every point gets the list of its triangles in that order
 *    (the links).
 * 2. Every point gets its shading normal: the input's, or where that is unusable (or the input
 *    has none) the area-weighted sum of its triangles' normals, through the links. Float normals
 *    that are all usable are read in place (ShadingNormals); any others become unit vectors.
 * 3. Every triangle gets its frame (ComputeTriangleFrame, a block of triangles at a time) and, per
 *    corner, its weight signed with the handedness it gives that corner's point (the triangle's
 *    orientation, flipped where its winding disagrees with the point's normal).
 * 4. Every point sums the weighted tangents of its triangles per handedness, in triangle order
 *    whatever thread computed them, a range of points (a chunk) at a time (ComputePointFrames).
 *    A point then takes the frame of its one handedness (a block of points at a time), or on a
 *    mirror seam the +1 frame (the -1 frame goes to the point's copy) or the heavier side
 *    (KindOf).
 * 5. Points without a usable triangle take their neighbours' frames; split points are appended
 *    and the corners on their mirrored side re-pointed; cell tangents are per-cell sums.
 */

namespace
{
using glm::dvec2;
using glm::dvec3;
using vtkNormalMapping::DegeneracyTolerance;
using vtkNormalMapping::IsUsableNormal;
using vtkNormalMapping::PerpendicularTangent;
using vtkNormalMapping::SafeNormalize;
using vtkNormalMapping::TangentMethod;
using vtkNormalMapping::TriangleBlock;
using vtkNormalMapping::TriangleFrame;
using vtkNormalMapping::detail::DispatchArray;
using vtkNormalMapping::detail::ForEachNormalRange;
using vtkNormalMapping::detail::FrameStorage;
using vtkNormalMapping::detail::OutputFrames;
using vtkNormalMapping::detail::WithCellStorage;

static_assert(static_cast<int>(TangentMethod::Unweighted) == vtkPolyDataTangentFrames::UNWEIGHTED &&
    static_cast<int>(TangentMethod::AreaWeighted) == vtkPolyDataTangentFrames::AREA_WEIGHTED &&
    static_cast<int>(TangentMethod::AngleWeighted) == vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
  "the weighted values of Method convert to TangentMethod");

/// Storage whose every entry the filter writes before reading it (not cleared first).
template<typename T>
using Buffer = std::unique_ptr<T[]>;

/// The triangles of the polygons and strips, in cell order.
struct Triangles
{
  vtkIdType Count = 0;
  /// Three point ids per triangle: the polygons' own connectivity when every polygon is a
  /// triangle stored with vtkIdType ids and there are no strips, else Storage.
  const vtkIdType* Ids = nullptr;
  Buffer<vtkIdType> Storage;
  /// Per polygon, then per strip, its first triangle, and one more entry for the end; empty
  /// when triangle t is polygon t.
  std::vector<vtkIdType> CellStart;

  vtkIdType NumberOfCells = 0;
  vtkIdType FirstTriangle(vtkIdType cell) const
  {
    return this->CellStart.empty() ? cell : this->CellStart[cell];
  }
};

/// The triangles of polygons that are all triangles, with no strips: the polygons' connectivity,
/// shared when it is stored as vtkIdType, else copied.
void ShareTrianglePolygons(vtkCellArray* polys, Triangles& out)
{
  out.Count = polys->GetNumberOfCells();
  WithCellStorage(polys,
    [&](const auto*, const auto* conn)
    {
      if constexpr (std::is_same<std::decay_t<decltype(*conn)>, vtkIdType>::value)
      {
        out.Ids = conn;
        return;
      }
      out.Storage.reset(new vtkIdType[3 * out.Count]);
      out.Ids = out.Storage.get();
      vtkSMPTools::For(0,
        3 * out.Count,
        [&](vtkIdType begin, vtkIdType end)
        { std::copy(conn + begin, conn + end, out.Storage.get() + begin); });
    });
}

/// The triangles of every polygon and strip (CellTriangle), in cell order.
void ListCellTriangles(vtkCellArray* const cellArrays[2], Triangles& out)
{
  out.CellStart.assign(static_cast<size_t>(out.NumberOfCells + 1), 0);
  vtkNormalMapping::detail::CellTriangleStarts(cellArrays[0], out.CellStart.data());
  vtkNormalMapping::detail::CellTriangleStarts(
    cellArrays[1], out.CellStart.data() + cellArrays[0]->GetNumberOfCells());
  out.Count = out.CellStart.back();
  out.Storage.reset(new vtkIdType[3 * out.Count]);
  out.Ids = out.Storage.get();
  vtkIdType firstCell = 0;
  for (int kind = 0; kind < 2; ++kind)
  {
    vtkCellArray* cells = cellArrays[kind];
    WithCellStorage(cells,
      [&](const auto* offsets, const auto* conn)
      {
        vtkSMPTools::For(0,
          cells->GetNumberOfCells(),
          [&](vtkIdType begin, vtkIdType end)
          {
            for (vtkIdType c = begin; c < end; ++c)
            {
              const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
              vtkIdType* tri = out.Storage.get() + 3 * out.CellStart[firstCell + c];
              for (vtkIdType j = 0; j + 2 < n; ++j, tri += 3)
              {
                vtkNormalMapping::detail::CellTriangle(conn + offsets[c], j, kind == 1, tri);
              }
            }
          });
      });
    firstCell += cells->GetNumberOfCells();
  }
}

/// Lists the triangles of polygons and strips, whose point ids are in range
/// (detail::PointIdsInRange). polysAreTriangles: every polygon has 3 points.
void BuildTriangles(vtkCellArray* const cellArrays[2], bool polysAreTriangles, Triangles& out)
{
  out.NumberOfCells = cellArrays[0]->GetNumberOfCells() + cellArrays[1]->GetNumberOfCells();
  if (polysAreTriangles && cellArrays[1]->GetNumberOfCells() == 0)
  {
    ShareTrianglePolygons(cellArrays[0], out);
    return;
  }
  ListCellTriangles(cellArrays, out);
}

/**
 * Per point, its triangles in triangle order: the order in which the computed normals add their
 * terms, whatever the number of threads.
 */
struct Links
{
  std::vector<vtkIdType> Start; // per point, and one more entry for the end
  Buffer<vtkIdType> Triangle;

  Links(const Triangles& tris, vtkIdType numPoints)
    : Start(static_cast<size_t>(numPoints + 1), 0)
    , Triangle(new vtkIdType[3 * tris.Count])
  {
    const vtkIdType numCorners = 3 * tris.Count;
    for (vtkIdType c = 0; c < numCorners; ++c)
    {
      ++this->Start[tris.Ids[c] + 1];
    }
    std::partial_sum(this->Start.begin(), this->Start.end(), this->Start.begin());
    // Filling moves each point's start to its end, which is the next point's start.
    for (vtkIdType c = 0; c < numCorners; ++c)
    {
      this->Triangle[this->Start[tris.Ids[c]]++] = c / 3;
    }
    std::copy_backward(this->Start.begin(), this->Start.end() - 1, this->Start.end());
    this->Start[0] = 0;
  }

  /// f(triangle) for the triangles of point p, in triangle order.
  template<typename F>
  void ForEach(vtkIdType p, F&& f) const
  {
    const vtkIdType* triangles = this->Triangle.get();
    std::for_each(triangles + this->Start[p], triangles + this->Start[p + 1], f);
  }
};

/// Every triangle's frame, kept for the cell tangents.
struct TriangleFrames
{
  Buffer<dvec3> Tangent; // unit dP/du; zero without a frame
  Buffer<dvec3> Normal;  // the winding normal
  Buffer<double> Area;

  explicit TriangleFrames(vtkIdType n)
    : Tangent(new dvec3[n])
    , Normal(new dvec3[n])
    , Area(new double[n])
  {
  }
  /// Stores the frames of a block's `count` triangles as triangles [first, first + count).
  void Set(vtkIdType first, const TriangleBlock& b, int count)
  {
    for (int i = 0; i < count; ++i)
    {
      const TriangleFrame f = b.Frame(i);
      this->Tangent[first + i] = f.Tangent;
      this->Normal[first + i] = f.Normal;
      this->Area[first + i] = f.Area;
    }
  }
};

/**
 * The shading normal of every point, as 3-tuples of T: either unit vectors of doubles (Unit), or
 * a float normal array whose every normal is usable, normalized where a unit vector is needed.
 * Corner signs need only the direction, so they read the stored vector: a float normal's dot
 * product with a triangle normal neither overflows nor underflows in double. The type is a
 * template argument, so that the loops that read a normal per corner or point do not choose.
 */
template<typename T>
struct ShadingNormals
{
  const T* Data = nullptr;
  bool Unit = true;

  dvec3 Stored(vtkIdType p) const
  {
    return dvec3(this->Data[3 * p], this->Data[3 * p + 1], this->Data[3 * p + 2]);
  }
  dvec3 UnitOf(vtkIdType p) const
  {
    return this->Unit ? this->Stored(p) : SafeNormalize(this->Stored(p));
  }
};

/**
 * ComputeTriangleBlock and, with `signedWeights`, SignCornerWeights for `method` (corner angles
 * only then, for AngleWeighted), multiversioned (VTK_NORMALMAPPING_TARGET_CLONES).
 */
VTK_NORMALMAPPING_TARGET_CLONES
void ComputeFrameBlock(TriangleBlock& block,
  int count,
  const DegeneracyTolerance& tol,
  bool signedWeights,
  TangentMethod method)
{
  vtkNormalMapping::ComputeTriangleBlock(
    block, count, tol, signedWeights && method == TangentMethod::AngleWeighted);
  if (signedWeights)
  {
    vtkNormalMapping::SignCornerWeights(block, count, method);
  }
}

/**
 * The weighted tangent sums of a range of points (a chunk), in half the memory of two per point:
 * per point the sum of the handedness its first corner gave it (Weight signed with that
 * handedness; 0 before any corner), and the other handedness, which only points on mirror seams
 * have, aside. A corner whose triangle has a frame adds a weight with the sign of its handedness
 * (its angle, its area clamped to DBL_MAX, or 1), non-zero unless an area underflows; other
 * corners add zero (Add). So a Sum with a corner of non-zero weight has a non-zero Weight. Each
 * Sum adds its corners in the order they come (triangle order). Points are indexed from the
 * chunk's first point.
 */
struct ChunkSums
{
  /// One handedness' sums of a point: 32 bytes, aligned to 32 so that adding a corner reads and
  /// writes one cache line, not two.
  struct alignas(32) Sum
  {
    dvec3 Tangent{ 0.0 };
    double Weight = 0.0;
    void Add(double signedWeight, const dvec3& tangent)
    {
      this->Tangent += std::abs(signedWeight) * tangent;
      this->Weight += signedWeight; // -(a + b) == -a + -b: |Weight| is the sum of the |weights|
    }
  };
  static_assert(sizeof(Sum) == 32, "a Sum fills half a cache line");
  vtkIdType Begin = 0;
  std::vector<Sum> First;
  std::vector<unsigned char> HasOther;
  std::unordered_map<vtkIdType, Sum> Other;
  /// The corners (3 t + k) of the chunk's points that have no handedness (zero weight), and
  /// those of the other handedness, in the order they came (CornerSigns).
  std::vector<vtkIdType> ZeroCorners;
  std::vector<vtkIdType> OtherCorners;

  /// Empty sums for the points [begin, end), in the memory of the previous chunk's.
  void Reset(vtkIdType begin, vtkIdType end)
  {
    this->Begin = begin;
    this->First.assign(static_cast<size_t>(end - begin), Sum());
    this->HasOther.assign(static_cast<size_t>(end - begin), 0);
    this->Other.clear();
    this->ZeroCorners.clear();
    this->OtherCorners.clear();
  }

  /// Adds corner `corner` of the chunk's point i: its triangle's tangent with the corner's
  /// signed weight. A corner of zero weight (its triangle has no frame) is only listed: adding
  /// it would add zeros to sums that are never -0, which changes none of their bits.
  void Add(vtkIdType i, vtkIdType corner, double signedWeight, const dvec3& tangent)
  {
    Sum& first = this->First[i];
    // One branch, taken only on mirror seams and for triangles without a frame: whether the
    // point's first handedness is already set and differs from this corner's, or the corner has
    // none.
    const bool other =
      (first.Weight != 0.0) & (std::signbit(first.Weight) != std::signbit(signedWeight));
    if ((signedWeight != 0.0) & !other)
    {
      first.Add(signedWeight, tangent);
      return;
    }
    this->AddRare(i, corner, signedWeight, tangent);
  }

  /// Add's path for a corner without handedness or of the other handedness, kept out of the
  /// loops that call Add, so that Add is small enough for any compiler to inline (compilers
  /// other than GCC and Clang ignore these attributes).
  [[gnu::noinline, gnu::cold]] void AddRare(vtkIdType i,
    vtkIdType corner,
    double signedWeight,
    const dvec3& tangent)
  {
    if (signedWeight == 0.0)
    {
      this->ZeroCorners.push_back(corner);
      return;
    }
    this->HasOther[i] = 1;
    this->Other[i].Add(signedWeight, tangent);
    this->OtherCorners.push_back(corner);
  }

  /// Adds the corners of the chunk's points among the block's `count` triangles, triangles
  /// [first, first + count) of `tris`, in order.
  void AddBlock(const vtkIdType* tris, vtkIdType first, const TriangleBlock& b, int count)
  {
    using Unsigned = std::make_unsigned<vtkIdType>::type;
    const Unsigned points = static_cast<Unsigned>(this->First.size());
    const vtkIdType* ids = tris + 3 * first;
    for (int t = 0; t < count; ++t)
    {
      const dvec3 tangent(b.Tangent[0][t], b.Tangent[1][t], b.Tangent[2][t]);
      for (int k = 0; k < 3; ++k)
      {
        const Unsigned i = static_cast<Unsigned>(ids[3 * t + k] - this->Begin);
        if (i < points) // the point is the chunk's
        {
          this->Add(static_cast<vtkIdType>(i), 3 * (first + t) + k, b.SignedWeight[k][t], tangent);
        }
      }
    }
  }

  /// The +1 or the -1 (`negative`) Sum of the chunk's point i on a mirror seam (HasOther), whose
  /// two Sums have opposite signs.
  const Sum& SeamSum(vtkIdType i, bool negative) const
  {
    const Sum& first = this->First[i];
    return (first.Weight < 0.0) == negative ? first : this->Other.at(i);
  }
};

/**
 * A range that holds the point ids of a tile: the AND and the OR of its ids, between which each
 * id lies (the ids are not negative: PointIdsInRange). It is exact about the chunks a tile
 * reaches where all its ids lie in one chunk: a chunk holds the ids that share their bits above
 * the chunk's size, a power of two (Chunks). Where they do not, it can reach more chunks than
 * the ids do; those compute the tile for nothing.
 */
struct IdRange
{
  vtkIdType First;
  vtkIdType Last;
};

/// Consecutive triangles that ComputePointFrames computes and adds together.
constexpr vtkIdType TileSize = 256;

/// Per tile of TileSize consecutive triangles, its IdRange, in a loop that vectorizes with any
/// instruction set.
std::vector<IdRange> TileBounds(const Triangles& tris)
{
  const vtkIdType tiles = (tris.Count + TileSize - 1) / TileSize;
  std::vector<IdRange> bounds(static_cast<size_t>(tiles));
  vtkSMPTools::For(0,
    tiles,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType tile = begin; tile < end; ++tile)
      {
        const vtkIdType* first = tris.Ids + 3 * tile * TileSize;
        const vtkIdType* last = tris.Ids + 3 * std::min(tris.Count, (tile + 1) * TileSize);
        vtkIdType all = ~vtkIdType(0);
        vtkIdType any = 0;
        for (const vtkIdType* id = first; id < last; ++id)
        {
          all &= *id;
          any |= *id;
        }
        bounds[tile] = IdRange{ all, any };
      }
    });
  return bounds;
}

/**
 * The points split into consecutive ranges (chunks) of 2^Shift points, the last one shorter. A
 * chunk's sums (ChunkSums, 32 bytes a point) stay in cache while its tiles add to them: at most
 * 2^16 points, 2 MiB.
 */
struct Chunks
{
  static constexpr int LargestShift = 16;
  /// Four chunks per thread where chunks of 2^SmallestShift points or more allow it, so that a
  /// thread that finishes early takes another chunk.
  static constexpr int SmallestShift = 10;
  static constexpr int ChunksPerThread = 4;

  int Shift = LargestShift;
  vtkIdType NumberOfPoints = 0;

  vtkIdType Count() const
  {
    return this->NumberOfPoints > 0 ? ((this->NumberOfPoints - 1) >> this->Shift) + 1 : 0;
  }
  vtkIdType First(vtkIdType chunk) const { return chunk << this->Shift; }
  vtkIdType End(vtkIdType chunk) const
  {
    return std::min(this->First(chunk + 1), this->NumberOfPoints);
  }
  /// The chunks a tile reaches, as far as its IdRange tells.
  vtkIdType FirstReached(const IdRange& r) const { return r.First >> this->Shift; }
  vtkIdType LastReached(const IdRange& r) const
  {
    return std::min(r.Last >> this->Shift, this->Count() - 1);
  }

  /// How many times tiles are computed more than once: once per chunk they reach.
  vtkIdType Recomputed(const std::vector<IdRange>& bounds) const
  {
    vtkIdType extra = 0;
    for (const IdRange& r : bounds)
    {
      extra += this->LastReached(r) - this->FirstReached(r);
    }
    return extra;
  }

  /**
   * Chunks for the points of tiles with these bounds (empty: one chunk, one thread). Where the
   * triangles' point ids spread, so that more than one tile in eight would be computed again,
   * fewer and larger chunks are used, down to one per thread.
   */
  static Chunks For(vtkIdType numPoints, int threads, const std::vector<IdRange>& bounds)
  {
    Chunks chunks;
    chunks.NumberOfPoints = numPoints;
    if (bounds.empty())
    {
      chunks.Shift = std::numeric_limits<vtkIdType>::digits - 1;
      return chunks;
    }
    while (chunks.Shift > SmallestShift && chunks.Count() < ChunksPerThread * threads)
    {
      --chunks.Shift;
    }
    while (chunks.Count() > threads &&
      8 * chunks.Recomputed(bounds) > static_cast<vtkIdType>(bounds.size()))
    {
      ++chunks.Shift;
    }
    return chunks;
  }
};

/// What the sums of a point show.
enum class PointKind : unsigned char
{
  Framed,   ///< its corners have one handedness
  Conflict, ///< both handednesses (a mirror seam)
  Fallback, ///< no usable triangle
};

/// A point on a mirror seam with splitting: its normal and the frame of its -1 side, which goes
/// to its copy, and the handedness of its first corner (+1 or -1).
struct SplitPoint
{
  vtkIdType Id;
  dvec3 Normal;
  dvec3 Tangent;
  int FirstHandedness;
};

/**
 * The corners (3 t + k) whose handedness differs from their point's first corner's, in
 * ascending order: those without handedness (a zero TriangleBlock::SignedWeight), and
 * those of the other handedness, which only points on mirror seams have (ChunkSums).
 */
struct CornerSigns
{
  std::vector<vtkIdType> Zero;
  std::vector<vtkIdType> Other;

  /// The handedness triangle t gives its corner at point id, whose first corner's is `first`.
  int At(const Triangles& tris, vtkIdType t, vtkIdType id, int first) const
  {
    for (vtkIdType c = 3 * t; c < 3 * t + 3; ++c)
    {
      if (tris.Ids[c] == id)
      {
        if (std::binary_search(this->Zero.begin(), this->Zero.end(), c))
        {
          return 0;
        }
        return std::binary_search(this->Other.begin(), this->Other.end(), c) ? -first : first;
      }
    }
    return 0;
  }
};

/// Which corners of the cells move to the copies of split points (MirroredCorners).
struct Repointing
{
  /// (connectivity position, copy id): polygon positions first, then strip positions after the
  /// polygons' connectivity.
  std::vector<std::pair<vtkIdType, vtkIdType>> Corners;
  /// The cells (over the polygons, then the strips) with a corner of a split point whose
  /// triangles there have both handednesses: one point id cannot give each its side's frame (a
  /// strip crossing a mirror seam, a polygon folded in UV).
  std::vector<vtkIdType> MixedCells;
};

/**
 * Re-pointing of the corners on the mirrored side of split points: the corners whose cell's
 * triangles there have the -1 handedness (or none). A corner whose triangles have both is not
 * re-pointed; its cell is listed in MixedCells instead. So, once no cell is mixed, every split
 * point's copy takes the corners of the triangles that gave the point its -1 sum.
 */
Repointing MirroredCorners(vtkCellArray* const cellArrays[2],
  const Triangles& tris,
  const CornerSigns& signs,
  const std::vector<SplitPoint>& splits,
  vtkIdType numPoints)
{
  Repointing repoint;
  if (splits.empty())
  {
    return repoint;
  }
  // Which points are split, looked up per connectivity entry; the few entries of split points
  // then find their cell and their copy by binary search.
  std::vector<unsigned char> isSplit(static_cast<size_t>(numPoints), 0);
  for (const SplitPoint& s : splits)
  {
    isSplit[s.Id] = 1;
  }
  vtkIdType firstCell = 0;
  vtkIdType base = 0;
  for (int kind = 0; kind < 2; ++kind)
  {
    const bool strip = kind == 1;
    vtkCellArray* cells = cellArrays[kind];
    const vtkIdType numCells = cells->GetNumberOfCells();
    WithCellStorage(cells,
      [&](const auto* offsets, const auto* conn)
      {
        for (vtkIdType pos = 0; pos < static_cast<vtkIdType>(offsets[numCells]); ++pos)
        {
          const vtkIdType id = conn[pos];
          if (!isSplit[id])
          {
            continue;
          }
          // The cell holding this entry (the last one starting at or before it: cells without
          // points start where the next one does) and its triangles that hold the corner.
          const vtkIdType c = std::upper_bound(offsets, offsets + numCells + 1, pos) - offsets - 1;
          const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
          const vtkIdType k = pos - static_cast<vtkIdType>(offsets[c]);
          const vtkIdType firstTriangle = tris.FirstTriangle(firstCell + c);
          vtkIdType first, last;
          vtkNormalMapping::detail::TrianglesAtCorner(k, n, strip, first, last);
          const auto split = std::lower_bound(splits.begin(),
            splits.end(),
            id,
            [](const SplitPoint& s, vtkIdType value) { return s.Id < value; });
          int positive = 0;
          int negative = 0;
          for (vtkIdType j = first; j <= last; ++j)
          {
            const int h = signs.At(tris, firstTriangle + j, id, split->FirstHandedness);
            positive += h > 0 ? 1 : 0;
            negative += h < 0 ? 1 : 0;
          }
          if (positive > 0 && negative > 0)
          {
            if (repoint.MixedCells.empty() || repoint.MixedCells.back() != firstCell + c)
            {
              repoint.MixedCells.push_back(firstCell + c);
            }
          }
          else if (negative > 0)
          {
            repoint.Corners.emplace_back(
              base + pos, numPoints + static_cast<vtkIdType>(split - splits.begin()));
          }
        }
      });
    firstCell += numCells;
    base += cells->GetNumberOfConnectivityIds();
  }
  return repoint;
}

/**
 * KindOf for a point on a mirror seam (Conflict): +1 with splitting, else the heavier side (+1
 * on a tie). Kept out of KindOf, so that KindOf is small enough for any compiler to inline in
 * the loop over the points.
 */
PointKind SeamKindOf(const ChunkSums& sums,
  vtkIdType i,
  bool splitting,
  double& sign,
  dvec3& tangent)
{
  const ChunkSums::Sum& positive = sums.SeamSum(i, false);
  const ChunkSums::Sum& negative = sums.SeamSum(i, true);
  sign = splitting || !(std::abs(negative.Weight) > std::abs(positive.Weight)) ? 1.0 : -1.0;
  tangent = (sign > 0.0 ? positive : negative).Tangent;
  return PointKind::Conflict;
}

/**
 * What the sums of the chunk's point i make of it, the handedness (+1 or -1) whose frame it
 * takes, and that handedness' tangent sum: its one handedness (Framed), none (Fallback: no usable
 * triangle, it takes its neighbours' frames later), or both, on a mirror seam (SeamKindOf).
 */
inline PointKind KindOf(const ChunkSums& sums,
  vtkIdType i,
  bool splitting,
  double& sign,
  dvec3& tangent)
{
  if (sums.HasOther[i])
  {
    return SeamKindOf(sums, i, splitting, sign, tangent);
  }
  const ChunkSums::Sum& first = sums.First[i];
  sign = first.Weight > 0.0 ? 1.0 : -1.0;
  tangent = first.Tangent;
  return std::abs(first.Weight) > 0.0 ? PointKind::Framed : PointKind::Fallback;
}

/// ComputePointBlock, multiversioned (VTK_NORMALMAPPING_TARGET_CLONES).
VTK_NORMALMAPPING_TARGET_CLONES
void ComputeUnitFrames(vtkNormalMapping::PointBlock& block, int count, bool normalize)
{
  vtkNormalMapping::ComputePointBlock(block, count, normalize);
}

/**
 * The frames of a chunk's points from their sums (KindOf): the tangent of its handedness made
 * perpendicular to its unit normal, a block of points at a time (ComputeUnitFrames). Fallback
 * points are only marked in `kinds`.
 */
template<typename OutT, typename NormalT>
void WriteChunkFrames(const ChunkSums& sums,
  const ShadingNormals<NormalT>& normals,
  bool splitting,
  const FrameStorage<OutT>& out,
  PointKind* kinds)
{
  using vtkNormalMapping::PointBlock;
  PointBlock b; // not initialized: each point's entries are written before use
  double signs[PointBlock::Size];
  const vtkIdType size = static_cast<vtkIdType>(sums.First.size());
  for (vtkIdType first = 0; first < size; first += PointBlock::Size)
  {
    const int count = static_cast<int>(std::min<vtkIdType>(PointBlock::Size, size - first));
    for (int i = 0; i < count; ++i)
    {
      dvec3 tangent;
      kinds[sums.Begin + first + i] = KindOf(sums, first + i, splitting, signs[i], tangent);
      b.Set(i, normals.Stored(sums.Begin + first + i), tangent);
    }
    ComputeUnitFrames(b, count, !normals.Unit);
    for (int i = 0; i < count; ++i)
    {
      const vtkIdType p = sums.Begin + first + i;
      if (kinds[p] != PointKind::Fallback)
      {
        out.Write(p, b.Normal(i), b.Tangent(i), signs[i]);
      }
    }
  }
}

/**
 * The -1 frames of a chunk's points on mirror seams (Conflict in `kinds`), those of `kept`
 * (non-zero per kept point, or null) left out, for their copies.
 */
template<typename NormalT>
std::vector<SplitPoint> ChunkSplitFrames(const ChunkSums& sums,
  const ShadingNormals<NormalT>& normals,
  const PointKind* kinds,
  const unsigned char* kept)
{
  std::vector<SplitPoint> splits;
  for (const auto& entry : sums.Other)
  {
    const vtkIdType p = sums.Begin + entry.first;
    if (kinds[p] == PointKind::Conflict && !(kept && kept[p]))
    {
      const dvec3 n = normals.UnitOf(p);
      splits.push_back(SplitPoint{ p,
        n,
        PerpendicularTangent(n, sums.SeamSum(entry.first, true).Tangent),
        sums.First[entry.first].Weight > 0.0 ? 1 : -1 });
    }
  }
  std::sort(splits.begin(),
    splits.end(),
    [](const SplitPoint& a, const SplitPoint& b) { return a.Id < b.Id; });
  return splits;
}

/// The points of one kind, in ascending order.
std::vector<vtkIdType> PointsOfKind(const PointKind* kinds, vtkIdType numPoints, PointKind kind)
{
  std::vector<vtkIdType> points;
  for (vtkIdType p = 0; p < numPoints; ++p)
  {
    if (kinds[p] == kind)
    {
      points.push_back(p);
    }
  }
  return points;
}

/**
 * Fallback points: the mean of their framed neighbours' tangents (as written) on their own
 * tangent plane, and their neighbours' majority sign (+1 when none). One pass over the triangle
 * corners in order collects, per fallback point, its neighbours in triangle order. A fallback
 * point's corners have no handedness (`signs.Zero`), so only those corners are looked at.
 */
template<typename OutT, typename NormalT>
void FillFallbacks(const Triangles& tris,
  const CornerSigns& signs,
  const ShadingNormals<NormalT>& normals,
  const PointKind* kinds,
  const std::vector<vtkIdType>& fallbacks,
  const FrameStorage<OutT>& out)
{
  std::vector<dvec3> sums(fallbacks.size(), dvec3(0.0));
  std::vector<int> votes(fallbacks.size(), 0);
  for (const vtkIdType c : signs.Zero)
  {
    const vtkIdType p = tris.Ids[c];
    if (kinds[p] != PointKind::Fallback)
    {
      continue;
    }
    const size_t i = std::lower_bound(fallbacks.begin(), fallbacks.end(), p) - fallbacks.begin();
    const vtkIdType* triangle = tris.Ids + 3 * (c / 3);
    for (int m = 0; m < 3; ++m)
    {
      const vtkIdType q = triangle[m];
      if (q != p && kinds[q] != PointKind::Fallback)
      {
        sums[i] += dvec3(out.Tangents[3 * q], out.Tangents[3 * q + 1], out.Tangents[3 * q + 2]);
        votes[i] += out.Signs[q] < 0 ? -1 : 1;
      }
    }
  }
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(fallbacks.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const vtkIdType p = fallbacks[i];
        const dvec3 n = normals.UnitOf(p);
        out.Write(p, n, PerpendicularTangent(n, sums[i]), votes[i] < 0 ? -1.0 : 1.0);
      }
    });
}

/// The output arrays' concrete class for OutT, so that users' SafeDownCasts work.
template<typename OutT>
using OutArray =
  typename std::conditional<std::is_same<OutT, float>::value, vtkFloatArray, vtkDoubleArray>::type;

} // namespace

/// One execution on one polydata, with what it needs from the filter.
struct vtkPolyDataTangentFrames::Internals : vtkPolyDataTangentFrames::BlockInput
{
  Internals(const BlockInput& block, vtkPolyDataTangentFrames* self)
    : BlockInput(block)
    , Self(self)
    , NumberOfPoints(block.Input->GetNumberOfPoints())
    , Cells{ block.Input->GetPolys(), block.Input->GetStrips() }
    , FirstSurfaceCell(block.Input->GetNumberOfVerts() + block.Input->GetNumberOfLines())
  {
  }

  vtkPolyDataTangentFrames* Self;

  const vtkIdType NumberOfPoints;
  vtkCellArray* const Cells[2]; // polygons, strips
  const vtkIdType FirstSurfaceCell;
  Triangles Tris;
  /// The triangles this execution computed frames for (the weighted methods' Tris, or
  /// MikkTSpace's), for the warning when none has a frame.
  vtkIdType NumberOfTriangles = 0;
  /// What ComputePointFrames keeps: the corners whose handedness is not their point's first's,
  /// and each triangle's frame when cell tangents are asked for.
  CornerSigns Signs;
  std::unique_ptr<TriangleFrames> Frames;

  /// Progress as a fraction of this execution; false (output emptied) when aborted.
  bool Continue(double fraction) { return this->Self->ContinueBlock(*this, fraction); }

  /**
   * Calls body(visitRange), where visitRange(begin, end, visit) calls visit(first, block, count)
   * for consecutive blocks of the triangles [begin, end), in order: `block` holds the frames of
   * triangles [first, first + count) (ComputeFrameBlock), with `normals` also their corners'
   * weights for `method` signed with their handedness. `body` decides which ranges to visit on
   * which threads. Float and double points and texture coordinates are read through their
   * concrete types, any other type through vtkDataArray.
   */
  template<typename Body, typename NormalT = double>
  void WithFrames(const Body& body,
    const ShadingNormals<NormalT>* normals = nullptr,
    TangentMethod method = TangentMethod::Unweighted)
  {
    vtkDataArray* pointArray = this->Input->GetPoints()->GetData();
    const DegeneracyTolerance tol = vtkNormalMapping::detail::ToleranceFor(pointArray, this->UVs);
    const bool hasV = this->UVs->GetNumberOfComponents() > 1;
    const vtkIdType* ids = this->Tris.Ids;
    const auto run = [&](auto* typedPoints, auto* typedUVs)
    {
      const auto points = vtk::DataArrayTupleRange<3>(typedPoints);
      const auto uvs = vtk::DataArrayTupleRange(typedUVs);
      const auto visitRange = [&](vtkIdType rangeBegin, vtkIdType rangeEnd, const auto& visit)
      {
        TriangleBlock b; // not initialized: each triangle's entries are written before use
        for (vtkIdType first = rangeBegin; first < rangeEnd; first += TriangleBlock::Size)
        {
          const int count =
            static_cast<int>(std::min<vtkIdType>(TriangleBlock::Size, rangeEnd - first));
          for (int i = 0; i < count; ++i)
          {
            dvec3 p[3];
            dvec2 uv[3];
            for (int k = 0; k < 3; ++k)
            {
              const vtkIdType id = ids[3 * (first + i) + k];
              const auto point = points[id];
              const auto texture = uvs[id];
              p[k] = dvec3(point[0], point[1], point[2]);
              uv[k] = dvec2(texture[0], hasV ? static_cast<double>(texture[1]) : 0.0);
              if (normals)
              {
                b.SetCornerNormal(k, i, normals->Stored(id));
              }
            }
            b.SetCorners(i, p, uv);
          }
          ComputeFrameBlock(b, count, tol, normals != nullptr, method);
          visit(first, static_cast<const TriangleBlock&>(b), count);
        }
      };
      body(visitRange);
    };
    using Dispatcher =
      vtkArrayDispatch::Dispatch2ByValueType<vtkArrayDispatch::Reals, vtkArrayDispatch::Reals>;
    if (!Dispatcher::Execute(pointArray, this->UVs, run))
    {
      run(pointArray, this->UVs);
    }
  }

  /**
   * Smooth area-weighted point normals from the triangles' geometric normals, or from the
   * input's cell normals when given; `empty` where a point has no area.
   */
  std::vector<dvec3> SmoothNormals(vtkDataArray* cellNormals, const dvec3& empty)
  {
    std::vector<dvec3> weighted(static_cast<size_t>(this->Tris.Count));
    std::vector<double> area(cellNormals ? weighted.size() : 0);
    const auto visit = [&](vtkIdType first, const TriangleBlock& b, int count)
    {
      for (int i = 0; i < count; ++i)
      {
        const TriangleFrame f = b.Frame(i);
        if (cellNormals)
        {
          area[first + i] = f.Area; // the cell's normal follows below
        }
        else
        {
          weighted[first + i] = f.Area * SafeNormalize(f.Normal);
        }
      }
    };
    this->WithFrames(
      [&](const auto& visitRange)
      {
        vtkSMPTools::For(0,
          this->Tris.Count,
          [&](vtkIdType begin, vtkIdType end) { visitRange(begin, end, visit); });
      });
    if (cellNormals)
    {
      vtkSMPTools::For(0,
        this->Tris.NumberOfCells,
        [&](vtkIdType begin, vtkIdType end)
        {
          for (vtkIdType c = begin; c < end; ++c)
          {
            double n[3];
            cellNormals->GetTuple(this->FirstSurfaceCell + c, n);
            const dvec3 cellNormal = SafeNormalize(dvec3(n[0], n[1], n[2]));
            for (vtkIdType t = this->Tris.FirstTriangle(c); t < this->Tris.FirstTriangle(c + 1);
                 ++t)
            {
              weighted[t] = area[t] * cellNormal;
            }
          }
        });
    }
    // Per point the sum of its triangles' area-weighted normals in triangle order (the links'),
    // so that the result is the same for any number of threads.
    const Links links(this->Tris, this->NumberOfPoints);
    std::vector<dvec3> normals(static_cast<size_t>(this->NumberOfPoints));
    vtkSMPTools::For(0,
      this->NumberOfPoints,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType p = begin; p < end; ++p)
        {
          dvec3 sum(0.0);
          links.ForEach(p, [&](vtkIdType t) { sum += weighted[t]; });
          const dvec3 n = SafeNormalize(sum);
          normals[p] = n == dvec3(0.0) ? empty : n;
        }
      });
    return normals;
  }

  /**
   * Every point's frame from its weighted tangent sums (ChunkSums), written to `out`, and its
   * kind to `kinds`; returns the -1 frames of the mirror-seam points that the caller does not
   * keep, in ascending order. The points go in chunks (Chunks::For), one chunk per thread at a
   * time. A chunk's thread goes through the triangles in order, computes the frames of the tiles
   * that reach its points (TileBounds) and adds the corners of its points, so that each point
   * adds the same terms in the same order, hence the same bits, for any number of threads; it
   * then writes its points' frames while their sums are in cache, and lists in Signs its corners
   * whose handedness is not their point's first's. A tile's first chunk stores its frames when
   * cell tangents are asked for. Counts the triangles without a frame in
   * NumberOfDegenerateTriangles.
   */
  template<typename OutT, typename NormalT>
  std::vector<SplitPoint> ComputePointFrames(TangentMethod method,
    const ShadingNormals<NormalT>& normals,
    const FrameStorage<OutT>& out,
    PointKind* kinds)
  {
    vtkPolyDataTangentFrames* self = this->Self;
    const vtkIdType numPoints = this->NumberOfPoints;
    const vtkIdType count = this->Tris.Count;
    const vtkIdType* ids = this->Tris.Ids;
    const vtkIdType tiles = (count + TileSize - 1) / TileSize;
    // A mesh of a few tiles does not pay for starting the threads.
    const int threads = tiles > 16 ? vtkNormalMapping::detail::UsableThreads() : 1;
    // One thread sums a mesh of up to one chunk's points in one chunk, without tile bounds.
    const bool chunked = threads > 1 || numPoints > (vtkIdType(1) << Chunks::LargestShift);
    const std::vector<IdRange> bounds = chunked ? TileBounds(this->Tris) : std::vector<IdRange>();
    const Chunks chunks = Chunks::For(numPoints, threads, bounds);
    if (self->ComputeCellTangents)
    {
      this->Frames.reset(new TriangleFrames(count));
    }
    std::vector<std::vector<SplitPoint>> splits(static_cast<size_t>(chunks.Count()));
    std::vector<CornerSigns> signs(static_cast<size_t>(chunks.Count()));
    std::atomic<vtkIdType> withoutFrame{ 0 };
    vtkSMPThreadLocal<ChunkSums> localSums;
    const auto computeChunk = [&](vtkIdType chunk, const auto& visitRange)
    {
      ChunkSums& sums = localSums.Local();
      sums.Reset(chunks.First(chunk), chunks.End(chunk));
      vtkIdType none = 0;
      for (vtkIdType tile = 0; tile < tiles; ++tile)
      {
        // The chunks a tile reaches compute it; the first of them also stores what is per
        // triangle.
        const vtkIdType firstChunk = bounds.empty() ? chunk : chunks.FirstReached(bounds[tile]);
        const vtkIdType lastChunk = bounds.empty() ? chunk : chunks.LastReached(bounds[tile]);
        if (chunk < firstChunk || chunk > lastChunk)
        {
          continue;
        }
        const bool first = chunk == firstChunk;
        visitRange(tile * TileSize,
          std::min(count, (tile + 1) * TileSize),
          [&](vtkIdType firstTriangle, const TriangleBlock& b, int n)
          {
            if (first)
            {
              for (int i = 0; i < n; ++i)
              {
                none += b.Orientation[i] == 0.0 ? 1 : 0;
              }
              if (this->Frames)
              {
                this->Frames->Set(firstTriangle, b, n);
              }
            }
            sums.AddBlock(ids, firstTriangle, b, n);
          });
      }
      withoutFrame += none;
      WriteChunkFrames(sums, normals, self->Splitting, out, kinds);
      splits[chunk] = ChunkSplitFrames(sums, normals, kinds, this->KeptPoints);
      signs[chunk] = CornerSigns{ sums.ZeroCorners, sums.OtherCorners };
    };
    this->WithFrames(
      [&](const auto& visitRange)
      {
        vtkSMPTools::For(0,
          chunks.Count(),
          1,
          [&](vtkIdType firstChunk, vtkIdType lastChunk)
          {
            for (vtkIdType chunk = firstChunk; chunk < lastChunk; ++chunk)
            {
              computeChunk(chunk, visitRange);
            }
          });
      },
      &normals,
      method);
    self->NumberOfDegenerateTriangles += withoutFrame;
    std::vector<SplitPoint> all;
    for (const std::vector<SplitPoint>& chunkSplits : splits)
    {
      all.insert(all.end(), chunkSplits.begin(), chunkSplits.end());
    }
    CornerSigns& merged = this->Signs;
    for (const CornerSigns& chunkSigns : signs)
    {
      merged.Zero.insert(merged.Zero.end(), chunkSigns.Zero.begin(), chunkSigns.Zero.end());
      merged.Other.insert(merged.Other.end(), chunkSigns.Other.begin(), chunkSigns.Other.end());
    }
    std::sort(merged.Zero.begin(), merged.Zero.end());
    std::sort(merged.Other.begin(), merged.Other.end());
    return all;
  }

  /**
   * The unit shading normals of a point normal array with `unusable` unusable normals, stored in
   * `unit`: the unusable ones take the area-weighted normal of their triangles.
   */
  ShadingNormals<double> UnitNormals(vtkDataArray* array, vtkIdType unusable, Buffer<dvec3>& unit)
  {
    unit.reset(new dvec3[this->NumberOfPoints]);
    // Unit normals, zero where a normal is zero or non-finite.
    ForEachNormalRange(array,
      this->NumberOfPoints,
      [&](vtkIdType begin, vtkIdType end, const auto& normal)
      {
        for (vtkIdType p = begin; p < end; ++p)
        {
          unit[p] = SafeNormalize(dvec3(normal(p)));
        }
      });
    if (unusable > 0)
    {
      const std::vector<dvec3> geometric = this->SmoothNormals(nullptr, dvec3(0.0));
      for (vtkIdType p = 0; p < this->NumberOfPoints; ++p)
      {
        unit[p] = unit[p] == dvec3(0.0) ? geometric[p] : unit[p];
      }
    }
    return ShadingNormals<double>{ &unit[0].x, true };
  }

  /// Smooth point normals (SmoothNormals, +z where a point has no area) as an output array.
  template<typename OutT>
  vtkSmartPointer<OutArray<OutT>> ComputedNormals()
  {
    const std::vector<dvec3> smooth = this->SmoothNormals(this->CellNormals, dvec3(0.0, 0.0, 1.0));
    auto normals =
      vtkNormalMapping::detail::NewArray<OutArray<OutT>>("Normals", 3, this->NumberOfPoints);
    OutT* out = normals->GetPointer(0);
    for (size_t p = 0; p < smooth.size(); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        out[3 * p + c] = static_cast<OutT>(smooth[p][c]);
      }
    }
    return normals;
  }

  template<typename OutT>
  void Run();
  template<typename OutT, typename NormalT>
  void RunWeighted(TangentMethod method,
    vtkSmartPointer<OutArray<OutT>> computedNormals,
    const ShadingNormals<NormalT>& normals);

  /**
   * The output (WriteSplitOutput): the split points' -1 frames after the input points', the
   * corners on their mirrored side re-pointed to them, and the cell tangents when asked for; or,
   * when cells are mixed (MirroredCorners) and MixedCells asks for them, only those cells.
   */
  template<typename OutT>
  void WriteOutput(std::vector<SplitPoint> splits,
    const OutputFrames<OutArray<OutT>>& frames,
    vtkDataArray* computedNormals)
  {
    Repointing repoint =
      MirroredCorners(this->Cells, this->Tris, this->Signs, splits, this->NumberOfPoints);
    if (this->MixedCells && !repoint.MixedCells.empty())
    {
      *this->MixedCells = std::move(repoint.MixedCells);
      return;
    }
    this->Self->NumberOfSplitPoints += static_cast<vtkIdType>(splits.size());
    frames.Resize(this->NumberOfPoints + static_cast<vtkIdType>(splits.size()));
    const FrameStorage<OutT> out = frames.Storage();
    std::vector<vtkIdType> splitSource(splits.size());
    for (size_t i = 0; i < splits.size(); ++i)
    {
      splitSource[i] = splits[i].Id;
      out.Write(this->NumberOfPoints + static_cast<vtkIdType>(i),
        splits[i].Normal,
        splits[i].Tangent,
        -1.0);
    }
    vtkNormalMapping::detail::WriteSplitOutput(
      this->Input, this->Output, splitSource, repoint.Corners, frames, computedNormals);
    if (this->SplitSources)
    {
      *this->SplitSources = std::move(splitSource);
    }
    if (this->Self->ComputeCellTangents)
    {
      // Per cell, its triangles' area-weighted tangents and normals.
      const Triangles& tris = this->Tris;
      const TriangleFrames& f = *this->Frames;
      vtkNormalMapping::detail::AddActiveTangents(this->Output->GetCellData(),
        vtkNormalMapping::detail::NewCellTangents<OutArray<OutT>>(this->Input,
          [&](vtkIdType c, dvec3& t, dvec3& n)
          {
            for (vtkIdType i = tris.FirstTriangle(c); i < tris.FirstTriangle(c + 1); ++i)
            {
              t += f.Area[i] * f.Tangent[i];
              n += f.Area[i] * SafeNormalize(f.Normal[i]);
            }
          }));
    }
  }
};

template<typename OutT>
void vtkPolyDataTangentFrames::Internals::Run()
{
  vtkPolyDataTangentFrames* self = this->Self;
  const bool mikkTSpace = self->Method == MIKKTSPACE;

  // Normals: the input's, or computed when it has none; how the frames read them follows below.
  vtkSmartPointer<OutArray<OutT>> computedNormals;
  const vtkIdType unusable = this->UnusableNormals;
  if (!mikkTSpace || !this->Normals)
  {
    BuildTriangles(this->Cells, this->PolysAreTriangles, this->Tris);
    this->NumberOfTriangles = this->Tris.Count;
    if (!this->Continue(0.2))
    {
      return;
    }
  }
  if (!this->Normals)
  {
    computedNormals = this->ComputedNormals<OutT>();
  }
  if (mikkTSpace)
  {
    this->NumberOfTriangles = self->ComputeMikkTSpace(
      *this, computedNormals ? computedNormals.Get() : this->Normals, computedNormals != nullptr);
    return;
  }
  // The frames follow the normals as stored: a float array whose every normal is usable as it
  // is, any other as unit vectors.
  const auto method = static_cast<TangentMethod>(self->Method);
  vtkDataArray* normals = computedNormals ? computedNormals.Get() : this->Normals;
  auto* floats = vtkFloatArray::FastDownCast(normals);
  if (floats && unusable == 0)
  {
    this->RunWeighted<OutT>(
      method, computedNormals, ShadingNormals<float>{ floats->GetPointer(0), false });
    return;
  }
  Buffer<dvec3> unitNormals;
  this->RunWeighted<OutT>(
    method, computedNormals, this->UnitNormals(normals, unusable, unitNormals));
}

template<typename OutT, typename NormalT>
void vtkPolyDataTangentFrames::Internals::RunWeighted(TangentMethod method,
  vtkSmartPointer<OutArray<OutT>> computedNormals,
  const ShadingNormals<NormalT>& normals)
{
  vtkPolyDataTangentFrames* self = this->Self;
  const vtkIdType numPoints = this->NumberOfPoints;

  // The input points' frames; WriteOutput adds the split points'.
  OutputFrames<OutArray<OutT>> frames(numPoints, self->ComputeBitangents);
  Buffer<PointKind> kinds(new PointKind[numPoints]);
  // With splitting, each mirror-seam point (a Conflict point) gets one copy, unless the caller
  // keeps its frame; kept points are neither split nor counted.
  std::vector<SplitPoint> splits =
    this->ComputePointFrames(method, normals, frames.Storage(), kinds.get());
  self->NumberOfHandednessConflicts += static_cast<vtkIdType>(splits.size());
  const std::vector<vtkIdType> fallbacks =
    PointsOfKind(kinds.get(), numPoints, PointKind::Fallback);
  const auto kept = [&](vtkIdType p) { return this->KeptPoints && this->KeptPoints[p] != 0; };
  self->NumberOfFallbackPoints += static_cast<vtkIdType>(
    fallbacks.size() - std::count_if(fallbacks.begin(), fallbacks.end(), kept));
  if (!this->Continue(0.7))
  {
    return;
  }
  if (!fallbacks.empty())
  {
    FillFallbacks(this->Tris, this->Signs, normals, kinds.get(), fallbacks, frames.Storage());
  }
  if (!self->Splitting)
  {
    splits.clear();
  }
  if (!this->Continue(0.85))
  {
    return;
  }
  // Freed before the output copies the point data and the connectivity, the kinds' memory can
  // hold those copies.
  kinds.reset();
  this->WriteOutput<OutT>(std::move(splits), frames, computedNormals);
  this->Continue(1.0);
}

vtkIdType vtkPolyDataTangentFrames::RunBlock(const BlockInput& block)
{
  Internals run(block, this);
  if (this->DoubleOutput(block.Input))
  {
    run.Run<double>();
  }
  else
  {
    run.Run<float>();
  }
  return run.NumberOfTriangles;
}

void vtkPolyDataTangentFrames::ComputeBlock(const BlockInput& block)
{
  vtkIdType* const counts[] = { &this->NumberOfDegenerateTriangles,
    &this->NumberOfFallbackPoints,
    &this->NumberOfHandednessConflicts,
    &this->NumberOfSplitPoints };
  const vtkIdType before[] = { *counts[0], *counts[1], *counts[2], *counts[3] };
  std::vector<vtkIdType> mixedCells;
  BlockInput first = block;
  first.MixedCells = this->Splitting ? &mixedCells : nullptr;
  vtkIdType triangles = this->RunBlock(first);
  if (!mixedCells.empty())
  {
    // A corner has one point id, so a cell whose triangles need both sides' frames at a corner
    // is cut into its triangles, each of which can then take its own side's point. The triangles
    // keep their order, so every frame is the one the first run computed.
    for (int i = 0; i < 4; ++i)
    {
      *counts[i] = before[i];
    }
    const vtkSmartPointer<vtkPolyData> cut =
      vtkNormalMapping::detail::CutIntoTriangles(block.Input, mixedCells);
    BlockInput again = block;
    again.Input = cut;
    again.CellNormals = block.CellNormals ? cut->GetCellData()->GetNormals() : nullptr;
    again.ProgressBegin = block.ProgressEnd;
    triangles = this->RunBlock(again);
  }
  const vtkIdType degenerateBefore = before[0];
  if (triangles > 0 && this->NumberOfDegenerateTriangles - degenerateBefore == triangles)
  {
    // Not an error (the output is complete), but no frame came from the texture coordinates.
    vtkWarningMacro("None of the " << triangles
                                   << " triangles has a usable frame (zero area, zero texture-"
                                      "coordinate area, or a height at the rounding noise of "
                                      "coordinates far from the origin for their precision): "
                                      "every point frame computed here is a fallback. Check the "
                                      "texture coordinates, or store the positions in double or "
                                      "nearer the origin.");
  }
}
