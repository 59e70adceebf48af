// Transparent huge pages for large temporaries and outputs (private; see the users in
// vtkMikkTSpaceKernel.cxx and vtkPolyDataTangentFrames.cxx for what they measured).
#ifndef vtkNormalMappingHugePages_h
#define vtkNormalMappingHugePages_h

#include <algorithm>
#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace vtkNormalMapping
{
namespace detail
{
/// The size of a transparent huge page on x86-64 Linux.
constexpr std::size_t HugePageBytes = std::size_t{ 1 } << 21;
/// The size of a base page on x86-64 Linux.
constexpr std::size_t SmallPageBytes = std::size_t{ 1 } << 12;

/// The whole pages of `page` bytes (a power of two) inside [ptr, ptr + bytes): [first, last).
struct PageRange
{
  std::uintptr_t First;
  std::uintptr_t Last;
  PageRange(const void* ptr, std::size_t bytes, std::size_t page)
  {
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(ptr);
    this->First = (begin + page - 1) & ~(page - 1);
    this->Last = std::max(this->First, (begin + bytes) & ~(page - 1));
  }
  std::size_t Bytes() const { return this->Last - this->First; }
  void* Begin() const { return reinterpret_cast<void*>(this->First); }
};

#if defined(__linux__)
/// madvise(advice) on the whole pages of `page` bytes inside [ptr, ptr + bytes), if any. Advice
/// only: a failure changes nothing.
inline void AdviseWholePages(void* ptr, std::size_t bytes, std::size_t page, int advice)
{
  const PageRange pages(ptr, bytes, page);
  if (pages.Bytes() > 0)
  {
    madvise(pages.Begin(), pages.Bytes(), advice);
  }
}
#endif

/**
 * Advises the whole huge pages inside [ptr, ptr + bytes) to use transparent huge pages (pages
 * fresh from the kernel then fault once per 2 MiB instead of once per 4 KiB); nothing for a range
 * that holds none, or where there is no such advice.
 */
inline void AdviseHugePages(void* ptr, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  AdviseWholePages(ptr, bytes, HugePageBytes, MADV_HUGEPAGE);
#else
  (void)ptr;
  (void)bytes;
#endif
}

/**
 * Whether [ptr, ptr + bytes), at least 16 small pages, is memory fresh from the kernel: its first
 * or its last whole page is not resident (as in a first execution; memory the allocator reused is
 * resident). False where that cannot be asked.
 */
inline bool IsFreshMemory(const void* ptr, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const PageRange pages(ptr, bytes, SmallPageBytes);
  if (pages.Bytes() < 16 * SmallPageBytes)
  {
    return false;
  }
  unsigned char resident[2] = { 0, 0 };
  if (mincore(pages.Begin(), SmallPageBytes, &resident[0]) != 0 ||
    mincore(reinterpret_cast<void*>(pages.Last - SmallPageBytes), SmallPageBytes, &resident[1]) !=
      0)
  {
    return false;
  }
  return (resident[0] & resident[1] & 1) == 0;
#else
  (void)ptr;
  (void)bytes;
  return false;
#endif
}

/**
 * Faults in the whole small pages inside [ptr, ptr + bytes) for writing, in one system call
 * (MADV_POPULATE_WRITE), instead of one page-fault exception per page when they are first written.
 * Only for memory the caller then writes whole: it commits the memory earlier, never more of it.
 * Advice only: a kernel without it (before Linux 5.14) answers EINVAL and nothing changes.
 */
inline void PopulateForWriting(void* ptr, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  AdviseWholePages(ptr, bytes, SmallPageBytes, MADV_POPULATE_WRITE);
#else
  (void)ptr;
  (void)bytes;
#endif
}

/**
 * The bytes to reserve for a block of `bytes` meant for huge pages: rounded up to whole huge
 * pages when that adds at most an eighth, so that the block's last part does not fault in 4 KiB at
 * a time; else `bytes`. The rounding costs memory (a huge page is backed whole once touched) and
 * saves page faults (see AllocatePointSums in vtkPolyDataTangentFramesInternals.h).
 */
inline std::size_t HugePageReservation(std::size_t bytes)
{
  const std::size_t rounded = (bytes + HugePageBytes - 1) & ~(HugePageBytes - 1);
  return rounded - bytes <= bytes / 8 ? rounded : bytes;
}
} // namespace detail
} // namespace vtkNormalMapping

#endif
