// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkPolyDataTangentFramesMikkTSpace.h
 * @brief  Private: the MikkTSpace method of vtkPolyDataTangentFrames (not installed).
 *
 * vtkPolyDataTangentFrames validates its input and provides point normals (the input's or ones
 * it computed), then calls RunMikkTSpace, which runs vtkNormalMapping::mikk::ComputeMikkTSpace
 * on the polygons and strips and turns its per-corner frames into per-point output.
 */
#ifndef vtkPolyDataTangentFramesMikkTSpace_h
#define vtkPolyDataTangentFramesMikkTSpace_h

#include "vtkType.h"

class vtkDataArray;
class vtkPolyData;
class vtkPolyDataTangentFrames;

namespace vtkNormalMapping
{
namespace detail
{
struct MikkTSpaceRequest
{
  vtkPolyDataTangentFrames* Filter = nullptr; // progress, abort and messages go through it
  vtkPolyData* Input = nullptr;
  vtkDataArray* TCoords = nullptr; // numeric, at least one tuple per point
  vtkDataArray* Normals = nullptr; // 3 components, one tuple per point (input's or computed)
  bool ComputedNormals = false;    // add Normals to the output point data as "Normals"
  bool DoublePrecision = false;    // output arrays as double (else float)
  bool GLTFSign = false;           // negate MikkTSpace's signs (glTF's v-down UVs)
  bool Splitting = true;
  bool Bitangents = false;
  bool CellTangents = false;
};

struct MikkTSpaceCounts
{
  vtkIdType Triangles = 0;           // kernel triangles (quads split, larger polygons fanned)
  vtkIdType DegenerateTriangles = 0; // kernel triangles with two equal corner positions
  // Kernel corners (polygon corners, 3 per strip triangle) left at MikkTSpace's default frame,
  // tangent (1,0,0) and sign -1.
  vtkIdType DefaultCorners = 0;
  // Kernel corners given the fallback frame: the default ones and those whose tangent cancelled
  // (not unit); see the contract in vtkPolyDataTangentFramesMikkTSpace.cxx.
  vtkIdType FallbackCorners = 0;
  // Points whose corners carry bitwise different frames, including points with a strip corner
  // whose strip triangles disagree (splitting cannot separate those).
  vtkIdType Conflicts = 0;
  vtkIdType SplitPoints = 0; // points appended (one per extra distinct frame)
};

/// Fills output with the frames; after an error, with the input passed through (and a
/// vtkErrorMacro message on the filter); when aborted, empty.
void RunMikkTSpace(const MikkTSpaceRequest& request, vtkPolyData* output, MikkTSpaceCounts& counts);
}
}

#endif
