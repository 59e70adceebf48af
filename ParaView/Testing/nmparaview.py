# SPDX-License-Identifier: BSD-3-Clause
"""Shared pieces of the plugin's pvbatch tests: the plugin, a mirrored test scene, pixel checks.

Every test runs as `pvbatch Test.py <plugin.so> <work dir> [<baseline dir>]`, under Xvfb. A
failing test raises (pvbatch then exits non-zero); sys.exit() would crash ParaView's teardown.
"""
import os
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

PLUGIN = sys.argv[1] if len(sys.argv) > 1 else ""
WORK = sys.argv[2] if len(sys.argv) > 2 else "."
BASELINES = sys.argv[3] if len(sys.argv) > 3 else ""


def load_plugin(namespace):
    """Loads the plugin into paraview.simple's namespace of the calling script."""
    if not os.path.exists(PLUGIN):
        raise RuntimeError("no plugin at '%s'" % PLUGIN)
    LoadPlugin(PLUGIN, ns=namespace)


class Checks:
    """Collects failed checks, prints every check, and raises at the end if any failed."""

    def __init__(self):
        self.failed = []

    def __call__(self, condition, what):
        print(("ok:     " if condition else "FAILED: ") + what)
        if not condition:
            self.failed.append(what)

    def finish(self):
        if self.failed:
            failed = "; ".join(self.failed)
            raise RuntimeError("%d check(s) failed: %s" % (len(self.failed), failed))
        print("all checks passed")


# ---------------------------------------------------------------- the mirrored quads
CELLS = 8  # grid cells along each side of each half


def mirrored_quads():
    """Two unit-UV halves that mirror each other about x = 0, sharing the seam's points.

    Left half: x in [-2, 0], u = (x + 2) / 2 (u grows with x). Right half: its mirror image,
    u = (2 - x) / 2 (u grows towards -x), so its texture is mirrored as on a symmetric model.
    The right triangles are the left ones mirrored, with their corners reordered so that both
    halves face +z. Point normals (0, 0, 1). A second UV set, "FlippedUV" = (1 - u, v), mirrors
    the handedness of every triangle.
    """
    n = CELLS
    points = vtkPoints()
    uv = vtkFloatArray()
    uv.SetName("UV")
    uv.SetNumberOfComponents(2)
    flipped = vtkFloatArray()
    flipped.SetName("FlippedUV")
    flipped.SetNumberOfComponents(2)
    normals = vtkFloatArray()
    normals.SetName("Normals")
    normals.SetNumberOfComponents(3)
    ids = {}

    def point(i, j, side):
        # i: column from the seam (0) outwards, j: row; the seam column is shared.
        key = (i, j, side if i else 0)
        if key not in ids:
            x = side * 2.0 * i / n
            y = -1.0 + 2.0 * j / n
            u = 1.0 - float(i) / n
            v = float(j) / n
            ids[key] = points.InsertNextPoint(x, y, 0.0)
            uv.InsertNextTuple2(u, v)
            flipped.InsertNextTuple2(1.0 - u, v)
            normals.InsertNextTuple3(0.0, 0.0, 1.0)
        return ids[key]

    triangles = vtkCellArray()
    for side in (-1, 1):
        for i in range(n):
            for j in range(n):
                a, b = point(i, j, side), point(i + 1, j, side)
                c, d = point(i + 1, j + 1, side), point(i, j + 1, side)
                for tri in ((a, b, c), (a, c, d)):
                    # Left (side -1) corners go outwards = towards -x: counter-clockwise seen
                    # from +z needs the reverse order there.
                    triangles.InsertNextCell(3, tri[::-1] if side < 0 else tri)
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(triangles)
    mesh.GetPointData().SetNormals(normals)
    mesh.GetPointData().SetTCoords(uv)
    mesh.GetPointData().AddArray(flipped)
    return mesh


SEAM_POINTS = CELLS + 1


def write_mirrored_quads():
    """mirrored.vtp in the work folder (a file, so that a saved state can reload it)."""
    path = os.path.join(WORK, "mirrored.vtp")
    writer = vtkXMLPolyDataWriter()
    writer.SetInputData(mirrored_quads())
    # Inline arrays: ParaView 5.11's reader fails on an appended data section with the libexpat1
    # of Debian bookworm's security updates (see the normalmap tool's WriteVTP).
    writer.SetDataModeToBinary()
    writer.SetFileName(path)
    writer.Write()
    return path


# ---------------------------------------------------------------- the normal map
def write_rivets_map(size=128, rivets=4):
    """rivets.png in the work folder: a tangent-space normal map (OpenGL convention) of
    rivets x rivets round bumps, whose normals lean along +u on their right and +v on top."""
    path = os.path.join(WORK, "rivets.png")
    pixels = bytearray()
    cell = size / rivets
    radius = 0.35 * cell
    for y in range(size):
        for x in range(size):
            dx = (x + 0.5) % cell - cell / 2
            dy = (y + 0.5) % cell - cell / 2
            r2 = dx * dx + dy * dy
            nx = ny = 0.0
            if r2 < radius * radius:
                # A paraboloid dome, height -(r^2) / (2 radius) * 1.5: its normal leans
                # outwards, (1.5 dx / radius, 1.5 dy / radius, 1) before normalization.
                nx, ny = 1.5 * dx / radius, 1.5 * dy / radius
            length = (nx * nx + ny * ny + 1.0) ** 0.5
            n = (nx / length, ny / length, 1.0 / length)
            pixels.extend(round(255 * (c + 1) / 2) for c in n)
    write_png(path, pixels, size, size)
    return path


# ---------------------------------------------------------------- pixels
def capture(view, name):
    """Saves the view's image as <work dir>/<name>.png; returns (RGB bytes, width, height)."""
    from paraview.simple import SaveScreenshot

    path = os.path.join(WORK, name + ".png")
    SaveScreenshot(path, view, ImageResolution=[WIDTH, HEIGHT])
    return read_png(path)


def read_png(path):
    """(RGB bytes, width, height) of a PNG file, rows bottom to top."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    channels = scalars.GetNumberOfComponents()
    raw = bytes(memoryview(scalars))
    if channels != 3:
        raw = bytes(b for i, b in enumerate(raw) if i % channels < 3)
    return raw, width, height


def write_png(path, pixels, width, height):
    """Writes RGB bytes, rows bottom to top, as a PNG file."""
    array = vtkUnsignedCharArray()
    array.SetNumberOfComponents(3)
    array.SetNumberOfTuples(width * height)
    for i, b in enumerate(pixels):
        array.SetValue(i, b)
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()


def symmetry(pixels, width, height, bound):
    """How mirror-symmetric an image is about its middle column, as in the mapper test
    Testing/Rendering/TestNormalMapMirrorSymmetry.cxx: over pixels covered on both sides, at
    least 3 pixels away from the middle seam and from uncovered pixels (there the rasterizer's
    fill rule decides, not shading), the fraction whose channels all agree with the mirrored
    pixel within `bound` levels. Returns (pixels compared, that fraction, largest difference)."""
    def covered(x, y):
        p = 3 * (y * width + x)
        q = 3 * (y * width + width - 1 - x)
        return pixels[p] > 0 and pixels[q] > 0 and abs(2 * x + 1 - width) > 6

    mask = [[covered(x, y) for x in range(width)] for y in range(height)]
    compared = within = largest = 0
    for y in range(3, height - 3):
        for x in range(3, width - 3):
            if not all(mask[y][x + d] and mask[y + d][x] for d in range(-3, 4)):
                continue
            p = 3 * (y * width + x)
            q = 3 * (y * width + width - 1 - x)
            diff = max(abs(pixels[p + c] - pixels[q + c]) for c in range(3))
            compared += 1
            within += diff <= bound
            largest = max(largest, diff)
    return compared, (within / compared if compared else 0.0), largest


def difference(pixels, other, bound):
    """Fraction of pixels whose channels all agree within `bound` levels, and the largest
    channel difference; images of different sizes do not agree at all."""
    if len(pixels) != len(other):
        return 0.0, 255
    within = largest = 0
    for i in range(0, len(pixels), 3):
        diff = max(abs(pixels[i + c] - other[i + c]) for c in range(3))
        within += diff <= bound
        largest = max(largest, diff)
    return within / (len(pixels) // 3), largest


# ---------------------------------------------------------------- the mirror scene
# A quad and its mirror image under a light on the mirror plane (x = 0), as in the mapper test
# TestNormalMapMirrorSymmetry.cxx: right shading renders them as mirror images of each other.
WIDTH, HEIGHT = 320, 160
# Mirror images agree up to rasterization and float rounding of the interpolated texture
# coordinates on each side: 2 levels (the mapper test's bound), on all but 0.1% of the pixels.
SYMMETRY_BOUND = 2
SYMMETRIC_FRACTION = 0.999
# A wrong bitangent on the mirrored half turns its rivets' lit side from top to bottom: far
# from symmetric. The mapper test measures VTK's own mapper below 95%; so must ParaView's.
ASYMMETRIC_FRACTION = 0.95


def mirror_view():
    """A 320 x 160 view of both halves, lit only by a directional light from (0, 1.5, 2)."""
    from paraview import simple

    simple._DisableFirstRenderCameraReset()  # the camera is set, not fitted to the data
    view = simple.CreateRenderView()
    view.ViewSize = [WIDTH, HEIGHT]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    light_on_mirror_plane(view)
    return view


def light_on_mirror_plane(view):
    """The view's only light: directional, from (0, 1.5, 2) towards the origin."""
    from paraview import simple

    view.UseLight = 0  # no light kit: its key and fill lights are off the mirror plane
    light = simple.AddLight(view=view)
    light.Coords = "Scene"
    light.Type = "Directional"
    light.Position = [0.0, 1.5, 2.0]
    light.FocalPoint = [0.0, 0.0, 0.0]


def show_mirrored(source, view, representation, texture=None, texture_property="NormalTexture"):
    """Shows `source` white and unlit by colour maps, with `texture` as its normal map."""
    from paraview.simple import ColorBy, Render, Show

    display = Show(source, view)
    display.Representation = representation
    ColorBy(display, ("POINTS", None))
    display.AmbientColor = [1.0, 1.0, 1.0]
    display.DiffuseColor = [1.0, 1.0, 1.0]
    display.Interpolation = "Gouraud"
    if texture is not None:
        setattr(display, texture_property, texture)
    # After Show, which resets the camera of an empty view. The halves fill 4 / 4.9 of the
    # view's width and 2 / 2.5 of its height.
    view.CameraPosition = [0.0, 0.0, 4.6]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = 30.0
    Render(view)
    return display


def measure_symmetry(view, name, check, symmetric, image):
    """Checks that the view's image is (or, for a control, is not) mirror-symmetric; saves it
    as <work dir>/<image>.png."""
    pixels, width, height = capture(view, image)
    compared, fraction, largest = symmetry(pixels, width, height, SYMMETRY_BOUND)
    print("%s: %d pixels, %.2f%% symmetric within %d levels, max difference %d"
          % (name, compared, 100.0 * fraction, SYMMETRY_BOUND, largest))
    # Both halves cover most of the view (a third of its pixels at least).
    check(compared > WIDTH * HEIGHT // 3, name + ": both halves cover the view")
    if symmetric:
        check(fraction >= SYMMETRIC_FRACTION, name + ": is mirror-symmetric")
    else:
        check(fraction < ASYMMETRIC_FRACTION, name + ": is not mirror-symmetric")
    return pixels, width, height


# ---------------------------------------------------------------- saved states
def save_and_reload(view, name, source_name):
    """Captures the view, saves the session's state as <work dir>/<name>.pvsm, resets the session
    and loads the state back. Returns the image before, the reloaded render view, and the
    display of the source registered as `source_name` in it."""
    from paraview import simple

    before, _, _ = capture(view, "before-state")
    state = os.path.join(WORK, name + ".pvsm")
    simple.SaveState(state)
    simple.ResetSession()
    simple.LoadState(state)
    reloaded_view = simple.GetActiveViewOrCreate("RenderView")
    return before, reloaded_view, simple.GetDisplayProperties(simple.FindSource(source_name),
                                                              reloaded_view)


def check_reloaded_image(view, before, check, same_fraction):
    """Checks that the reloaded view renders the image saved before (save_and_reload): the same
    process and renderer, so within 1 level on at least `same_fraction` of the pixels."""
    from paraview.simple import Render

    Render(view)
    after, _, _ = capture(view, "after-state")
    fraction, largest = difference(after, before, 1)
    print("reloaded state: %.3f%% within 1 level, max difference %d" % (100 * fraction, largest))
    check(fraction >= same_fraction, "the reloaded state renders the same image")
