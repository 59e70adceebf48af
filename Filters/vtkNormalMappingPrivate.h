/**
 * @file   vtkNormalMappingPrivate.h
 * @brief  Private helpers shared by the filter's translation units (not installed).
 */
#ifndef vtkNormalMappingPrivate_h
#define vtkNormalMappingPrivate_h

#include "vtkCellArray.h"

namespace vtkNormalMapping
{
namespace detail
{
/// Calls f(offsets, connectivity) with the typed raw storage of a cell array (32 or 64 bit),
/// so that cells are read without a virtual call per cell.
template<typename F>
void WithCellStorage(vtkCellArray* cells, F&& f)
{
  if (cells->IsStorage64Bit())
  {
    f(cells->GetOffsetsArray64()->GetPointer(0), cells->GetConnectivityArray64()->GetPointer(0));
  }
  else
  {
    f(cells->GetOffsetsArray32()->GetPointer(0), cells->GetConnectivityArray32()->GetPointer(0));
  }
}
}
}

#endif
