"""The picture docs/paraview.png: ParaView's window with the plugin loaded (PV_PLUGIN_PATH, as a
user would), the mirrored quads through Tangent Frames, shown as a Normal Mapped Surface.

Run by `scripts/paraview.sh screenshot`: paraview --script=GuiScreenshot.py, with
NORMALMAPPING_WORK naming a work folder; the script writes <work>/ready when the scene is set.
"""
import os
import sys

work = os.environ["NORMALMAPPING_WORK"]
sys.argv = ["GuiScreenshot.py", "", work]  # nmparaview's arguments: no plugin file, the work dir
import nmparaview as nm  # noqa: E402
from paraview.simple import *  # noqa: E402,F401,F403

reader = XMLPolyDataReader(registrationName="mirrored.vtp", FileName=[nm.write_mirrored_quads()])
reader.UpdatePipeline()
frames = TangentFrames(registrationName="TangentFrames1", Input=reader)
view = GetActiveViewOrCreate("RenderView")
display = Show(frames, view)
display.Representation = "Normal Mapped Surface"
ColorBy(display, ("POINTS", None))
display.NormalTexture = CreateTexture(nm.write_rivets_map())
view.OrientationAxesVisibility = 1
view.CameraPosition = [1.2, -3.2, 3.4]
view.CameraFocalPoint = [0.0, 0.0, 0.0]
view.CameraViewUp = [0.0, 0.7, 0.7]
SetActiveSource(frames)
Render(view)
open(os.path.join(work, "ready"), "w").close()
