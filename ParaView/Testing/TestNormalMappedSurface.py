# SPDX-License-Identifier: BSD-3-Clause
"""The Normal Mapped Surface representation: the plugin adds it to ParaView's list, it renders
the mirrored quads symmetric where ParaView's Surface does not (TestSurfaceMirrorControl), with
the Tangent Frames filter's tangents and without any tangents, its image matches the baseline,
its settings reach the mapper, the map shows on surfaces colored by an array, it is offered for
image data and structured grids, and a saved state reloads to the same image.

pvbatch TestNormalMappedSurface.py <plugin.so> <work dir> <baseline dir>
"""
import os

from paraview.simple import *  # noqa: F401,F403

import nmparaview as nm

nm.load_plugin(globals())
check = nm.Checks()

REPRESENTATION = "Normal Mapped Surface"
BASELINE = os.path.join(nm.BASELINES, "NormalMappedSurface.png")
# The baseline and a new rendering on the same llvmpipe differ only by rasterization and
# rounding: 2 levels, as for the symmetry check, on all but 0.1% of the pixels.
BASELINE_BOUND = 2
BASELINE_FRACTION = 0.999

reader = XMLPolyDataReader(FileName=[nm.write_mirrored_quads()])
frames = TangentFrames(Input=reader)
texture = CreateTexture(nm.write_rivets_map())
view = nm.mirror_view()

display = nm.show_mirrored(frames, view, "Surface")
check(REPRESENTATION in display.GetProperty("Representation").Available,
      "the plugin adds '%s' to the representations" % REPRESENTATION)

# Point tangents and signs from the Tangent Frames filter, ParaView's own NormalTexture.
display.Representation = REPRESENTATION
display.NormalTexture = texture
Render(view)
ours, width, height = nm.measure_symmetry(
    view, "Normal Mapped Surface, point tangents", check, True, "normal-mapped-surface")

# The same image as the baseline; and ParaView's Surface, which shades the mirrored half wrong,
# does not pass that comparison (the comparison can fail).
if os.path.exists(BASELINE):
    baseline, _, _ = nm.read_png(BASELINE)
    fraction, largest = nm.difference(ours, baseline, BASELINE_BOUND)
    print("against the baseline: %.3f%% within %d levels, max difference %d"
          % (100 * fraction, BASELINE_BOUND, largest))
    check(fraction >= BASELINE_FRACTION, "the image matches the baseline " + BASELINE)
    display.Representation = "Surface"
    Render(view)
    stock, _, _ = nm.capture(view, "surface-normal-map")
    fraction, _ = nm.difference(stock, baseline, BASELINE_BOUND)
    check(fraction < BASELINE_FRACTION, "ParaView's Surface does not match the baseline (%.1f%%)"
          % (100 * fraction))
    display.Representation = REPRESENTATION
else:
    check(False, "no baseline %s: review %s/normal-mapped-surface.png and copy it there"
          % (BASELINE, nm.WORK))

# Settings reach the mapper: the DirectX convention reads the green channel the other way, so
# every rivet is lit from below: still symmetric, but not the baseline image.
display.NormalMapEncoding = "Tangent space, DirectX (-Y green)"
Render(view)
directx, _, _ = nm.measure_symmetry(view, "DirectX encoding", check, True, "directx")
fraction, _ = nm.difference(directx, ours, BASELINE_BOUND)
check(fraction < 0.9, "the map encoding changes the image (%.1f%% unchanged)" % (100 * fraction))
display.NormalMapEncoding = "Tangent space, OpenGL (+Y green)"

# Tangents without signs take each triangle's handedness from its texture coordinates, so the
# mirrored half stays right: naming an array that does not exist leaves the tangents unsigned,
# and a cleared name asks for unsigned tangents (TangentSigns, though present, is not read).
# Signs that are all +1, which is what unsigned tangents meant to VTK's mapper, shade the
# mirrored half wrong (the check can fail).
display.TangentSignsArray = "NoSuchArray"
Render(view)
nm.measure_symmetry(view, "Normal Mapped Surface, signs not found", check, True, "no-signs")
display.TangentSignsArray = ""
Render(view)
nm.measure_symmetry(view, "Normal Mapped Surface, signs cleared", check, True, "signs-cleared")
plus_one = Calculator(Input=frames, ResultArrayName="PlusOne", Function="1")
display_plus_one = nm.show_mirrored(plus_one, view, REPRESENTATION, texture)
Hide(frames, view)
display_plus_one.TangentSignsArray = "PlusOne"
Render(view)
nm.measure_symmetry(view, "Normal Mapped Surface, signs all +1", check, False, "signs-plus-one")
Hide(plus_one, view)
Show(frames, view)
display.TangentSignsArray = "TangentSigns"

# 4-component tangents, the sign in w (glTF's TANGENT), chosen as the Tangent Array: ParaView
# cannot make them the active tangents, so the mapper reads them by name. T4 = (T, sign) gives
# the frame of Tangents and TangentSigns, the image above. On these flat quads the derivative
# frame, which the mapper falls back to when it finds no tangents, gives that image too; so
# T4 = (T, -sign), the bitangent reversed, which lights every rivet from below (the light is in
# the mirror plane, above the quads), shows that T4 is what the mapper reads.
def show_packed_tangents(sign):
    packed = ProgrammableFilter(Input=frames)
    packed.Script = (
        "import numpy\n"
        "pd = inputs[0].PointData\n"
        "t4 = numpy.hstack([pd['Tangents'], %g * pd['TangentSigns'].reshape(-1, 1)])\n"
        "output.ShallowCopy(inputs[0].VTKObject)\n"
        "output.PointData.RemoveArray('Tangents')\n"
        "output.PointData.RemoveArray('TangentSigns')\n"
        "output.PointData.append(t4, 'T4')\n" % sign)
    shown = nm.show_mirrored(packed, view, REPRESENTATION, texture, "NormalMapTexture")
    shown.SelectTangentArray = "T4"
    shown.NormalMapFrameSource = "Point tangents"
    name = "4-component tangents, signs x %g" % sign
    image, _, _ = nm.measure_symmetry(view, name, check, True, "four-component-%g" % sign)
    Hide(packed, view)
    fraction, largest = nm.difference(image, ours, BASELINE_BOUND)
    print("%s against Tangents + TangentSigns: %.3f%% within %d levels, max %d"
          % (name, 100 * fraction, BASELINE_BOUND, largest))
    return fraction


Hide(frames, view)
check(show_packed_tangents(1) >= BASELINE_FRACTION,
      "4-component tangents shade as Tangents + TangentSigns do")
check(show_packed_tangents(-1) < 0.9, "4-component tangents are the ones the mapper reads")
Show(frames, view)

# No tangent array at all: the reader's output, with this representation's NormalMapTexture
# (ParaView's NormalTexture widget is disabled without tangents). The frame comes from screen
# derivatives, which handle mirroring by themselves.
Hide(frames, view)
plain = nm.show_mirrored(reader, view, REPRESENTATION, texture, "NormalMapTexture")
check(plain.NormalTexture is None, "ParaView's NormalTexture is not needed")
derivatives, _, _ = nm.measure_symmetry(
    view, "Normal Mapped Surface, no tangents", check, True, "no-tangents")
fraction, largest = nm.difference(derivatives, ours, 8)
print("derivative frames against point tangents: %.2f%% within 8 levels, max %d"
      % (100 * fraction, largest))
# Both frames are exact for this planar mesh with affine UVs; they differ only in rounding,
# by a few levels where the lighting is steep: 8 levels on 99% of the pixels.
check(fraction >= 0.99, "derivative frames shade like the point tangents")
# Normal Map Scale is the strength of Normal Map, and ParaView's Normal Scale (which belongs to
# its Normal Texture) does not change it: scale 0 draws the surface as without a map, and with
# Normal Scale 0 the map is drawn as before. Same process and renderer: within 1 level.
plain.NormalMapScale = 0.0
Render(view)
zero, _, _ = nm.capture(view, "normal-map-scale-0")
plain.NormalMapScale = 1.0
plain.NormalScale = 0.0
Render(view)
unscaled, _, _ = nm.capture(view, "normal-scale-0")
plain.NormalScale = 1.0
plain.NormalMapTexture = None
Render(view)
unmapped, _, _ = nm.capture(view, "no-normal-map")
plain.NormalMapTexture = texture
scaled_off, _ = nm.difference(zero, unmapped, 1)
kept, _ = nm.difference(unscaled, derivatives, 1)
print("Normal Map Scale 0 against no map: %.2f%%; Normal Scale 0 against the map: %.2f%%"
      % (100 * scaled_off, 100 * kept))
check(scaled_off >= BASELINE_FRACTION and kept >= BASELINE_FRACTION,
      "Normal Map Scale sets the map's strength, Normal Scale leaves it alone")
# The texture is filtered as ParaView filters a representation's textures: mipmapped only with
# Use Mipmap Textures.
mipmaps = []
for use in (1, 0):
    plain.UseMipmapTextures = use
    plain.NormalMapTexture = None
    plain.NormalMapTexture = texture
    Render(view)
    mipmaps.append(texture.GetClientSideObject().GetMipmap())
check(mipmaps == [1, 0], "Use Mipmap Textures decides the normal texture's mipmaps (%s)" % mipmaps)
mapper = plain.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
check(mapper.GetCompositeIdArrayName() == "vtkCompositeIndex"
      and mapper.GetProcessIdArrayName() == "vtkProcessId",
      "the mapper keeps ParaView's selection arrays (%s, %s)"
      % (mapper.GetCompositeIdArrayName(), mapper.GetProcessIdArrayName()))
# Colored by a point array with Interpolate Scalars Before Mapping (ParaView's default), VTK's
# texture coordinates are the color map's; the map is sampled at the dataset's own, so the image
# is that of the colors mapped at the points (the same arithmetic: within 1 level), and the map
# shows on most of the covered view. The colors are constant (every normal's magnitude is 1).
ColorBy(plain, ("POINTS", "Normals", "Magnitude"))
colored = []
for interpolate in (1, 0):
    plain.InterpolateScalarsBeforeMapping = interpolate
    Render(view)
    colored.append(nm.capture(view, "colored-interpolated-%d" % interpolate)[0])
plain.NormalMapScale = 0.0
Render(view)
colored_unmapped = nm.capture(view, "colored-unmapped")[0]
plain.NormalMapScale = 1.0
plain.InterpolateScalarsBeforeMapping = 1
ColorBy(plain, ("POINTS", None))
same, largest = nm.difference(colored[0], colored[1], 1)
shows, _ = nm.difference(colored[0], colored_unmapped, 4)
print("colored, scalars interpolated before mapping against mapped at the points: %.2f%% within "
      "1 level, max %d; %.1f%% of the pixels within 4 levels of the unmapped image"
      % (100 * same, largest, 100 * shows))
check(same >= BASELINE_FRACTION and shows < 0.9,
      "colored by a point array, the map shows with Interpolate Scalars Before Mapping")
Hide(reader, view)

# Image data and structured grids draw their surface through representations of their own; the
# representation type is offered there too, and a flat image with texture coordinates renders
# as its extracted polydata surface does (derivative frames: the map needs no tangents).
flat = TextureMaptoPlane(Input=Wavelet(WholeExtent=[-10, 10, -10, 10, 0, 0]))
grid = TextureMaptoPlane(Input=Transform(Input=flat))
for name, source in (("image data", flat), ("structured grid", grid)):
    shown = Show(source, view)
    check(REPRESENTATION in shown.GetProperty("Representation").Available,
          "%s (%s) offers Normal Mapped Surface" % (name, shown.GetXMLName()))
    Hide(source, view)
images = []
for source in (flat, ExtractSurface(Input=flat)):
    nm.show_mirrored(source, view, REPRESENTATION, texture, "NormalMapTexture")
    view.CameraPosition = [0.0, 0.0, 45.0]
    Render(view)
    images.append(nm.capture(view, "image-data-%d" % len(images))[0])
    Hide(source, view)
nm.show_mirrored(flat, view, "Surface")
view.CameraPosition = [0.0, 0.0, 45.0]
Render(view)
unmapped = nm.capture(view, "image-data-unmapped")[0]
Hide(flat, view)
same, largest = nm.difference(images[0], images[1], BASELINE_BOUND)
shows, _ = nm.difference(images[0], unmapped, 4)
print("image data against its polydata surface: %.2f%% within %d levels, max %d; %.1f%% of "
      "the pixels within 4 levels of the unmapped image" % (100 * same, BASELINE_BOUND, largest,
                                                            100 * shows))
# The same triangles and texture coordinates: rasterization and rounding only, as for the
# baseline; the map shows on most of the covered view.
check(same >= BASELINE_FRACTION and shows < 0.9,
      "image data is normal-mapped as its polydata surface is")
Show(frames, view)
Render(view)

# A saved state reloads to the same image (same process and renderer: within 1 level).
before, reloaded_view, reloaded_display = nm.save_and_reload(view, "normal-mapped-surface",
                                                             "TangentFrames1")
check(reloaded_display.Representation == REPRESENTATION, "the state keeps the representation")
nm.check_reloaded_image(reloaded_view, before, check, BASELINE_FRACTION)

check.finish()
