#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Tangent frames and normal mapping from Python, with the vtknormalmapping package.

Builds a torus whose two halves use the same texture mirrored, computes its tangent frames with
vtkPolyDataTangentFrames (printing what the filter counted), makes a procedural normal map of
round studs, renders the torus offscreen with vtkNormalMapPolyDataMapper and writes a PNG.

    PYTHONPATH=<build>/lib/python3/dist-packages python3 tangent_frames.py -o torus.png

(or <prefix>/lib/python3/dist-packages after `cmake --install`). Debian's VTK renders through X:
without a display run it under `xvfb-run -a` or the project's Testing/Rendering/RunHeadless.sh.
"""
import argparse
import math
import os
import sys
import time

from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkCommonComputationalGeometry import vtkParametricTorus
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersSources import vtkParametricFunctionSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkRenderer, vtkRenderWindow,
                                         vtkTexture, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtknormalmapping import vtkNormalMapPolyDataMapper, vtkPolyDataTangentFrames


def mirrored_torus(ring_quads=192, tube_quads=64):
    """A torus with texture coordinates mirrored halfway round the ring: u runs 0 -> 4 over the
    first half and back 4 -> 0 over the second (four tiles each way), v 0 -> 2 round the tube.
    The source gives the first and last rows and columns points of their own (its Join options
    would only add zero-area triangles between them), so the mirror seam halfway round is the
    one whose points both sides share: those are the points the filter splits."""
    torus = vtkParametricTorus()
    torus.SetRingRadius(1.0)
    torus.SetCrossSectionRadius(0.35)
    torus.JoinUOff()
    torus.JoinVOff()
    source = vtkParametricFunctionSource()
    source.SetParametricFunction(torus)
    source.SetUResolution(ring_quads)
    source.SetVResolution(tube_quads)
    source.GenerateTextureCoordinatesOn()
    source.Update()
    mesh = source.GetOutput()
    uv = mesh.GetPointData().GetTCoords()
    for p in range(uv.GetNumberOfTuples()):
        s, t = uv.GetTuple2(p)
        uv.SetTuple2(p, 8.0 * min(s, 1.0 - s), 2.0 * t)
    return mesh


def stud_normal_map(size=256, studs=4, radius=0.36, height=0.05):
    """A tangent-space normal map (OpenGL convention, RGB = 255 (n + 1) / 2) of studs x studs
    round studs: a dome (1 - r^2) * height over each cell's centre, radius in cell units."""
    texels = vtkUnsignedCharArray()
    texels.SetNumberOfComponents(3)
    texels.SetNumberOfTuples(size * size)
    cell = size / studs
    for j in range(size):
        for i in range(size):
            # Position in the texel's cell, in cell units from its centre.
            x = ((i + 0.5) % cell) / cell - 0.5
            y = ((j + 0.5) % cell) / cell - 0.5
            r2 = (x * x + y * y) / (radius * radius)
            # Slope of h = height (1 - r^2) in texture units (one cell is 1 / studs of them).
            slope = -2.0 * height / (radius * radius) * studs if r2 < 1.0 else 0.0
            dhdu, dhdv = slope * x, slope * y
            length = math.sqrt(dhdu * dhdu + dhdv * dhdv + 1.0)
            n = (-dhdu / length, -dhdv / length, 1.0 / length)
            texels.SetTuple3(j * size + i, *(round(255.0 * (c + 1.0) / 2.0) for c in n))
    image = vtkImageData()
    image.SetDimensions(size, size, 1)
    image.GetPointData().SetScalars(texels)
    return image


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="tangent-frames.png", help="the PNG to write")
    parser.add_argument("--size", default="800x600", help="picture size, WxH")
    args = parser.parse_args()
    width, height = (int(n) for n in args.size.lower().split("x"))

    # 1. The mesh and its tangent frames.
    mesh = mirrored_torus()
    frames = vtkPolyDataTangentFrames()
    frames.SetInputData(mesh)
    frames.SetMethodToAngleWeighted()
    start = time.perf_counter()
    frames.Update()
    elapsed = 1000.0 * (time.perf_counter() - start)
    out = frames.GetOutput()
    print("tangent frames (%s), %.1f ms" % (
        vtkPolyDataTangentFrames.GetMethodName(frames.GetMethod()), elapsed))
    print("  points         %d in, %d out" % (mesh.GetNumberOfPoints(), out.GetNumberOfPoints()))
    print("  triangles      %d" % out.GetNumberOfPolys())
    print("  points split   %d (mirror seams)" % frames.GetNumberOfSplitPoints())
    print("  degenerate     %d triangles, %d fallback points" % (
        frames.GetNumberOfDegenerateTriangles(), frames.GetNumberOfFallbackPoints()))

    # 2. The picture. VTK 9.1 aborts when its X window finds no display: say so instead.
    window = vtkRenderWindow()
    if window.GetClassName() == "vtkXOpenGLRenderWindow" and not os.environ.get("DISPLAY"):
        print("error: this VTK renders through X and DISPLAY is not set (try xvfb-run -a)",
              file=sys.stderr)
        return 1
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    renderer = vtkRenderer()
    renderer.SetBackground(0.1, 0.1, 0.12)
    light = vtkLight()
    light.SetLightTypeToCameraLight()  # from the upper left of the viewer, turning with the camera
    light.SetPosition(-0.6, 0.8, 1.0)
    light.SetFocalPoint(0.0, 0.0, 0.0)
    renderer.AddLight(light)

    normal_map = vtkTexture()
    normal_map.SetInputData(stud_normal_map())
    normal_map.InterpolateOn()
    normal_map.MipmapOn()  # trilinear filtering where the map is minified
    normal_map.RepeatOn()
    mapper = vtkNormalMapPolyDataMapper()  # or vtkNormalMapObjectFactory.Install()
    mapper.SetInputData(out)
    actor = vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(0.85, 0.62, 0.48)
    prop.SetInterpolationToPhong()
    prop.SetSpecular(0.3)
    prop.SetSpecularPower(30.0)
    prop.SetNormalTexture(normal_map)
    prop.SetNormalScale(1.0)
    renderer.AddActor(actor)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0.0, -2.4, 2.6)
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetViewUp(0.0, 0.0, 1.0)
    renderer.ResetCamera()
    window.AddRenderer(renderer)
    window.Render()
    print("  rendered       %dx%d with %s, frame %s" % (
        width, height, mapper.GetClassName(),
        vtkNormalMapPolyDataMapper.GetAppliedFrameName(mapper.GetLastAppliedFrame())))

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(args.output)
    writer.Write()
    if writer.GetErrorCode() != 0:
        print("error: cannot write '%s'" % args.output, file=sys.stderr)
        return 1
    print("  wrote          " + os.path.abspath(args.output))
    return 0


if __name__ == "__main__":
    sys.exit(main())
