#include "vtkNormalMappingPrivate.h"

#include "vtkSMPTools.h"

#include <algorithm>

void vtkNormalMapping::detail::ParallelFor(vtkIdType n, vtkIdType grain, RangeFunction f)
{
  vtkSMPTools::For(0, n, grain, [&f](vtkIdType begin, vtkIdType end) { f(begin, end); });
}

int vtkNormalMapping::detail::UsableThreads()
{
  if (vtkSMPTools::IsParallelScope() && !vtkSMPTools::GetNestedParallelism())
  {
    return 1;
  }
  return std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
}
