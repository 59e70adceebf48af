# SPDX-License-Identifier: BSD-3-Clause
"""vtkPolyDataTangentFrames from Python: the wrapped filter on a curved mesh with mirrored UVs.

Run by ctest (NormalMappingPython.TangentFrames) with PYTHONPATH set to the build tree's
package folder, and by the InstalledPackageExample test against the installed package with
NORMALMAPPING_EXPECT_PREFIX set: then the package and the module's library it loads must both
come from that prefix.
"""
import math
import os

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import vtknormalmapping
from vtknormalmapping import vtkPolyDataTangentFrames

from normalmapping_testing import Checks, textured_mesh

check = Checks()


# A height field z = 0.15 sin(pi x) cos(pi y) over x in [-1, 1], y in [0, 1], whose texture is
# mirrored at x = 0: u = |x|, v = y. On the right half dP/du points to +x with handedness +1; on
# the left half u grows towards -x, so dP/du points to -x and the handedness is -1. The column
# x = 0 is the mirror seam: its COLS + 1 points are shared by both sides.
HALF = 12  # quads across each half
ROWS = 12


def height(x, y):
    return 0.15 * math.sin(math.pi * x) * math.cos(math.pi * y)


def normal(x, y):
    # Unit normal of the height field: (-dz/dx, -dz/dy, 1), normalized.
    dzdx = 0.15 * math.pi * math.cos(math.pi * x) * math.cos(math.pi * y)
    dzdy = -0.15 * math.pi * math.sin(math.pi * x) * math.sin(math.pi * y)
    length = math.sqrt(dzdx * dzdx + dzdy * dzdy + 1.0)
    return (-dzdx / length, -dzdy / length, 1.0 / length)


def mirrored_height_field(with_tcoords=True, with_normals=True):
    columns = 2 * HALF + 1
    xy = [(-1.0 + i / HALF, j / ROWS) for j in range(ROWS + 1) for i in range(columns)]
    triangles = []
    for j in range(ROWS):
        for i in range(2 * HALF):
            a = j * columns + i
            triangles += [(a, a + 1, a + columns + 1), (a, a + columns + 1, a + columns)]
    return textured_mesh([(x, y, height(x, y)) for x, y in xy],
                         [normal(x, y) for x, y in xy] if with_normals else None,
                         [(abs(x), y) for x, y in xy] if with_tcoords else None, triangles)


class Messages:
    """Collects a VTK object's ErrorEvent / WarningEvent texts (the observer keeps them off the
    console and proves the filter reported them)."""

    def __init__(self, obj):
        self.errors = []
        self.warnings = []

        @calldata_type(VTK_STRING)
        def on_error(caller, event, text):
            self.errors.append(text)

        @calldata_type(VTK_STRING)
        def on_warning(caller, event, text):
            self.warnings.append(text)

        # The callbacks must outlive this call: VTK holds them only weakly through the observer.
        self._callbacks = (on_error, on_warning)
        obj.AddObserver("ErrorEvent", on_error)
        obj.AddObserver("WarningEvent", on_warning)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def where_from():
    """The package's folder and the libvtkNormalMapping file this process loaded."""
    library = ""
    with open("/proc/self/maps") as maps:
        for line in maps:
            if "libvtkNormalMapping" in line:
                library = line.split()[-1]
                break
    return os.path.dirname(os.path.abspath(vtknormalmapping.__file__)), library


# ---------------------------------------------------------------------------- where from
package_dir, library = where_from()
print("vtknormalmapping from " + package_dir + "; module library " + library)
expected_prefix = os.environ.get("NORMALMAPPING_EXPECT_PREFIX")
if expected_prefix:
    prefix = os.path.realpath(expected_prefix) + os.sep
    check(os.path.realpath(package_dir).startswith(prefix),
          "the package comes from the installed prefix " + prefix)
    check(os.path.realpath(library).startswith(prefix),
          "its module library comes from the installed prefix too (found through the RPATH)")

# ------------------------------------------------------------------ enums and names from Python
check([vtkPolyDataTangentFrames.UNWEIGHTED, vtkPolyDataTangentFrames.AREA_WEIGHTED,
       vtkPolyDataTangentFrames.ANGLE_WEIGHTED, vtkPolyDataTangentFrames.MIKKTSPACE] == [0, 1, 2, 3],
      "the Methods enum is usable from Python (0..3)")
names = [vtkPolyDataTangentFrames.GetMethodName(m) for m in range(4)]
check(len(set(names)) == 4 and all(names), "GetMethodName gives four names: " + ", ".join(names))
frames = vtkPolyDataTangentFrames()
check(frames.GetMethod() == vtkPolyDataTangentFrames.ANGLE_WEIGHTED, "default method AngleWeighted")
frames.SetMethodToMikkTSpace()
check(frames.GetMethod() == vtkPolyDataTangentFrames.MIKKTSPACE, "SetMethodToMikkTSpace()")
frames.SetTCoordsArrayName("UV")
check(frames.GetTCoordsArrayName() == "UV", "TCoordsArrayName round-trips a Python str")
check([vtkPolyDataTangentFrames.RECOMPUTE, vtkPolyDataTangentFrames.KEEP,
       vtkPolyDataTangentFrames.KEEP_VALID] == [0, 1, 2] and
      frames.GetSuppliedTangents() == vtkPolyDataTangentFrames.RECOMPUTE,
      "the SuppliedTangents enum is usable from Python, default RECOMPUTE")
frames.SetSuppliedTangentsToKeepValid()
frames.SetSuppliedTangentsArrayName("TANGENT")
check(frames.GetSuppliedTangents() == vtkPolyDataTangentFrames.KEEP_VALID and
      vtkPolyDataTangentFrames.GetSuppliedTangentsName(2) == "KeepValid" and
      frames.GetSuppliedTangentsArrayName() == "TANGENT" and
      frames.GetNumberOfReplacedTangents() == 0,
      "SetSuppliedTangentsToKeepValid(), its name, array name and counts are wrapped")
check(vtkPolyDataTangentFrames.TangentsArrayName() == "Tangents" and
      vtkPolyDataTangentFrames.SignsArrayName() == "TangentSigns",
      "the output array names are reachable")

# -------------------------------------------------------------- the frames, method by method
mesh = mirrored_height_field()
seam_points = ROWS + 1
for method in range(4):
    name = vtkPolyDataTangentFrames.GetMethodName(method)
    frames = vtkPolyDataTangentFrames()
    frames.SetInputData(mesh)
    frames.SetMethod(method)
    frames.ComputeBitangentsOn()
    messages = Messages(frames)
    frames.Update()
    out = frames.GetOutput()
    print(name + ": points %d -> %d, split %d, conflicts %d, degenerate %d, fallback %d" % (
        mesh.GetNumberOfPoints(), out.GetNumberOfPoints(), frames.GetNumberOfSplitPoints(),
        frames.GetNumberOfHandednessConflicts(), frames.GetNumberOfDegenerateTriangles(),
        frames.GetNumberOfFallbackPoints()))
    check(not messages.errors and not messages.warnings, name + ": no error or warning")

    # The counts. Every seam point has triangles of both handedness, so the weighted methods
    # split exactly those; MikkTSpace splits by its own welding rules, at least those.
    split = frames.GetNumberOfSplitPoints()
    if method == vtkPolyDataTangentFrames.MIKKTSPACE:
        check(split >= seam_points, name + ": split %d >= %d seam points" % (split, seam_points))
    else:
        check(split == seam_points, name + ": split %d == %d seam points" % (split, seam_points))
        check(frames.GetNumberOfHandednessConflicts() == seam_points,
              name + ": one handedness conflict per seam point")
    check(out.GetNumberOfPoints() == mesh.GetNumberOfPoints() + split,
          name + ": the split points are appended")
    check(frames.GetNumberOfDegenerateTriangles() == 0 and frames.GetNumberOfFallbackPoints() == 0
          and frames.GetNumberOfInvalidNormals() == 0, name + ": nothing degenerate on this mesh")

    pd = out.GetPointData()
    tangents = pd.GetTangents()
    signs = pd.GetArray("TangentSigns")
    bitangents = pd.GetArray("Bitangents")
    normals = pd.GetNormals()
    check(tangents is not None and tangents.GetName() == "Tangents" and signs is not None and
          bitangents is not None, name + ": Tangents (active), TangentSigns and Bitangents")
    if tangents is None or signs is None or bitangents is None:
        continue

    # Unit and perpendicular to the normal. The arrays are float: each component of T and N is
    # rounded to 2^-24 relative, which moves |T| - 1 and T.N by a few 1e-7 at most; 1e-6 leaves
    # a margin and still catches any frame that is not orthonormalized (errors ~1e-2 here).
    worst_length = max(abs(math.sqrt(dot(tangents.GetTuple3(p), tangents.GetTuple3(p))) - 1.0)
                       for p in range(out.GetNumberOfPoints()))
    worst_dot = max(abs(dot(tangents.GetTuple3(p), normals.GetTuple3(p)))
                    for p in range(out.GetNumberOfPoints()))
    check(worst_length < 1e-6, name + ": unit tangents (worst | |T| - 1 | = %.2g)" % worst_length)
    check(worst_dot < 1e-6, name + ": tangents perpendicular to the normals (worst |T.N| = %.2g)"
          % worst_dot)

    # Signs and directions, half by half: +1 and T.x > 0 right of the seam, -1 and T.x < 0 left
    # of it; the bitangent sign * cross(N, T) follows +v (+y) everywhere.
    points = out.GetPoints()
    wrong_side = 0
    bad_bitangent = 0
    for p in range(out.GetNumberOfPoints()):
        x = points.GetPoint(p)[0]
        s = signs.GetValue(p)
        t = tangents.GetTuple3(p)
        if x > 1e-9 and not (s == 1.0 and t[0] > 0.0):
            wrong_side += 1
        if x < -1e-9 and not (s == -1.0 and t[0] < 0.0):
            wrong_side += 1
        if not bitangents.GetTuple3(p)[1] > 0.0:
            bad_bitangent += 1
    check(wrong_side == 0, name + ": sign +1 on the right half, -1 on the mirrored half (%d wrong)"
          % wrong_side)
    check(bad_bitangent == 0, name + ": every bitangent points to +v (%d wrong)" % bad_bitangent)

    # Every triangle left of the seam uses only -1 points, right of it only +1 points: the seam
    # triangles were re-pointed to the copies.
    mixed = 0
    for c in range(out.GetNumberOfCells()):
        corners = [out.GetCell(c).GetPointId(k) for k in range(3)]
        centroid_x = sum(points.GetPoint(k)[0] for k in corners) / 3.0
        wanted = 1.0 if centroid_x > 0.0 else -1.0
        if any(signs.GetValue(k) != wanted for k in corners):
            mixed += 1
    check(mixed == 0, name + ": each triangle's corners share its half's sign (%d mixed)" % mixed)

# ------------------------------------------------------- bad input: an error, not a crash
bare = mirrored_height_field(with_tcoords=False)
frames = vtkPolyDataTangentFrames()
frames.SetInputData(bare)
messages = Messages(frames)
frames.Update()
out = frames.GetOutput()
print("no texture coordinates: errors %r" % messages.errors)
check(len(messages.errors) == 1 and "texture coordinates" in messages.errors[0].lower(),
      "no texture coordinates: one ErrorEvent that says so")
check(out.GetNumberOfPoints() == bare.GetNumberOfPoints() and
      out.GetPointData().GetArray("Tangents") is None,
      "no texture coordinates: the input passed through, no Tangents")

frames = vtkPolyDataTangentFrames()
frames.SetInputData(mesh)
frames.SetTCoordsArrayName("NoSuchArray")
messages = Messages(frames)
frames.Update()
print("unknown TCoordsArrayName: errors %r" % messages.errors)
check(len(messages.errors) == 1 and "NoSuchArray" in messages.errors[0],
      "an unknown TCoordsArrayName: one ErrorEvent naming it")

no_normals = mirrored_height_field(with_normals=False)
frames = vtkPolyDataTangentFrames()
frames.SetInputData(no_normals)
messages = Messages(frames)
frames.Update()
print("no normals: warnings %r" % messages.warnings)
check(not messages.errors and len(messages.warnings) == 1,
      "no normals: one WarningEvent and no error")
check(frames.GetOutput().GetPointData().GetNormals() is not None and
      frames.GetOutput().GetPointData().GetArray("Tangents") is not None,
      "no normals: normals computed, tangents written")

check.finish()
