# SPDX-License-Identifier: BSD-3-Clause
"""A glTF scene as `normalmap tangents scene.gltf -o scene.vtm` writes it for ParaView: ParaView
reads its block with the tool's arrays and texture file, and draws its normal map the way round it
draws the same quad stored the VTK way (v up).

pvbatch TestGltfSceneAsMultiblock.py <plugin.so> <work dir>, with the normalmap tool as
NORMALMAPPING_TOOL (scripts/paraview.sh passes the main build's); skipped (exit code 125)
without it.
"""
import os
import subprocess

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

import nmparaview as nm

TOOL = os.environ.get("NORMALMAPPING_TOOL", "")
if not os.access(TOOL, os.X_OK):
    print("SKIPPED: no normalmap tool (NORMALMAPPING_TOOL is '%s'): build the project first" % TOOL)
    os._exit(125)  # sys.exit would crash ParaView's teardown

nm.load_plugin(globals())
check = nm.Checks()
DATA = os.path.normpath(
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../Examples/normalmap/Testing/Data")
)

# The tool's unit quad: positions (0..1, 0..1, 0), normal +z, glTF's v-down UVs, a normal texture.
scene = os.path.join(nm.WORK, "scene.vtm")
subprocess.run([TOOL, "tangents", os.path.join(DATA, "quad.gltf"), "-o", scene], check=True)
reader = XMLMultiBlockDataReader(FileName=[scene])
reader.UpdatePipeline()
data = servermanager.Fetch(reader)
check(data.GetNumberOfBlocks() == 1, "one block for the glTF's one primitive")
block = data.GetBlock(0)
arrays = block.GetPointData()
for name in ("Normals", "Tangents", "TangentSigns", "TEXCOORD_0"):
    check(arrays.GetArray(name) is not None, "the block has " + name)
tcoords = arrays.GetTCoords()
check(tcoords is not None and tcoords.GetName() == "TEXCOORD_0", "TEXCOORD_0 is the active TCoords")
check(block.GetFieldData().GetArray("TCoordsVDown") is None, "no TCoordsVDown mark: v points up")
texture = block.GetFieldData().GetAbstractArray("NormalTextureFile").GetValue(0)
check(
    os.path.samefile(os.path.join(nm.WORK, texture), os.path.join(DATA, "quad_normal.png")),
    "NormalTextureFile (%s), relative to the .vtm, is the glTF's texture" % texture,
)

# Drawn with rivets (normals leaning towards +v on their top half) under a light from above
# (nm.mirror_view): the top of each rivet is lit where v points up, the bottom where it points
# down.
view = nm.mirror_view()
rivets = CreateTexture(nm.write_rivets_map())


def draw(source, name):
    display = nm.show_mirrored(source, view, "Normal Mapped Surface", rivets, "NormalMapTexture")
    # The unit quad fills most of the 320 x 160 view.
    view.CameraPosition = [0.5, 0.5, 2.2]
    view.CameraFocalPoint = [0.5, 0.5, 0.0]
    Render(view)
    pixels = nm.capture(view, name)[0]
    Hide(source, view)
    return pixels


from_vtm = draw(reader, "vtm")
# The reference: the same quad from a legacy VTK file with v-up UVs, framed in ParaView.
quad = LegacyVTKReader(FileNames=[os.path.join(DATA, "quad.vtk")])
reference = draw(TangentFrames(Input=quad), "vtk")
# The two quads differ only in their diagonal, across which their affine UVs, constant normals
# and tangents interpolate alike: 2 levels of rounding (the symmetry tests' bound) on all but
# 0.1% of the pixels.
agree, largest = nm.difference(from_vtm, reference, nm.SYMMETRY_BOUND)
print("the .vtm against the v-up quad: %.2f%% within %d levels, max %d"
      % (100 * agree, nm.SYMMETRY_BOUND, largest))
check(agree >= nm.SYMMETRIC_FRACTION, "the .vtm's map is drawn as the v-up quad's")

# The control: the block with v turned down again, as glTF stores it (written as a .vtp). The
# rivets then show their lit side at the bottom, so the comparison must fail.
down_block = vtkPolyData()
down_block.DeepCopy(block)
uv = down_block.GetPointData().GetArray("TEXCOORD_0")
for i in range(uv.GetNumberOfTuples()):
    uv.SetComponent(i, 1, 1.0 - uv.GetComponent(i, 1))
writer = vtkXMLPolyDataWriter()
writer.SetInputData(down_block)
writer.SetDataModeToBinary()  # inline arrays, as nm.write_mirrored_quads says why
writer.SetFileName(os.path.join(nm.WORK, "v_down.vtp"))
writer.Write()
down = XMLPolyDataReader(FileName=[os.path.join(nm.WORK, "v_down.vtp")])
from_down = draw(down, "vtm_v_down")
agree_down, _ = nm.difference(from_down, reference, nm.SYMMETRY_BOUND)
print("v down against the v-up quad: %.2f%% within %d levels" % (100 * agree_down, nm.SYMMETRY_BOUND))
check(agree_down < nm.ASYMMETRIC_FRACTION, "with v down, the map is drawn otherwise (the check can fail)")

check.finish()
