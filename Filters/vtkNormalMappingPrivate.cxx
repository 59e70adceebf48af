// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMappingPrivate.h"

#include "vtkIdList.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <numeric>

namespace
{
/**
 * Adds copy(array) to `out` for each array of `in`, with its attribute, except the global ids:
 * the copies of a point or of a cell's triangles would repeat their source's id (VTK's filters
 * drop them too).
 */
template<typename F>
void CopyArraysButGlobalIds(vtkDataSetAttributes* in, vtkDataSetAttributes* out, F&& copy)
{
  for (int k = 0; k < in->GetNumberOfArrays(); ++k)
  {
    const int attribute = in->IsArrayAnAttribute(k);
    if (attribute == vtkDataSetAttributes::GLOBALIDS)
    {
      continue;
    }
    out->AddArray(copy(in->GetAbstractArray(k)));
    if (attribute >= 0)
    {
      out->SetActiveAttribute(out->GetNumberOfArrays() - 1, attribute);
    }
  }
}
}

bool vtkNormalMapping::detail::MultiversionedLoops()
{
  return VTK_NORMALMAPPING_MULTIVERSIONED != 0;
}

int vtkNormalMapping::detail::UsableThreads()
{
  if (vtkSMPTools::IsParallelScope() && !vtkSMPTools::GetNestedParallelism())
  {
    return 1;
  }
  return std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads());
}

vtkDataArray* vtkNormalMapping::detail::PointArray(vtkPolyData* mesh,
  vtkDataArray* array,
  const char* what,
  int components,
  std::string& problem)
{
  if (!array)
  {
    return nullptr;
  }
  const std::string label =
    std::string(what) + " array '" + (array->GetName() ? array->GetName() : "") + "' has ";
  if (components > 0 && array->GetNumberOfComponents() != components)
  {
    problem = label + std::to_string(array->GetNumberOfComponents()) + " components instead of " +
      std::to_string(components);
    return nullptr;
  }
  if (array->GetNumberOfTuples() < mesh->GetNumberOfPoints())
  {
    problem = label + std::to_string(array->GetNumberOfTuples()) + " tuples for " +
      std::to_string(mesh->GetNumberOfPoints()) + " points";
    return nullptr;
  }
  return array;
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
  auto copy = vtkSmartPointer<vtkCellArray>::New();
  if (!cells->IsStorage64Bit() && maxId > VTK_TYPE_INT32_MAX)
  {
    copy->DeepCopy(cells);
    copy->ConvertTo64BitStorage();
  }
  else
  {
    vtkDataArray* connectivity = cells->GetConnectivityArray();
    auto newConnectivity = vtk::TakeSmartPointer(connectivity->NewInstance());
    newConnectivity->DeepCopy(connectivity);
    copy->SetData(cells->GetOffsetsArray(), newConnectivity);
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

vtkSmartPointer<vtkPolyData> vtkNormalMapping::detail::CutIntoTriangles(vtkPolyData* input,
  const std::vector<vtkIdType>& cells)
{
  auto cut = vtkSmartPointer<vtkPolyData>::New();
  cut->ShallowCopy(input);
  // Per output cell, the input cell whose cell data it takes: vertices and lines unchanged.
  vtkNew<vtkIdList> source;
  const vtkIdType firstSurfaceCell = input->GetNumberOfVerts() + input->GetNumberOfLines();
  for (vtkIdType c = 0; c < firstSurfaceCell; ++c)
  {
    source->InsertNextId(c);
  }
  auto next = cells.begin();
  vtkIdType index = 0; // over the polygons, then the strips
  for (int kind = 0; kind < 2; ++kind)
  {
    const bool strip = kind == 1;
    vtkCellArray* in = strip ? input->GetStrips() : input->GetPolys();
    vtkNew<vtkCellArray> out;
    out->AllocateEstimate(in->GetNumberOfCells(), 3);
    vtkIdType n;
    const vtkIdType* pts;
    for (in->InitTraversal(); in->GetNextCell(n, pts); ++index)
    {
      if (next == cells.end() || *next != index)
      {
        out->InsertNextCell(n, pts);
        source->InsertNextId(firstSurfaceCell + index);
        continue;
      }
      ++next;
      for (vtkIdType j = 0; j + 2 < n; ++j)
      {
        vtkIdType tri[3];
        CellTriangle(pts, j, strip, tri);
        out->InsertNextCell(3, tri);
        source->InsertNextId(firstSurfaceCell + index);
      }
    }
    if (strip)
    {
      cut->SetStrips(out);
    }
    else
    {
      cut->SetPolys(out);
    }
  }
  vtkCellData* inCD = input->GetCellData();
  vtkCellData* outCD = cut->GetCellData();
  outCD->Initialize();
  vtkNew<vtkIdList> target;
  target->SetNumberOfIds(source->GetNumberOfIds());
  std::iota(target->begin(), target->end(), 0);
  CopyArraysButGlobalIds(inCD,
    outCD,
    [&](vtkAbstractArray* array) -> vtkSmartPointer<vtkAbstractArray>
    {
      if (array->GetNumberOfTuples() < input->GetNumberOfCells())
      {
        return array;
      }
      vtkSmartPointer<vtkAbstractArray> copy = EmptyCopyOf(array);
      copy->SetNumberOfTuples(source->GetNumberOfIds());
      copy->InsertTuples(target, source, array);
      return copy;
    });
  return cut;
}

vtkSmartPointer<vtkAbstractArray> vtkNormalMapping::detail::EmptyCopyOf(vtkAbstractArray* array)
{
  vtkSmartPointer<vtkAbstractArray> copy = vtk::TakeSmartPointer(array->NewInstance());
  copy->SetNumberOfComponents(array->GetNumberOfComponents());
  copy->SetName(array->GetName());
  copy->CopyComponentNames(array);
  if (array->HasInformation())
  {
    copy->CopyInformation(array->GetInformation());
  }
  auto* values = vtkDataArray::SafeDownCast(array);
  if (values && values->GetLookupTable())
  {
    vtkDataArray::SafeDownCast(copy)->SetLookupTable(values->GetLookupTable());
  }
  return copy;
}

vtkSmartPointer<vtkAbstractArray> vtkNormalMapping::detail::ExtendPointArray(
  vtkAbstractArray* array,
  vtkIdType numIn,
  const std::vector<vtkIdType>& source)
{
  if (array->GetNumberOfTuples() < numIn)
  {
    return array;
  }
  const vtkIdType extra = static_cast<vtkIdType>(source.size());
  vtkSmartPointer<vtkAbstractArray> copy = EmptyCopyOf(array);
  copy->SetNumberOfTuples(numIn + extra);
  copy->InsertTuples(0, numIn, 0, array);
  vtkNew<vtkIdList> src, dst;
  src->SetNumberOfIds(extra);
  dst->SetNumberOfIds(extra);
  for (vtkIdType i = 0; i < extra; ++i)
  {
    src->SetId(i, source[static_cast<size_t>(i)]);
    dst->SetId(i, numIn + i);
  }
  copy->InsertTuples(dst, src, array);
  return copy;
}

void vtkNormalMapping::detail::CopyWithAppendedPoints(vtkPolyData* input,
  vtkPolyData* output,
  const std::vector<vtkIdType>& source,
  const std::vector<std::string>& replaced)
{
  output->CopyStructure(input);
  output->GetCellData()->PassData(input->GetCellData());
  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  if (source.empty())
  {
    outPD->PassData(inPD);
    return;
  }
  const vtkIdType numIn = input->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetData(
    vtkDataArray::SafeDownCast(ExtendPointArray(input->GetPoints()->GetData(), numIn, source)));
  output->SetPoints(points);
  outPD->Initialize();
  CopyArraysButGlobalIds(inPD,
    outPD,
    [&](vtkAbstractArray* array) -> vtkSmartPointer<vtkAbstractArray>
    {
      const char* name = array->GetName();
      const bool isReplaced =
        name && std::find(replaced.begin(), replaced.end(), name) != replaced.end();
      return isReplaced ? vtkSmartPointer<vtkAbstractArray>(array)
                        : ExtendPointArray(array, numIn, source);
    });
}

void vtkNormalMapping::detail::AddFrameArray(vtkDataSetAttributes* attributes, vtkDataArray* array)
{
  int index = -1;
  if (attributes->GetAbstractArray(array->GetName(), index))
  {
    const int attribute = attributes->IsArrayAnAttribute(index);
    if (attribute == vtkDataSetAttributes::NORMALS || attribute == vtkDataSetAttributes::TCOORDS)
    {
      attributes->RemoveArray(index);
    }
  }
  attributes->AddArray(array);
}

void vtkNormalMapping::detail::AddActiveTangents(vtkDataSetAttributes* attributes,
  vtkDataArray* tangents)
{
  AddFrameArray(attributes, tangents);
  attributes->SetActiveTangents(tangents->GetName());
}
