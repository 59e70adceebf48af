// SPDX-License-Identifier: BSD-3-Clause
// Peak resident memory of one phase of a benchmark program (Linux), and the bytes of a filter's
// output that its input does not share. Used by BenchTangentFrames and TangentFramesLargeInput.
//
// How a phase is measured: VmHWM (the resident-set high-water mark) is reset to the current
// resident set by writing "5" to /proc/self/clear_refs (Linux >= 4.0); after the phase, VmHWM
// minus the resident set before it is the phase's peak: every page the phase touched that was
// not resident before (its outputs, its scratch, new thread stacks). Freed heap that is still
// resident would hide allocations, so ReleaseFreedMemory() asks glibc to give freed memory back
// and AllocateLargeBlocksWithMmap() makes large blocks come from (and return to) mmap.
#ifndef BenchMemory_h
#define BenchMemory_h

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <sys/resource.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

namespace BenchMemory
{
constexpr double MiB = 1024.0 * 1024.0;

/// A field of /proc/self/status in bytes (VmRSS: current, VmHWM: peak since the last reset).
inline double StatusBytes(const char* field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, std::strlen(field), field) == 0)
    {
      return std::atof(line.c_str() + std::strlen(field) + 1) * 1024.0;
    }
  }
  return 0.0;
}

/// Restarts VmHWM at the current RSS (Linux >= 4.0), so that it measures one phase.
inline bool ResetPeak()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  return static_cast<bool>(clear.flush());
}

/// The process's peak RSS since it started (the fallback when ResetPeak is not available).
inline double MaxRssBytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss * 1024.0; // kilobytes on Linux
}

/// Blocks of 128 KiB and more from mmap, always (glibc otherwise raises that threshold after a
/// large free and serves later blocks from heap that is already resident).
inline void AllocateLargeBlocksWithMmap()
{
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  mallopt(M_TRIM_THRESHOLD, 128 * 1024);
#endif
}

/// Gives freed heap memory back to the system, so that the next phase starts from it.
inline void ReleaseFreedMemory()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

/// Bytes of the output's arrays that the input does not share (new or copied by the filter).
inline double NewOutputBytes(vtkPolyData* input, vtkPolyData* output)
{
  const auto collect = [](vtkPolyData* pd, std::set<vtkAbstractArray*>& arrays)
  {
    arrays.insert(pd->GetPoints() ? pd->GetPoints()->GetData() : nullptr);
    for (vtkCellArray* cells : { pd->GetPolys(), pd->GetStrips(), pd->GetVerts(), pd->GetLines() })
    {
      arrays.insert(cells->GetOffsetsArray());
      arrays.insert(cells->GetConnectivityArray());
    }
    for (vtkFieldData* fd : { static_cast<vtkFieldData*>(pd->GetPointData()),
           static_cast<vtkFieldData*>(pd->GetCellData()) })
    {
      for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
      {
        arrays.insert(fd->GetAbstractArray(a));
      }
    }
  };
  std::set<vtkAbstractArray*> in, out;
  collect(input, in);
  collect(output, out);
  double bytes = 0.0;
  for (vtkAbstractArray* a : out)
  {
    if (a && !in.count(a))
    {
      bytes += a->GetNumberOfValues() * static_cast<double>(a->GetDataTypeSize());
    }
  }
  return bytes;
}
}

#endif
