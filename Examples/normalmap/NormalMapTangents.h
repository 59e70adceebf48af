// SPDX-License-Identifier: BSD-3-Clause
// Runs vtkPolyDataTangentFrames for the normalmap tool and its tests, with one rule for the
// handedness sign whatever the method: TangentSigns always means
// bitangent = sign * cross(N, T) points towards the top of the texture image, which is glTF's
// TANGENT.w. For texture coordinates stored with v down (glTF's convention, marked by the
// field data TCoordsVDown) the signs of the weighted methods are negated here, because the
// filter's GLTFSignConvention only applies to its MikkTSpace method.
#ifndef NormalMapTangents_h
#define NormalMapTangents_h

#include "vtkPolyDataTangentFrames.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <functional>
#include <string>
#include <vector>

class vtkPolyData;

namespace NormalMapTangents
{
/// Field data (one int, 1) marking texture coordinates stored with v pointing down (glTF).
constexpr const char* VDownArrayName = "TCoordsVDown";
bool IsVDown(vtkPolyData* mesh);
void MarkVDown(vtkPolyData* mesh);
/**
 * Turns `mesh`'s v-down texture coordinates to VTK's v up (v' = 1 - v): the active TCoords and
 * every 2-component point array named TEXCOORD_<n>, as new arrays of the same types, and removes
 * the TCoordsVDown mark. The tangents and their signs stay valid: the bitangent still points to
 * the top of the image.
 */
void FlipToVUp(vtkPolyData* mesh);

struct Options
{
  int Method = vtkPolyDataTangentFrames::MIKKTSPACE;
  bool Splitting = true;
  /// Point array holding the texture coordinates; empty: the active TCoords.
  std::string TCoordsName;
  /// The texture coordinates have v pointing down (glTF); also set by TCoordsVDown field data.
  bool VDown = false;
  /// vtkPolyDataTangentFrames::SuppliedTangents: RECOMPUTE, KEEP or KEEP_VALID.
  int SuppliedTangents = vtkPolyDataTangentFrames::RECOMPUTE;
};

struct Counts
{
  vtkIdType InputPoints = 0;
  vtkIdType OutputPoints = 0;
  vtkIdType Triangles = 0;
  vtkIdType SplitPoints = 0;
  vtkIdType DegenerateTriangles = 0;
  vtkIdType FallbackPoints = 0;
  vtkIdType InvalidNormals = 0;
  vtkIdType ReplacedTangents = 0;
  void Add(const Counts& other);
};

/// The texture coordinate array the filter would use (nullptr when there is none usable).
vtkDataArray* FindTCoords(vtkPolyData* mesh, const std::string& name);

/// Tangent frames of `input`; nullptr with `error` set (one line) on failure. Filter warnings
/// are appended to `warnings`; `progress` receives the filter's progress (0..1).
vtkSmartPointer<vtkPolyData> Compute(vtkPolyData* input,
  const Options& options,
  Counts& counts,
  std::vector<std::string>& warnings,
  std::string& error,
  const std::function<void(double)>& progress = {});
}

#endif
