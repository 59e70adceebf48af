# SPDX-License-Identifier: BSD-3-Clause
"""VTK::NormalMapping for Python.

vtkPolyDataTangentFrames computes per-point tangent frames (tangents, handedness signs, optional
bitangents) from texture coordinates and normals, correct on mirrored UVs.
vtkNormalMapPolyDataMapper renders normal-mapped surfaces (the normal texture and strength come
from the actor's vtkProperty); vtkNormalMapObjectFactory.Install() makes every new
vtkPolyDataMapper one of them.

Importing this package imports the VTK modules it builds on (vtkmodules.vtkCommonCore,
vtkmodules.vtkRenderingOpenGL2, ...).
"""
from .vtkNormalMapping import *  # noqa: F401,F403 (the wrapped classes)
