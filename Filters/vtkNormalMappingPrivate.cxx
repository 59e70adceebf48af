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
  const bool moves = std::any_of(repoint.begin(),
    repoint.end(),
    [&](const std::pair<vtkIdType, vtkIdType>& r)
    { return r.first >= base && r.first < base + size; });
  if (!moves)
  {
    return cells;
  }
  // A new connectivity array; the offsets do not change and are shared.
  auto copy = vtkSmartPointer<vtkCellArray>::New();
  const auto copyConnectivity = [&](auto* offsets, auto* connectivity)
  {
    using Array = std::remove_pointer_t<decltype(connectivity)>;
    auto ids = vtkSmartPointer<Array>::New();
    ids->DeepCopy(connectivity);
    copy->SetData(offsets, ids);
  };
  if (cells->IsStorage64Bit())
  {
    copyConnectivity(cells->GetOffsetsArray64(), cells->GetConnectivityArray64());
  }
  else if (maxId <= VTK_TYPE_INT32_MAX)
  {
    copyConnectivity(cells->GetOffsetsArray32(), cells->GetConnectivityArray32());
  }
  else
  {
    copy->DeepCopy(cells);
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
