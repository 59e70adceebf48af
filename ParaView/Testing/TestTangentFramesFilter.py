# SPDX-License-Identifier: BSD-3-Clause
"""The Tangent Frames filter in ParaView: every setting reaches vtkPolyDataTangentFrames, and its
arrays and counts on a mirrored mesh are those of the mirror seam, it takes 3-component texture
coordinates named from Python and multiblocks with blocks of other types.

pvbatch TestTangentFramesFilter.py <plugin.so> <work dir>
"""
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet, vtkUnstructuredGrid

import nmparaview as nm

nm.load_plugin(globals())
check = nm.Checks()

reader = XMLPolyDataReader(FileName=[nm.write_mirrored_quads()])
reader.UpdatePipeline()
frames = TangentFrames(Input=reader)
check(frames.TextureCoordinates == "UV", "the texture coordinates default to the active ones")
check(
    frames.GetProperty("TextureCoordinates").SMProperty.GetDomain("array_list").GetNumberOfStrings()
    >= 2,
    "the texture coordinates are chosen from the input's point arrays",
)


def run():
    """Executes the filter; returns its output and its counts."""
    frames.UpdatePipeline()
    frames.UpdatePropertyInformation()
    counts = {
        name: frames.GetPropertyValue(name)
        for name in (
            "NumberOfSplitPoints",
            "NumberOfHandednessConflicts",
            "NumberOfDegenerateTriangles",
            "NumberOfFallbackPoints",
            "NumberOfInvalidNormals",
        )
    }
    return servermanager.Fetch(frames), counts


def signs_by_side(mesh):
    """The sets of TangentSigns values of the points left and right of the seam (x = 0)."""
    signs = mesh.GetPointData().GetArray("TangentSigns")
    left, right = set(), set()
    for i in range(mesh.GetNumberOfPoints()):
        x = mesh.GetPoint(i)[0]
        if x < -1e-6:
            left.add(signs.GetValue(i))
        elif x > 1e-6:
            right.add(signs.GetValue(i))
    return left, right


input_points = reader.GetDataInformation().GetNumberOfPoints()
mesh, counts = run()
print("default settings:", counts)
arrays = mesh.GetPointData()
tangents = arrays.GetArray("Tangents")
check(tangents is not None and tangents.GetNumberOfComponents() == 3, "Tangents: 3 components")
check(arrays.GetTangents() is tangents, "Tangents is the active tangent attribute")
check(tangents is not None and tangents.GetDataTypeAsString() == "float",
      "float points give float arrays")
# Every tangent points along dP/du: +x on the left half, -x on the right (exact: the mesh is
# planar with axis-aligned UVs, so 1e-5 is float rounding).
along_u = all(
    abs(tangents.GetTuple3(i)[0] - (1.0 if mesh.GetPoint(i)[0] < 0 or (
        mesh.GetPoint(i)[0] == 0 and arrays.GetArray("TangentSigns").GetValue(i) > 0) else -1.0))
    < 1e-5
    for i in range(mesh.GetNumberOfPoints())
)
check(along_u, "tangents point along +u: +x on the left half, -x on the mirrored right half")
check(signs_by_side(mesh) == ({1.0}, {-1.0}), "signs: +1 on the left half, -1 on the mirrored one")
check(counts["NumberOfHandednessConflicts"] == nm.SEAM_POINTS,
      "every seam point is a handedness conflict (%d)" % nm.SEAM_POINTS)
check(counts["NumberOfSplitPoints"] == nm.SEAM_POINTS, "every seam point is split")
check(mesh.GetNumberOfPoints() == input_points + nm.SEAM_POINTS,
      "the split copies are appended to the points")
check(counts["NumberOfDegenerateTriangles"] == 0 and counts["NumberOfFallbackPoints"] == 0
      and counts["NumberOfInvalidNormals"] == 0, "no degenerate triangles, fallbacks, bad normals")
check(arrays.GetArray("Bitangents") is None and mesh.GetCellData().GetArray("Tangents") is None,
      "no bitangents or cell tangents unless asked")

frames.Splitting = 0
mesh, counts = run()
check(counts["NumberOfSplitPoints"] == 0 and mesh.GetNumberOfPoints() == input_points,
      "Splitting off: no point is added")
check(counts["NumberOfHandednessConflicts"] == nm.SEAM_POINTS,
      "Splitting off: the seam points are still counted as conflicts")
frames.Splitting = 1

frames.TextureCoordinates = "FlippedUV"
mesh, _ = run()
check(signs_by_side(mesh) == ({-1.0}, {1.0}),
      "the chosen texture coordinates are used: FlippedUV mirrors every sign")
frames.TextureCoordinates = "UV"

frames.ComputeBitangents = 1
frames.ComputeCellTangents = 1
frames.OutputPrecision = "Double"
mesh, _ = run()
bitangents = mesh.GetPointData().GetArray("Bitangents")
check(bitangents is not None and bitangents.GetNumberOfComponents() == 3, "Bitangents on request")
# Bitangent = sign * cross(N, T) = +y on both halves: dP/dv is +y everywhere. Double output of
# unit vectors along the axes: a few ulps (1e-16) off at most, so 1e-12 holds with room.
check(bitangents is not None and all(abs(bitangents.GetTuple3(i)[1] - 1.0) < 1e-12
                                     for i in range(mesh.GetNumberOfPoints())),
      "bitangents follow +v (+y) on both halves")
check(mesh.GetCellData().GetArray("Tangents") is not None, "cell Tangents on request")
check(mesh.GetPointData().GetArray("Tangents").GetDataTypeAsString() == "double",
      "OutputPrecision Double gives double arrays")

frames.Method = "MikkTSpace"
mesh, counts = run()
mikk_signs = signs_by_side(mesh)
check(mikk_signs == ({1.0}, {-1.0}), "MikkTSpace: the same signs (%s)" % (mikk_signs,))
frames.glTFSignConvention = 1
mesh, _ = run()
check(signs_by_side(mesh) == ({-1.0}, {1.0}), "glTF sign convention: MikkTSpace's signs negated")

# Supplied tangents: a second filter fed the first one's frames keeps them all with Keep Valid
# (they pass every check: nothing replaced, the same tangents and signs), and replaces the ones
# planted wrong.
frames.Method = "Angle Weighted"
frames.glTFSignConvention = 0
frames.OutputPrecision = "Same as input points"
computed, _ = run()
again = TangentFrames(Input=frames, SuppliedTangents="Keep Valid")
again.UpdatePipeline()
again.UpdatePropertyInformation()
kept = servermanager.Fetch(again)
check(again.GetPropertyValue("NumberOfReplacedTangents") == 0,
      "Keep Valid on valid frames replaces none (%s)"
      % again.GetPropertyValue("NumberOfReplacedTangents"))
same = all(
    kept.GetPointData().GetArray("Tangents").GetTuple3(i)
    == computed.GetPointData().GetArray("Tangents").GetTuple3(i)
    and kept.GetPointData().GetArray("TangentSigns").GetValue(i)
    == computed.GetPointData().GetArray("TangentSigns").GetValue(i)
    for i in range(computed.GetNumberOfPoints()))
check(kept.GetNumberOfPoints() == computed.GetNumberOfPoints() and same,
      "Keep Valid keeps valid frames bit for bit")
flipped = Calculator(Input=frames, AttributeType="Point Data", ResultArrayName="TangentSigns",
                     Function="-TangentSigns")
again.Input = flipped
again.UpdatePipeline()
again.UpdatePropertyInformation()
check(again.GetPropertyValue("NumberOfReplacedTangents") == computed.GetNumberOfPoints(),
      "Keep Valid replaces every frame whose sign was flipped (%s of %d)"
      % (again.GetPropertyValue("NumberOfReplacedTangents"), computed.GetNumberOfPoints()))
defects = {name: again.GetPropertyValue(name) for name in (
    "NumberOfNonFiniteTangents", "NumberOfNonUnitTangents", "NumberOfNonPerpendicularTangents",
    "NumberOfWrongSignTangents")}
check(defects == {"NumberOfNonFiniteTangents": 0, "NumberOfNonUnitTangents": 0,
                  "NumberOfNonPerpendicularTangents": 0,
                  "NumberOfWrongSignTangents": computed.GetNumberOfPoints()},
      "the defect counts say why: every sign wrong, nothing else (%s)" % defects)
check(signs_by_side(servermanager.Fetch(again)) == ({1.0}, {-1.0}),
      "the replaced frames have the computed signs")
again.SuppliedTangents = "Keep"
again.UpdatePipeline()
check(signs_by_side(servermanager.Fetch(again)) == ({-1.0}, {1.0}),
      "Keep writes the supplied (flipped) signs as they are")

# Texture coordinates of 3 components (u, v, w) are not offered: data without texture
# coordinates would get its normals chosen. Named from Python, their first two give the frames
# of UV.
quads = nm.mirrored_quads()
uv = quads.GetPointData().GetArray("UV")
uvw = vtkFloatArray()
uvw.SetName("UVW")
uvw.SetNumberOfComponents(3)
for i in range(uv.GetNumberOfTuples()):
    uvw.InsertNextTuple3(uv.GetTuple2(i)[0], uv.GetTuple2(i)[1], 0.5)
quads.GetPointData().AddArray(uvw)
with_uvw = PVTrivialProducer()
with_uvw.GetClientSideObject().SetOutput(quads)
with_uvw.UpdatePipeline()
from_uvw = TangentFrames(Input=with_uvw)
check("UVW" not in from_uvw.GetProperty("TextureCoordinates").Available,
      "3-component texture coordinates are not offered (%s)"
      % from_uvw.GetProperty("TextureCoordinates").Available)
from_uvw.TextureCoordinates = "UVW"
from_uvw.UpdatePipeline()
check(signs_by_side(servermanager.Fetch(from_uvw)) == ({1.0}, {-1.0}),
      "3-component texture coordinates named from Python give the frames of their first two")

# A multiblock whose blocks are not all polydata (a scene with a volume) is accepted: the
# polydata block gets frames, the other passes through.
scene = vtkMultiBlockDataSet()
scene.SetBlock(0, nm.mirrored_quads())
grid = vtkUnstructuredGrid()
grid.SetPoints(quads.GetPoints())
scene.SetBlock(1, grid)
mixed = PVTrivialProducer()
mixed.GetClientSideObject().SetOutput(scene)
mixed.UpdatePipeline()
input_property = servermanager.CreateProxy("filters", "TangentFrames").GetProperty("Input")
input_property.AddUncheckedInputConnection(mixed.SMProxy, 0)
check(input_property.GetDomain("input_type").IsInDomain(input_property) == 1,
      "a multiblock of polydata and an unstructured grid is a valid input")
from_mixed = TangentFrames(Input=mixed)
from_mixed.UpdatePipeline()
blocks = servermanager.Fetch(from_mixed)
check(blocks.GetBlock(0).GetPointData().GetArray("Tangents") is not None
      and blocks.GetBlock(1).IsA("vtkUnstructuredGrid"),
      "its polydata block gets frames, the grid passes through")

# Bad input: no texture coordinates. The filter reports an error and passes the input through.
plain = Sphere()
plain.UpdatePipeline()
bad = TangentFrames(Input=plain)
bad.UpdatePipeline()
out = servermanager.Fetch(bad)
check(out.GetNumberOfPoints() == plain.GetDataInformation().GetNumberOfPoints()
      and out.GetPointData().GetArray("Tangents") is None,
      "no texture coordinates: the input passes through, without tangents")

check.finish()
