"""Helpers of the Python tests: a checklist that reports every check, and textured polydata."""
import sys

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData


class Checks:
    """Prints every check as ok or FAIL and keeps going; finish() exits 1 if any failed."""

    def __init__(self):
        self.failures = 0

    def __call__(self, ok, what):
        print(("  ok:   " if ok else "  FAIL: ") + what)
        self.failures += 0 if ok else 1

    def finish(self):
        print("%d failure(s)" % self.failures)
        sys.exit(1 if self.failures else 0)


def textured_mesh(positions, normals, uvs, triangles):
    """Triangles over `positions`, with point `Normals` (the active normals, or none when
    `normals` is None) and `UV` (the active texture coordinates, or none when `uvs` is None)."""
    points = vtkPoints()
    for p in positions:
        points.InsertNextPoint(*p)
    cells = vtkCellArray()
    for t in triangles:
        cells.InsertNextCell(3, t)
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(cells)
    for name, values, components in (("Normals", normals, 3), ("UV", uvs, 2)):
        if values is None:
            continue
        array = vtkFloatArray()
        array.SetName(name)
        array.SetNumberOfComponents(components)
        for v in values:
            array.InsertNextTuple(v)
        if name == "Normals":
            mesh.GetPointData().SetNormals(array)
        else:
            mesh.GetPointData().SetTCoords(array)
    return mesh
