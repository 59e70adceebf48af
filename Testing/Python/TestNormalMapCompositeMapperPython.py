# SPDX-License-Identifier: BSD-3-Clause
"""vtkNormalMapCompositePolyDataMapper from Python, offscreen (ctest
NormalMappingPython.CompositeMapper, under Testing/Rendering/RunHeadless.sh).

The closed-form scene of TestNormalMapMapperPython.py (see there) split into blocks of a
vtkMultiBlockDataSet: block 1 is the mirrored left half (u = -x) with tangents and signs from
vtkPolyDataTangentFrames (sign -1), block 2 the right half (u = x) without tangents (its frame
comes from screen-space derivatives), block 3 a quad without texture coordinates outside the
view. A constant map tilted by A = 30 degrees towards +v, a light at B = 45 degrees:
  map applied, signs right: 255 cos(B - A) = 246.3 on both halves;
  strength 0 (no map):      255 cos B       = 180.3;
  a sign ignored on the mirrored half: 255 cos(B + A) = 66.0 there (VTK's composite mapper).
"""
import math

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkObjectFactory
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet

from vtknormalmapping import (vtkNormalMapCompositePolyDataMapper, vtkNormalMapObjectFactory,
                              vtkNormalMapPolyDataMapper, vtkPolyDataTangentFrames)

from normalmapping_testing import (Checks, constant_normal_map, half_values, needs_display,
                                   render_tilted_light, textured_mesh)

WIDTH, HEIGHT = 200, 100
A = math.radians(30.0)
B = math.radians(45.0)
check = Checks()
# VTK's own composite mapper, the superclass of ours: vtkCompositePolyDataMapper2 up to VTK 9.2,
# vtkCompositePolyDataMapper from 9.3.
StockMapper = vtkNormalMapCompositePolyDataMapper.__bases__[0]


def unit_quad(x0, y0, with_uvs=True):
    """A unit quad [x0, x0 + 1] x [y0, y0 + 1] with normals +z and u = |x|, v = y + 1/2."""
    xy = [(x0, y0), (x0 + 1.0, y0), (x0 + 1.0, y0 + 1.0), (x0, y0 + 1.0)]
    return textured_mesh([(x, y, 0.0) for x, y in xy], [(0.0, 0.0, 1.0)] * 4,
                         [(abs(x), y + 0.5) for x, y in xy] if with_uvs else None,
                         [(0, 1, 2), (0, 2, 3)])


def with_tangents(mesh):
    frames = vtkPolyDataTangentFrames()
    frames.SetInputData(mesh)
    frames.Update()
    return frames.GetOutput()


def blocks(right_tangents):
    data = vtkMultiBlockDataSet()
    right = unit_quad(0.0, -0.5)
    data.SetBlock(0, with_tangents(unit_quad(-1.0, -0.5)))
    data.SetBlock(1, with_tangents(right) if right_tangents else right)
    data.SetBlock(2, unit_quad(-0.5, 2.0, with_uvs=False))
    return data


def render(data, mapper, texture, strength):
    return render_tilted_light(data, mapper, texture, strength, B, WIDTH, HEIGHT)[0]


needs_display()
tilted = constant_normal_map((0.0, math.sin(A), math.cos(A)))

warnings = []


@calldata_type(VTK_STRING)
def on_warning(caller, event, message):
    warnings.append(message)


mapper = vtkNormalMapCompositePolyDataMapper()
mapper.AddObserver("WarningEvent", on_warning)
check(mapper.GetFrameSource() == vtkNormalMapPolyDataMapper.AUTOMATIC,
      "the settings take vtkNormalMapPolyDataMapper's enums (default AUTOMATIC)")
mapped = render(blocks(False), mapper, tilted, 1.0)
frames = [mapper.GetLastAppliedFrame(i) for i in (1, 2, 3)]
check(frames == [vtkNormalMapPolyDataMapper.APPLIED_POINT_TANGENTS,
                 vtkNormalMapPolyDataMapper.APPLIED_DERIVATIVES,
                 vtkNormalMapPolyDataMapper.NOT_APPLIED],
      "per-block frames: %s" % [vtkNormalMapPolyDataMapper.GetAppliedFrameName(f)
                                for f in frames])
check(any("Block 3: The normal texture is not applied" in w for w in warnings),
      "the block without texture coordinates is named in a warning (%d warning(s))"
      % len(warnings))
flat = render(blocks(False), vtkNormalMapCompositePolyDataMapper(), tilted, 0.0)
stock = render(blocks(True), StockMapper(), tilted, 1.0)

# Bound: 3 of 255 levels, as in TestNormalMapMapperPython.py (8-bit map, framebuffer rounding,
# llvmpipe's float shading). A missing map (180) or an ignored sign (66) is 60+ levels away.
for label, pixels, expected in (("map", mapped, 255.0 * math.cos(B - A)),
                                ("strength 0", flat, 255.0 * math.cos(B))):
    for left in (True, False):
        values = half_values(pixels, left, WIDTH, HEIGHT)
        worst = max(abs(v - expected) for v in values)
        check(worst <= 3.0, "%s, %s: %d pixels %.0f..%.0f, expected %.1f (worst off by %.1f)"
              % (label, "block 1 (mirrored, tangents)" if left else "block 2 (derivatives)",
                 len(values), min(values), max(values), expected, worst))

# The control: VTK's composite mapper ignores the sign of the mirrored block.
values = half_values(stock, True, WIDTH, HEIGHT)
worst = max(abs(v - 255.0 * math.cos(B - A)) for v in values)
check(worst > 30.0, "VTK's %s fails the same check on the mirrored block (%.0f..%.0f, off by %.0f)"
      % (StockMapper.__name__, min(values), max(values), worst))

# The factory: Install() registers the override, which creation by class name reaches.
vtkNormalMapObjectFactory.Install()
created = vtkObjectFactory.CreateInstance(StockMapper.__name__)
check(created is not None and created.GetClassName() == "vtkNormalMapCompositePolyDataMapper",
      "after Install(): the factory creates %s" % (created.GetClassName() if created else None))
vtkNormalMapObjectFactory.Uninstall()

check.finish()
