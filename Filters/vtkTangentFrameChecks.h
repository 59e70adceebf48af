// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkTangentFrameChecks.h
 * @brief  Checks of supplied tangent frames (a glTF TANGENT, a reader's `Tangents` array).
 *
 * One code path for vtkPolyDataTangentFrames' SuppliedTangents setting and for the report of
 * `normalmap check`: each point's supplied tangent and sign are tested against its normal and
 * against the UV winding of its triangles, and every failure is named.
 *
 * Sign convention: bitangent = sign * cross(N, T) points towards growing v of texture
 * coordinates with v up (VTK's convention). With `vDown` (glTF's texture coordinates, stored as
 * in the file) the expected sign is the opposite of the UV winding, which is what glTF's
 * TANGENT.w holds.
 *
 * Installed (not wrapped) because the normalmap tool, which can be built against an installed
 * module, reports with it; it is not part of the filter's public interface.
 */
#ifndef vtkTangentFrameChecks_h
#define vtkTangentFrameChecks_h

#include "vtkNormalMappingModule.h" // For export macro
#include "vtkType.h"                // For vtkIdType

#include <cfloat> // For DBL_MAX
#include <string>
#include <vector>

class vtkDataArray;
class vtkPolyData;

namespace vtkNormalMapping
{
/**
 * How far a supplied frame may be from the ideal before it counts as broken. The defaults accept
 * tangents and normals stored as 8-bit normalized integers (KHR_mesh_quantization) and reject
 * defects large enough to show in shading; docs/filter.md, "Supplied tangents", gives the reason
 * for each and the defects of real files.
 */
struct FrameCheckTolerances
{
  double Unit = 1e-2;          ///< largest | |T| - 1 |
  double Perpendicular = 2e-2; ///< largest |T.N| / |T|, the cosine of the tangent-normal angle
  double Sign = 1e-2;          ///< largest | |w| - 1 |
};

/// What can be wrong with one point's supplied frame (bits of FrameCheck::Defects).
enum FrameDefect : unsigned char
{
  /// A tangent component or the sign is NaN or infinite, or the tangent is longer than the
  /// largest length CheckSuppliedFrames was given (what the caller's output can hold).
  DefectNonFinite = 1,
  /// The tangent's length is not 1 within FrameCheckTolerances::Unit.
  DefectNotUnit = 2,
  /// The tangent is not perpendicular to the normal within FrameCheckTolerances::Perpendicular,
  /// or the point's normal is zero or non-finite so that nothing can be checked against it.
  DefectNotPerpendicular = 4,
  /// The sign is not +1 or -1 within FrameCheckTolerances::Sign.
  DefectSignNotUnit = 8,
  /// Every usable triangle of the point has the other UV winding than the sign says.
  DefectSignAgainstWinding = 16,
  /// The point's triangles have both windings (a mirror seam whose point is shared, not split):
  /// one sign cannot be right for all of them.
  DefectMixedWinding = 32,
};

/// The supplied arrays: tangents with 4 components (w: the sign), or 3 plus a sign array.
struct SuppliedFrameArrays
{
  vtkDataArray* Tangents = nullptr;
  /// One component per point; nullptr when Tangents has 4 components.
  vtkDataArray* Signs = nullptr;
  /// Whether the tangents (and signs) can be read: numeric, one tuple per point at least.
  bool IsUsable() const { return this->Tangents != nullptr; }
};

/**
 * The supplied frames of `mesh`: the point array `name`, or with an empty name the active
 * tangents attribute, else a point array named `Tangents`. With 3 components the signs come from
 * the point array `TangentSigns`. Unusable (with `problem` set to one line) when an array is
 * missing, not numeric, shorter than the points, or of another number of components.
 */
VTKNORMALMAPPING_EXPORT SuppliedFrameArrays FindSuppliedFrames(vtkPolyData* mesh,
  const std::string& name,
  std::string& problem);

/// Counts over the points of a FrameCheck.
struct FrameCheckCounts
{
  vtkIdType Points = 0;
  /// Points with at least one defect.
  vtkIdType Failed = 0;
  vtkIdType NonFinite = 0;
  vtkIdType NotUnit = 0;
  vtkIdType NotPerpendicular = 0;
  vtkIdType SignNotUnit = 0;
  vtkIdType SignAgainstWinding = 0;
  vtkIdType MixedWinding = 0;
  /// Points whose triangles all have one winding and whose sign agrees with it.
  vtkIdType SignAgreesWithWinding = 0;
  /// Points with no usable triangle (zero UV or position area): their sign is not checked.
  vtkIdType NoWinding = 0;
  /// Points whose supplied sign is positive.
  vtkIdType PositiveSigns = 0;
  /// Largest | |T| - 1 | and |T.N| / |T| over the finite tangents (0 when there are none).
  double MaxLengthError = 0.0;
  double MaxCosineToNormal = 0.0;
};

/// The result of CheckSuppliedFrames.
struct FrameCheck
{
  /// Per point, its FrameDefect bits (0: the supplied frame is good).
  std::vector<unsigned char> Defects;
  FrameCheckCounts Counts;
};

/**
 * Checks every point's supplied frame against its normal (`normals`: 3 components, one tuple
 * per point) and, when `uvs` is given, against the winding of its triangles (polygons fanned
 * from corner 0 and strips, as vtkPolyDataTangentFrames reads them; triangles with zero UV or
 * position area, by vtkNormalMapping::DegeneracyTolerance, are not counted). Without `uvs` the
 * winding is not checked (no DefectSignAgainstWinding nor DefectMixedWinding). Point ids outside
 * the points make their triangle count as unusable. A tangent longer than `largest` counts as
 * non-finite: a caller that writes frames to float arrays passes a length they can hold. Runs
 * on vtkSMPTools.
 */
VTKNORMALMAPPING_EXPORT FrameCheck CheckSuppliedFrames(vtkPolyData* mesh,
  vtkDataArray* normals,
  vtkDataArray* uvs,
  const SuppliedFrameArrays& supplied,
  bool vDown,
  const FrameCheckTolerances& tolerances = FrameCheckTolerances(),
  double largest = DBL_MAX);

/// Tangent and sign of point `id` of the supplied arrays (sign: the raw w or sign value).
VTKNORMALMAPPING_EXPORT void SuppliedFrame(const SuppliedFrameArrays& supplied,
  vtkIdType id,
  double tangent[3],
  double& sign);
}

#endif
