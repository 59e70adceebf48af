"""vtkNormalMapPolyDataMapper from Python, offscreen (ctest NormalMappingPython.Mapper, under
Testing/Rendering/RunHeadless.sh).

The scene is chosen so the right answer is known in closed form. A flat quad in z = 0 has two
halves whose texture is mirrored at x = 0 (u = |x|, v = y + 1/2); the frames come from the
wrapped vtkPolyDataTangentFrames (sign +1 right, -1 left). The normal map is one constant
tangent-space normal tilted by A = 30 degrees towards +v: n = (0, sin A, cos A). With the
bitangent sign handled, both halves get the same perturbed normal (0, sin A, cos A), since +v is
+y on both. One directional light shines from (0, sin B, cos B), B = 45 degrees, on a white
surface with diffuse 1 and no ambient or specular, so a pixel is 255 N.L:
  map applied, signs right: 255 cos(B - A) = 246.3 on both halves;
  strength 0 (no map):      255 cos B       = 180.3;
  a sign ignored on the mirrored half: 255 cos(B + A) = 66.0 there.
"""
import math
import os
import sys

from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTexture, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (VTK's OpenGL classes and factory)

from vtknormalmapping import (vtkNormalMapObjectFactory, vtkNormalMapPolyDataMapper,
                              vtkPolyDataTangentFrames)

from normalmapping_testing import Checks, textured_mesh

WIDTH, HEIGHT = 200, 100
A = math.radians(30.0)
B = math.radians(45.0)
check = Checks()


def mirrored_quad():
    """Two unit quads side by side, x in [-1, 1], y in [-1/2, 1/2], texture mirrored at x = 0."""
    xy = [(x, y) for y in (-0.5, 0.5) for x in (-1.0, 0.0, 1.0)]
    # The left and right quads: corners a, a+1, a+4, a+3.
    triangles = [t for a in (0, 1) for t in ((a, a + 1, a + 4), (a, a + 4, a + 3))]
    return textured_mesh([(x, y, 0.0) for x, y in xy], [(0.0, 0.0, 1.0)] * len(xy),
                         [(abs(x), y + 0.5) for x, y in xy], triangles)


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


def render(mesh, mapper, texture, strength):
    """Renders the mesh with `mapper` and returns the RGB pixels (bottom row first)."""
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)  # one sample per pixel: pixels are the shading itself
    window.SetSize(WIDTH, HEIGHT)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.AutomaticLightCreationOff()
    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(False)
    light.SetPosition(0.0, math.sin(B), math.cos(B))
    light.SetFocalPoint(0.0, 0.0, 0.0)
    renderer.AddLight(light)
    mapper.SetInputData(mesh)
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


def half_values(pixels, left):
    """Red channel of the pixels well inside one half (20 pixels away from the seam and the
    borders, where every pixel is a whole sample of that half's interior)."""
    x0 = 20 if left else WIDTH // 2 + 20
    values = []
    for y in range(20, HEIGHT - 20):
        for x in range(x0, x0 + WIDTH // 2 - 40):
            values.append(pixels.GetComponent(y * WIDTH + x, 0))
    return values


# The window needs an X display with Debian's VTK (no OSMesa); VTK 9.1 aborts without one.
if vtkRenderWindow().GetClassName() == "vtkXOpenGLRenderWindow" and not os.environ.get("DISPLAY"):
    print("SKIPPED: this VTK renders through X and DISPLAY is not set "
          "(run under Testing/Rendering/RunHeadless.sh)")
    sys.exit(125)

frames = vtkPolyDataTangentFrames()
frames.SetInputData(mirrored_quad())
frames.Update()
mesh = frames.GetOutput()
check(frames.GetNumberOfSplitPoints() == 2, "the filter split the 2 seam points")
tilted = constant_normal_map((0.0, math.sin(A), math.cos(A)))

# The factory: after Install(), vtkPolyDataMapper() makes our mapper; Uninstall() restores VTK's.
check(vtkPolyDataMapper().GetClassName() != "vtkNormalMapPolyDataMapper",
      "before Install(): vtkPolyDataMapper() is VTK's (%s)" % vtkPolyDataMapper().GetClassName())
vtkNormalMapObjectFactory.Install()
check(vtkNormalMapObjectFactory.IsInstalled(), "vtkNormalMapObjectFactory.IsInstalled()")
mapper = vtkPolyDataMapper()
check(mapper.GetClassName() == "vtkNormalMapPolyDataMapper",
      "after Install(): vtkPolyDataMapper() is a %s" % mapper.GetClassName())
check(mapper.GetFrameSource() == vtkNormalMapPolyDataMapper.AUTOMATIC and
      mapper.GetMapEncoding() == vtkNormalMapPolyDataMapper.TANGENT_SPACE_OPENGL,
      "the enums are usable from Python (defaults AUTOMATIC, TANGENT_SPACE_OPENGL)")

mapped, window_class, gl_renderer = render(mesh, mapper, tilted, 1.0)
print("Rendering path: %s, %s; %s" % (
    os.environ.get("NORMALMAPPING_HEADLESS_PATH", "display " + os.environ.get("DISPLAY", "?")),
    window_class, gl_renderer))
applied = mapper.GetLastAppliedFrame()
check(applied == vtkNormalMapPolyDataMapper.APPLIED_POINT_TANGENTS,
      "the mapper applied the map with point tangents and signs (%s)"
      % vtkNormalMapPolyDataMapper.GetAppliedFrameName(applied))

flat_mapper = vtkPolyDataMapper()
flat, _, _ = render(mesh, flat_mapper, tilted, 0.0)
vtkNormalMapObjectFactory.Uninstall()
check(not vtkNormalMapObjectFactory.IsInstalled() and
      vtkPolyDataMapper().GetClassName() != "vtkNormalMapPolyDataMapper",
      "after Uninstall(): VTK's mapper again")

derivatives_mapper = vtkNormalMapPolyDataMapper()
derivatives_mapper.SetFrameSource(vtkNormalMapPolyDataMapper.SCREEN_DERIVATIVES)
derivatives, _, _ = render(mesh, derivatives_mapper, tilted, 1.0)
check(derivatives_mapper.GetLastAppliedFrame() == vtkNormalMapPolyDataMapper.APPLIED_DERIVATIVES,
      "SetFrameSource(SCREEN_DERIVATIVES) applied derivatives")

# Bound: 3 of 255 levels. The map stores the normal in 8 bits, which moves N.L by < 0.001
# (0.3 level) here; the framebuffer rounds to 0.5 level; llvmpipe's float shading adds a level
# at most. A missing map (180) or an ignored sign (66) is 60+ levels away.
expected_mapped = 255.0 * math.cos(B - A)
expected_flat = 255.0 * math.cos(B)
for label, pixels, expected in (("map, point tangents", mapped, expected_mapped),
                                ("map, derivatives", derivatives, expected_mapped),
                                ("strength 0", flat, expected_flat)):
    for left in (True, False):
        values = half_values(pixels, left)
        worst = max(abs(v - expected) for v in values)
        check(worst <= 3.0, "%s, %s half: %d pixels %.0f..%.0f, expected %.1f (worst off by %.1f)"
              % (label, "mirrored left" if left else "right", len(values), min(values),
                 max(values), expected, worst))

# The map's effect, measured: every interior pixel brighter by 255 (cos(B - A) - cos B) = 66.
effect = [m - f for m, f in zip(half_values(mapped, True) + half_values(mapped, False),
                                half_values(flat, True) + half_values(flat, False))]
check(min(effect) >= 60, "the map brightens every interior pixel by %.0f..%.0f levels (expected "
      "%.1f)" % (min(effect), max(effect), expected_mapped - expected_flat))

check.finish()
