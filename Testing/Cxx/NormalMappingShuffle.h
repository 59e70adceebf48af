// SPDX-License-Identifier: BSD-3-Clause
// A mesh with its point ids in random order, for tests and benchmarks of the filter's threads.
#ifndef NormalMappingShuffle_h
#define NormalMappingShuffle_h

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

namespace NormalMappingTesting
{
/**
 * The same surface as `mesh` (its points, point data and polygons) with the point ids in a
 * random order drawn from `seed`: its triangles, in their order, reach points all over the id
 * range.
 */
inline vtkSmartPointer<vtkPolyData> ShuffledPoints(vtkPolyData* mesh, unsigned seed)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<vtkIdType> newId(static_cast<size_t>(n));
  std::iota(newId.begin(), newId.end(), 0);
  std::shuffle(newId.begin(), newId.end(), std::mt19937(seed));
  vtkNew<vtkPoints> points;
  points->SetDataType(mesh->GetPoints()->GetDataType());
  points->SetNumberOfPoints(n);
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->GetPointData()->CopyAllocate(mesh->GetPointData(), n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    points->SetPoint(newId[p], mesh->GetPoint(p));
    out->GetPointData()->CopyData(mesh->GetPointData(), p, newId[p]);
  }
  out->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfPolys(); ++c)
  {
    mesh->GetCellPoints(mesh->GetNumberOfVerts() + mesh->GetNumberOfLines() + c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      ids->SetId(k, newId[ids->GetId(k)]);
    }
    polys->InsertNextCell(ids);
  }
  out->SetPolys(polys);
  return out;
}
}

#endif
