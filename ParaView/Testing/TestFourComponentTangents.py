# SPDX-License-Identifier: BSD-3-Clause
"""The Normal Mapped Surface's Tangents list, the one the Properties panel shows: it offers
4-component point tangents (the sign in w, as glTF's TANGENT), float and double, as well as
3-component ones, and not arrays of other sizes; its default is the active tangents, else None;
an array chosen in it is the one the mapper reads, and shades the mirrored quads as the Tangent
Frames filter's Tangents + TangentSigns do; ParaView's own Tangent Array still sets it; a saved
state keeps the choice.

pvbatch TestFourComponentTangents.py <plugin.so> <work dir> <baseline dir>
"""
import os

from paraview.simple import *  # noqa: F401,F403

import nmparaview as nm

nm.load_plugin(globals())
check = nm.Checks()

REPRESENTATION = "Normal Mapped Surface"
# The same scene in the same process and renderer: images that should agree differ only by
# rasterization and rounding: 2 levels on all but 0.1% of the pixels, as TestNormalMappedSurface
# allows against its baseline (which this scene is compared with too).
BOUND = 2
SAME_FRACTION = 0.999

reader = XMLPolyDataReader(FileName=[nm.write_mirrored_quads()])
frames = TangentFrames(Input=reader)
# The filter's frames packed as 4-component arrays, with no active tangents left: TANGENT (float)
# = (Tangents, TangentSigns), and ReversedTANGENT (double) = (Tangents, -TangentSigns), whose
# bitangent is reversed and lights every rivet from below.
packed = ProgrammableFilter(Input=frames)
packed.Script = (
    "import numpy\n"
    "pd = inputs[0].PointData\n"
    "signs = pd['TangentSigns'].reshape(-1, 1)\n"
    "tangent = numpy.hstack([pd['Tangents'], signs]).astype(numpy.float32)\n"
    "reversed_tangent = numpy.hstack([pd['Tangents'], -signs]).astype(numpy.float64)\n"
    "output.ShallowCopy(inputs[0].VTKObject)\n"
    "output.PointData.RemoveArray('Tangents')\n"
    "output.PointData.RemoveArray('TangentSigns')\n"
    "output.PointData.append(tangent, 'TANGENT')\n"
    "output.PointData.append(reversed_tangent, 'ReversedTANGENT')\n")
texture = CreateTexture(nm.write_rivets_map())
view = nm.mirror_view()


def tangents_list(display, name="TangentsArray"):
    """The list the Properties panel offers for a display's property."""
    prop = display.GetProperty(name)
    return list(prop.Available) if prop is not None else None


# Data without tangents: the list's default is None, not another 3-component array (Normals).
plain = nm.show_mirrored(reader, view, REPRESENTATION, texture, "NormalMapTexture")
offered = tangents_list(plain)
check(offered is not None, "the representation has a Tangents list (TangentsArray)")
if offered is None:
    check.finish()
print("without tangents: %s offered, %r chosen" % (offered, plain.TangentsArray))
check(plain.TangentsArray == "None", "without tangents the default is None (%r)"
      % plain.TangentsArray)
Hide(reader, view)

# 3 components + signs (the filter's output): the default is the active tangents, and they give
# the reference image. The frame is the point tangents' throughout: the derivative frame would
# shade these flat quads right by itself.
three = nm.show_mirrored(frames, view, REPRESENTATION, texture, "NormalMapTexture")
three.NormalMapFrameSource = "Point tangents"
Render(view)
check(three.TangentsArray == "Tangents", "with the filter's tangents the default is Tangents (%r)"
      % three.TangentsArray)
reference, _, _ = nm.measure_symmetry(view, "Tangents + TangentSigns", check, True, "reference")
# The reviewed image of this scene (TestNormalMappedSurface's baseline): the map is applied.
baseline, _, _ = nm.read_png(os.path.join(nm.BASELINES, "NormalMappedSurface.png"))
fraction, largest = nm.difference(reference, baseline, BOUND)
print("Tangents + TangentSigns against the baseline: %.3f%% within %d levels, max %d"
      % (100 * fraction, BOUND, largest))
check(fraction >= SAME_FRACTION, "Tangents + TangentSigns draw the baseline image")
Hide(frames, view)

# 4 components: offered in this list, not in ParaView's Tangent Array list (which stays the
# Surface's, 3 components); arrays of other sizes are not offered; the default is None.
four = nm.show_mirrored(packed, view, REPRESENTATION, texture, "NormalMapTexture")
offered = tangents_list(four)
print("4-component data: Tangents offers %s, ParaView's Tangent Array offers %s, %r chosen"
      % (offered, tangents_list(four, "SelectTangentArray"), four.TangentsArray))
check("TANGENT" in offered and "ReversedTANGENT" in offered,
      "the list offers the 4-component arrays, float and double")
check("TANGENT" not in tangents_list(four, "SelectTangentArray"),
      "ParaView's Tangent Array list is left as it is (3 components)")
check("UV" not in offered and "FlippedUV" not in offered, "2-component arrays are not offered")
check(four.TangentsArray == "None", "with 4-component tangents only, the default is None (%r)"
      % four.TangentsArray)

# Chosen in the list, as the panel chooses: the mapper reads it, and it shades as the reference.
before = four.SelectTangentArray
four.TangentsArray = "TANGENT"
four.NormalMapFrameSource = "Point tangents"
Render(view)
chosen, _, _ = nm.measure_symmetry(view, "TANGENT chosen", check, True, "tangent")
fraction, largest = nm.difference(chosen, reference, BOUND)
print("TANGENT against Tangents + TangentSigns: %.3f%% within %d levels, max %d"
      % (100 * fraction, BOUND, largest))
check(fraction >= SAME_FRACTION, "TANGENT shades as Tangents + TangentSigns do")
check(four.SelectTangentArray == before, "choosing Tangents leaves ParaView's Tangent Array alone")
four.TangentsArray = "ReversedTANGENT"
Render(view)
reversed_image, _, _ = nm.capture(view, "reversed-tangent")
fraction, _ = nm.difference(reversed_image, reference, BOUND)
check(fraction < 0.9, "the chosen array is the one the mapper reads (%.1f%% unchanged)"
      % (100 * fraction))

# ParaView's Tangent Array, as scripts set it, sets this list too.
four.SelectTangentArray = "TANGENT"
Render(view)
check(four.TangentsArray == "TANGENT", "ParaView's Tangent Array sets Tangents (%r)"
      % four.TangentsArray)
by_script, _, _ = nm.capture(view, "select-tangent-array")
fraction, _ = nm.difference(by_script, chosen, 1)
check(fraction >= SAME_FRACTION, "and draws the same image (%.3f%%)" % (100 * fraction))

# A saved state keeps the choice made in the list while ParaView's Tangent Array names another
# array. ReversedTANGENT, whose image no other frame gives (TANGENT's is also the derivative
# frame's, which the mapper falls back to without tangents). Same process and renderer: within
# 1 level.
four.SelectTangentArray = "None"
four.TangentsArray = "ReversedTANGENT"
Render(view)
before, reloaded_view, reloaded = nm.save_and_reload(view, "four-component-tangents",
                                                     "ProgrammableFilter1")
check(reloaded.TangentsArray == "ReversedTANGENT" and reloaded.SelectTangentArray == "None",
      "the state keeps Tangents and Tangent Array (%r, %r)"
      % (reloaded.TangentsArray, reloaded.SelectTangentArray))
nm.check_reloaded_image(reloaded_view, before, check, SAME_FRACTION)

check.finish()
