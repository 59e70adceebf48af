// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkNormalMappingMeshes.h
 * @brief  Generated meshes with texture coordinates whose true tangent frames are known.
 *
 * Used by the demo, the tests and the benchmarks, and handy for users trying the module out.
 */
#ifndef vtkNormalMappingMeshes_h
#define vtkNormalMappingMeshes_h

#include "vtkNormalMappingModule.h" // For export macro
#include "vtkSmartPointer.h"        // For return values

class vtkPolyData;

namespace vtkNormalMapping
{
struct TorusOptions
{
  /// Quads around the ring (u) and around the tube (v); the mesh has 2 * U * V triangles.
  int U = 256;
  int V = 128;
  double RingRadius = 1.0;
  double TubeRadius = 0.35;
  /**
   * Mirror the texture in u: u' = 2 min(s, 1 - s) for s in [0, 1] around the ring, so the two
   * halves use the same texture mirrored (handedness +1 for s < 1/2, -1 beyond). The columns at
   * s = 0 and s = 1/2 are mirror seams whose points are shared by both sides. Without
   * mirroring u' = s and the column at s = 0 is duplicated (an ordinary UV seam).
   */
  bool MirrorU = false;
  /// Store points, normals and texture coordinates as double instead of float.
  bool DoublePrecision = false;
};

/**
 * A torus of triangles with point `Normals` (exact, unit) and `TCoords`. At a point at angle
 * phi around the ring the true tangent dP/du' is sign * (-sin phi, cos phi, 0), sign being -1
 * on the mirrored half.
 */
VTKNORMALMAPPING_EXPORT vtkSmartPointer<vtkPolyData> MakeTorus(const TorusOptions& options);
}

#endif
