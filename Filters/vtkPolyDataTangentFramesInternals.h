// The execution of vtkPolyDataTangentFrames (private header, not installed).
//
// vtkPolyDataTangentFrames.cxx is the pipeline shell (argument and cell-array checks, then
// Internals::Run); Run<float> and Run<double> (the output precision) are instantiated in
// vtkPolyDataTangentFramesRunFloat.cxx and vtkPolyDataTangentFramesRunDouble.cxx, so that the two
// halves of the largest translation unit compile in parallel. Everything here is in namespace
// vtkNormalMapping::frames.
#ifndef vtkPolyDataTangentFramesInternals_h
#define vtkPolyDataTangentFramesInternals_h

#include "vtkPolyDataTangentFrames.h"

#include "vtkMikkTSpaceKernel.h"
#include "vtkNormalMappingHugePages.h"
#include "vtkNormalMappingPrivate.h"
#include "vtkPolyDataTangentFramesMikkTSpace.h"
#include "vtkTangentFrameBatch.h"
#include "vtkTangentFrameKernels.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/*
 * How the work is organized (sums and point frames in double; triangle frames in double, or
 * in float for float points and texture coordinates):
 *
 * 1. Scatter: every triangle of every polygon and strip is visited in cell order; its frame is
 *    computed (in batches, vtkTangentFrameBatch.h, which gives the bits of
 *    vtkNormalMapping::ComputeTriangleFrame or of its float form) and added, weighted, to one
 *    accumulator per corner point, which also records the handednesses its corners have. With
 *    several threads the points are dealt to blocks (four per thread, a power of two) in runs of
 *    consecutive ids (ScanBlocks::Choose); each block computes and adds only the triangles with
 *    a corner in it (a run of triangles with no such corner is skipped, one with only such
 *    corners taken whole), and the threads share out the blocks.
 *    Every point therefore sums its triangles in cell order whatever the number of threads: the
 *    output is bit-identical for any thread count, without a stored point-to-triangle table or
 *    per-triangle frames. Points whose corners have both handednesses (mirror seams) get their
 *    per-handedness sums from a second scan of only the triangles that hold them.
 * 2. Finish: per point, choose or split the handedness, Gram-Schmidt against the normal, write.
 * 3. Only when needed: fallback frames from neighbours (another ordered scan), split points
 *    (cells re-pointed), cell tangents.
 * The accumulators (33 bytes per point; 64 more per seam point) are the only per-point memory
 * besides the outputs.
 */
namespace vtkNormalMapping
{
namespace frames
{
using vtkNormalMapping::detail::ChunkCount;
using vtkNormalMapping::detail::CopyWithAppendedPoints;
using vtkNormalMapping::detail::ExtendPointArray;
using vtkNormalMapping::detail::FrameBatch;
using vtkNormalMapping::detail::ParallelChunks;
using vtkNormalMapping::detail::ParallelFor;
using vtkNormalMapping::detail::WithCellStorage;

/// The sum of count(begin, end) over ranges that cover [0, n), in parallel (ranges of `grain`):
/// the checking passes over whole input arrays, which are memory-bound.
template<typename Count>
vtkIdType ParallelCount(vtkIdType n, vtkIdType grain, const Count& count)
{
  std::vector<vtkIdType> counts(static_cast<size_t>(ChunkCount(n, grain)), 0);
  ParallelChunks(
    n, grain, [&](vtkIdType chunk, vtkIdType b, vtkIdType e) { counts[chunk] = count(b, e); });
  vtkIdType total = 0;
  for (vtkIdType c : counts)
  {
    total += c;
  }
  return total;
}

/// A float or double array read through a raw pointer; any other type is copied to double once.
struct RealArray
{
  vtkSmartPointer<vtkDataArray> Array;
  int Components = 0;

  explicit RealArray(vtkDataArray* array)
    : Array(array)
  {
    if (array && array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE)
    {
      // Held by this->Array: the copy must outlive the constructor.
      auto copy = vtkSmartPointer<vtkDoubleArray>::New();
      copy->DeepCopy(array);
      this->Array = copy;
    }
    this->Components = array ? array->GetNumberOfComponents() : 0;
  }
  bool IsDouble() const { return this->Array->GetDataType() == VTK_DOUBLE; }
  template<typename T>
  const T* Pointer() const
  {
    return static_cast<const T*>(this->Array->GetVoidPointer(0));
  }
};

/// Calls f(const float*) or f(const double*) for a RealArray.
template<typename F>
void WithPointer(const RealArray& a, F&& f)
{
  if (a.IsDouble())
  {
    f(a.Pointer<double>());
  }
  else
  {
    f(a.Pointer<float>());
  }
}

/// Typed views of the inputs the kernels read.
template<typename PT, typename UT, typename NT>
struct MeshView
{
  const PT* Points;
  const UT* UVs;
  int UVComponents;
  const NT* Normals;      // may be null (normals not known yet)
  const double* Fallback; // geometric normals for points whose normal is unusable, or null

  glm::dvec3 Point(vtkIdType p) const
  {
    return glm::dvec3(this->Points[3 * p], this->Points[3 * p + 1], this->Points[3 * p + 2]);
  }
  glm::dvec2 UV(vtkIdType p) const
  {
    const UT* uv = this->UVs + this->UVComponents * p;
    return glm::dvec2(uv[0], this->UVComponents > 1 ? static_cast<double>(uv[1]) : 0.0);
  }
  /// The unit shading normal of a point, or zero when it has none.
  glm::dvec3 Normal(vtkIdType p) const
  {
    const glm::dvec3 n = SafeNormalize(
      glm::dvec3(this->Normals[3 * p], this->Normals[3 * p + 1], this->Normals[3 * p + 2]));
    if (n == glm::dvec3(0.0) && this->Fallback)
    {
      return glm::dvec3(
        this->Fallback[3 * p], this->Fallback[3 * p + 1], this->Fallback[3 * p + 2]);
    }
    return n;
  }
  TriangleFrame Frame(const vtkIdType* tri,
    const DegeneracyTolerance& tol,
    bool withArea = true,
    double* angles = nullptr) const
  {
    return ComputeTriangleFrame(this->Point(tri[0]),
      this->Point(tri[1]),
      this->Point(tri[2]),
      this->UV(tri[0]),
      this->UV(tri[1]),
      this->UV(tri[2]),
      tol,
      withArea,
      angles);
  }
};

/// Calls f(view) with the MeshView of the right types.
template<typename F>
void WithMeshView(const RealArray& points,
  const RealArray& uvs,
  const RealArray& normals,
  const double* fallback,
  F&& f)
{
  WithPointer(points,
    [&](auto* p)
    {
      WithPointer(uvs,
        [&](auto* u)
        {
          using PT = std::remove_const_t<std::remove_pointer_t<decltype(p)>>;
          using UT = std::remove_const_t<std::remove_pointer_t<decltype(u)>>;
          if (!normals.Array)
          {
            f(MeshView<PT, UT, float>{ p, u, uvs.Components, nullptr, fallback });
            return;
          }
          WithPointer(normals,
            [&](auto* n)
            {
              using NT = std::remove_const_t<std::remove_pointer_t<decltype(n)>>;
              f(MeshView<PT, UT, NT>{ p, u, uvs.Components, n, fallback });
            });
        });
    });
}

/// Whether the three ids are in [0, numPoints) (a negative id is huge as unsigned).
inline bool InRange(const vtkIdType* tri, vtkIdType numPoints)
{
  const std::uint64_t largest = std::max({ static_cast<std::uint64_t>(tri[0]),
    static_cast<std::uint64_t>(tri[1]),
    static_cast<std::uint64_t>(tri[2]) });
  return largest < static_cast<std::uint64_t>(numPoints);
}

/// Appends the n triangles of `ids` (three each) to the batch, which has room, if every id is in
/// [0, numPoints); else appends nothing and returns false.
template<typename IdT>
bool TakeTriangles(const IdT* ids, vtkIdType n, vtkIdType numPoints, FrameBatch& b)
{
  // An id is in range when id - numPoints is negative and id is not: the sign bit of
  // (id - numPoints) & ~id, and-ed over all ids (branch-free, so the compiler vectorizes it).
  std::int64_t inRange = -1;
  for (vtkIdType j = 0; j < 3 * n; ++j)
  {
    const std::int64_t id = ids[j];
    inRange &= static_cast<std::int64_t>(
      (static_cast<std::uint64_t>(id) - static_cast<std::uint64_t>(numPoints)) &
      ~static_cast<std::uint64_t>(id));
  }
  if (inRange >= 0)
  {
    return false;
  }
  const int first = b.Size;
  for (vtkIdType t = 0; t < n; ++t)
  {
    b.Ids[0][first + t] = ids[3 * t];
    b.Ids[1][first + t] = ids[3 * t + 1];
    b.Ids[2][first + t] = ids[3 * t + 2];
  }
  b.Size += static_cast<int>(n);
  return true;
}

/// Calls f(cellIndex, triangleIndexInCell, ids[3]) for the triangles of cells [begin, end):
/// polygons fan from corner 0, strip triangle j is (j, j+1, j+2) with every odd one reversed so
/// that all triangles of a strip share its winding. Cells with a point id outside
/// [0, numPoints) are skipped and reported through `bad`.
template<typename IdT, typename F>
void ForEachTriangle(const IdT* offsets,
  const IdT* conn,
  bool strip,
  vtkIdType begin,
  vtkIdType end,
  vtkIdType numPoints,
  bool& bad,
  F&& f)
{
  vtkIdType tri[3];
  for (vtkIdType c = begin; c < end; ++c)
  {
    const IdT* pts = conn + offsets[c];
    const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
    if (n == 3 && !strip)
    {
      // The common case, without the loops below.
      tri[0] = pts[0];
      tri[1] = pts[1];
      tri[2] = pts[2];
      if (!InRange(tri, numPoints))
      {
        bad = true;
        continue;
      }
      f(c, 0, static_cast<const vtkIdType*>(tri));
      continue;
    }
    bool inRange = true;
    for (vtkIdType k = 0; k < n; ++k)
    {
      inRange &= pts[k] >= 0 && static_cast<vtkIdType>(pts[k]) < numPoints;
    }
    if (!inRange)
    {
      bad = true;
      continue;
    }
    for (vtkIdType j = 0; j + 2 < n; ++j)
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
      f(c, j, static_cast<const vtkIdType*>(tri));
    }
  }
}

/// Per point (vtkTangentFrameBatch.h): one weighted tangent sum and weight for both handednesses.
/// A point whose corners all have one handedness (nearly every point) needs nothing else; a point
/// with both (on a mirror seam) gets SideSums in a second scan.
using vtkNormalMapping::detail::PointSum;

using vtkNormalMapping::detail::BothSides;
using vtkNormalMapping::detail::FallbackMark;
using vtkNormalMapping::detail::PlusSide;

/// The sums of one point per handedness (index 0: +1, 1: -1), for points with both.
struct SideSums
{
  double Sum[2][4] = { { 0.0, 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0, 0.0 } };

  glm::dvec3 Tangent(int side) const
  {
    return glm::dvec3(this->Sum[side][0], this->Sum[side][1], this->Sum[side][2]);
  }
  double Weight(int side) const { return this->Sum[side][3]; }
};

/// Triangles per entry of ChunkOwners.
constexpr vtkIdType OwnerChunk = 64;

/**
 * For a connectivity of n triangles (three ids each), per chunk of OwnerChunk consecutive
 * triangles: bit b set when block b owns one of its corners (points are dealt to `blocks`, a power
 * of two, in runs of 2^ownerShift ids, see Execution). One parallel pass, so that with several
 * blocks each reads only the chunks it has a corner in, instead of every block reading every id.
 * Ids are not checked here: an id outside [0, numPoints) still sets some block's bit, and that
 * block's scan finds it.
 */
template<typename IdT>
std::vector<std::uint64_t> ChunkOwners(const IdT* conn,
  vtkIdType n,
  int blocks,
  int ownerShift,
  vtkNormalMapping::detail::BatchCode code)
{
  const vtkIdType chunks = ChunkCount(n, OwnerChunk);
  std::vector<std::uint64_t> owners(static_cast<size_t>(chunks));
  ParallelFor(chunks,
    256,
    [&](vtkIdType c0, vtkIdType c1)
    {
      for (vtkIdType c = c0; c < c1; ++c)
      {
        const IdT* ids = conn + 3 * OwnerChunk * c;
        const vtkIdType count = 3 * std::min(OwnerChunk, n - OwnerChunk * c);
#ifdef VTK_TANGENT_BATCH_AVX2
        if constexpr (sizeof(IdT) == sizeof(std::int64_t))
        {
          if (code == vtkNormalMapping::detail::BatchCode::AVX512)
          {
            owners[c] = vtkNormalMapping::detail::avx512::OwnerBits(
              reinterpret_cast<const std::int64_t*>(ids),
              static_cast<int>(count),
              blocks,
              ownerShift);
            continue;
          }
        }
#endif
        (void)code;
        owners[c] = vtkNormalMapping::detail::ScalarOwnerBits(ids, count, blocks, ownerShift);
      }
    });
  return owners;
}

/// Frees per-point sums: std::free(Raw) when they came from malloc (Raw: the block that holds
/// them), else delete[].
struct PointSumRelease
{
  void* Raw = nullptr;
  void operator()(PointSum* p) const
  {
    if (this->Raw)
    {
      std::free(this->Raw);
      return;
    }
    delete[] p;
  }
};

/**
 * Storage for the per-point sums and, after them, the per-point side bytes (see
 * AllocatePointSums).
 */
struct PointSumStorage
{
  std::unique_ptr<PointSum[], PointSumRelease> Block;
  vtkIdType Count = 0;
  PointSum* Sums() const { return this->Block.get(); }
  /// Count bytes after the sums, not cleared.
  unsigned char* Sides() const
  {
    return reinterpret_cast<unsigned char*>(this->Block.get() + this->Count);
  }
  explicit operator bool() const { return this->Block != nullptr; }
};

/**
 * Storage for `count` PointSums, all zero, followed by `count` side bytes that Finish writes
 * (null if memory is short): one block, which the passes after the scan use together and free
 * together. On Linux, blocks of 8 MiB or more start on a 2 MiB boundary of a malloc block one huge
 * page larger than the whole huge pages they span, advised to use transparent huge pages: pages
 * fresh from the kernel then fault once per 2 MiB instead of once per 4 KiB. Zeroing the 16 MiB of
 * sums of the 1M-triangle torus took 5.7-8 ms on fresh small pages, about 1 ms on fresh huge
 * pages, 0.5 ms on memory the allocator reused. glibc reuses such a block from the second or third
 * execution on (its mmap threshold rises to the freed size); mapping fresh memory every time
 * instead was 3-4% slower per Update. posix_memalign, as for the output arrays
 * (AllocateOnHugePages), does not do here: re-executions then faulted in about 340 pages each and
 * were 12% slower. With the block's end on whole huge pages (HugePageReservation) and the side
 * bytes in it, a first execution on the 1M-triangle torus took 949 page faults instead of 1,405
 * (the sums' last huge page was partly on small pages, and the 0.5 MB of side bytes all) and 5%
 * less time. The output arrays are not rounded so (AllocateOnHugePages): that saved another 940
 * faults, but in an application that frees them into glibc's heap the rounded regions, advised
 * for huge pages, then back later small allocations with whole huge pages (after ten Updates and
 * the filter deleted: 40 MiB of huge pages resident against 18).
 */
inline PointSumStorage AllocatePointSums(vtkIdType count)
{
  const size_t n = static_cast<size_t>(std::max<vtkIdType>(count, 1));
  // The side bytes in whole PointSums after the sums.
  const size_t total = n + (n + sizeof(PointSum) - 1) / sizeof(PointSum);
  PointSumStorage storage;
  storage.Count = static_cast<vtkIdType>(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr size_t huge = vtkNormalMapping::detail::HugePageBytes;
  const size_t bytes = vtkNormalMapping::detail::HugePageReservation(sizeof(PointSum) * total);
  if (bytes >= 4 * huge)
  {
    void* raw = std::malloc(bytes + huge);
    if (!raw)
    {
      return storage;
    }
    const std::uintptr_t aligned = (reinterpret_cast<std::uintptr_t>(raw) + huge - 1) / huge * huge;
    vtkNormalMapping::detail::AdviseHugePages(reinterpret_cast<void*>(aligned), bytes);
    storage.Block = std::unique_ptr<PointSum[], PointSumRelease>(
      reinterpret_cast<PointSum*>(aligned), PointSumRelease{ raw });
  }
#endif
  if (!storage.Block)
  {
    storage.Block.reset(new (std::nothrow) PointSum[total]);
  }
  if (storage.Block)
  {
    PointSum* sums = storage.Sums();
    ParallelFor(static_cast<vtkIdType>(n),
      [&](vtkIdType b, vtkIdType e)
      {
        // All bits zero: 0.0 sums and no marks. memset's wide stores clear it faster than a
        // loop of PointSum copies.
        std::memset(static_cast<void*>(sums + b), 0, sizeof(PointSum) * (e - b));
      });
  }
  return storage;
}

/**
 * On Linux, gives a large output array (2 MiB or more) values that start on a 2 MiB boundary,
 * its whole 2 MiB pages advised to use transparent huge pages, and returns true; else false, and
 * the caller allocates as usual. The array frees them with free(). Memory fresh from the kernel (a
 * first execution, or every execution once glibc maps large blocks anew) then faults in once per
 * 2 MiB instead of once per 4 KiB. On the 1M-triangle torus on fresh memory, writing the frames
 * took 1,890 page faults and 3.7 ms per execution; with this, 960 faults (the 2 MB of signs and
 * the tangents' last 2 MB stay on small pages), and the execution is 10% faster. Memory that the
 * allocator reuses is unaffected (the same time, and no page fault per re-execution).
 */
template<typename ArrayT>
bool AllocateOnHugePages(ArrayT* array, vtkIdType tuples)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  using T = typename ArrayT::ValueType;
  constexpr size_t huge = vtkNormalMapping::detail::HugePageBytes;
  const vtkIdType values = tuples * array->GetNumberOfComponents();
  const size_t bytes = sizeof(T) * static_cast<size_t>(values);
  void* p = nullptr;
  if (tuples <= 0 || bytes < huge || posix_memalign(&p, huge, bytes) != 0)
  {
    return false;
  }
  vtkNormalMapping::detail::AdviseHugePages(p, bytes);
  array->SetArray(static_cast<T*>(p), values, 0, ArrayT::VTK_DATA_ARRAY_FREE);
  return true;
#else
  (void)array;
  (void)tuples;
  return false;
#endif
}

/**
 * For an output array of `bytes` at `data` that the finish then writes whole: when its memory is
 * fresh from the kernel (IsFreshMemory: a first execution), faults in its parts that are not on
 * whole huge pages (AllocateOnHugePages: an array under 2 MiB, the ends of a larger one) with
 * MADV_POPULATE_WRITE, in parallel chunks of 256 KiB, instead of one page fault per 4 KiB page
 * when the finish writes it. The whole huge pages are left to fault when written, once per 2 MiB:
 * the page the kernel has just zeroed is then still in cache. On the 1M-triangle torus (its 2 MB of
 * float signs and the last 1.7 MB of its tangents: 926 of the 949 page faults of a first execution
 * go), new library against old alternated in one process, on fresh memory: 0.937-0.965 of the
 * time per Update on one thread, 0.970-0.99 on two, 4M triangles 0.965, 100K 0.987. On memory
 * the allocator reused nothing is populated: 0.99-1.012, about the spread that rebuilding alone
 * gives (the residency check is two mincore calls of 0.7 us; ten times as many cost 0.3%).
 * Populating the whole arrays in 2 MiB chunks: 0.945 on one thread but 1.02 on two, as was the
 * small-page part in one call instead of parallel chunks (1.02).
 */
inline void PrefaultOutput(void* data, size_t bytes)
{
  if (!vtkNormalMapping::detail::IsFreshMemory(data, bytes))
  {
    return;
  }
  constexpr std::uintptr_t huge = vtkNormalMapping::detail::HugePageBytes;
  const std::uintptr_t b = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t e = b + bytes;
  // The whole huge pages AllocateOnHugePages advised (none under 2 MiB): [hugeBegin, hugeEnd).
  std::uintptr_t hugeBegin = (b + huge - 1) & ~(huge - 1);
  std::uintptr_t hugeEnd = e & ~(huge - 1);
  if (bytes < huge || hugeEnd <= hugeBegin)
  {
    hugeBegin = hugeEnd = e;
  }
  const auto populate = [](std::uintptr_t from, std::uintptr_t to)
  {
    // Chunks of whole pages, so that no page is cut between two of them and left out of both.
    constexpr std::uintptr_t page = vtkNormalMapping::detail::SmallPageBytes;
    from = std::min(to, (from + page - 1) & ~(page - 1));
    ParallelChunks(static_cast<vtkIdType>(to - from),
      vtkIdType{ 1 } << 18,
      [&](vtkIdType, vtkIdType begin, vtkIdType end)
      {
        vtkNormalMapping::detail::PopulateForWriting(
          reinterpret_cast<void*>(from + static_cast<std::uintptr_t>(begin)),
          static_cast<size_t>(end - begin));
      });
  };
  populate(b, hugeBegin);
  populate(hugeEnd, e);
}

/// Everything the passes of one execution share.
struct Execution
{
  vtkPolyDataTangentFrames* Filter = nullptr;
  TangentMethod Method = TangentMethod::AngleWeighted;
  bool Splitting = true;
  vtkIdType NumberOfPoints = 0;
  vtkCellArray* Cells[2] = { nullptr, nullptr }; // polygons, strips
  DegeneracyTolerance Tolerance;
  int Blocks = 1;
  /// Every polygon is a triangle (the common case): scans may read the connectivity as triples.
  bool TrianglesOnly = false;
  bool BadIds = false;
  /// The batch code for triangle frames (see vtkTangentFrameBatch.h); Vector: AVX2 or better,
  /// for the scatter and the point frames.
  vtkNormalMapping::detail::BatchCode Code = vtkNormalMapping::detail::BatchCode::Scalar;
  bool Vector = false;

  /// Points are dealt to the blocks in runs of 2^OwnerShift consecutive ids, round robin (see
  /// ScanBlocks::Choose): every batch of cells (CellBatch, about two runs per block) has work for
  /// every block, since meshes number their points and cells with the same locality.
  int OwnerShift = vtkNormalMapping::detail::ScanBlocks::MaxShift;
  /// Cells scanned between two synchronizations of the blocks (and progress reports).
  vtkIdType CellBatch() const
  {
    return std::max<vtkIdType>(
      1 << 16, static_cast<vtkIdType>(this->Blocks) << (this->OwnerShift + 1));
  }
  /// Blocks is a power of two, so that this is a mask and not a division (it runs several times
  /// per triangle).
  bool Owns(int block, vtkIdType p) const
  {
    return static_cast<int>((p >> this->OwnerShift) & (this->Blocks - 1)) == block;
  }

  /**
   * Visits every triangle in cell order, in parallel over point blocks: f(block, cell index,
   * triangle index in cell, ids, cellsAreStrips) runs for each block on the triangles that
   * have a corner in that block (the caller checks which corners with Owns). Progress goes
   * from p0 to p1; false when aborted.
   */
  template<typename F>
  bool OrderedScan(double p0, double p1, const F& f)
  {
    return this->OrderedScan(p0, p1, f, nullptr);
  }

  /**
   * OrderedScan, but when every polygon is a triangle, each block's part of the polygons goes to
   * runs(block, conn, begin, end, owners) instead (owners: ChunkOwners of the connectivity with
   * several blocks, else null), which visits triangles [begin, end) from the
   * connectivity `conn` (three ids each) itself and returns whether one has an id out of range
   * (it must skip those, as ForEachTriangle does).
   */
  template<typename F, typename R>
  bool OrderedScan(double p0, double p1, const F& f, const R& runs)
  {
    const vtkIdType total = this->Cells[0]->GetNumberOfCells() + this->Cells[1]->GetNumberOfCells();
    vtkIdType done = 0;
    std::vector<char> bad(this->Blocks, 0);
    for (int kind = 0; kind < 2; ++kind)
    {
      vtkCellArray* cells = this->Cells[kind];
      const vtkIdType numCells = cells->GetNumberOfCells();
      bool aborted = false;
      WithCellStorage(cells,
        [&](const auto* offsets, const auto* conn)
        {
          std::vector<std::uint64_t> owners;
          if constexpr (!std::is_same<R, std::nullptr_t>::value)
          {
            if (kind == 0 && this->TrianglesOnly && this->Blocks > 1)
            {
              owners = ChunkOwners(conn, numCells, this->Blocks, this->OwnerShift, this->Code);
            }
          }
          const std::uint64_t* chunkOwners = owners.empty() ? nullptr : owners.data();
          const vtkIdType cellBatch = this->CellBatch();
          for (vtkIdType begin = 0; begin < numCells && !aborted; begin += cellBatch)
          {
            if (this->Filter->GetAbortExecute())
            {
              aborted = true;
              return;
            }
            const vtkIdType end = std::min(numCells, begin + cellBatch);
            ParallelFor(this->Blocks,
              1,
              [&](vtkIdType b0, vtkIdType b1)
              {
                for (vtkIdType b = b0; b < b1; ++b)
                {
                  const int block = static_cast<int>(b);
                  bool badIds = false;
                  if constexpr (!std::is_same<R, std::nullptr_t>::value)
                  {
                    if (kind == 0 && this->TrianglesOnly)
                    {
                      bad[b] |= runs(block, conn, begin, end, chunkOwners) ? 1 : 0;
                      continue;
                    }
                  }
                  ForEachTriangle(offsets,
                    conn,
                    kind == 1,
                    begin,
                    end,
                    this->NumberOfPoints,
                    badIds,
                    [&](vtkIdType c, vtkIdType j, const vtkIdType* tri)
                    {
                      if (this->Owns(block, tri[0]) || this->Owns(block, tri[1]) ||
                        this->Owns(block, tri[2]))
                      {
                        f(block, c, j, tri, kind == 1);
                      }
                    });
                  bad[b] |= badIds ? 1 : 0;
                }
              });
            done += end - begin;
            this->Filter->UpdateProgress(p0 + (p1 - p0) * static_cast<double>(done) / total);
          }
        });
      if (aborted)
      {
        return false;
      }
    }
    this->BadIds |= std::any_of(bad.begin(), bad.end(), [](char c) { return c != 0; });
    return !this->Filter->GetAbortExecute();
  }
};

/// Smooth, area-weighted point normals: the triangles' geometric normals, or the input cell
/// normals with the same weights. Writes unit normals (points with no area get `empty`).
template<typename View>
bool ComputePointNormals(Execution& ex,
  const View& view,
  vtkDataArray* cellNormals,
  vtkIdType firstSurfaceCell,
  const glm::dvec3& empty,
  double* out,
  double p0,
  double p1)
{
  std::fill(out, out + 3 * ex.NumberOfPoints, 0.0);
  const vtkIdType numPolys = ex.Cells[0]->GetNumberOfCells();
  const bool done = ex.OrderedScan(p0,
    p1,
    [&](int block, vtkIdType c, vtkIdType, const vtkIdType* tri, bool strip)
    {
      const TriangleFrame f = view.Frame(tri, ex.Tolerance);
      glm::dvec3 n = f.Area * SafeNormalize(f.Normal);
      if (cellNormals)
      {
        double cn[3];
        cellNormals->GetTuple(firstSurfaceCell + c + (strip ? numPolys : 0), cn);
        n = f.Area * SafeNormalize(glm::dvec3(cn[0], cn[1], cn[2]));
      }
      for (int k = 0; k < 3; ++k)
      {
        if (ex.Owns(block, tri[k]))
        {
          for (int d = 0; d < 3; ++d)
          {
            out[3 * tri[k] + d] += n[d];
          }
        }
      }
    });
  ParallelFor(ex.NumberOfPoints,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType p = b; p < e; ++p)
      {
        glm::dvec3 n = SafeNormalize(glm::dvec3(out[3 * p], out[3 * p + 1], out[3 * p + 2]));
        n = n == glm::dvec3(0.0) ? empty : n;
        for (int d = 0; d < 3; ++d)
        {
          out[3 * p + d] = n[d];
        }
      }
    });
  return done;
}

/**
 * Visits the triangles, in cell order per block (Execution::OrderedScan), that `accept(block,
 * tri)` takes (every one with an owned corner when `everyTriangle`: then accept is not called);
 * computes their frames in batches (vtkTangentFrameBatch.h) and hands each computed batch to
 * consume(block, batch), in cell order. Counts the triangles without a frame (each once, by the
 * block owning its first corner). The frames, and so the sums, are the same bits in every scan.
 * `sums`, when given, is the per-point array consume() adds to: its entries for a batch are
 * prefetched while the batch's frames are computed.
 */
template<typename View, typename Accept, typename Consume>
bool ScanFrames(Execution& ex,
  const View& view,
  double p0,
  double p1,
  bool everyTriangle,
  const Accept& accept,
  const Consume& consume,
  const PointSum* sums,
  vtkIdType& degenerate)
{
  using namespace vtkNormalMapping::detail;
  std::vector<vtkIdType> degenerateByBlock(ex.Blocks, 0);
  std::vector<FrameBatch> batches(ex.Blocks);
  using PT = std::remove_const_t<std::remove_pointer_t<decltype(view.Points)>>;
  using UT = std::remove_const_t<std::remove_pointer_t<decltype(view.UVs)>>;
  using NT = std::remove_const_t<std::remove_pointer_t<decltype(view.Normals)>>;
  const BatchInput<PT, UT, NT> input{ view.Points,
    view.UVs,
    view.UVComponents,
    view.Normals,
    view.Fallback,
    ex.Tolerance,
    ex.Method == TangentMethod::AngleWeighted
      ? BatchWeights::Angle
      : (ex.Method == TangentMethod::AreaWeighted ? BatchWeights::Area : BatchWeights::One),
    ex.NumberOfPoints,
    sums };
  const auto code = ex.Code;
  const auto flush = [&](int block)
  {
    FrameBatch& b = batches[block];
    ComputeBatch(input, b, code);
    // Counted in a local: the blocks' counters share a cache line, and adding to them per
    // triangle made the threads fight over it (two threads were no faster than one).
    vtkIdType degenerateHere = 0;
    for (std::uint64_t unframed = b.UnframedTriangles(); unframed != 0; unframed &= unframed - 1)
    {
      degenerateHere += ex.Owns(block, b.Ids[0][LowestBit64(unframed)]) ? 1 : 0;
    }
    degenerateByBlock[block] += degenerateHere;
    consume(block, b);
    b.Size = 0;
    b.Shared = false;
  };
  const auto visit = [&](int block, vtkIdType, vtkIdType, const vtkIdType* tri, bool)
  {
    if (!accept(block, tri))
    {
      return;
    }
    FrameBatch& b = batches[block];
    b.Add(tri);
    b.Shared = b.Shared || ex.Blocks > 1;
    if (b.Full())
    {
      flush(block);
    }
  };
  // Whole runs of triangles into the batch, with AVX-512 or AVX2 when the ids are 64-bit.
  const auto takeRun = [&](FrameBatch& b, const auto* ids, vtkIdType n)
  {
#ifdef VTK_TANGENT_BATCH_AVX2
    using IdT = std::remove_const_t<std::remove_pointer_t<decltype(ids)>>;
    if constexpr (sizeof(IdT) == sizeof(std::int64_t))
    {
      const auto* ids64 = reinterpret_cast<const std::int64_t*>(ids);
      if (ex.Code == vtkNormalMapping::detail::BatchCode::AVX512)
      {
        return vtkNormalMapping::detail::avx512::TakeTriangles(
          ids64, static_cast<int>(n), ex.NumberOfPoints, b);
      }
      if (ex.Code == vtkNormalMapping::detail::BatchCode::AVX2)
      {
        return vtkNormalMapping::detail::avx2::TakeTriangles(
          ids64, static_cast<int>(n), ex.NumberOfPoints, b);
      }
    }
#endif
    return TakeTriangles(ids, n, ex.NumberOfPoints, b);
  };
  // Polygons that are all triangles, when every triangle is wanted: whole runs of ids into the
  // batch. With one block every triangle is its; with several (`owners`, see ChunkOwners), chunks
  // the block owns no corner of are skipped unread, chunks it owns every corner of are taken
  // whole, and the rest triangle by triangle.
  const auto runs =
    [&](int block, const auto* conn, vtkIdType begin, vtkIdType end, const std::uint64_t* owners)
  {
    FrameBatch& b = batches[block];
    const std::uint64_t mine = std::uint64_t{ 1 } << block;
    bool bad = false;
    for (vtkIdType c = begin; c < end;)
    {
      const vtkIdType chunkEnd = owners ? std::min(end, (c / OwnerChunk + 1) * OwnerChunk) : end;
      const std::uint64_t chunkOwners = owners ? owners[c / OwnerChunk] : mine;
      if ((chunkOwners & mine) == 0)
      {
        c = chunkEnd; // no corner here, and so no bad id either (every id has an owner)
        continue;
      }
      const vtkIdType n = std::min<vtkIdType>(FrameBatch::Capacity - b.Size, chunkEnd - c);
      const auto* ids = conn + 3 * c;
#if defined(__GNUC__) || defined(__clang__)
      // The connectivity is read once, run by run with a batch's work in between, which is too
      // slow a stream for the hardware prefetcher to run ahead of: fetch the runs two ahead.
      const auto* ahead = ids + 2 * 3 * FrameBatch::Capacity;
      for (vtkIdType j = 0; j < 3 * n && ahead + j < conn + 3 * end; j += 64 / sizeof(*ids))
      {
        __builtin_prefetch(ahead + j);
      }
#endif
      if (chunkOwners != mine || !takeRun(b, ids, n))
      {
        for (vtkIdType t = 0; t < n; ++t)
        {
          const vtkIdType tri[3] = { ids[3 * t], ids[3 * t + 1], ids[3 * t + 2] };
          if (!InRange(tri, ex.NumberOfPoints))
          {
            bad = true;
            continue;
          }
          const bool owned[3] = {
            ex.Owns(block, tri[0]), ex.Owns(block, tri[1]), ex.Owns(block, tri[2])
          };
          if (owned[0] || owned[1] || owned[2])
          {
            b.Add(tri);
            b.Shared = b.Shared || !(owned[0] && owned[1] && owned[2]);
          }
        }
      }
      c += n;
      if (b.Full())
      {
        flush(block);
      }
    }
    return bad;
  };
  bool done = everyTriangle ? ex.OrderedScan(p0, p1, visit, runs) : ex.OrderedScan(p0, p1, visit);
  if (done)
  {
    ParallelFor(ex.Blocks,
      1,
      [&](vtkIdType b0, vtkIdType b1)
      {
        for (vtkIdType block = b0; block < b1; ++block)
        {
          flush(static_cast<int>(block));
        }
      });
  }
  degenerate = 0;
  for (vtkIdType d : degenerateByBlock)
  {
    degenerate += d;
  }
  return done;
}

/// The weighted sums of every point and the marks of its corners' handednesses (the scatter).
template<typename View>
bool Scatter(Execution& ex, const View& view, PointSum* sums, vtkIdType& degenerate)
{
  return ScanFrames(
    ex,
    view,
    0.05,
    0.70,
    true,
    [](int, const vtkIdType*) { return true; },
    [&](int block, const vtkNormalMapping::detail::FrameBatch& b)
    {
      const vtkNormalMapping::detail::ScatterTarget target{ sums, ex.Blocks, block, ex.OwnerShift };
      vtkNormalMapping::detail::ScatterBatch(b, target, ex.Vector);
    },
    sums,
    degenerate);
}

/// The per-handedness sums of the points with both handednesses (sorted ids), by a second scan
/// of the triangles that hold one of them.
template<typename View>
bool SumSides(Execution& ex,
  const View& view,
  const unsigned char* sides,
  const std::vector<vtkIdType>& conflicted,
  std::vector<SideSums>& out)
{
  out.assign(conflicted.size(), SideSums());
  vtkIdType ignored = 0;
  return ScanFrames(
    ex,
    view,
    0.70,
    0.75,
    false,
    [&](int block, const vtkIdType* tri)
    {
      for (int k = 0; k < 3; ++k)
      {
        if (sides[tri[k]] == BothSides && ex.Owns(block, tri[k]))
        {
          return true;
        }
      }
      return false;
    },
    [&](int block, const vtkNormalMapping::detail::FrameBatch& b)
    {
      for (std::uint64_t framed = b.FramedTriangles(); framed != 0; framed &= framed - 1)
      {
        const int i = vtkNormalMapping::detail::LowestBit64(framed);
        for (int k = 0; k < 3; ++k)
        {
          const vtkIdType p = b.Ids[k][i];
          if (sides[p] != BothSides || !ex.Owns(block, p))
          {
            continue;
          }
          const auto it = std::lower_bound(conflicted.begin(), conflicted.end(), p);
          double* sum = out[it - conflicted.begin()].Sum[b.Side(k, i)];
          const double w = b.Weight[k][i];
          sum[0] += w * b.Tangent[0][i];
          sum[1] += w * b.Tangent[1][i];
          sum[2] += w * b.Tangent[2][i];
          sum[3] += w;
        }
      }
    },
    nullptr,
    ignored);
}

/// A point on a mirror seam: its normal, and the frame of its mirrored (-1) side, which goes
/// to the point's copy when splitting.
struct SplitPoint
{
  vtkIdType Id;
  glm::dvec3 Normal;
  glm::dvec3 Tangent;
};

template<typename OutT>
inline void WriteFrame(vtkIdType p,
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

/// Per point, its handedness byte from its sum's marks into `sides` (PlusSide, MinusSide,
/// BothSides, or FallbackMark when none). One handedness: Gram-Schmidt, write. None: listed in
/// `fallbacks`; both: listed for FinishConflicts. Runs of points go through the lane code
/// (vtkTangentFrameLanes.h), which gives the bits of the scalar code below.
template<typename View, typename OutT>
void Finish(Execution& ex,
  const View& view,
  const PointSum* sums,
  unsigned char* sides,
  OutT* tOut,
  OutT* sOut,
  OutT* bOut,
  std::vector<vtkIdType>& conflicted,
  std::vector<vtkIdType>& fallbacks)
{
  using vtkNormalMapping::detail::BatchCode;
  // Each range lists its fallback and conflicted points in ascending order, and hands a list
  // that is not empty over under a lock, with the range's first id; joined in the order of those
  // ids, the lists are ascending whatever the split. (Not vtkSMPThreadLocal, whose construction
  // costs a read of /sys, see ParallelChunks; nor fixed chunks, which made the finish of the 1M
  // torus 4% slower than the ranges vtkSMPTools chooses.)
  using Run = std::pair<vtkIdType, std::vector<vtkIdType>>;
  std::vector<Run> conflictRuns, fallbackRuns;
  std::mutex runsMutex;
  ParallelFor(ex.NumberOfPoints,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<vtkIdType> conflictHere, fallbackHere;
      const auto point = [&](vtkIdType p)
      {
        const unsigned char has = sums[p].Sides();
        sides[p] = has == 0 ? FallbackMark : has;
        if (has == 0)
        {
          fallbackHere.push_back(p);
          return;
        }
        if (has == BothSides)
        {
          conflictHere.push_back(p);
          return;
        }
        const glm::dvec3 n = view.Normal(p);
        WriteFrame(p,
          n,
          PerpendicularTangent(n, sums[p].Tangent()),
          has == PlusSide ? 1.0 : -1.0,
          tOut,
          sOut,
          bOut);
      };
      vtkIdType p = begin;
#ifdef VTK_TANGENT_BATCH_AVX2
      const auto lanes = [&](int count, auto finish)
      {
        for (; p + count <= end; p += count)
        {
          for (unsigned rest =
                 finish(view.Normals, ex.NumberOfPoints, sums, sides, p, tOut, sOut, bOut);
               rest != 0;
               rest &= rest - 1)
          {
            point(p + vtkNormalMapping::detail::LowestBit(rest));
          }
        }
      };
      using NT = std::remove_const_t<std::remove_pointer_t<decltype(view.Normals)>>;
      if (ex.Code == BatchCode::AVX512)
      {
        lanes(8, vtkNormalMapping::detail::avx512::FinishLanes<NT, OutT>);
      }
      else if (ex.Code == BatchCode::AVX2)
      {
        lanes(4, vtkNormalMapping::detail::avx2::FinishLanes<NT, OutT>);
      }
#endif
      for (; p < end; ++p)
      {
        point(p);
      }
      if (!conflictHere.empty() || !fallbackHere.empty())
      {
        std::lock_guard<std::mutex> lock(runsMutex);
        if (!conflictHere.empty())
        {
          conflictRuns.emplace_back(begin, std::move(conflictHere));
        }
        if (!fallbackHere.empty())
        {
          fallbackRuns.emplace_back(begin, std::move(fallbackHere));
        }
      }
    });
  const auto join = [](std::vector<Run>& runs)
  {
    std::sort(
      runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.first < b.first; });
    std::vector<vtkIdType> all;
    for (const Run& run : runs)
    {
      all.insert(all.end(), run.second.begin(), run.second.end());
    }
    return all;
  };
  conflicted = join(conflictRuns);
  fallbacks = join(fallbackRuns);
}

/// Points with both handednesses: the frame of the side with the larger weight, or with
/// splitting the +1 frame here and the -1 frame listed for the point's copy.
template<typename View, typename OutT>
void FinishConflicts(const Execution& ex,
  const View& view,
  const std::vector<vtkIdType>& conflicted,
  const std::vector<SideSums>& sums,
  OutT* tOut,
  OutT* sOut,
  OutT* bOut,
  std::vector<SplitPoint>& splits)
{
  splits.clear();
  for (size_t i = 0; i < conflicted.size(); ++i)
  {
    const vtkIdType p = conflicted[i];
    const SideSums& a = sums[i];
    const glm::dvec3 n = view.Normal(p);
    int side = a.Weight(1) > a.Weight(0) ? 1 : 0;
    if (ex.Splitting)
    {
      side = 0;
      splits.push_back({ p, n, PerpendicularTangent(n, a.Tangent(1)) });
    }
    const glm::dvec3 t = PerpendicularTangent(n, a.Tangent(side));
    WriteFrame(p, n, t, side == 0 ? 1.0 : -1.0, tOut, sOut, bOut);
  }
}

/// Points with no usable triangle: the mean of their non-fallback neighbours' tangents on their
/// own tangent plane and their neighbours' majority sign; the fixed rule where that fails.
template<typename View, typename OutT>
bool FillFallbacks(Execution& ex,
  const View& view,
  PointSum* acc,
  const unsigned char* sides,
  const std::vector<vtkIdType>& fallbacks,
  OutT* tOut,
  OutT* sOut,
  OutT* bOut)
{
  // Reuse the fallback points' sums: Sum adds the neighbours' tangents, Marks counts their signs
  // (+1 / -1). Only fallback points are written; others are only read.
  for (vtkIdType p : fallbacks)
  {
    acc[p] = PointSum{};
  }
  const bool done = ex.OrderedScan(0.80,
    0.85,
    [&](int block, vtkIdType, vtkIdType, const vtkIdType* tri, bool)
    {
      for (int k = 0; k < 3; ++k)
      {
        const vtkIdType p = tri[k];
        if (!ex.Owns(block, p) || sides[p] != FallbackMark)
        {
          continue;
        }
        for (int m = 0; m < 3; ++m)
        {
          const vtkIdType q = tri[m];
          if (q != p && sides[q] != FallbackMark)
          {
            double* sum = acc[p].Sum;
            for (int d = 0; d < 3; ++d)
            {
              sum[d] += tOut[3 * q + d];
            }
            acc[p].Marks += sOut[q] < 0 ? -1 : 1;
          }
        }
      }
    });
  ParallelFor(static_cast<vtkIdType>(fallbacks.size()),
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType i = b; i < e; ++i)
      {
        const vtkIdType p = fallbacks[i];
        const glm::dvec3 n = view.Normals ? view.Normal(p) : glm::dvec3(0.0);
        const glm::dvec3 t = PerpendicularTangent(n, acc[p].Tangent());
        WriteFrame(p, n, t, acc[p].Marks < 0 ? -1.0 : 1.0, tOut, sOut, bOut);
      }
    });
  return done;
}

/// Re-points the corners on the mirrored side of split points to the points' copies. A corner's
/// side is the majority handedness of the cell's triangles that hold it.
template<typename View, typename IdT>
void RepointCells(const Execution& ex,
  const View& view,
  const std::vector<SplitPoint>& splits,
  IdT* offsets,
  IdT* conn,
  vtkIdType numCells,
  bool strip)
{
  const vtkIdType firstNew = ex.NumberOfPoints;
  ParallelFor(numCells,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<TriangleFrame> frames;
      for (vtkIdType c = begin; c < end; ++c)
      {
        IdT* pts = conn + offsets[c];
        const vtkIdType n = static_cast<vtkIdType>(offsets[c + 1] - offsets[c]);
        frames.clear();
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
          if (frames.empty())
          {
            // The frames of this cell's triangles (the same as in the scatter).
            bool bad = false;
            ForEachTriangle(offsets,
              conn,
              strip,
              c,
              c + 1,
              ex.NumberOfPoints,
              bad,
              [&](vtkIdType, vtkIdType, const vtkIdType* tri)
              { frames.push_back(view.Frame(tri, ex.Tolerance)); });
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
            vote += frames[j].Orientation == 0 ? 0 : CornerSign(frames[j], it->Normal);
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
template<typename View, typename OutT>
void ComputeCellTangentArray(const Execution& ex,
  const View& view,
  vtkIdType firstSurfaceCell,
  OutT* out,
  vtkIdType numCells)
{
  std::fill(out, out + 3 * numCells, OutT(0));
  for (int kind = 0; kind < 2; ++kind)
  {
    vtkCellArray* cells = ex.Cells[kind];
    const vtkIdType first = firstSurfaceCell + (kind == 1 ? ex.Cells[0]->GetNumberOfCells() : 0);
    WithCellStorage(cells,
      [&](const auto* offsets, const auto* conn)
      {
        ParallelFor(cells->GetNumberOfCells(),
          [&](vtkIdType begin, vtkIdType end)
          {
            for (vtkIdType c = begin; c < end; ++c)
            {
              glm::dvec3 t(0.0), n(0.0);
              bool bad = false;
              ForEachTriangle(offsets,
                conn,
                kind == 1,
                c,
                c + 1,
                ex.NumberOfPoints,
                bad,
                [&](vtkIdType, vtkIdType, const vtkIdType* tri)
                {
                  const TriangleFrame f = view.Frame(tri, ex.Tolerance);
                  t += f.Area * f.Tangent;
                  n += f.Area * SafeNormalize(f.Normal);
                });
              n = SafeNormalize(n);
              const glm::dvec3 unit = PerpendicularTangent(n, t);
              for (int k = 0; k < 3; ++k)
              {
                out[3 * (first + c) + k] = static_cast<OutT>(unit[k]);
              }
            }
          });
      });
  }
}

/// What a cell array holds: how many cells have fewer than 3 points, and whether every cell has
/// exactly 3.
struct CellSizes
{
  vtkIdType Short = 0;
  bool TrianglesOnly = true;
};

} // namespace frames
} // namespace vtkNormalMapping

struct vtkPolyDataTangentFrames::Internals
{
  template<typename OutT>
  static int Run(vtkPolyDataTangentFrames* self,
    vtkPolyData* input,
    vtkPolyData* output,
    vtkDataArray* uvs,
    vtkDataArray* normals,
    vtkDataArray* cellNormals,
    const vtkNormalMapping::frames::CellSizes polygonAndStripSizes[2]);
};

template<typename OutT>
int vtkPolyDataTangentFrames::Internals::Run(vtkPolyDataTangentFrames* self,
  vtkPolyData* input,
  vtkPolyData* output,
  vtkDataArray* uvs,
  vtkDataArray* normals,
  vtkDataArray* cellNormals,
  const vtkNormalMapping::frames::CellSizes polygonAndStripSizes[2])
{
  using namespace vtkNormalMapping;
  using namespace vtkNormalMapping::frames;
  // The concrete vtkFloatArray / vtkDoubleArray, so that users' SafeDownCasts work.
  using OutArray = typename std::
    conditional<std::is_same<OutT, float>::value, vtkFloatArray, vtkDoubleArray>::type;
  Execution ex;
  ex.Filter = self;
  ex.Method = static_cast<TangentMethod>(self->Method);
  ex.Splitting = self->Splitting;
  ex.Code = vtkNormalMapping::detail::BestBatchCode();
  ex.Vector = ex.Code >= vtkNormalMapping::detail::BatchCode::AVX2;
  ex.NumberOfPoints = input->GetNumberOfPoints();
  ex.Cells[0] = input->GetPolys();
  ex.Cells[1] = input->GetStrips();
  const vtkNormalMapping::detail::ScanBlocks blocks = vtkNormalMapping::detail::ScanBlocks::Choose(
    ex.NumberOfPoints, vtkNormalMapping::detail::UsableThreads());
  ex.Blocks = blocks.Blocks;
  ex.OwnerShift = blocks.OwnerShift;
  const vtkIdType numPoints = ex.NumberOfPoints;
  const auto epsilon = [](vtkDataArray* a)
  { return a->GetDataType() == VTK_DOUBLE ? DBL_EPSILON : static_cast<double>(FLT_EPSILON); };
  ex.Tolerance =
    DegeneracyTolerance::ForEpsilons(epsilon(input->GetPoints()->GetData()), epsilon(uvs));
  const auto aborted = [&]()
  {
    output->Initialize();
    return 1;
  };
  const auto badIds = [&]()
  {
    vtkErrorWithObjectMacro(self,
      "Cannot compute tangent frames: a polygon or strip refers to a "
      "point id outside [0, "
        << numPoints << "); passing the input through.");
    output->ShallowCopy(input);
    return 1;
  };
  ex.TrianglesOnly = polygonAndStripSizes[0].TrianglesOnly;
  const vtkIdType shortCells = polygonAndStripSizes[0].Short + polygonAndStripSizes[1].Short;
  if (shortCells > 0)
  {
    vtkWarningWithObjectMacro(self,
      << shortCells
      << " polygon or strip cells have fewer than 3 points; they "
         "pass through and give no frames.");
  }

  const RealArray points(input->GetPoints()->GetData());
  const RealArray uv(uvs);
  RealArray normal(normals);
  const vtkIdType firstSurfaceCell = input->GetNumberOfVerts() + input->GetNumberOfLines();

  // 1. Normals: computed when the input has none; geometric stand-ins where they are unusable.
  vtkSmartPointer<OutArray> computedNormals;
  std::vector<double> geometric;
  if (!normals)
  {
    geometric.resize(3 * numPoints);
    bool done = true;
    WithMeshView(points,
      uv,
      normal,
      nullptr,
      [&](const auto& view)
      {
        done = ComputePointNormals(ex,
          view,
          cellNormals,
          firstSurfaceCell,
          glm::dvec3(0, 0, 1),
          geometric.data(),
          0.0,
          0.05);
      });
    if (!done)
    {
      return aborted();
    }
    if (ex.BadIds)
    {
      return badIds();
    }
    computedNormals = vtkSmartPointer<OutArray>::New();
    computedNormals->SetName("Normals");
    computedNormals->SetNumberOfComponents(3);
    computedNormals->SetNumberOfTuples(numPoints);
    std::copy(geometric.begin(), geometric.end(), computedNormals->GetPointer(0));
    geometric.clear();
    normal = RealArray(computedNormals);
  }
  else
  {
    vtkIdType invalid = 0;
    WithPointer(normal,
      [&](const auto* n)
      {
        using NT = std::remove_const_t<std::remove_pointer_t<decltype(n)>>;
#ifdef VTK_TANGENT_BATCH_AVX2
        if constexpr (std::is_same<NT, float>::value)
        {
          using vtkNormalMapping::detail::BatchCode;
          if (ex.Code != BatchCode::Scalar)
          {
            invalid = ParallelCount(numPoints,
              1 << 16,
              [&](vtkIdType b, vtkIdType e)
              {
                return ex.Code == BatchCode::AVX512
                  ? vtkNormalMapping::detail::avx512::CountUnusableNormals(n + 3 * b, e - b)
                  : vtkNormalMapping::detail::avx2::CountUnusableNormals(n + 3 * b, e - b);
              });
            return;
          }
        }
#endif
        invalid = ParallelCount(numPoints,
          1 << 16,
          [&](vtkIdType b, vtkIdType e)
          {
            vtkIdType count = 0;
            for (vtkIdType p = b; p < e; ++p)
            {
              count += IsUsableNormal(glm::dvec3(n[3 * p], n[3 * p + 1], n[3 * p + 2])) ? 0 : 1;
            }
            return count;
          });
      });
    self->NumberOfInvalidNormals = invalid;
    if (invalid > 0)
    {
      geometric.resize(3 * numPoints);
      bool done = true;
      WithMeshView(points,
        uv,
        RealArray(nullptr),
        nullptr,
        [&](const auto& view)
        {
          done = ComputePointNormals(
            ex, view, nullptr, firstSurfaceCell, glm::dvec3(0.0), geometric.data(), 0.0, 0.05);
        });
      if (!done)
      {
        return aborted();
      }
    }
  }

  if (self->Method == MIKKTSPACE)
  {
    vtkNormalMapping::detail::MikkTSpaceRequest request;
    request.Filter = self;
    request.Input = input;
    request.TCoords = uvs;
    request.Normals = computedNormals ? computedNormals.Get() : normals;
    request.ComputedNormals = computedNormals != nullptr;
    request.DoublePrecision = std::is_same<OutT, double>::value;
    request.GLTFSign = self->GLTFSignConvention;
    request.Splitting = self->Splitting;
    request.Bitangents = self->ComputeBitangents;
    request.CellTangents = self->ComputeCellTangents;
    vtkNormalMapping::detail::MikkTSpaceCounts counts;
    const int result = vtkNormalMapping::detail::RunMikkTSpace(request, output, counts);
    self->NumberOfDegenerateTriangles = counts.DegenerateTriangles;
    self->NumberOfFallbackPoints = counts.FallbackCorners;
    self->NumberOfHandednessConflicts = counts.Conflicts;
    self->NumberOfSplitPoints = counts.SplitPoints;
    return result;
  }

  // 2. Scatter and finish.
  PointSumStorage acc = AllocatePointSums(numPoints);
  if (!acc)
  {
    vtkErrorWithObjectMacro(
      self, "Cannot allocate the per-point sums for " << numPoints << " points.");
    output->Initialize();
    return 0;
  }
  // Written by Finish, point by point, from the sums' marks.
  unsigned char* const sides = acc.Sides();
  const auto makeArray = [&](const char* name, int components, vtkIdType tuples)
  {
    auto array = vtkSmartPointer<OutArray>::New();
    array->SetName(name);
    array->SetNumberOfComponents(components);
    if (!AllocateOnHugePages(array.Get(), tuples))
    {
      array->SetNumberOfTuples(tuples);
    }
    PrefaultOutput(array->GetPointer(0), sizeof(OutT) * static_cast<size_t>(tuples) * components);
    return array;
  };
  auto tangents = makeArray(TangentsArrayName(), 3, numPoints);
  auto signs = makeArray(SignsArrayName(), 1, numPoints);
  vtkSmartPointer<OutArray> bitangents;
  if (self->ComputeBitangents)
  {
    bitangents = makeArray(BitangentsArrayName(), 3, numPoints);
  }
  const auto tOut = [&]() { return tangents->GetPointer(0); };
  const auto sOut = [&]() { return signs->GetPointer(0); };
  const auto bOut = [&]() { return bitangents ? bitangents->GetPointer(0) : nullptr; };

  std::vector<SplitPoint> splits;
  std::vector<vtkIdType> fallbacks;
  bool done = true;
  const double* fallbackNormals = geometric.empty() ? nullptr : geometric.data();
  WithMeshView(points,
    uv,
    normal,
    fallbackNormals,
    [&](const auto& view)
    {
      done = Scatter(ex, view, acc.Sums(), self->NumberOfDegenerateTriangles);
      if (!done || ex.BadIds)
      {
        return;
      }
      std::vector<vtkIdType> conflicted;
      Finish(ex, view, acc.Sums(), sides, tOut(), sOut(), bOut(), conflicted, fallbacks);
      self->NumberOfHandednessConflicts = static_cast<vtkIdType>(conflicted.size());
      if (!conflicted.empty())
      {
        std::vector<SideSums> sideSums;
        done = SumSides(ex, view, sides, conflicted, sideSums);
        if (!done)
        {
          return;
        }
        FinishConflicts(ex, view, conflicted, sideSums, tOut(), sOut(), bOut(), splits);
      }
      if (!fallbacks.empty())
      {
        done = FillFallbacks(ex, view, acc.Sums(), sides, fallbacks, tOut(), sOut(), bOut());
      }
    });
  acc.Block.reset();
  if (!done)
  {
    return aborted();
  }
  if (ex.BadIds)
  {
    return badIds();
  }
  self->NumberOfFallbackPoints = static_cast<vtkIdType>(fallbacks.size());
  self->UpdateProgress(0.90);

  // 3. Split points: copies appended after the input points, cells re-pointed.
  const vtkIdType numSplits = ex.Splitting ? static_cast<vtkIdType>(splits.size()) : 0;
  self->NumberOfSplitPoints = numSplits;
  std::vector<vtkIdType> splitSource(static_cast<size_t>(numSplits));
  for (vtkIdType i = 0; i < numSplits; ++i)
  {
    splitSource[i] = splits[i].Id;
  }
  CopyWithAppendedPoints(input, output, splitSource);
  if (numSplits > 0)
  {
    if (computedNormals)
    {
      computedNormals = OutArray::SafeDownCast(
        ExtendPointArray(computedNormals, numPoints, splitSource).GetPointer());
    }
    for (OutArray* array : { tangents.Get(), signs.Get(), bitangents.Get() })
    {
      if (array)
      {
        array->Resize(numPoints + numSplits);
        array->SetNumberOfTuples(numPoints + numSplits);
      }
    }
    for (vtkIdType i = 0; i < numSplits; ++i)
    {
      WriteFrame(numPoints + i, splits[i].Normal, splits[i].Tangent, -1.0, tOut(), sOut(), bOut());
    }
    for (int kind = 0; kind < 2; ++kind)
    {
      vtkNew<vtkCellArray> copy;
      copy->DeepCopy(ex.Cells[kind]);
      WithMeshView(points,
        uv,
        normal,
        fallbackNormals,
        [&](const auto& view)
        {
          WithCellStorage(copy,
            [&](auto* offsets, auto* conn) {
              RepointCells(ex, view, splits, offsets, conn, copy->GetNumberOfCells(), kind == 1);
            });
        });
      if (kind == 1)
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
    WithMeshView(points,
      uv,
      normal,
      fallbackNormals,
      [&](const auto& view)
      {
        ComputeCellTangentArray(
          ex, view, firstSurfaceCell, cellTangents->GetPointer(0), input->GetNumberOfCells());
      });
    output->GetCellData()->SetTangents(cellTangents);
  }
  self->UpdateProgress(1.0);
  return 1;
}

/// The explicit instance of Internals::Run for output type T: declared extern here, defined in
/// vtkPolyDataTangentFramesRunFloat.cxx and vtkPolyDataTangentFramesRunDouble.cxx.
#define VTK_TANGENT_FRAMES_RUN_INSTANCE(T)                                                         \
  template int vtkPolyDataTangentFrames::Internals::Run<T>(vtkPolyDataTangentFrames*,              \
    vtkPolyData*,                                                                                  \
    vtkPolyData*,                                                                                  \
    vtkDataArray*,                                                                                 \
    vtkDataArray*,                                                                                 \
    vtkDataArray*,                                                                                 \
    const vtkNormalMapping::frames::CellSizes[2])
extern VTK_TANGENT_FRAMES_RUN_INSTANCE(float);
extern VTK_TANGENT_FRAMES_RUN_INSTANCE(double);

#endif
