// SPDX-License-Identifier: BSD-3-Clause
// A parametric grid with texture coordinates and normals, for the tests and the benchmarks.
#ifndef NormalMappingGrid_h
#define NormalMappingGrid_h

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <functional>

namespace NormalMappingTesting
{
/// A (nu x nv) grid over [0,1]^2 mapped by `surface`, with texture coordinates from `uv` and
/// normals from `normal`: the analytic test surfaces.
inline vtkSmartPointer<vtkPolyData> MakeGrid(int nu,
  int nv,
  const std::function<std::array<double, 3>(double, double)>& surface,
  const std::function<std::array<double, 3>(double, double)>& normal,
  const std::function<std::array<double, 2>(double, double)>& uv)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> normals, tcoords;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  for (int i = 0; i <= nu; ++i)
  {
    for (int j = 0; j <= nv; ++j)
    {
      const double s = double(i) / nu, t = double(j) / nv;
      points->InsertNextPoint(surface(s, t).data());
      normals->InsertNextTuple(normal(s, t).data());
      tcoords->InsertNextTuple(uv(s, t).data());
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const vtkIdType a = i * (nv + 1) + j, b = a + nv + 1;
      const vtkIdType t1[3] = { a, b, b + 1 }, t2[3] = { a, b + 1, a + 1 };
      polys->InsertNextCell(3, t1);
      polys->InsertNextCell(3, t2);
    }
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetNormals(normals);
  mesh->GetPointData()->SetTCoords(tcoords);
  return mesh;
}

/// A float array of `tuples` tuples of `components` values, every value `value`; added to
/// `data` (a mesh's point or cell data), which owns it.
inline vtkFloatArray* AddFilledArray(vtkDataSetAttributes* data,
  vtkIdType tuples,
  const char* name,
  int components,
  double value)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  array->Fill(value);
  data->AddArray(array);
  return array;
}
}

#endif
