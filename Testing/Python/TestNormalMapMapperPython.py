# SPDX-License-Identifier: BSD-3-Clause
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

from vtkmodules.vtkRenderingCore import vtkPolyDataMapper

from vtknormalmapping import (vtkNormalMapObjectFactory, vtkNormalMapPolyDataMapper,
                              vtkPolyDataTangentFrames)

from normalmapping_testing import (Checks, constant_normal_map, half_values, needs_display,
                                   render_tilted_light, textured_mesh)

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


def render(mesh, mapper, texture, strength):
    """Renders the mesh with `mapper` under the light at angle B; the RGB pixels and more."""
    return render_tilted_light(mesh, mapper, texture, strength, B, WIDTH, HEIGHT)


needs_display()

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
        values = half_values(pixels, left, WIDTH, HEIGHT)
        worst = max(abs(v - expected) for v in values)
        check(worst <= 3.0, "%s, %s half: %d pixels %.0f..%.0f, expected %.1f (worst off by %.1f)"
              % (label, "mirrored left" if left else "right", len(values), min(values),
                 max(values), expected, worst))

# The map's effect, measured: every interior pixel brighter by 255 (cos(B - A) - cos B) = 66.
effect = [m - f for m, f in zip(half_values(mapped, True, WIDTH, HEIGHT) + half_values(mapped, False, WIDTH, HEIGHT),
                                half_values(flat, True, WIDTH, HEIGHT) + half_values(flat, False, WIDTH, HEIGHT))]
check(min(effect) >= 60, "the map brightens every interior pixel by %.0f..%.0f levels (expected "
      "%.1f)" % (min(effect), max(effect), expected_mapped - expected_flat))

check.finish()
