// Transparent huge pages for large temporaries and outputs (private; see the users in
// vtkMikkTSpaceKernel.cxx and vtkPolyDataTangentFrames.cxx for what they measured).
#ifndef vtkNormalMappingHugePages_h
#define vtkNormalMappingHugePages_h

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

/**
 * Advises the whole huge pages inside [ptr, ptr + bytes) to use transparent huge pages (pages
 * fresh from the kernel then fault once per 2 MiB instead of once per 4 KiB); nothing for a range
 * that holds none, or where there is no such advice. Advice only: a failure changes nothing.
 */
inline void AdviseHugePages(void* ptr, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(ptr);
  const std::uintptr_t b = (first + HugePageBytes - 1) & ~(HugePageBytes - 1);
  const std::uintptr_t e = (first + bytes) & ~(HugePageBytes - 1);
  if (e > b)
  {
    madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
  }
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
