// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkMikkTSpaceKernel.h
 * @brief MikkTSpace-compatible per-corner tangent frames (plain C++17 kernel, no vtkObject).
 *
 * ComputeMikkTSpace() reproduces the behaviour of the reference mikktspace.c
 * (Morten Mikkelsen's, github.com/mmikk/MikkTSpace: genTangSpaceDefault, angular threshold 180
 * degrees), reimplemented from a description of that behaviour:
 *
 * - Triangles and quads follow the reference exactly: quads are split on the shorter UV
 *   diagonal (position diagonal on an exact tie), welding is by exact value equality of
 *   position, normal and texture coordinate (+0 == -0, NaN never equal), triangles with two
 *   equal corner positions are degenerate and copy the frame of the first good corner with the
 *   same welded vertex, angle-weighted averaging per group in the reference's triangle order,
 *   float arithmetic as the reference (acos evaluated in double and rounded to float).
 * - Faces with more than 4 corners (the reference skips them) are fan-triangulated
 *   (corner 0, i, i+1). The fan triangles are ordinary triangles of that face: they weld,
 *   group and average like any other triangle, a face corner used by several fan triangles
 *   receives the reference's pairwise average of their frames (in group creation order), and a
 *   degenerate fan triangle only fills face corners that no good fan triangle covers. The quad
 *   specific rules (orientation forcing, "quad with one degenerate triangle") do not apply.
 * - Faces with fewer than 3 corners, and faces with a point id outside [0, NumberOfPoints),
 *   offsets outside the connectivity or a start before an earlier face's end (no two faces share
 *   a face corner), are skipped: their corners get the default frame.
 * - Corners never reached by a tangent group get the reference default: tangent (1,0,0),
 *   sign -1 (note: not perpendicular to the normal). Any non-finite result (for example from
 *   NaN or Inf input) is replaced by that default and counted. Result::CornerKinds marks these
 *   corners (CornerKind::Default), since a computed frame can have the same bits.
 *
 * Differences from the reference are limited to float rounding in the sign of zero components
 * (the reference reads a welded vertex's representative, whose zeros may carry the other sign),
 * to inputs with NaN/Inf (where the reference produces NaN or reads out of its grid), to the
 * reference's unsorted last run of edges (it leaves the edges at the welded vertex of the
 * largest index in quicksort order; docs/mikktspace.md) and to coordinates beyond about 1.7e38
 * (where the reference's welding grid overflows and it welds nothing).
 *
 * Sign convention: MikkTSpace's, bitangent = Sign * cross(N, T) with the texture coordinates
 * as given. glTF stores v downward: tangents for glTF are obtained by running on the glTF UVs
 * and negating Sign.
 *
 * Threading: vtkSMPTools' threads (those of the enclosing LocalScope, if any); the results are
 * bit-identical for any number of threads. vtkMikkTSpaceKernel.cxx lists the phases and which of
 * them run on the calling thread.
 *
 * Limits: 3 * (number of face corners) + NumberOfPoints must be at most 2^31 - 17 (32-bit
 * indices); larger inputs return Result::TooLarge with default frames.
 *
 * Build: without -ffast-math and without floating-point contraction, which would change the
 * last bits of the reference's float arithmetic (see the FP_CONTRACT pragma in
 * vtkMikkTSpaceKernel.cxx).
 */
#ifndef vtkMikkTSpaceKernel_h
#define vtkMikkTSpaceKernel_h

#include <functional>
#include <vector>

namespace vtkNormalMapping
{
namespace mikk
{

struct MeshInput
{
  long long NumberOfFaces = 0;                 ///< faces (polygons)
  const long long* FaceOffsets = nullptr;      ///< NumberOfFaces+1 offsets into FaceConnectivity
  const long long* FaceConnectivity = nullptr; ///< point ids, face corners in order
  long long NumberOfPoints = 0;
  const float* Positions = nullptr; ///< 3 per point
  const float* Normals = nullptr;   ///< 3 per point, assumed unit length (not renormalised)
  const float* TCoords = nullptr;   ///< 2 per point
};

/// Tangent of one face corner: tangent (unit unless IsCancelled) and sign (+1/-1, MikkTSpace
/// convention).
struct CornerFrame
{
  float Tangent[3];
  float Sign;
};

/// What a corner's frame in Result::Corners is. A computed frame can have the default's bits
/// (tangent exactly (1,0,0), sign -1, on an axis-aligned mesh), so only this tells them apart.
enum class CornerKind : unsigned char
{
  Computed,  ///< a tangent group's frame, with a unit tangent
  Default,   ///< DefaultCornerFrame: no group reached the corner, or its result was not finite
  Cancelled, ///< a tangent group's frame whose tangent is not unit (IsCancelled)
};

struct Result
{
  /// One per face corner, same layout as FaceConnectivity (size FaceOffsets[NumberOfFaces]).
  std::vector<CornerFrame> Corners;
  /// One per face corner, as Corners: what each corner's frame is.
  std::vector<CornerKind> CornerKinds;
  /// After splitting quads and fanning larger faces; faces with a point id out of range count too.
  long long NumberOfTriangles = 0;
  long long NumberOfDegenerateTriangles = 0;   ///< triangles with two equal corner positions
  long long NumberOfDefaultCorners = 0;        ///< corners of CornerKind::Default
  long long NumberOfNonFiniteCorners = 0;      ///< of those, corners whose result was not finite
  long long NumberOfCancelledCorners = 0;      ///< corners of CornerKind::Cancelled
  long long NumberOfGroupWithAnyTriangles = 0; ///< zero UV area / zero derivative triangles
  long long NumberOfSkippedFaces = 0;          ///< faces with fewer than 3 corners
  long long NumberOfInvalidFaces = 0;          ///< faces with bad point ids or offsets
  bool Aborted = false;                        ///< progress callback requested a stop
  bool TooLarge = false;                       ///< input exceeds the 32-bit index limits
};

/// Default frame of a corner that no group reached (the reference's initial value).
constexpr CornerFrame DefaultCornerFrame = { { 1.0f, 0.0f, 0.0f }, -1.0f };

/**
 * Whether a corner's tangent is not unit (|length - 1| > 1e-6; a normalized float tangent is
 * unit within a few ulps). The reference normalizes a group's summed tangent, in float, only
 * where a component exceeds FLT_MIN: where the group's tangents cancel, the sum comes back as
 * it is (every component at most FLT_MIN), or, with a squared length below FLT_MIN, normalized
 * only roughly. Sums that normalize to a non-finite tangent count as non-finite instead.
 */
inline bool IsCancelled(const CornerFrame& f)
{
  constexpr double tolerance = 1e-6;
  constexpr double lowest = (1.0 - tolerance) * (1.0 - tolerance);
  constexpr double highest = (1.0 + tolerance) * (1.0 + tolerance);
  const double tt = double(f.Tangent[0]) * f.Tangent[0] + double(f.Tangent[1]) * f.Tangent[1] +
    double(f.Tangent[2]) * f.Tangent[2];
  return !(tt >= lowest && tt <= highest);
}

/**
 * Compute MikkTSpace tangents for every face corner.
 * progressAndAbort: optional, called from the calling thread between phases with a progress in
 * [0,1]; returning true stops the computation (Result::Aborted, corners set to the default).
 * Empty Normals/TCoords/Positions pointers with a non-empty mesh yield all-default corners.
 */
Result ComputeMikkTSpace(const MeshInput& in,
  const std::function<bool(double progress)>& progressAndAbort = {});

} // namespace mikk
} // namespace vtkNormalMapping

#endif
