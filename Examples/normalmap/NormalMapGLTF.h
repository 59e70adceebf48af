// SPDX-License-Identifier: BSD-3-Clause
/**
 * glTF 2.0 in and out for tangent frames, with tinygltf (Debian: libtinygltf-dev).
 *
 * VTK 9.1's own glTF reader drops TANGENT.w; this one keeps it. A triangle primitive (mode
 * TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN) becomes one vtkPolyData:
 * - points: POSITION (float);
 * - point data: `Normals` (NORMAL, the active normals), `TEXCOORD_<n>` (2 components, float,
 *   dequantized when normalized integers; TEXCOORD_0 is the active TCoords, stored as in the
 *   file: v points down), `Tangents` (TANGENT.xyz, the active tangents) and `TangentSigns`
 *   (TANGENT.w), the names vtkPolyDataTangentFrames writes; `GLTFVertexId` (the vertex index in
 *   the primitive, which the filter copies to the points it splits);
 * - cells: triangles (strips and fans turned into triangles, winding kept);
 * - field data: `TCoordsVDown` = 1, `GLTFMesh`, `GLTFPrimitive`, `GLTFMaterial` (-1: none) and,
 *   when the material has a normal texture, `NormalTextureImage` (image index, -1 if the
 *   texture has no source), `NormalTextureTexCoord`, `NormalTextureScale`,
 *   `NormalTextureURI` (as stored, relative to the glTF file) and `NormalTextureFile` (that URI
 *   decoded and resolved against the glTF file's folder; empty for embedded images).
 *
 * Writing back (UpdatePrimitive) stores TANGENT as FLOAT VEC4: xyz unit (renormalized only
 * when not already unit to float precision), w exactly +1 or -1 (bitangent =
 * w * cross(N, T) points to the top of the image). When the filter split points, every
 * attribute of the primitive (and of its morph targets) is rewritten by copying the original
 * vertices' bytes through `GLTFVertexId`, so types, quantization and normalization are kept,
 * and new indices are written (mode TRIANGLES). Everything else in the file (materials,
 * textures, images, nodes, skins, animations, extras, other primitives) is kept. On writing,
 * accessors this module replaced and left unused are removed (unless the file uses an
 * extension that might refer to accessors by index), all buffers are packed into one (the .bin
 * of a .gltf, or the BIN chunk of a .glb), images stored as data URIs move into buffer views,
 * and relative image URIs are rewritten for the output's folder.
 *
 * Every index, offset, stride and count is checked before use: corrupt files give an error
 * (one line), never a crash.
 */
#ifndef NormalMapGLTF_h
#define NormalMapGLTF_h

#include <tiny_gltf.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

class vtkPolyData;

namespace NormalMapFiles
{
class OutputTransaction;
}

namespace NormalMapGLTF
{
constexpr const char* VertexIdArrayName = "GLTFVertexId";

struct Document
{
  tinygltf::Model Model;
  /// The file it was read from: relative image URIs are resolved against its folder.
  std::string Path;
  /// Accessors that UpdatePrimitive stopped using (removed on writing if nothing else uses them).
  std::vector<int> ReplacedAccessors;
};

struct PrimitiveId
{
  int Mesh = -1;
  int Primitive = -1;
};

/// "mesh M primitive P", as messages and the tool's reports name a primitive.
std::string PrimitiveName(PrimitiveId id);

/// Reads a .gltf (external or embedded buffers) or a .glb (detected by its magic number).
/// Image files are not decoded (nor needed).
bool ReadDocument(const std::string& path, Document& doc, std::string& error);
/// The same from memory (.gltf JSON or .glb bytes); `baseDir` resolves external URIs.
bool ReadDocumentFromMemory(const unsigned char* data,
  size_t size,
  const std::string& baseDir,
  Document& doc,
  std::string& error);

/// The triangle primitives (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN), mesh by mesh.
std::vector<PrimitiveId> TrianglePrimitives(const Document& doc);

/// A node of the scene that draws a mesh, and its world matrix (row-major: the product of its
/// ancestors' transforms and its own).
struct MeshPlacement
{
  int Node = -1;
  std::array<double, 16> Matrix{};
};

/**
 * Per mesh (by index), the nodes of the default scene (the first scene when none is marked)
 * that draw it. A mesh no node of that scene draws has none; so has every mesh of a file
 * without scenes.
 */
std::vector<std::vector<MeshPlacement>> PlaceMeshes(const Document& doc);

/**
 * A copy of `mesh` placed by the row-major matrix `m`: points by m, normals by the inverse
 * transpose of its linear part and tangents by that part (both unit again), and the
 * TangentSigns negated when m mirrors, so that sign * cross(N, T) still follows the bitangent.
 */
vtkSmartPointer<vtkPolyData> Placed(vtkPolyData* mesh, const std::array<double, 16>& m);

/// A primitive as the scene shows it.
struct PlacedMesh
{
  vtkSmartPointer<vtkPolyData> Mesh;
  std::string Name;
  bool ByNode = false; // placed by a node, not as stored
};

/**
 * `mesh`, a primitive of glTF mesh `meshIndex` named `name`, where the scene places it
 * (`placements`, PlaceMeshes'): a copy per node that draws that mesh (Placed; ", node N"
 * appended to the name when several do), else `mesh` as stored (also for `meshIndex` -1).
 */
std::vector<PlacedMesh> PlaceMesh(const std::vector<std::vector<MeshPlacement>>& placements,
  int meshIndex,
  vtkPolyData* mesh,
  const std::string& name);

/// The texture coordinate set the primitive's normal texture uses ("TEXCOORD_<texCoord>"), or
/// TEXCOORD_0 when its material has no normal texture.
std::string NormalTextureTexCoordName(const Document& doc, PrimitiveId id);

/// The encoded bytes of image `index` when the file holds them (a data: URI, or a buffer view,
/// whose byte range is checked against its buffer) and its declared mimeType (may be empty);
/// false with `error` (one line) when the image does not exist, is an external file, is empty
/// or its buffer view lies outside its buffer.
bool EmbeddedImage(const Document& doc,
  int index,
  std::vector<unsigned char>& bytes,
  std::string& mimeType,
  std::string& error);

/// One primitive as polydata (see above); nullptr with `error` set when it is corrupt.
vtkSmartPointer<vtkPolyData> PrimitiveToPolyData(const Document& doc,
  PrimitiveId id,
  std::string& error);

/// Writes the tangent frames of `frames` (the filter's output for PrimitiveToPolyData's polydata:
/// `GLTFVertexId`, `Tangents`, `TangentSigns` in glTF's convention, triangles) into the
/// primitive. Adds NORMAL from `Normals` when the primitive had none.
bool UpdatePrimitive(Document& doc, PrimitiveId id, vtkPolyData* frames, std::string& error);

/// A new document with one mesh, node and scene from `frames` (points, `Normals`, texture
/// coordinates from `tcoordsName` or the active TCoords, `Tangents` + `TangentSigns`, polygons
/// fan-triangulated and strips). Texture coordinates with v up (no TCoordsVDown field data)
/// are flipped to glTF's v down (v' = 1 - v); the signs need no change.
bool DocumentFromPolyData(vtkPolyData* frames,
  const std::string& tcoordsName,
  Document& doc,
  std::string& error);

/// Writes `doc` (modified: buffers packed) as .gltf + .bin or as .glb, by the extension of the
/// transaction's final path, into the transaction's folder (Commit() to publish).
bool WriteDocument(Document& doc, NormalMapFiles::OutputTransaction& output, std::string& error);
/// The same, all-or-nothing, to `path`.
bool WriteDocument(Document& doc, const std::string& path, std::string& error);
}

#endif
