#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of FuzzNormalMapGLTF (Testing/Fuzz/gltf-corpus/).

Small hand-made glTF 2.0 files, .gltf (JSON, buffers as base64 data URIs) and .glb: valid ones
that reach every branch of the tool's reader and writer (indexed and non-indexed triangles,
strips, fans, quantized attributes, sparse accessors, morph targets, a second UV set, mirrored
UVs that split points, images in buffer views and data URIs), and nearly valid ones, each
broken in one way a file can be broken. Run it from anywhere; it rewrites the folder.
"""
import base64
import json
import pathlib
import struct

FLOAT, BYTE, UBYTE, SHORT, USHORT, UINT = 5126, 5120, 5121, 5122, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
# Not a decodable picture: the tool keeps image bytes as they are and never decodes them.
FAKE_PNG = b"\x89PNG\r\n\x1a\n" + bytes(8)


class Gltf:
    """A document under construction: one buffer, views, accessors, one mesh."""

    def __init__(self):
        self.data = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "make_gltf_corpus.py"},
                    "buffers": [], "bufferViews": [], "accessors": [],
                    "meshes": [{"primitives": []}], "nodes": [{"mesh": 0}],
                    "scenes": [{"nodes": [0]}], "scene": 0}

    def view(self, payload, target=None, stride=None):
        while len(self.data) % 4:
            self.data.append(0)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target:
            v["target"] = target
        if stride:
            v["byteStride"] = stride
        self.data += payload
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, kind, component=FLOAT, normalized=False, target=ARRAY_BUFFER,
                 view=True):
        """values: a list of tuples (or numbers for SCALAR)."""
        fmt = {FLOAT: "f", BYTE: "b", UBYTE: "B", SHORT: "h", USHORT: "H", UINT: "I"}[component]
        flat = [c for v in values for c in (v if isinstance(v, tuple) else (v,))]
        a = {"componentType": component, "count": len(values), "type": kind}
        if normalized:
            a["normalized"] = True
        if view:
            a["bufferView"] = self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat), target)
        if kind == "VEC3" and component == FLOAT and values:
            a["min"] = [min(v[k] for v in values) for k in range(3)]
            a["max"] = [max(v[k] for v in values) for k in range(3)]
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def primitive(self, attributes, indices=None, mode=None, material=None, targets=None):
        p = {"attributes": attributes}
        if indices is not None:
            p["indices"] = indices
        if mode is not None:
            p["mode"] = mode
        if material is not None:
            p["material"] = material
        if targets:
            p["targets"] = targets
        self.doc["meshes"][0]["primitives"].append(p)

    def normal_texture(self, tex_coord=0, image=None):
        """A material whose normal texture uses `tex_coord`; image: a dict (uri or view)."""
        self.doc.setdefault("images", []).append(image or {"uri": "quad_normal.png"})
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        self.doc.setdefault("materials", []).append(
            {"normalTexture": {"index": len(self.doc["textures"]) - 1, "texCoord": tex_coord,
                               "scale": 0.5}})
        return len(self.doc["materials"]) - 1

    def gltf(self):
        doc = dict(self.doc)
        doc["buffers"] = [{"byteLength": len(self.data), "uri":
                           "data:application/octet-stream;base64," +
                           base64.b64encode(bytes(self.data)).decode()}]
        return json.dumps(doc, separators=(",", ":")).encode()

    def glb(self):
        doc = dict(self.doc)
        doc["buffers"] = [{"byteLength": len(self.data)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        binary = bytes(self.data) + bytes(-len(self.data) % 4)
        chunks = (struct.pack("<I4s", len(text), b"JSON") + text +
                  struct.pack("<I4s", len(binary), b"BIN\0") + binary)
        return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


QUAD_P = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
QUAD_N = [(0.0, 0.0, 1.0)] * 4
QUAD_UV = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]  # glTF: v down


def quad(tangents=False, image=None):
    g = Gltf()
    attributes = {"POSITION": g.accessor(QUAD_P, "VEC3"), "NORMAL": g.accessor(QUAD_N, "VEC3"),
                  "TEXCOORD_0": g.accessor(QUAD_UV, "VEC2")}
    if tangents:
        attributes["TANGENT"] = g.accessor([(1.0, 0.0, 0.0, 1.0)] * 4, "VEC4")
    g.primitive(attributes, g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT,
                                       target=ELEMENT_ARRAY_BUFFER),
                material=g.normal_texture(image=image))
    return g


def main():
    seeds = {}
    seeds["quad.gltf"] = quad().gltf()
    g = quad(tangents=True)
    g.doc["images"] = [{"bufferView": g.view(FAKE_PNG), "mimeType": "image/png"}]
    seeds["quad_tangent_image_in_buffer.glb"] = g.glb()
    seeds["quad_data_uri_image.gltf"] = quad(image={
        "uri": "data:image/png;base64," + base64.b64encode(FAKE_PNG).decode()}).gltf()

    # A strip without indices or normals (the filter computes them; NORMAL is added).
    g = Gltf()
    sp = [(i // 2, i % 2, 0.0) for i in range(6)]
    suv = [(i // 2 / 2, 1 - i % 2) for i in range(6)]
    g.primitive({"POSITION": g.accessor(sp, "VEC3"), "TEXCOORD_0": g.accessor(suv, "VEC2")},
                mode=5)
    seeds["strip_no_indices_no_normals.gltf"] = g.gltf()

    # A fan with quantized attributes (KHR_mesh_quantization) and unsigned byte indices.
    g = Gltf()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    fp = [(0, 0, 0), (100, 0, 0), (100, 100, 0), (0, 100, 0), (-100, 50, 0)]
    g.primitive({"POSITION": g.accessor(fp, "VEC3", SHORT),
                 "NORMAL": g.accessor([(0, 0, 127)] * 5, "VEC3", BYTE, normalized=True),
                 "TEXCOORD_0": g.accessor([(0, 65535), (65535, 65535), (65535, 0), (0, 0),
                                           (0, 32768)], "VEC2", USHORT, normalized=True)},
                g.accessor([0, 1, 2, 3, 4], "SCALAR", UBYTE, target=ELEMENT_ARRAY_BUFFER),
                mode=6)
    seeds["fan_quantized.gltf"] = g.gltf()

    # Mirrored UVs (points on the seam split), a sparse TEXCOORD_0 without a buffer view, and a
    # morph target whose attributes are copied for the split points.
    g = Gltf()
    mp = [(-1.0, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0),
          (-1.0, 1.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]
    muv = [(1.0, 1.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0), (1.0, 0.0)]
    uv = g.accessor([(0.0, 0.0)] * 6, "VEC2", view=False)
    g.doc["accessors"][uv]["sparse"] = {
        "count": 6,
        "indices": {"bufferView": g.view(struct.pack("<6B", *range(6))), "componentType": UBYTE},
        "values": {"bufferView": g.view(struct.pack("<12f", *[c for v in muv for c in v]))}}
    g.primitive({"POSITION": g.accessor(mp, "VEC3"), "NORMAL": g.accessor([(0., 0., 1.)] * 6,
                                                                          "VEC3"),
                 "TEXCOORD_0": uv},
                g.accessor([0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4], "SCALAR", UINT,
                           target=ELEMENT_ARRAY_BUFFER),
                targets=[{"POSITION": g.accessor([(0.0, 0.0, 0.5)] * 6, "VEC3")}])
    g.doc["meshes"][0]["weights"] = [0.5]
    seeds["mirrored_sparse_morph.gltf"] = g.gltf()

    # Two primitives: the first interleaved (POSITION + TEXCOORD_0 in one strided view) with a
    # second UV set that its normal texture uses; the second without UVs (left unchanged).
    g = Gltf()
    inter = b"".join(struct.pack("<5f", *p, *uv) for p, uv in zip(QUAD_P, QUAD_UV))
    view = g.view(inter, ARRAY_BUFFER, stride=20)
    g.doc["accessors"] += [
        {"bufferView": view, "componentType": FLOAT, "count": 4, "type": "VEC3",
         "min": [0, 0, 0], "max": [1, 1, 0]},
        {"bufferView": view, "byteOffset": 12, "componentType": FLOAT, "count": 4,
         "type": "VEC2"}]
    uv1 = g.accessor([(v, u) for u, v in QUAD_UV], "VEC2")
    ind = g.accessor([0, 1, 2, 0, 2, 3], "SCALAR", USHORT, target=ELEMENT_ARRAY_BUFFER)
    g.primitive({"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": uv1}, ind,
                material=g.normal_texture(tex_coord=1))
    g.primitive({"POSITION": 0}, ind)
    seeds["two_primitives_interleaved.glb"] = g.glb()

    # Nearly valid files, each broken in one way.
    g = quad()
    g.data[g.doc["bufferViews"][3]["byteOffset"]] = 9  # the first index: 9 of 4 vertices
    seeds["bad_index_out_of_range.gltf"] = g.gltf()
    g = quad()
    g.doc["bufferViews"][1]["byteOffset"] = 4000  # past the end of the buffer
    seeds["bad_bufferview_past_buffer.gltf"] = g.gltf()
    g = quad()
    g.doc["accessors"][0]["count"] = 5  # one more POSITION than its view holds
    seeds["bad_accessor_count.gltf"] = g.gltf()
    g = quad()
    g.doc["bufferViews"][0]["byteStride"] = 4  # smaller than a VEC3 of floats
    seeds["bad_stride.gltf"] = g.gltf()
    g = quad()
    g.doc["accessors"][3]["componentType"] = FLOAT  # float indices
    seeds["bad_index_type.gltf"] = g.gltf()
    g = quad()
    g.doc["meshes"][0]["primitives"][0]["mode"] = 0  # points: no triangle primitive
    seeds["bad_points_only.gltf"] = g.gltf()
    g = quad(tangents=True)
    # An image in a buffer view that lies past the end of its buffer: tinygltf 2.7.0 hands the
    # image loader a pointer past the buffer's end without checking.
    g.doc["images"] = [{"bufferView": len(g.doc["bufferViews"]), "mimeType": "image/png"}]
    g.doc["bufferViews"].append({"buffer": 0, "byteOffset": 4096, "byteLength": 64})
    seeds["bad_image_bufferview_past_buffer.glb"] = g.glb()
    seeds["bad_truncated.glb"] = quad(tangents=True).glb()[:-20]

    # Regression inputs: what FuzzNormalMapGLTF found, reduced to the point (the tool's fix is
    # named in NormalMapGLTF.cxx).
    # tinygltf 2.7.0 wrote an empty node, scene, texture or material as `null`, and could not read
    # its own output back.
    g = quad()
    g.doc["nodes"].append({})
    g.doc["scenes"].append({})
    g.doc["textures"].append({})
    g.doc["materials"].append({})
    seeds["regression_empty_objects.gltf"] = g.gltf()
    # tinygltf 2.7.0 wrote integer min/max through static_cast<int> (undefined behaviour above
    # 2^31 - 1), here an UNSIGNED_INT attribute's declared max, and the bounds the tool
    # recomputes for it when points split (mirrored UVs).
    g = Gltf()
    mp = [(-1.0, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (-1.0, 1.0, 0.0), (0.0, 1.0, 0.0),
          (1.0, 1.0, 0.0)]
    ids = g.accessor([3000000000 + i for i in range(6)], "SCALAR", UINT)
    g.doc["accessors"][ids]["min"] = [3000000000]
    g.doc["accessors"][ids]["max"] = [3000000005]
    g.primitive({"POSITION": g.accessor(mp, "VEC3"),
                 "NORMAL": g.accessor([(0.0, 0.0, 1.0)] * 6, "VEC3"),
                 "TEXCOORD_0": g.accessor(muv, "VEC2"), "_FEATURE_ID_0": ids},
                g.accessor([0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4], "SCALAR", UBYTE,
                           target=ELEMENT_ARRAY_BUFFER))
    seeds["regression_uint_bounds.glb"] = g.glb()

    out = pathlib.Path(__file__).resolve().parent / "gltf-corpus"
    out.mkdir(exist_ok=True)
    for old in out.iterdir():
        old.unlink()
    for name, data in seeds.items():
        (out / name).write_bytes(data)


if __name__ == "__main__":
    main()
