#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A glTF scene through VTK's own importer, drawn by the vtknormalmapping mappers.

vtkGLTFImporter makes its mappers with vtkPolyDataMapper(), so installing
vtkNormalMapObjectFactory first is all it takes: the importer's actors, materials and textures
stay as they are, and the normal maps are applied by vtkNormalMapPolyDataMapper. VTK's glTF
loader keeps three of TANGENT's four components; the mapper takes each triangle's handedness
from its texture coordinates, so mirrored UVs shade right where VTK's mapper inverts them.

    PYTHONPATH=<build>/lib/python3/dist-packages python3 view_gltf.py scene.gltf -o scene.png
    PYTHONPATH=<build>/lib/python3/dist-packages python3 view_gltf.py scene.gltf   # a window

Prints each normal-mapped actor's mapper and the frame it applied. --vtk draws with VTK's own
mapper instead, to compare. Debian's VTK renders through X: without a display run it under
`xvfb-run -a` or the project's Testing/Rendering/RunHeadless.sh.
"""
import argparse
import sys

from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOImport import vtkGLTFImporter
from vtkmodules.vtkRenderingCore import (vtkRenderer, vtkRenderWindow,
                                         vtkRenderWindowInteractor, vtkWindowToImageFilter)
import vtkmodules.vtkInteractionStyle  # noqa: F401 (the interactor's default style)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtknormalmapping import vtkNormalMapObjectFactory, vtkNormalMapPolyDataMapper


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("gltf", help="a .gltf or .glb file")
    parser.add_argument("-o", "--output", help="write a PNG offscreen instead of opening a window")
    parser.add_argument("--size", default="800x600", help="window size, WxH (default 800x600)")
    parser.add_argument("--vtk", action="store_true", help="draw with VTK's own mapper")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))

    if not args.vtk:
        vtkNormalMapObjectFactory.Install()  # before the importer makes its mappers

    window = vtkRenderWindow()
    window.SetSize(width, height)
    window.SetOffScreenRendering(args.output is not None)
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    importer = vtkGLTFImporter()
    importer.SetFileName(args.gltf)
    importer.SetRenderWindow(window)
    importer.Update()
    renderer.ResetCamera()
    window.Render()

    actors = renderer.GetActors()
    actors.InitTraversal()
    mapped = 0
    for _ in range(actors.GetNumberOfItems()):
        actor = actors.GetNextActor()
        if actor.GetProperty().GetTexture("normalTex") is None:
            continue
        mapped += 1
        mapper = actor.GetMapper()
        line = "normal-mapped actor %d: %s" % (mapped, mapper.GetClassName())
        if isinstance(mapper, vtkNormalMapPolyDataMapper):
            line += ", frame " + vtkNormalMapPolyDataMapper.GetAppliedFrameName(
                mapper.GetLastAppliedFrame())
        print(line)
    print("%d of %d actors have a normal map" % (mapped, actors.GetNumberOfItems()))

    if args.output:
        grab = vtkWindowToImageFilter()
        grab.SetInput(window)
        writer = vtkPNGWriter()
        writer.SetInputConnection(grab.GetOutputPort())
        writer.SetFileName(args.output)
        writer.Write()
        print("wrote", args.output)
    else:
        interactor = vtkRenderWindowInteractor()
        interactor.SetRenderWindow(window)
        interactor.Start()
    if not args.vtk:
        vtkNormalMapObjectFactory.Uninstall()
    return 0


if __name__ == "__main__":
    sys.exit(main())
