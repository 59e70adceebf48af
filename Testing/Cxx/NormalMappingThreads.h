// SPDX-License-Identifier: BSD-3-Clause
// Runs code with a given number of vtkSMPTools threads, for tests and benchmarks.
#ifndef NormalMappingThreads_h
#define NormalMappingThreads_h

#include "vtkSMPTools.h"
#include "vtkVersionMacros.h"

#include <string>

namespace NormalMappingTesting
{
/**
 * f() with at most `threads` threads (fewer when the backend has fewer: TBB caps the count at the
 * machine's threads). Each call starts from the backend's default count (Initialize(0)), because
 * VTK 9.1's TBB backend ignores a scope whose count equals the previous scope's.
 */
template<typename F>
void WithThreads(int threads, F&& f)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
  // From VTK 9.4 the TBB backend cannot raise its count again once a scope lowered it (its task
  // arena keeps the lowest count); the STDThread backend can, so the runs that compare thread
  // counts use it there.
  if (std::string(vtkSMPTools::GetBackend()) == "TBB")
  {
    vtkSMPTools::SetBackend("STDThread");
  }
#endif
  vtkSMPTools::Initialize(0);
  vtkSMPTools::Config config;
  config.MaxNumberOfThreads = threads;
  vtkSMPTools::LocalScope(config, f);
}
}

#endif
