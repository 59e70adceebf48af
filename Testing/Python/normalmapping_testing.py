# SPDX-License-Identifier: BSD-3-Clause
"""Helpers of the Python tests: a checklist that reports every check, textured polydata, and
offscreen renders of flat scenes whose pixel values are known in closed form."""
import math
import os
import sys

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkPolyData
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkRenderer, vtkRenderWindow,
                                         vtkTexture, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (VTK's OpenGL classes and factory)


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


def constant_normal_map(normal, size=8):
    """An RGB texture holding one tangent-space normal, encoded as 255 (n + 1) / 2."""
    rgb = [int(round(255.0 * (c + 1.0) / 2.0)) for c in normal]
    texels = vtkUnsignedCharArray()
    texels.SetNumberOfComponents(3)
    texels.SetNumberOfTuples(size * size)
    for t in range(size * size):
        texels.SetTuple3(t, *rgb)
    image = vtkImageData()
    image.SetDimensions(size, size, 1)
    image.GetPointData().SetScalars(texels)
    texture = vtkTexture()
    texture.SetInputData(image)
    texture.InterpolateOn()
    return texture


def render_tilted_light(data, mapper, texture, strength, light_angle, width, height):
    """Renders `data` (polydata or multiblock) with `mapper`: a white, purely diffuse surface
    seen from +z with parallel projection (y in [-1/2, 1/2] fills the height), lit by one
    directional light from (0, sin(light_angle), cos(light_angle)). Returns the RGB pixels
    (bottom row first), the window's class name and the OpenGL renderer string."""
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)  # one sample per pixel: pixels are the shading itself
    window.SetSize(width, height)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AutomaticLightCreationOff()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(0.0, math.sin(light_angle), math.cos(light_angle))
    light.SetFocalPoint(0.0, 0.0, 0.0)
    renderer.AddLight(light)
    mapper.SetInputDataObject(0, data)
    actor = vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(1.0, 1.0, 1.0)
    prop.SetAmbient(0.0)
    prop.SetDiffuse(1.0)
    prop.SetSpecular(0.0)
    prop.SetNormalTexture(texture)
    prop.SetNormalScale(strength)
    renderer.AddActor(actor)
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    camera.SetPosition(0.0, 0.0, 5.0)
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetParallelScale(0.5)  # the window shows y in [-1/2, 1/2], x in [-1, 1]
    renderer.ResetCameraClippingRange()
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.Update()
    pixels = grab.GetOutput().GetPointData().GetScalars()
    info = window.ReportCapabilities()
    renderer_line = [l for l in info.splitlines() if "OpenGL renderer string" in l]
    window.Finalize()
    return pixels, window.GetClassName(), (renderer_line[0].split(":", 1)[1].strip()
                                           if renderer_line else "unknown")


def half_values(pixels, left, width, height):
    """Red channel of the pixels well inside the left or right half of the image (20 pixels
    away from the middle and the borders, where every pixel is a whole sample of that half's
    interior)."""
    x0 = 20 if left else width // 2 + 20
    values = []
    for y in range(20, height - 20):
        for x in range(x0, x0 + width // 2 - 40):
            values.append(pixels.GetComponent(y * width + x, 0))
    return values


def needs_display():
    """Exits with the skip code when the window needs an X display and there is none (Debian's
    VTK has no OSMesa; VTK 9.1 aborts without a display)."""
    if (vtkRenderWindow().GetClassName() == "vtkXOpenGLRenderWindow" and
            not os.environ.get("DISPLAY")):
        print("SKIPPED: this VTK renders through X and DISPLAY is not set "
              "(run under Testing/Rendering/RunHeadless.sh)")
        sys.exit(125)
