// SPDX-License-Identifier: BSD-3-Clause
#include "vtkNormalMappingMeshes.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <cmath>

namespace vtkNormalMapping
{
vtkSmartPointer<vtkPolyData> MakeTorus(const TorusOptions& options)
{
  const int nu = std::max(options.U, 3);
  const int nv = std::max(options.V, 3);
  const int columns = options.MirrorU ? nu : nu + 1; // mirrored: u' is periodic, share column 0
  const int rows = nv + 1;                           // v seam: duplicated row
  const vtkIdType numPoints = static_cast<vtkIdType>(columns) * rows;
  const int type = options.DoublePrecision ? VTK_DOUBLE : VTK_FLOAT;

  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  points->SetNumberOfPoints(numPoints);
  vtkSmartPointer<vtkDataArray> normals =
    vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(numPoints);
  vtkSmartPointer<vtkDataArray> tcoords =
    vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(numPoints);

  const double twoPi = 2.0 * std::acos(-1.0);
  for (int i = 0; i < columns; ++i)
  {
    const double s = static_cast<double>(i) / nu;
    const double phi = twoPi * s;
    const double u = options.MirrorU ? 2.0 * std::min(s, 1.0 - s) : s;
    for (int j = 0; j < rows; ++j)
    {
      const double t = static_cast<double>(j) / nv;
      const double theta = twoPi * t;
      const double ring = options.RingRadius + options.TubeRadius * std::cos(theta);
      const vtkIdType id = static_cast<vtkIdType>(i) * rows + j;
      points->SetPoint(
        id, ring * std::cos(phi), ring * std::sin(phi), options.TubeRadius * std::sin(theta));
      normals->SetTuple3(
        id, std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta));
      tcoords->SetTuple2(id, u, t);
    }
  }

  // Two triangles per quad, counter-clockwise seen from outside (along the normal).
  vtkNew<vtkTypeInt64Array> offsets, connectivity;
  const vtkIdType numTris = 2 * static_cast<vtkIdType>(nu) * nv;
  offsets->SetNumberOfValues(numTris + 1);
  connectivity->SetNumberOfValues(3 * numTris);
  vtkIdType tri = 0;
  for (int i = 0; i < nu; ++i)
  {
    const int i1 = (i + 1) % columns;
    for (int j = 0; j < nv; ++j)
    {
      const vtkIdType a = static_cast<vtkIdType>(i) * rows + j;
      const vtkIdType b = static_cast<vtkIdType>(i1) * rows + j;
      const vtkIdType c = b + 1;
      const vtkIdType d = a + 1;
      const vtkIdType corners[6] = { a, b, c, a, c, d };
      for (int k = 0; k < 6; k += 3, ++tri)
      {
        offsets->SetValue(tri, 3 * tri);
        for (int m = 0; m < 3; ++m)
        {
          connectivity->SetValue(3 * tri + m, corners[k + m]);
        }
      }
    }
  }
  offsets->SetValue(numTris, 3 * numTris);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);

  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetNormals(normals);
  mesh->GetPointData()->SetTCoords(tcoords);
  return mesh;
}
}
