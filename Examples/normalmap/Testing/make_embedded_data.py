#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the test data for normal textures embedded in glTF files (Testing/Data/embedded/).

    /usr/bin/python3 make_embedded_data.py [OUTPUT_FOLDER]

Needs Debian's python3 with VTK (python3-vtk9) for the PNG and JPEG encoders; the rest is the
standard library. The files, all a unit quad (two triangles, normals +z, glTF texture
coordinates with v down) whose material's normalTexture (scale 0.8) is a 64 x 64 map of 2 x 2
round studs:

  studs_normal.png     the map as a PNG file, for --normal-map (the reference renders)
  studs_normal.jpg     the same as JPEG (quality 95)
  studs_truncated.png  the PNG cut off halfway: a corrupt --normal-map file
  quad_png.glb         the PNG in a buffer view of the GLB's binary chunk
  quad_jpeg.gltf       the JPEG as a data: URI (the mesh data too)
  quad_truncated.glb   like quad_png.glb with the PNG cut off halfway (the view fits it)
  quad_outside.glb     like quad_png.glb with the image's buffer view running 1000 bytes past
                       the end of the binary chunk
  quad_garbage.gltf    a data:image/png URI whose bytes are not an image
  quad_missing_map.gltf  the image as a file beside the glTF that does not exist
                       (no_such_normal.png)
  three_quads.gltf     one mesh of three primitives, quads side by side (x from 0, 1.25, 2.5),
                       everything in data: URIs: primitive 0 with material 0 (the PNG, scale
                       0.8), primitive 1 with TANGENT (1, 0, 0, 1) and material 1 (the JPEG,
                       scale 0.5), primitive 2 with material 2 (no normal texture)
"""
import base64
import json
import math
import os
import struct
import sys

from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkJPEGWriter, vtkPNGWriter

SIZE = 64
SCALE = 0.8


def stud_map():
    """2 x 2 studs: domes h = 0.03 (1 - r^2 / R^2), R = 0.35 of a cell, as a tangent-space normal
    map (OpenGL convention, RGB = 255 (n + 1) / 2; image row 0 at v = 0)."""
    texels = vtkUnsignedCharArray()
    texels.SetNumberOfComponents(3)
    texels.SetNumberOfTuples(SIZE * SIZE)
    studs, radius, height = 2, 0.35, 0.03
    cell = SIZE // studs
    for j in range(SIZE):
        for i in range(SIZE):
            x = ((i % cell) + 0.5) / cell - 0.5
            y = ((j % cell) + 0.5) / cell - 0.5
            inside = x * x + y * y < radius * radius
            # dh/du in texture units: one cell is 1 / studs of them.
            slope = -2.0 * height / (radius * radius) * studs if inside else 0.0
            n = (-slope * x, -slope * y, 1.0)
            length = math.sqrt(sum(c * c for c in n))
            texels.SetTuple3(j * SIZE + i, *(round(255.0 * (c / length + 1.0) / 2.0) for c in n))
    image = vtkImageData()
    image.SetDimensions(SIZE, SIZE, 1)
    image.GetPointData().SetScalars(texels)
    return image


def encode(writer, image):
    writer.SetInputData(image)
    writer.WriteToMemoryOn()
    writer.Write()
    result = writer.GetResult()
    return bytes(result.GetValue(k) for k in range(result.GetNumberOfValues()))


def quad_bytes():
    """Indices (u16), positions, normals, texture coordinates (v down) of the unit quad."""
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    positions = b"".join(struct.pack("<3f", x, y, 0.0) for x, y in corners)
    normals = b"".join(struct.pack("<3f", 0.0, 0.0, 1.0) for _ in corners)
    uvs = b"".join(struct.pack("<2f", x, 1.0 - y) for x, y in corners)
    return [indices, positions, normals, uvs]


def document(image_entry, mesh_buffer):
    """The glTF JSON: the quad's accessors on buffer views 0-3 of buffer 0, one image."""
    views, offset = [], 0
    targets = [34963, 34962, 34962, 34962]
    for part, target in zip(quad_bytes(), targets):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part),
                      "target": target})
        offset += len(part)
    return {
        "asset": {"version": "2.0",
                  "generator": "NormalMapping test data (make_embedded_data.py)"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "quad"}],
        "meshes": [{"name": "quad", "primitives": [{
            "attributes": {"POSITION": 1, "NORMAL": 2, "TEXCOORD_0": 3},
            "indices": 0, "material": 0}]}],
        "materials": [{"name": "studs", "normalTexture": {"index": 0, "scale": SCALE}}],
        "textures": [{"source": 0}],
        "images": [image_entry],
        "accessors": [
            {"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2"}],
        "bufferViews": views,
        "buffers": [mesh_buffer],
    }


def write_glb(path, image, extra_view_length=0):
    """A GLB whose binary chunk holds the quad, then `image` in buffer view 4."""
    binary = b"".join(quad_bytes())
    image_offset = len(binary)
    binary += image
    binary += b"\0" * (-len(binary) % 4)
    doc = document({"bufferView": 4, "mimeType": "image/png"}, {"byteLength": len(binary)})
    doc["bufferViews"].append({"buffer": 0, "byteOffset": image_offset,
                               "byteLength": len(image) + extra_view_length})
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    chunks = (struct.pack("<I4s", len(text), b"JSON") + text +
              struct.pack("<I4s", len(binary), b"BIN\0") + binary)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)


def data_uri(mime_type, data):
    return "data:%s;base64,%s" % (mime_type, base64.b64encode(data).decode())


def write_gltf(path, image_uri):
    """A .gltf with the mesh data as a data: URI and the image at `image_uri`."""
    binary = b"".join(quad_bytes())
    doc = document(
        {"uri": image_uri},
        {"byteLength": len(binary),
         "uri": "data:application/octet-stream;base64," + base64.b64encode(binary).decode()})
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def write_three_quads(path, png, jpeg):
    """Three primitives of one mesh, each with its own positions, and their materials."""
    indices, positions, normals, uvs = quad_bytes()
    shifted = [b"".join(struct.pack("<3f", x + 1.25 * k, y, z)
                        for x, y, z in struct.iter_unpack("<3f", positions)) for k in range(3)]
    tangents = b"".join(struct.pack("<4f", 1.0, 0.0, 0.0, 1.0) for _ in range(4))
    parts = [indices, normals, uvs, tangents] + shifted
    binary = b"".join(parts)
    views, offset = [], 0
    for part in parts:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part)})
        offset += len(part)
    accessors = [
        {"bufferView": 0, "componentType": 5123, "count": 6, "type": "SCALAR"},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC4"}]
    for k in range(3):
        accessors.append({"bufferView": 4 + k, "componentType": 5126, "count": 4,
                          "type": "VEC3", "min": [1.25 * k, 0, 0], "max": [1.25 * k + 1, 1, 0]})
    primitives = []
    for k in range(3):
        attributes = {"POSITION": 4 + k, "NORMAL": 1, "TEXCOORD_0": 2}
        if k == 1:
            attributes["TANGENT"] = 3
        primitives.append({"attributes": attributes, "indices": 0, "material": k})
    doc = {
        "asset": {"version": "2.0",
                  "generator": "NormalMapping test data (make_embedded_data.py)"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "three quads"}],
        "meshes": [{"name": "three quads", "primitives": primitives}],
        "materials": [{"name": "studs png", "normalTexture": {"index": 0, "scale": SCALE}},
                      {"name": "studs jpeg", "normalTexture": {"index": 1, "scale": 0.5}},
                      {"name": "plain"}],
        "textures": [{"source": 0}, {"source": 1}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()},
                   {"uri": "data:image/jpeg;base64," + base64.b64encode(jpeg).decode()}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(binary), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(binary).decode()}],
    }
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "Data", "embedded")
    os.makedirs(folder, exist_ok=True)
    image = stud_map()
    png = encode(vtkPNGWriter(), image)
    jpeg_writer = vtkJPEGWriter()
    jpeg_writer.SetQuality(95)
    jpeg = encode(jpeg_writer, image)
    truncated = png[: len(png) // 2]
    for name, data in (("studs_normal.png", png), ("studs_normal.jpg", jpeg),
                       ("studs_truncated.png", truncated)):
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)
    write_glb(os.path.join(folder, "quad_png.glb"), png)
    write_gltf(os.path.join(folder, "quad_jpeg.gltf"), data_uri("image/jpeg", jpeg))
    write_glb(os.path.join(folder, "quad_truncated.glb"), truncated)
    write_glb(os.path.join(folder, "quad_outside.glb"), png, extra_view_length=1000)
    write_gltf(os.path.join(folder, "quad_garbage.gltf"), data_uri(
        "image/png", b"this is not an image, only text pretending to be one" * 4))
    write_gltf(os.path.join(folder, "quad_missing_map.gltf"), "no_such_normal.png")
    write_three_quads(os.path.join(folder, "three_quads.gltf"), png, jpeg)
    print("wrote the embedded-texture test data in " + folder)


if __name__ == "__main__":
    main()
