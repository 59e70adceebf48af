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

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
TEST(TangentFrameKernels, FreshOutputsFaultInOnlyTheirSmallPageParts)
{
  using vtkNormalMapping::detail::HugePageBytes;
  using vtkNormalMapping::detail::IsFreshMemory;
  using vtkNormalMapping::detail::SmallPageBytes;
  // A kernel before 5.14 has no MADV_POPULATE_WRITE: PrefaultOutput is then advice that changes
  // nothing, and there is nothing to check here.
  void* probe =
    mmap(nullptr, SmallPageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(probe, MAP_FAILED);
  const bool populates = madvise(probe, SmallPageBytes, MADV_POPULATE_WRITE) == 0;
  munmap(probe, SmallPageBytes);
  if (!populates)
  {
    GTEST_SKIP() << "this Linux kernel (before 5.14) has no MADV_POPULATE_WRITE: the filter's "
                    "outputs then fault in page by page as before, and there is nothing to check";
  }
  // An output of two whole huge pages with 3 small pages before them and 50 after, in a fresh
  // mapping: the small-page parts must come out resident, the huge pages untouched (left to fault
  // once per 2 MiB when the finish writes them), the contents zero.
  const std::size_t mapped = 8 * HugePageBytes;
  void* map = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(map, MAP_FAILED);
  const std::uintptr_t hugeBegin =
    (reinterpret_cast<std::uintptr_t>(map) + 2 * HugePageBytes) & ~(HugePageBytes - 1);
  char* const data = reinterpret_cast<char*>(hugeBegin - 3 * SmallPageBytes);
  const std::size_t bytes = 3 * SmallPageBytes + 2 * HugePageBytes + 50 * SmallPageBytes;
  ASSERT_TRUE(IsFreshMemory(data, bytes));
  vtkNormalMapping::frames::PrefaultOutput(data, bytes);
  const std::size_t pages = bytes / SmallPageBytes;
  std::vector<unsigned char> resident(pages);
  ASSERT_EQ(mincore(data, bytes, resident.data()), 0);
  for (std::size_t i = 0; i < pages; ++i)
  {
    const bool onHugePages = i >= 3 && i < 3 + 2 * HugePageBytes / SmallPageBytes;
    ASSERT_EQ(resident[i] & 1, onHugePages ? 0 : 1) << "page " << i;
  }
  EXPECT_TRUE(std::all_of(data, data + bytes, [](char c) { return c == 0; }));
  // Now resident at both ends: memory like this (which the allocator reuses) is left alone.
  EXPECT_FALSE(IsFreshMemory(data, bytes));
  std::vector<char> reused(64 * SmallPageBytes, 1);
  EXPECT_FALSE(IsFreshMemory(reused.data(), reused.size()));

  // An array under 2 MiB (no huge pages at all) that starts 16 bytes into a page, as a malloc
  // block does, and spans several 256 KiB chunks: every whole page in it must come out resident,
  // those at the chunks' seams included.
  char* const small = reinterpret_cast<char*>(hugeBegin + 3 * HugePageBytes + 16);
  const std::size_t smallBytes = 300 * SmallPageBytes;
  ASSERT_TRUE(IsFreshMemory(small, smallBytes));
  vtkNormalMapping::frames::PrefaultOutput(small, smallBytes);
  char* const firstWhole = small - 16 + SmallPageBytes;
  std::vector<unsigned char> smallResident(299);
  ASSERT_EQ(mincore(firstWhole, 299 * SmallPageBytes, smallResident.data()), 0);
  for (std::size_t i = 0; i < smallResident.size(); ++i)
  {
    ASSERT_EQ(smallResident[i] & 1, 1) << "page " << i;
  }
  munmap(map, mapped);
}
#endif
