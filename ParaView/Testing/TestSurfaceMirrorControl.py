# SPDX-License-Identifier: BSD-3-Clause
"""The control of the mirror-symmetry check: ParaView's own Surface representation, normal
mapping with the Tangent Frames filter's tangents, shades the mirrored half wrong, and the
check sees it; without the normal map the same scene is symmetric, so what the check sees is
the normal mapping and not the scene.

pvbatch TestSurfaceMirrorControl.py <plugin.so> <work dir>
"""
from paraview.simple import *  # noqa: F401,F403

import nmparaview as nm

nm.load_plugin(globals())
check = nm.Checks()

reader = XMLPolyDataReader(FileName=[nm.write_mirrored_quads()])
frames = TangentFrames(Input=reader)
texture = CreateTexture(nm.write_rivets_map())
view = nm.mirror_view()

display = nm.show_mirrored(frames, view, "Surface")
nm.measure_symmetry(view, "ParaView's Surface, no normal map", check, True, "surface")

display.NormalTexture = texture
Render(view)
nm.measure_symmetry(
    view, "ParaView's Surface with the normal map", check, False, "surface-normal-map")

check.finish()
