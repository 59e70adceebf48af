// SPDX-License-Identifier: BSD-3-Clause
// Runs code with a given number of vtkSMPTools threads, for tests and benchmarks.
#ifndef NormalMappingThreads_h
#define NormalMappingThreads_h

#include "vtkSMPTools.h"
#include "vtkVersionMacros.h"

#include <cstdlib>
#include <iostream>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace NormalMappingTesting
{
/**
 * The number of threads that took part in a vtkSMPTools::For of many small chunks, each long
 * enough (a few microseconds) that every thread the backend lets run picks up some.
 */
inline int ThreadsTakingPart()
{
  std::mutex mutex;
  std::set<std::thread::id> ids;
  vtkSMPTools::For(0,
    256,
    1,
    [&](vtkIdType, vtkIdType)
    {
      volatile double sum = 0.0;
      for (int i = 0; i < 4000; ++i)
      {
        sum = sum + i;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ids.insert(std::this_thread::get_id());
    });
  return static_cast<int>(ids.size());
}

/**
 * f() with at most `threads` threads (fewer when the backend has fewer: TBB caps the count at the
 * machine's threads). Aborts when more threads take part than asked for: the runs that compare
 * thread counts would compare nothing.
 */
template<typename F>
void WithThreads(int threads, F&& f)
{
  const auto limited = [&]()
  {
    const int taking = ThreadsTakingPart();
    if (taking > threads)
    {
      std::cerr << "WithThreads: " << taking << " threads take part where " << threads
                << " were asked for (vtkSMPTools backend " << vtkSMPTools::GetBackend() << ")"
                << std::endl;
      std::abort();
    }
    f();
  };
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
  // From VTK 9.4 the TBB backend cannot raise its count again once a scope lowered it (its task
  // arena keeps the lowest count); the STDThread backend can, so the runs that compare thread
  // counts use it there.
  if (std::string(vtkSMPTools::GetBackend()) == "TBB")
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  vtkSMPTools::Config config;
  config.MaxNumberOfThreads = threads;
  vtkSMPTools::LocalScope(config, limited);
#else
  // VTK 9.1's TBB backend ignores a scope, or an Initialize after Initialize(0), whose count is
  // the one it set last: the work then runs with the default count. An Initialize with another
  // non-zero count always takes effect, so the count is set, and restored, that way.
  const int previous = vtkSMPTools::GetEstimatedNumberOfThreads();
  vtkSMPTools::Initialize(threads);
  limited();
  vtkSMPTools::Initialize(previous);
#endif
}
}

#endif
