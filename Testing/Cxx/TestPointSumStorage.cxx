// The per-point scratch storage of vtkPolyDataTangentFrames' weighted methods, and the chunked
// parallel loop their per-chunk results use (private code; a translation unit of its own, since
// the filter's internals bring in names that the kernel tests' short `detail::` would find twice).
#include "vtkPolyDataTangentFramesInternals.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

TEST(TangentFrameKernels, PointSumsComeClearedWithTheSideBytesAfterThem)
{
  using vtkNormalMapping::frames::AllocatePointSums;
  using vtkNormalMapping::frames::PointSumStorage;
  using Sum = vtkNormalMapping::detail::PointSum;
  // A small block, and blocks large enough for huge pages (8 MiB or more: the 1M-triangle torus'
  // 501,501 points, and a count whose side bytes end exactly on a PointSum); every byte of both
  // parts must be writable, and the sums all zero.
  for (vtkIdType n : { vtkIdType(1), vtkIdType(1000), vtkIdType(501501), vtkIdType(524288) })
  {
    // Twice, the first block dirtied before it is freed: the allocator may hand the same memory
    // back, and the sums must be cleared all the same.
    for (int round = 0; round < 2; ++round)
    {
      const PointSumStorage storage = AllocatePointSums(n);
      ASSERT_TRUE(storage);
      EXPECT_EQ(storage.Count, n);
      EXPECT_EQ(static_cast<void*>(storage.Sides()), static_cast<void*>(storage.Sums() + n));
      EXPECT_EQ(reinterpret_cast<std::uintptr_t>(storage.Sums()) % alignof(Sum), 0u);
      const auto* bytes = reinterpret_cast<const unsigned char*>(storage.Sums());
      EXPECT_TRUE(
        std::all_of(bytes, bytes + n * sizeof(Sum), [](unsigned char c) { return c == 0; }))
        << n << " points, round " << round;
      std::memset(static_cast<void*>(storage.Sums()), 0xff, n * sizeof(Sum) + n);
      EXPECT_EQ(storage.Sides()[n - 1], 0xff);
    }
  }
}

TEST(TangentFrameKernels, ParallelChunksCoverTheRangeOnceInOrder)
{
  using vtkNormalMapping::detail::ChunkCount;
  using vtkNormalMapping::detail::ParallelChunks;
  // Every id in exactly one chunk, chunk c holding [c size, min(n, (c + 1) size)): the per-chunk
  // results the filter keeps instead of thread-local ones rely on it.
  for (vtkIdType n :
    { vtkIdType(0), vtkIdType(1), vtkIdType(10), vtkIdType(65536), vtkIdType(200001) })
  {
    for (vtkIdType size : { vtkIdType(1), vtkIdType(3), vtkIdType(1024), vtkIdType(1) << 16 })
    {
      const vtkIdType chunks = ChunkCount(n, size);
      EXPECT_EQ(chunks, n == 0 ? 0 : (n - 1) / size + 1) << n << " ids, chunks of " << size;
      std::vector<int> seen(static_cast<size_t>(n), 0);
      std::vector<vtkIdType> begins(static_cast<size_t>(chunks), -1), ends(begins);
      ParallelChunks(n,
        size,
        [&](vtkIdType chunk, vtkIdType begin, vtkIdType end)
        {
          begins[chunk] = begin;
          ends[chunk] = end;
          for (vtkIdType i = begin; i < end; ++i)
          {
            ++seen[static_cast<size_t>(i)];
          }
        });
      EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }))
        << n << " ids, chunks of " << size;
      for (vtkIdType c = 0; c < chunks; ++c)
      {
        EXPECT_EQ(begins[c], c * size);
        EXPECT_EQ(ends[c], std::min(n, (c + 1) * size));
      }
    }
  }
}
