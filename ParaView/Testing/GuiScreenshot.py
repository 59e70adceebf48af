# SPDX-License-Identifier: BSD-3-Clause
"""The picture docs/paraview.png: ParaView's window with the plugin loaded (PV_PLUGIN_PATH, as a
user would), the mirrored quads through Tangent Frames, shown as a Normal Mapped Surface (top)
and, for comparison, as ParaView's own Surface with the same normal texture (bottom), where the
mirrored right half's rivets are lit from the wrong side. The light is the tests' own.

Run by `scripts/paraview.sh screenshot`: paraview --script=GuiScreenshot.py, with
NORMALMAPPING_WORK naming a work folder; the script writes <work>/ready when the scene is set.
"""
import os
import sys

work = os.environ["NORMALMAPPING_WORK"]
sys.argv = ["GuiScreenshot.py", "", work]  # nmparaview's arguments: no plugin file, the work dir
import nmparaview as nm  # noqa: E402
from paraview import simple  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

simple._DisableFirstRenderCameraReset()  # the cameras are set, not fitted to the data

reader = XMLPolyDataReader(registrationName="mirrored.vtp", FileName=[nm.write_mirrored_quads()])
reader.UpdatePipeline()
frames = TangentFrames(registrationName="TangentFrames1", Input=reader)
texture = CreateTexture(nm.write_rivets_map())

ours = GetActiveViewOrCreate("RenderView")
layout = GetLayout(ours)
layout.SplitVertical(0, 0.5)
theirs = CreateView("RenderView")
AssignViewToLayout(view=theirs, layout=layout, hint=2)

for view, representation in ((ours, "Normal Mapped Surface"), (theirs, "Surface")):
    display = Show(frames, view)
    display.Representation = representation
    ColorBy(display, ("POINTS", None))
    display.NormalTexture = texture
    title = Text(Text=representation if view is ours else "ParaView's own Surface")
    Show(title, view).FontSize = 20
    view.OrientationAxesVisibility = 0
    nm.light_on_mirror_plane(view)  # as in the tests: the light shows which way rivets lean
    view.CameraPosition = [0.0, -1.0, 4.6]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.2]
    view.CameraViewAngle = 30.0
    Render(view)
SetActiveView(ours)
SetActiveSource(frames)
open(os.path.join(work, "ready"), "w").close()
