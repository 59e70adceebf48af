#include "vtkNormalMappingPrivate.h"

#include "vtkSMPTools.h"

#include <algorithm>

int vtkNormalMapping::detail::UsableThreads()
{
  if (vtkSMPTools::IsParallelScope() && !vtkSMPTools::GetNestedParallelism())
  {
    return 1;
  }
  return std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
}

vtkSmartPointer<vtkCellArray> vtkNormalMapping::detail::RepointCells(vtkCellArray* cells,
  const std::vector<std::pair<vtkIdType, vtkIdType>>& repoint,
  vtkIdType base,
  vtkIdType size,
  vtkIdType maxId)
{
  auto copy = vtkSmartPointer<vtkCellArray>::New();
  copy->DeepCopy(cells);
  if (!copy->IsStorage64Bit() && maxId > VTK_TYPE_INT32_MAX)
  {
    copy->ConvertTo64BitStorage();
  }
  WithCellStorage(copy,
    [&](auto*, auto* conn)
    {
      using IdT = std::remove_pointer_t<decltype(conn)>;
      for (const auto& r : repoint)
      {
        if (r.first >= base && r.first < base + size)
        {
          conn[r.first - base] = static_cast<IdT>(r.second);
        }
      }
    });
  return copy;
}
