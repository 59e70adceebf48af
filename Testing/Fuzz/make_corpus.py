#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of FuzzTangentFrames (Testing/Fuzz/corpus/*.bin).

Each seed is a small mesh in the byte layout that FuzzTangentFrames.cxx documents at its top:
good meshes (so that mutations start from inputs that reach the frame code) and one example of
each kind of hostile input. Run it from anywhere; it rewrites its seeds in the corpus directory
and leaves the other files there (inputs the fuzzer found, kept as it wrote them).
"""
import math
import pathlib
import struct

SPECIALS = ["nan", "-nan", "inf", "-inf", 0.0, "-0", 1.0, -1.0, 1e-300]  # first entries only


def value(v):
    """One value: a grid byte when v is a multiple of 1/8 in [-12.5, 12.375], else special/raw."""
    if isinstance(v, str):
        return bytes([200 + SPECIALS.index(v)])
    if math.isfinite(v) and v * 8 == int(v * 8) and -100 <= v * 8 < 100:
        return bytes([int(v * 8) + 100])
    return bytes([232]) + struct.pack("<d", v)


def cell(kind, ids, n_points):
    """A cell byte (kind 0 vertex, 1 line, 2 polygon, 3 strip) and one byte per id; ids
    outside [0, n_points) become the decoder's out-of-range codes (-1 or n_points)."""
    out = bytes([kind + 4 * len(ids)])
    for i in ids:
        out += bytes([i if 0 <= i < n_points else (240 if i < 0 else 241)])
    return out


def mesh(points, uvs, cells, normals=None, flags=0, uv_mode=0, uv_components=2, normal_mode=1,
         deltas=0, extra=None, malformed=None, supplied=None):
    """Bytes for one input. uvs/normals may be longer or shorter than points (set `deltas`
    accordingly); normals are per cell for normal_mode 4; extra: the 'Extra' values or None;
    malformed: None or (cell array 0-3, defect 0-7, position byte), see the decoder;
    supplied: None or (mode 1 KEEP / 2 KEEP_VALID, double, tangents, signs), tangents 3 or 4
    values per point, signs (for 3) one per point."""
    if malformed:
        flags |= 64
    data = bytes([flags, uv_mode + 8 * (uv_components - 1), normal_mode, deltas, len(points)])
    for p in points:
        data += b"".join(value(c) for c in p)
    for uv in uvs:
        data += b"".join(value(c) for c in uv)
    cell_normals = normal_mode >= 4  # read after the cells, one per cell
    for n in [] if cell_normals else normals or []:
        data += b"".join(value(c) for c in n)
    for e in extra or []:
        data += value(e)
    data += bytes([len(cells)])
    for kind, ids in cells:
        data += cell(kind, ids, len(points))
    if malformed:
        array, defect, where = malformed
        data += bytes([array + 4 * defect, where])
    for n in normals or [] if cell_normals else []:
        data += b"".join(value(c) for c in n)
    if supplied:
        mode, double, tangents, signs = supplied
        components = len(tangents[0])
        data += bytes([mode + 3 * int(double) + 6 * (components - 3)])
        for t in tangents:
            data += b"".join(value(c) for c in t)
        for s in signs or []:
            data += value(s)
    return data


def grid(nx, ny, mirror):
    """An nx x ny grid of quads in z = 0; with mirror the u coordinate folds at the middle."""
    points, uvs = [], []
    for j in range(ny + 1):
        for i in range(nx + 1):
            points.append((i, j, 0))
            u = min(i, nx - i) if mirror else i
            uvs.append((u / 8, j / 8))
    cells = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            cells.append((2, [a, a + 1, a + nx + 2, a + nx + 1]))
    return points, uvs, cells


def main():
    tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    tri_uv = [(0, 0), (1, 0), (0, 1)]
    up = [(0, 0, 1)] * 3
    seeds = {}
    seeds["triangle"] = mesh(tri, tri_uv, [(2, [0, 1, 2])], up)
    p, uv, c = grid(4, 2, True)
    seeds["mirrored_grid"] = mesh(p, uv, c, [(0, 0, 1)] * len(p), flags=8 | 16)
    p, uv, c = grid(3, 3, False)
    seeds["grid_no_normals_double"] = mesh(p, uv, c, flags=1 | 2, normal_mode=0)
    strip_points = [(i // 2, i % 2, 0) for i in range(6)]
    strip_uv = [(i // 2 / 4, i % 2 / 2) for i in range(6)]
    seeds["strip"] = mesh(strip_points, strip_uv, [(3, list(range(6)))], [(0, 0, 1)] * 6)
    seeds["mixed_cells_32bit"] = mesh(strip_points, strip_uv,
                                      [(0, [0, 5]), (1, [0, 2, 4]), (2, [0, 2, 3, 1]),
                                       (3, [0, 1, 2, 3]), (2, [1, 3]), (3, [4, 5])],
                                      [(0, 0, 1)] * 6, flags=32 | 16)
    seeds["non_finite"] = mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0), ("nan", 1, 0)],
                               [(0, 0), (1, 0), (0, "inf"), (1, 1)],
                               [(2, [0, 1, 2]), (2, [1, 3, 2])],
                               [(0, 0, 1), (0, 0, 0), ("nan", 0, 1), (0, 0, 1e-300)])
    seeds["huge_and_tiny"] = mesh([(0, 0, 0), (1e30, 0, 0), (0, 1e-30, 0)],
                                  [(0, 0), (1e-10, 0), (0, 1e10)], [(2, [0, 1, 2])], up)
    seeds["out_of_range_ids"] = mesh(tri, tri_uv, [(2, [0, 1, 7]), (3, [0, -1])], up)
    seeds["short_tcoords"] = mesh(tri, tri_uv[:2], [(2, [0, 1, 2])], up, deltas=4)
    seeds["cell_normals_extra_array"] = mesh(tri + [(1, 1, 0)], tri_uv + [(1, 1)],
                                             [(2, [0, 1, 2]), (2, [1, 3, 2])], normal_mode=4,
                                             normals=[(0, 0, 2), (0, 0, 1)],
                                             deltas=3 << 6, extra=[1, 2, 3, 4, 5, 6])
    seeds["named_uv_3_components"] = mesh(tri, [(0, 0, 5), (1, 0, 5), (0, 1, 5)],
                                          [(2, [0, 1, 2])], up, uv_mode=3, uv_components=3)
    seeds["repeated_ids_hexagon"] = mesh(strip_points, strip_uv, [(2, [0, 2, 2, 3, 1, 0])],
                                         [(0, 0, 1)] * 6)
    # Inputs that found bugs (now regression seeds): integer texture coordinates (a use after
    # free), a short strip with a bad id beside good cells (MikkTSpace read out of bounds), and
    # only empty polygons with cell tangents (MikkTSpace: a false error, an out-of-bounds read).
    seeds["short_integer_uv"] = mesh(tri, tri_uv, [(2, [0, 1, 2])], up, uv_mode=2)
    seeds["short_strip_bad_id"] = mesh(tri, tri_uv, [(2, [0, 1, 2]), (3, [1, 5])], up)
    seeds["empty_polygons_cell_tangents"] = mesh(tri, tri_uv, [(2, []), (3, [])], up, flags=16)
    # Malformed cell arrays (the filter read and wrote outside them before): polygon offsets
    # that decrease, strip offsets past the connectivity (32-bit storage), vertices without
    # offsets.
    p, uv, c = grid(4, 2, True)
    seeds["malformed_polygon_offsets"] = mesh(p, uv, c, [(0, 0, 1)] * len(p),
                                              malformed=(2, 3, 1))
    seeds["malformed_strip_offsets_32bit"] = mesh(strip_points, strip_uv,
                                                  [(3, list(range(6)))], [(0, 0, 1)] * 6,
                                                  flags=32, malformed=(3, 5, 1))
    seeds["malformed_no_vertex_offsets"] = mesh(strip_points, strip_uv,
                                                [(0, [0, 5]), (2, [0, 2, 3, 1])],
                                                [(0, 0, 1)] * 6, malformed=(0, 6, 0))
    # MikkTSpace corners the reference leaves without a unit perpendicular tangent: normals
    # along dP/du (the projected tangents cancel to zero), and zero UV area with normals that
    # are not perpendicular to its default (1, 0, 0).
    seeds["mikktspace_cancelled_corners"] = mesh(tri, tri_uv, [(2, [0, 1, 2])],
                                                 [(1, 0, 0)] * 3, flags=8)
    seeds["mikktspace_default_corners"] = mesh(tri, [(0.5, 0.5)] * 3, [(2, [0, 1, 2])],
                                               [(0.625, 0, 0.75)] * 3)
    # Supplied tangents kept as they are (KEEP) or where they pass the checks (KEEP_VALID): glTF
    # style 4-component tangents with one NaN, 3-component doubles with signs (one not unit, one
    # wrong sign), and doubles too large for the float output.
    p, uv, c = grid(4, 2, True)
    along_u = [((1 if i % 5 < 2.5 else -1), 0, 0, (1 if i % 5 < 2.5 else -1)) for i in range(len(p))]
    along_u[3] = ("nan", 0, 0, 1)
    seeds["supplied_keep_gltf"] = mesh(p, uv, c, [(0, 0, 1)] * len(p),
                                       supplied=(1, False, along_u, None))
    seeds["supplied_keep_valid_doubles"] = mesh(tri, tri_uv, [(2, [0, 1, 2])], up,
                                                supplied=(2, True,
                                                          [(1, 0, 0), (2, 0, 0), (1, 0, 0)],
                                                          [1, 1, -1]))
    seeds["supplied_keep_too_large_for_float"] = mesh(tri, tri_uv, [(2, [0, 1, 2])], up, flags=8,
                                                      supplied=(1, True,
                                                                [(1e300, 0, 0), (1, 0, 0),
                                                                 (0, 1e39, 0)],
                                                                [1, 1, 1]))
    # Found by the fuzzer: KEEP with every value finite computed no frame, so nothing found the
    # out-of-range id (no error, the broken cells passed on).
    seeds["supplied_keep_out_of_range_id"] = mesh(tri, tri_uv, [(2, [0, 1, 7])], up,
                                                  supplied=(1, False, [(1, 0, 0)] * 3, [1] * 3))
    # Cells whose triangles need both sides of a mirror seam at one corner, which splitting cuts
    # into triangles: a strip across the seam, with cell normals and cell tangents (cell data
    # that follows the cut), and a quad folded in UV.
    seam_points = [(i // 2, i % 2, 0) for i in range(8)]  # 8: the largest cell the decoder makes
    seam_uv = [(abs(i // 2 - 2) / 4, i % 2 / 2) for i in range(8)]
    seeds["strip_across_mirror_seam"] = mesh(seam_points, seam_uv, [(3, list(range(8)))],
                                             normal_mode=4, normals=[(0, 0, 1)], flags=16)
    seeds["quad_folded_in_uv"] = mesh([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
                                      [(0, 0), (1, 0), (1, 1), (1.5, 0.25)],
                                      [(2, [0, 1, 2, 3])], up + [(0, 0, 1)])
    out = pathlib.Path(__file__).resolve().parent / "corpus"
    out.mkdir(exist_ok=True)
    for name, data in seeds.items():
        (out / (name + ".bin")).write_bytes(data)


if __name__ == "__main__":
    main()
