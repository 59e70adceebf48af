// SPDX-License-Identifier: BSD-3-Clause
// What `normalmap check` reports about a mesh's supplied tangents: the defects of
// vtkTangentFrameChecks.h (the checks vtkPolyDataTangentFrames' KEEP_VALID uses), how far the
// tangents are from MikkTSpace computed on the same mesh, and a one-line verdict per primitive.
#ifndef NormalMapCheck_h
#define NormalMapCheck_h

#include "vtkTangentFrameChecks.h"

#include <vtkType.h>

#include <iosfwd>
#include <string>
#include <vector>

class vtkPolyData;

namespace NormalMapCheck
{
/// A vertex "differs" from MikkTSpace when its tangent is more than this many degrees from
/// MikkTSpace's or its sign is the other one. Two MikkTSpace implementations on the same mesh
/// agree to float rounding (about 1e-4 degree); a degree is far above that and below what a
/// normal map shows.
constexpr double DifferingAngleDegrees = 1.0;

/// Tangents are "MikkTSpace-like" when at most this fraction of their vertices differ: authoring
/// tools that run MikkTSpace on their own welding or on quads before triangulating change the
/// frames along seams and across quads (up to a tenth of the vertices on the Khronos samples made
/// that way); other methods differ on most vertices.
constexpr double MikkTSpaceLikeFraction = 0.1;

/// The supplied tangents against MikkTSpace on the same mesh (Splitting off).
struct MikkTSpaceComparison
{
  /// Vertices with a finite, non-zero supplied tangent.
  vtkIdType Compared = 0;
  double MedianDegrees = 0.0;
  double P99Degrees = 0.0;
  double MaxDegrees = 0.0;
  vtkIdType SignsAgree = 0;
  /// Vertices whose w is against the winding of their UVs (or of some of them) and also differs
  /// from MikkTSpace's: those shade inside out. (Where the point normal faces away from a
  /// triangle, the winding relative to the normal and MikkTSpace's sign, which ignores the
  /// normal, disagree: such vertices are against one but not both.)
  vtkIdType SignsWrong = 0;
  /// Vertices more than DifferingAngleDegrees away or with the other sign.
  vtkIdType Differing = 0;
};

/// The report on one mesh (a glTF primitive, or a whole VTK file).
struct Report
{
  std::string Name;
  vtkIdType Vertices = 0;
  bool HasTangents = false;
  bool HasNormals = false;
  bool HasTCoords = false;
  /// Texture coordinates stored with v down (glTF): the expected signs are glTF's.
  bool VDown = false;
  vtkNormalMapping::FrameCheckCounts Counts;
  /// Groups of vertices with the same position, normal and texture coordinates whose tangents
  /// differ (by DifferingAngleDegrees, or in sign): seams where there is no seam.
  vtkIdType InconsistentDuplicates = 0;
  MikkTSpaceComparison MikkTSpace;
  /// One line naming the defect, or starting with "OK".
  std::string Verdict;
  bool Ok = false;
};

/**
 * Checks the supplied tangents of `mesh` (FindSuppliedFrames with `tangentsName`) against its
 * point `Normals` and texture coordinates `tcoordsName` (empty: the active ones).
 */
Report CheckMesh(vtkPolyData* mesh,
  const std::string& name,
  const std::string& tcoordsName,
  const std::string& tangentsName,
  bool vDown);

/**
 * Reports on every triangle primitive of a .gltf / .glb file (with the texture coordinates of its
 * normal texture), on every polydata block of a .vtm file, or on the mesh of a VTK-readable file;
 * false with `error` when the file cannot be read. `vDown` forces glTF's sign convention for
 * non-glTF files (TCoordsVDown field data sets it too). `warnings`, when given, receives what
 * was skipped (blocks of a .vtm that are not polydata with polygons).
 */
bool CheckFile(const std::string& path,
  const std::string& tangentsName,
  bool vDown,
  std::vector<Report>& reports,
  std::string& error,
  std::vector<std::string>* warnings = nullptr);

/// The reports as text (one block per primitive) or as one JSON object.
void PrintText(std::ostream& os, const std::string& path, const std::vector<Report>& reports);
void PrintJson(std::ostream& os, const std::string& path, const std::vector<Report>& reports);
}

#endif
