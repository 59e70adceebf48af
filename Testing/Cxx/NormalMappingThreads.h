// Runs code with a given number of vtkSMPTools threads, for tests and benchmarks.
#ifndef NormalMappingThreads_h
#define NormalMappingThreads_h

#include "vtkSMPTools.h"

namespace NormalMappingTesting
{
/**
 * f() with at most `threads` threads. VTK 9.1's TBB backend ignores a LocalScope whose thread
 * count equals the previous scope's (the second of two 1-thread scopes runs on every thread), so
 * a scope with a different count is entered first; then the requested count holds. That other
 * count is below the requested one (2 for 1 thread): TBB caps its workers at the machine's
 * threads minus one, and a scope asking for more makes it warn and ignore later requests.
 */
template<typename F>
void WithThreads(int threads, F&& f)
{
  vtkSMPTools::Config other;
  other.MaxNumberOfThreads = threads > 1 ? threads - 1 : 2;
  vtkSMPTools::LocalScope(other, []() {});
  vtkSMPTools::Config config;
  config.MaxNumberOfThreads = threads;
  vtkSMPTools::LocalScope(config, f);
}
}

#endif
