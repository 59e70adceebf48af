#include "vtkNormalMappingPrivate.h"

#include "vtkSMPTools.h"

void vtkNormalMapping::detail::ParallelFor(vtkIdType n, vtkIdType grain, RangeFunction f)
{
  vtkSMPTools::For(0, n, grain, [&f](vtkIdType begin, vtkIdType end) { f(begin, end); });
}
