# SPDX-License-Identifier: BSD-3-Clause
"""Selecting on a Normal Mapped Surface: ParaView's surface cell, point and block selection
find what they find on ParaView's own Surface representation of the same data, for a polydata
and for a multiblock dataset, colored by a point array (scalars interpolated before mapping,
ParaView's default); and after the selection is cleared the view renders as before it.

pvbatch TestNormalMappedSelection.py <plugin.so> <work dir> <baseline dir>
"""
from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403

import nmparaview as nm

nm.load_plugin(globals())
check = nm.Checks()

REPRESENTATION = "Normal Mapped Surface"
WHOLE_VIEW = [0, 0, nm.WIDTH - 1, nm.HEIGHT - 1]

reader = XMLPolyDataReader(FileName=[nm.write_mirrored_quads()])
frames = TangentFrames(Input=reader)
# A second copy behind the first, shifted up and right: the selection must keep to what is in
# front. Its points are seen at least 6 pixels from the first copy's edges: a point within a
# pixel of an edge that hides it is a depth tie, which VTK's own mappers already decide
# differently (a single and a composite mapper, for instance).
shifted = Transform(Input=frames)
shifted.Transform.Translate = [0.6, 0.5, -0.5]
group = GroupDatasets(Input=[frames, shifted])
texture = CreateTexture(nm.write_rivets_map())
view = nm.mirror_view()


def selected_ids(source, field):
    """The original ids of the selected cells or points of `source`, per block: a set of
    (block, id) pairs."""
    extracted = ExtractSelection(Input=source)
    data = servermanager.Fetch(extracted)
    Delete(extracted)
    name = "vtkOriginalCellIds" if field == "CELL" else "vtkOriginalPointIds"
    blocks = []
    if data.IsA("vtkCompositeDataSet"):
        iterator = data.NewIterator()
        iterator.InitTraversal()
        while not iterator.IsDoneWithTraversal():
            blocks.append((iterator.GetCurrentFlatIndex(), iterator.GetCurrentDataObject()))
            iterator.GoToNextItem()
    else:
        blocks.append((0, data))
    found = set()
    for index, block in blocks:
        attributes = block.GetCellData() if field == "CELL" else block.GetPointData()
        ids = attributes.GetArray(name)
        for i in range(ids.GetNumberOfTuples() if ids else 0):
            found.add((index, int(ids.GetTuple1(i))))
    return found


def selections(source, representation):
    """What surface cell, point (and, for a multiblock, block) selection of the whole view find
    on `source` shown with `representation` and colored by a point array; and the view's image
    before the selection and after it is cleared."""
    display = nm.show_mirrored(source, view, representation, texture)
    ColorBy(display, ("POINTS", "TangentSigns"))
    display.InterpolateScalarsBeforeMapping = 1
    Render(view)
    before = nm.capture(view, "before-%s-%s" % (source.GetXMLName(), representation[0]))[0]
    found = {}
    for field, select in (("CELL", SelectSurfaceCells), ("POINT", SelectSurfacePoints)):
        select(Rectangle=WHOLE_VIEW, View=view)
        found[field] = selected_ids(source, field)
        ClearSelection(source)
    if source is group:
        SetActiveSource(source)  # SelectSurfaceBlocks clears the active source's selection
        SelectSurfaceBlocks(Rectangle=WHOLE_VIEW, View=view)
        found["BLOCK"] = {index for index, _ in selected_ids(source, "CELL")}
        ClearSelection(source)
    Render(view)
    after = nm.capture(view, "after-%s-%s" % (source.GetXMLName(), representation[0]))[0]
    Hide(source, view)
    return found, before, after


for name, source in (("polydata", frames), ("multiblock", group)):
    ours, before, after = selections(source, REPRESENTATION)
    theirs, _, _ = selections(source, "Surface")
    for field in sorted(ours):
        print("%s, %s selection: %d found on %s, %d on Surface"
              % (name, field.lower(), len(ours[field]), REPRESENTATION, len(theirs[field])))
        check(len(ours[field]) > 0 and ours[field] == theirs[field],
              "%s: %s selection finds what it finds on Surface" % (name, field.lower()))
    same, largest = nm.difference(after, before, 0)
    print("%s: after the selection, %.2f%% of the pixels as before, max difference %d"
          % (name, 100 * same, largest))
    check(same == 1.0, "%s: the view renders as before the selection" % name)

check.finish()
