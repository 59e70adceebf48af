// SPDX-License-Identifier: BSD-3-Clause
// File helpers of the normalmap tool: reading the VTK-readable mesh formats, writing outputs
// all-or-nothing (a temporary folder beside the output, renamed into place on success), and
// turning VTK's error and warning messages into one-line strings instead of console output.
#ifndef NormalMapFiles_h
#define NormalMapFiles_h

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkMultiBlockDataSet;
class vtkPolyData;

namespace NormalMapFiles
{
/// Lower-case extension with its dot ("/a/b.GLB" -> ".glb"); empty when there is none.
std::string Extension(const std::string& path);

/// "Reason" part of a VTK message ("ERROR: In f.cxx, line 3\nvtkX (0x1): reason\n\n"), on one
/// line; any other text with its line breaks folded into spaces; at most 400 characters.
std::string OneLine(const std::string& text);

/// While alive, VTK errors and warnings are collected (one line each) instead of printed.
class VTKMessageCapture
{
public:
  VTKMessageCapture();
  ~VTKMessageCapture();
  VTKMessageCapture(const VTKMessageCapture&) = delete;
  VTKMessageCapture& operator=(const VTKMessageCapture&) = delete;
  const std::vector<std::string>& Errors() const;
  const std::vector<std::string>& Warnings() const;

private:
  struct Internals;
  Internals* Internal;
};

/// The first value of the string array `name` of `mesh`'s field data; empty when there is none.
std::string FieldString(vtkPolyData* mesh, const char* name);

/// Sets the string array `name` of `mesh`'s field data to `value`, in a copy of its field data,
/// so that meshes sharing them keep theirs.
void SetFieldString(vtkPolyData* mesh, const char* name, const std::string& value);

/// Reads .vtp, .vtk (legacy polydata), .ply, .obj or .stl into polydata; nullptr with `error`
/// set (one line) when the file is missing, unreadable, of another format or has no cells.
vtkSmartPointer<vtkPolyData> ReadVTKMesh(const std::string& path, std::string& error);

/// Writes `mesh` as VTK XML polydata (binary, zlib-compressed) to `path`.
bool WriteVTP(vtkPolyData* mesh, const std::string& path, std::string& error);

/// The folder a VTK XML multiblock file keeps its blocks in: beside it, named after it without
/// its extension ("out/scene.vtm" -> "out/scene").
std::string BlockFolder(const std::string& vtmPath);

/// Writes `blocks` as a VTK XML multiblock file: `path` (.vtm) and its BlockFolder, which holds
/// one .vtp per block, written as WriteVTP writes them.
bool WriteVTM(vtkMultiBlockDataSet* blocks, const std::string& path, std::string& error);

/// A polydata block of a multiblock file and its name.
struct Block
{
  std::string Name; // the block's name in the file, else "block <i>" (its index among leaves)
  vtkSmartPointer<vtkPolyData> Mesh;
  /// The texture coordinates of its glTF material's normal texture ("TEXCOORD_<n>" from the
  /// field data NormalTextureTexCoord) when it has that array; else empty (the active ones).
  std::string TCoordsName;
  /// Its normal texture's strength (field data NormalTextureScale; 1 without, or when not finite,
  /// with a warning).
  double NormalTextureScale = 1.0;
};

/**
 * The polydata blocks with polygons of the VTK XML multiblock file `path`, in the file's order;
 * other blocks are skipped with a warning each. False with `error` (one line) when the file is
 * missing, unreadable or has no such block.
 */
bool ReadVTMBlocks(const std::string& path,
  std::vector<Block>& blocks,
  std::vector<std::string>& warnings,
  std::string& error);

/**
 * An output written all-or-nothing. Begin() makes a temporary folder in the output's folder
 * (so it fails at once when that folder is not writable); writers put their files in it with
 * PathFor(); Commit() renames them into the output's folder, the main file last. Anything not
 * committed is deleted when the object goes away, so no partial output is ever left behind.
 * A .vtm output's BlockFolder replaces the one a previous run wrote; Begin() refuses a folder of
 * that name that holds anything but .vtp files, which are not such a run's.
 */
class OutputTransaction
{
public:
  OutputTransaction() = default;
  ~OutputTransaction();
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;

  bool Begin(const std::string& finalPath, std::string& error);
  /// The final path of the main output.
  const std::string& FinalPath() const { return this->Final; }
  /// Where to write the file that will be `fileName` in the output's folder.
  std::string PathFor(const std::string& fileName) const;
  /// Where to write the main output.
  std::string MainPath() const;
  bool Commit(std::string& error);

private:
  void Discard();
  std::string Final;
  std::string TempDir;
};
}

#endif
