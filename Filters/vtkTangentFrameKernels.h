// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkTangentFrameKernels.h
 * @brief  The math of tangent frames, as free functions over GLM vectors.
 *
 * vtkPolyDataTangentFrames is a pipeline shell around these kernels; the tests call them directly,
 * without a pipeline (private: not installed). Everything is computed in double precision, whatever
 * the precision of the stored data: float input converts to double exactly, and the rounding of
 * the double arithmetic lies far below that of the stored float coordinates.
 *
 * Robustness at the extremes (docs/numerics.md, "Scale"): edge and UV-delta vectors whose largest
 * component lies outside [2^-160, 2^160] are rescaled by an exact power of two before any product
 * is formed; inside, where every float input lies (float differences lie in [2^-149, 2^129]),
 * rescaling could not change a bit and is skipped. Non-finite input makes a triangle degenerate
 * instead of spreading NaN.
 *
 * The block loops (ComputeTriangleBlock, SignCornerWeights, ComputePointBlock) and the functions
 * their vectorized loops call are VTK_ALWAYS_INLINE: every compiler then sees each such loop
 * whole and can vectorize it, also inside the clones of a multiversioned caller
 * (VTK_NORMALMAPPING_TARGET_CLONES), which only inline what they are made to. The loops over the
 * rare cases call ordinary functions.
 */
#ifndef vtkTangentFrameKernels_h
#define vtkTangentFrameKernels_h

#include "vtkSetGet.h" // VTK_ALWAYS_INLINE

#include <glm/glm.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace vtkNormalMapping
{

/// How the triangles around a point are weighted when their tangents are summed.
enum class TangentMethod : int
{
  /// Sum of the unit per-triangle tangents. Cheapest; over-weights small triangles and
  /// depends on how a fan is tessellated.
  Unweighted = 0,
  /// Each unit per-triangle tangent weighted by the triangle's area (Lengyel-style
  /// accumulation with explicit area weights). Large triangles dominate; cheap.
  AreaWeighted = 1,
  /// Each unit per-triangle tangent weighted by the triangle's interior angle at the point.
  /// Independent of how a fan is split into triangles; costs three corner angles per triangle.
  AngleWeighted = 2,
};

/**
 * Relative thresholds below which a triangle is degenerate (docs/numerics.md, "Degenerate
 * triangles"): UV bounds the shape ratio 2*area / (longest edge)^2 in UV space, below which the
 * rounding of the stored texture coordinates alone decides the frame; PositionNoise bounds the
 * height of a triangle relative to its largest coordinate (IsRoundingNoise), which also bounds
 * its shape ratio in position space.
 */
struct DegeneracyTolerance
{
  /// The thresholds in units of the stored precision's machine epsilon.
  static constexpr double UVFactor = 4.0;
  static constexpr double PositionNoiseFactor = 64.0;

  double UV = UVFactor * FLT_EPSILON;
  double PositionNoise = PositionNoiseFactor * FLT_EPSILON;

  /// Tolerances for data stored with the given machine epsilons.
  static DegeneracyTolerance ForEpsilons(double positionEpsilon, double uvEpsilon)
  {
    DegeneracyTolerance tol;
    tol.UV = UVFactor * uvEpsilon;
    tol.PositionNoise = PositionNoiseFactor * positionEpsilon;
    return tol;
  }
};

/**
 * Whether a triangle's height h = |n| / L (n the cross product of two edges, L the longest edge)
 * lies within the rounding noise of its coordinates, where it carries no direction
 * (docs/numerics.md, "Degenerate triangles"): h <= noise * m, where m is the largest coordinate
 * magnitude of its corners and noise = DegeneracyTolerance::PositionNoise. Inputs are those of
 * ComputeTriangleFrame, in its rescaled units: twiceArea2 = |n|^2, longest2 = L^2, m scaled
 * likewise (inf where that overflows, which makes the triangle noise, as it is). Squared, without
 * a square root; NaN is noise.
 */
VTK_ALWAYS_INLINE bool IsRoundingNoise(double twiceArea2, double longest2, double m, double noise)
{
  const double bound = noise * m;
  return !(twiceArea2 > bound * bound * longest2);
}

/// What one triangle contributes to the frames of its corners.
struct TriangleFrame
{
  /// Unit dP/du (the direction in which u grows on the triangle); zero when Orientation is 0.
  glm::dvec3 Tangent{ 0.0 };
  /// Along the winding normal (p1-p0)x(p2-p0), of no particular length (it is the cross product
  /// of the rescaled edges: normalizing it here would cost a square root and a division per
  /// triangle that the sign tests do not need); zero when degenerate in position.
  glm::dvec3 Normal{ 0.0 };
  /// Area of the triangle in position space: 0, or clamped to [detail::AreaMinimum,
  /// detail::AreaMaximum].
  double Area = 0.0;
  /// +1 when the UV winding agrees with the position winding, -1 when mirrored, 0 when the
  /// triangle has no usable frame (zero UV area, zero area, or non-finite input).
  signed char Orientation = 0;
};

namespace detail
{
VTK_ALWAYS_INLINE double MaxAbs(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::max(
    { std::abs(a.x), std::abs(a.y), std::abs(a.z), std::abs(b.x), std::abs(b.y), std::abs(b.z) });
}
/// The largest component magnitude of a.
inline double MaxAbs(const glm::dvec3& a)
{
  return std::max(std::abs(a.x), std::max(std::abs(a.y), std::abs(a.z)));
}
VTK_ALWAYS_INLINE double MaxAbs(const glm::dvec2& a, const glm::dvec2& b)
{
  return std::max({ std::abs(a.x), std::abs(a.y), std::abs(b.x), std::abs(b.y) });
}
/// The exponent k such that x * 2^k lies in [0.5, 1), for positive finite x.
inline int UnitExponent(double x)
{
  int e = 0;
  std::frexp(x, &e);
  return -e;
}

/// 2^k for k in [-1022, 1023], built from its bits.
inline double PowerOfTwo(int k)
{
  const std::uint64_t bits = static_cast<std::uint64_t>(k + 1023) << 52;
  double p;
  std::memcpy(&p, &bits, sizeof(p));
  return p;
}

/// Largest components of edge and UV-delta vectors that need no rescaling (see the file comment):
/// products of four such numbers stay within [2^-640, 2^644] times small constants.
constexpr double SafeMinimum = 0x1p-160;
constexpr double SafeMaximum = 0x1p160;

/// Whether vectors whose largest component is m need no rescaling (false for 0 and non-finite m).
VTK_ALWAYS_INLINE bool InSafeRange(double m)
{
  return (m >= SafeMinimum) & (m <= SafeMaximum);
}

/// The exponent by which vectors whose largest component is m > 0 are rescaled: 0 inside the
/// safe range, else the one that brings m into [0.5, 1).
inline int RescaleExponent(double m)
{
  return InSafeRange(m) ? 0 : UnitExponent(m);
}

/// The range of triangle areas as weights. Only edges outside the safe range give areas outside
/// it (a triangle whose edges lie inside and that is not rounding noise has an area within about
/// [2^-340, 2^320]); those areas are clamped to it, so that they weigh alike there: sums of up to
/// 2^63 of them, or of their multiples by unit vectors, neither overflow nor vanish, and the
/// weighted directions degrade to unweighted ones instead of to a fallback.
constexpr double AreaMinimum = 0x1p-900;
constexpr double AreaMaximum = 0x1p900;

/// The same for the normalization of one vector (normals, summed tangents): no product of two
/// components of a vector whose largest component lies in [NormalizeMinimum, NormalizeMaximum]
/// can overflow, and a product that underflows is below 2^-222 of the largest square it is added
/// to, so it cannot change the sum: rescaling would not change a bit of the unit vector and is
/// skipped.
constexpr double NormalizeMinimum = 0x1p-400;
constexpr double NormalizeMaximum = 0x1p400;
inline int NormalizeExponent(double m)
{
  return (m >= NormalizeMinimum && m <= NormalizeMaximum) ? 0 : UnitExponent(m);
}

/// v * 2^k for any k a double exponent can need (two steps outside the normal range). Exact
/// whenever the result components are normal numbers: directions and ratios do not change.
template<typename V>
inline V ScaleByPowerOfTwo(const V& v, int k)
{
  if (k > 1023 || k < -1022)
  {
    const int half = k / 2;
    return (v * PowerOfTwo(half)) * PowerOfTwo(k - half);
  }
  return v * PowerOfTwo(k);
}

/// atan(z) = z + z x Q(x) with x = z^2 on |z| <= tan(pi/8): the coefficients of Q, a minimax fit
/// of degree 9 (scripts/atan_minimax.py: Remez exchange on the relative error of atan), accurate
/// to double precision (TestTangentFrameKernels bounds the angles).
constexpr double AtanMinimax[10] = { -0.3333333333333015,
  0.19999999999088963,
  -0.1428571419526196,
  0.1111110665361545,
  -0.0909078241313454,
  0.07690068309805519,
  -0.06641121267638711,
  0.05692539356211354,
  -0.04359096199725628,
  0.02125985465703717 };

/// atan(z) for |z| <= tan(pi/8): z + (z x) Q(x) (AtanMinimax), with x = z^2 and Q in Estrin's
/// order, whose chain of dependent operations is half as long as Horner's.
VTK_ALWAYS_INLINE double AtanOfReduced(double z)
{
  const double* c = AtanMinimax;
  const double x = z * z;
  const double x2 = x * x;
  const double x4 = x2 * x2;
  const double x8 = x4 * x4;
  const double low = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2;
  const double high = (c[4] + c[5] * x) + (c[6] + c[7] * x) * x2;
  const double q = (low + high * x4) + (c[8] + c[9] * x) * x8;
  return z + (z * x) * q;
}

constexpr double TanPiOver8 = 0.41421356237309504880;
constexpr double PiOver4 = 0.78539816339744830962;
constexpr double PiOver2 = 1.5707963267948966192;
constexpr double Pi = 3.14159265358979323846;

/**
 * atan2(s, c) for s >= 0, in [0, pi]: reduce to z = min/max in [0, 1], then to |z'| <= tan(pi/8)
 * with atan(z) = pi/4 + atan((z - 1) / (z + 1)), and evaluate AtanOfReduced: one division and a
 * polynomial, for the three corner angles of every triangle, instead of a library call. Within
 * about one ulp of std::atan2 (TestTangentFrameKernels bounds it). Selects instead of branches,
 * so that loops over many angles vectorize.
 */
VTK_ALWAYS_INLINE double AngleFromSineCosine(double s, double c)
{
  const double ac = std::abs(c);
  const bool steep = s > ac;
  const double num = steep ? ac : s;
  const double den = steep ? s : ac;
  // One division either way: (num - den) / (num + den) is (z - 1) / (z + 1) for z = num / den.
  const bool reduce = num > TanPiOver8 * den;
  const double z = (reduce ? num - den : num) / (reduce ? num + den : den);
  const double base = reduce ? PiOver4 : 0.0;
  double angle = base + AtanOfReduced(z); // atan(num / den) in [0, pi/2]
  angle = steep ? PiOver2 - angle : angle;
  angle = c < 0.0 ? Pi - angle : angle;
  return den > 0.0 ? angle : 0.0;
}

/// c ? a : b, per component: selects of scalars, which a vectorizing compiler turns into blends.
VTK_ALWAYS_INLINE glm::dvec3 Select(bool c, const glm::dvec3& a, const glm::dvec3& b)
{
  return glm::dvec3(c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z);
}

inline bool IsFinite(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/**
 * The frame of a triangle from its edges e1 = p1 - p0, e2 = p2 - p0 and UV deltas d1, d2, whose
 * largest components need no rescaling (RescaleExponent 0, or rescaled already). Selects instead
 * of branches, so that a loop over many triangles vectorizes (ComputeTriangleBlock); the Area is
 * that of the edges as given.
 */
VTK_ALWAYS_INLINE TriangleFrame FrameFromEdges(const glm::dvec3& e1,
  const glm::dvec3& e2,
  const glm::dvec2& d1,
  const glm::dvec2& d2,
  double maxCoordinate,
  const DegeneracyTolerance& tol)
{
  const glm::dvec3 e3 = e2 - e1;
  const glm::dvec3 n = glm::cross(e1, e2);
  const double twiceArea2 = glm::dot(n, n);
  const double longest2 = std::max({ glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3) });
  const glm::dvec2 d3 = d2 - d1;
  const double det = d1.x * d2.y - d2.x * d1.y;
  const double longestUV2 = std::max({ glm::dot(d1, d1), glm::dot(d2, d2), glm::dot(d3, d3) });
  // The tangent direction is sign(det) * (dv2 E1 - dv1 E2): dP/du without the division by det,
  // so a tiny determinant never overflows.
  glm::dvec3 t = d2.y * e1 - d1.y * e2;
  t = Select(det < 0.0, -t, t);
  const double tLength = glm::length(t);

  // Degeneracy, decided here only. Position: a height above the rounding noise of the
  // coordinates (IsRoundingNoise); UV: |det| > tol * longestUV^2. NaN fails both.
  const bool hasArea = !IsRoundingNoise(twiceArea2, longest2, maxCoordinate, tol.PositionNoise);
  const bool hasUVArea = std::abs(det) > tol.UV * longestUV2;
  // With edges and UV deltas in the safe range, tLength is finite: only its zero needs a test.
  const bool hasTangent = hasArea & hasUVArea & (tLength > 0.0);

  const double twiceArea = std::sqrt(twiceArea2);
  TriangleFrame frame;
  frame.Normal = Select(hasArea, n, glm::dvec3(0.0));
  frame.Area = hasArea ? 0.5 * twiceArea : 0.0;
  frame.Tangent = Select(hasTangent, t * (1.0 / tLength), glm::dvec3(0.0));
  frame.Orientation = static_cast<signed char>(hasTangent ? (det > 0.0 ? 1 : -1) : 0);
  return frame;
}

/**
 * The cosines of a triangle's interior angles, scaled by the lengths of the two edges at each
 * corner: e1.e2 at corner 0, -e1.e3 at corner 1, e2.e3 at corner 2, with e3 = e2 - e1.
 */
VTK_ALWAYS_INLINE void ScaledCornerCosines(const glm::dvec3& e1,
  const glm::dvec3& e2,
  double cosines[3])
{
  const glm::dvec3 e3 = e2 - e1;
  cosines[0] = glm::dot(e1, e2);
  cosines[1] = -glm::dot(e1, e3);
  cosines[2] = glm::dot(e2, e3);
}

/**
 * The interior angle at a corner of a triangle whose FrameFromEdges area is `area`, from the
 * scaled cosine there (ScaledCornerCosines); zero when the triangle is degenerate in position
 * (its area is zero). The two edges at any corner span the same parallelogram, so its area
 * serves as the sine of all three corners.
 */
VTK_ALWAYS_INLINE double CornerAngle(double area, double scaledCosine)
{
  const double sine = 2.0 * area; // |e1 x e2| (FrameFromEdges halves it exactly), or 0
  const double angle = AngleFromSineCosine(sine, scaledCosine);
  return sine > 0.0 ? angle : 0.0;
}

/// The largest coordinate magnitude of a triangle's corners (the scale of their rounding).
inline double MaxCoordinate(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2)
{
  return std::max(MaxAbs(p0), std::max(MaxAbs(p1), MaxAbs(p2)));
}
} // namespace detail

/**
 * ComputeTriangleFrame from a triangle's edges e1 = p1 - p0, e2 = p2 - p0, UV deltas
 * d1 = uv1 - uv0, d2 = uv2 - uv0 and detail::MaxCoordinate of its corners: the edges and UV
 * deltas are rescaled by exact powers of two when they lie outside the safe range (see the file
 * comment), then solved and classified (detail::FrameFromEdges).
 */
inline TriangleFrame ComputeFrameFromEdges(glm::dvec3 e1,
  glm::dvec3 e2,
  glm::dvec2 d1,
  glm::dvec2 d2,
  double maxCoordinate,
  const DegeneracyTolerance& tol,
  double* angles)
{
  if (angles)
  {
    angles[0] = angles[1] = angles[2] = 0.0;
  }
  const double maxE = detail::MaxAbs(e1, e2);
  if (!(maxE > 0.0) || !std::isfinite(maxE))
  {
    return TriangleFrame(); // coincident corners or non-finite positions
  }
  const int ePos = detail::RescaleExponent(maxE);
  e1 = detail::ScaleByPowerOfTwo(e1, ePos);
  e2 = detail::ScaleByPowerOfTwo(e2, ePos);

  const double maxUV = detail::MaxAbs(d1, d2);
  // Coincident or non-finite UVs leave the triangle with no tangent (hasUVArea below).
  const bool usableUV = maxUV > 0.0 && std::isfinite(maxUV);
  const int eUV = usableUV ? detail::RescaleExponent(maxUV) : 0;
  d1 = usableUV ? detail::ScaleByPowerOfTwo(d1, eUV) : glm::dvec2(0.0);
  d2 = usableUV ? detail::ScaleByPowerOfTwo(d2, eUV) : glm::dvec2(0.0);

  // The rounding-noise bound scales with the edges (IsRoundingNoise).
  const double scaledMaxP =
    ePos == 0 ? maxCoordinate : detail::ScaleByPowerOfTwo(maxCoordinate, ePos);
  TriangleFrame frame = detail::FrameFromEdges(e1, e2, d1, d2, scaledMaxP, tol);
  if (angles)
  {
    detail::ScaledCornerCosines(e1, e2, angles);
    for (int k = 0; k < 3; ++k)
    {
      angles[k] = detail::CornerAngle(frame.Area, angles[k]);
    }
  }
  // Back to the input's units, clamped to [AreaMinimum, AreaMaximum] (see there).
  const double area =
    detail::ScaleByPowerOfTwo(detail::ScaleByPowerOfTwo(frame.Area, -ePos), -ePos);
  frame.Area =
    frame.Area > 0.0 ? std::min(std::max(area, detail::AreaMinimum), detail::AreaMaximum) : 0.0;
  return frame;
}

/**
 * Solve E1 = du1 T + dv1 B, E2 = du2 T + dv2 B for one triangle and classify it
 * (ComputeFrameFromEdges). With `angles`, also its interior angles in radians, from
 * atan2(|e1 x e2|, e1.e2), which stays accurate near 0 and pi where acos does not; zero when the
 * triangle is degenerate in position.
 */
inline TriangleFrame ComputeTriangleFrame(const glm::dvec3& p0,
  const glm::dvec3& p1,
  const glm::dvec3& p2,
  const glm::dvec2& uv0,
  const glm::dvec2& uv1,
  const glm::dvec2& uv2,
  const DegeneracyTolerance& tol = DegeneracyTolerance(),
  double* angles = nullptr)
{
  return ComputeFrameFromEdges(
    p1 - p0, p2 - p0, uv1 - uv0, uv2 - uv0, detail::MaxCoordinate(p0, p1, p2), tol, angles);
}

/**
 * The triangles of a block, as separate arrays per component (triangle i at index i), so that
 * loops over them vectorize: their edges, UV deltas and largest coordinates (SetCorners), and
 * after ComputeTriangleBlock their frames and corner angles; with their corners' shading normals
 * (SetCornerNormal), after SignCornerWeights their signed corner weights.
 */
struct TriangleBlock
{
  static constexpr int Size = 64;
  double E[2][3][Size]; ///< component c of edge p1 - p0 (j = 0) or p2 - p0 (j = 1) at E[j][c][i]
  double D[2][2][Size]; ///< the same for the UV deltas
  double MaxCoordinate[Size];
  double Tangent[3][Size];
  double Normal[3][Size];
  double Area[Size];
  double Angle[3][Size];    ///< corner angles, when asked for
  double Orientation[Size]; ///< +1, -1 or 0 (TriangleFrame::Orientation)
  double Rare[Size];        ///< 1 where the edges or UV deltas need rescaling or are not finite
  /// For SignCornerWeights: component c of the shading normal at corner k at CornerNormal[k][c][i]
  double CornerNormal[3][3][Size];
  /// After SignCornerWeights: corner k's signed weight, whose sign (+1, -1, or 0 without a frame
  /// or weight) is the corner's handedness.
  double SignedWeight[3][Size];

  /// Triangle i's input, from its corners.
  void SetCorners(int i, const glm::dvec3 p[3], const glm::dvec2 uv[3])
  {
    for (int c = 0; c < 3; ++c)
    {
      this->E[0][c][i] = p[1][c] - p[0][c];
      this->E[1][c][i] = p[2][c] - p[0][c];
    }
    for (int c = 0; c < 2; ++c)
    {
      this->D[0][c][i] = uv[1][c] - uv[0][c];
      this->D[1][c][i] = uv[2][c] - uv[0][c];
    }
    this->MaxCoordinate[i] = detail::MaxCoordinate(p[0], p[1], p[2]);
  }

  /// The shading normal at corner k of triangle i.
  void SetCornerNormal(int k, int i, const glm::dvec3& n)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->CornerNormal[k][c][i] = n[c];
    }
  }

  glm::dvec3 Edge(int j, int i) const
  {
    return glm::dvec3(this->E[j][0][i], this->E[j][1][i], this->E[j][2][i]);
  }
  glm::dvec2 Delta(int j, int i) const { return glm::dvec2(this->D[j][0][i], this->D[j][1][i]); }

  /// Stores triangle i's frame and corner angles.
  void Set(int i, const TriangleFrame& f, const double angles[3])
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Tangent[c][i] = f.Tangent[c];
      this->Normal[c][i] = f.Normal[c];
      this->Angle[c][i] = angles[c];
    }
    this->Area[i] = f.Area;
    this->Orientation[i] = f.Orientation;
  }

  /// Triangle i's frame.
  TriangleFrame Frame(int i) const
  {
    TriangleFrame f;
    f.Tangent = glm::dvec3(this->Tangent[0][i], this->Tangent[1][i], this->Tangent[2][i]);
    f.Normal = glm::dvec3(this->Normal[0][i], this->Normal[1][i], this->Normal[2][i]);
    f.Area = this->Area[i];
    f.Orientation = static_cast<signed char>(this->Orientation[i]);
    return f;
  }
};

namespace detail
{
/**
 * The common-case pass of ComputeTriangleBlock; WithAngles a template argument so that the
 * loops have no branch. The angles have a loop of their own, whose small body every compiler
 * inlines and vectorizes.
 */
template<bool WithAngles>
VTK_ALWAYS_INLINE void ComputeCommonTriangleBlock(TriangleBlock& b,
  int count,
  const DegeneracyTolerance& tol)
{
  for (int i = 0; i < count; ++i)
  {
    const glm::dvec3 e1 = b.Edge(0, i);
    const glm::dvec3 e2 = b.Edge(1, i);
    const glm::dvec2 d1 = b.Delta(0, i);
    const glm::dvec2 d2 = b.Delta(1, i);
    const bool safe = InSafeRange(MaxAbs(e1, e2)) && InSafeRange(MaxAbs(d1, d2));
    b.Rare[i] = safe ? 0.0 : 1.0;
    double cosines[3] = { 0.0, 0.0, 0.0 };
    if (WithAngles)
    {
      ScaledCornerCosines(e1, e2, cosines);
    }
    b.Set(i, FrameFromEdges(e1, e2, d1, d2, b.MaxCoordinate[i], tol), cosines);
  }
  // Angle holds the scaled cosines (zeros without angles) until here.
  for (int k = 0; WithAngles && k < 3; ++k)
  {
    for (int i = 0; i < count; ++i)
    {
      b.Angle[k][i] = CornerAngle(b.Area[i], b.Angle[k][i]);
    }
  }
}
} // namespace detail

/**
 * ComputeTriangleFrame (with the area) for the first `count` triangles of a block, bit for bit,
 * and their corner angles when `withAngles` (else zeros): a plain loop over the common case
 * (edges and UV deltas that need no rescaling) that the compiler vectorizes, then
 * ComputeFrameFromEdges again for the triangles that need rescaling or are not finite.
 */
VTK_ALWAYS_INLINE void ComputeTriangleBlock(TriangleBlock& b,
  int count,
  const DegeneracyTolerance& tol,
  bool withAngles)
{
  if (withAngles)
  {
    detail::ComputeCommonTriangleBlock<true>(b, count, tol);
  }
  else
  {
    detail::ComputeCommonTriangleBlock<false>(b, count, tol);
  }
  for (int i = 0; i < count; ++i)
  {
    if (b.Rare[i] == 0.0)
    {
      continue;
    }
    double angles[3];
    const TriangleFrame f = ComputeFrameFromEdges(
      b.Edge(0, i), b.Edge(1, i), b.Delta(0, i), b.Delta(1, i), b.MaxCoordinate[i], tol, angles);
    const double none[3] = { 0.0, 0.0, 0.0 };
    b.Set(i, f, withAngles ? angles : none);
  }
}

/// Weight of a triangle's contribution at a corner: its area or its angle there, or 1.
VTK_ALWAYS_INLINE double CornerWeight(TangentMethod method, double area, double angle)
{
  return method == TangentMethod::AreaWeighted
    ? area
    : (method == TangentMethod::AngleWeighted ? angle : 1.0);
}

/// The handedness a triangle gives at a corner whose shading normal is n: the sign w for which
/// w * cross(n, T) points along the triangle's dP/dv. A triangle whose winding disagrees with n
/// (flipped winding, inward normals) flips its orientation here. For orientations stored as any
/// number type (+1, -1, 0).
template<typename T>
VTK_ALWAYS_INLINE T CornerSign(T orientation, const glm::dvec3& triangleNormal, const glm::dvec3& n)
{
  return glm::dot(n, triangleNormal) < 0.0 ? -orientation : orientation;
}
inline int CornerSign(const TriangleFrame& frame, const glm::dvec3& n)
{
  return CornerSign<int>(frame.Orientation, frame.Normal, n);
}

namespace detail
{
/// SignCornerWeights for one method, a template argument so that the loops have no branch.
template<TangentMethod Method>
VTK_ALWAYS_INLINE void SignCornerWeightsFor(TriangleBlock& b, int count)
{
  for (int k = 0; k < 3; ++k)
  {
    for (int i = 0; i < count; ++i)
    {
      const glm::dvec3 normal(b.Normal[0][i], b.Normal[1][i], b.Normal[2][i]);
      const glm::dvec3 n(b.CornerNormal[k][0][i], b.CornerNormal[k][1][i], b.CornerNormal[k][2][i]);
      b.SignedWeight[k][i] =
        CornerSign(b.Orientation[i], normal, n) * CornerWeight(Method, b.Area[i], b.Angle[k][i]);
    }
  }
}
} // namespace detail

/**
 * For the first `count` triangles of a block whose frames ComputeTriangleBlock gave (with their
 * corner angles for AngleWeighted) and whose corner normals are set: each corner's CornerWeight,
 * signed with the handedness its triangle gives its shading normal (CornerSign), in plain loops
 * the compiler vectorizes.
 */
VTK_ALWAYS_INLINE void SignCornerWeights(TriangleBlock& b, int count, TangentMethod method)
{
  switch (method)
  {
    case TangentMethod::Unweighted:
      detail::SignCornerWeightsFor<TangentMethod::Unweighted>(b, count);
      break;
    case TangentMethod::AreaWeighted:
      detail::SignCornerWeightsFor<TangentMethod::AreaWeighted>(b, count);
      break;
    case TangentMethod::AngleWeighted:
      detail::SignCornerWeightsFor<TangentMethod::AngleWeighted>(b, count);
      break;
  }
}

namespace detail
{
/// v / |v|, for a v whose largest component needs no rescaling (NormalizeExponent 0).
VTK_ALWAYS_INLINE glm::dvec3 Unit(const glm::dvec3& v)
{
  return v / glm::length(v);
}

/**
 * The unit component of t perpendicular to the unit normal n, for a t whose largest component
 * needs no rescaling; `usable` tells whether that component is long enough to carry a direction
 * (|perp| > 1e-9 |t|, squared: with t's largest component in [2^-400, 2^400] no square
 * overflows, and none that passes, above 2^-860, underflows). Not usable: the result is
 * meaningless.
 */
VTK_ALWAYS_INLINE glm::dvec3 UnitPerpendicular(const glm::dvec3& n,
  const glm::dvec3& t,
  bool& usable)
{
  const glm::dvec3 perp = t - glm::dot(n, t) * n;
  const double len2 = glm::dot(perp, perp);
  usable = len2 > 1e-18 * glm::dot(t, t);
  return perp / std::sqrt(len2);
}
} // namespace detail

/// The bitangent of a frame: sign * (n x t), for the unit normal n and unit tangent t.
inline glm::dvec3 Bitangent(const glm::dvec3& n, const glm::dvec3& t, double sign)
{
  return sign * glm::cross(n, t);
}

/// Unit normal, or zero when n is zero or not finite.
inline glm::dvec3 SafeNormalize(const glm::dvec3& n)
{
  if (!detail::IsFinite(n))
  {
    return glm::dvec3(0.0);
  }
  const double m = detail::MaxAbs(n);
  if (!(m > 0.0))
  {
    return glm::dvec3(0.0);
  }
  const int k = detail::NormalizeExponent(m);
  return detail::Unit(k == 0 ? n : detail::ScaleByPowerOfTwo(n, k));
}

/**
 * Whether SafeNormalize(n) is non-zero, i.e. n is finite and not the zero vector, for a normal of
 * floats or doubles as stored (without the scaling and square root). Read from the bits: of the
 * component magnitudes, as integers, one is above zero (not the zero vector) and each is below
 * that of infinity (finite, not NaN). Integer comparisons have no NaN cases, and the test has no
 * branch, so its cost does not depend on the data.
 */
template<typename T>
inline bool IsUsableNormal(const glm::vec<3, T>& n)
{
  using Bits = typename std::conditional<sizeof(T) == 4, std::int32_t, std::int64_t>::type;
  const auto magnitude = [](T x)
  {
    Bits bits;
    std::memcpy(&bits, &x, sizeof(bits));
    return static_cast<Bits>(bits & std::numeric_limits<Bits>::max());
  };
  const Bits infinity = magnitude(std::numeric_limits<T>::infinity());
  const Bits x = magnitude(n.x), y = magnitude(n.y), z = magnitude(n.z);
  return ((x | y | z) != 0) & (x < infinity) & (y < infinity) & (z < infinity);
}

/**
 * A fixed unit tangent perpendicular to the unit normal n, continuous except where n.z changes
 * sign (the branch-free orthonormal basis of Duff et al., JCGT 2017). For n == 0 it gives
 * (1, 0, 0).
 */
inline glm::dvec3 FallbackTangent(const glm::dvec3& n)
{
  if (n == glm::dvec3(0.0))
  {
    return glm::dvec3(1.0, 0.0, 0.0);
  }
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  return glm::dvec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

/**
 * Gram-Schmidt: the unit component of t perpendicular to the unit normal n. Returns false (and
 * leaves out untouched) when t has no usable perpendicular part: zero, non-finite, or parallel
 * to n within 1e-9 relative (cancellation leaves fewer than ~20 good bits below that).
 */
inline bool OrthonormalizeTangent(const glm::dvec3& n, const glm::dvec3& t, glm::dvec3& out)
{
  const double tMax = detail::MaxAbs(t);
  if (!(tMax > 0.0) || !std::isfinite(tMax))
  {
    return false;
  }
  const int k = detail::NormalizeExponent(tMax);
  bool usable = false;
  const glm::dvec3 unit =
    detail::UnitPerpendicular(n, k == 0 ? t : detail::ScaleByPowerOfTwo(t, k), usable);
  if (usable)
  {
    out = unit;
  }
  return usable;
}

/// The unit tangent perpendicular to n that t points along, or FallbackTangent(n) where t has
/// no usable perpendicular part (see OrthonormalizeTangent).
inline glm::dvec3 PerpendicularTangent(const glm::dvec3& n, const glm::dvec3& t)
{
  glm::dvec3 out;
  return OrthonormalizeTangent(n, t, out) ? out : FallbackTangent(n);
}

/**
 * Points as separate arrays per component (point i at index i), so that loops over them
 * vectorize: each point's shading normal and tangent sum, and after ComputePointBlock its unit
 * normal and unit tangent perpendicular to it.
 */
struct PointBlock
{
  static constexpr int Size = 64;
  double N[3][Size];     ///< shading normal
  double T[3][Size];     ///< tangent direction (any length)
  double UnitN[3][Size]; ///< SafeNormalize(N), or N when it is unit already
  double UnitT[3][Size]; ///< PerpendicularTangent(UnitN, T)
  double Rare[Size];     ///< 1 where the plain loop does not apply

  void Set(int i, const glm::dvec3& n, const glm::dvec3& t)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->N[c][i] = n[c];
      this->T[c][i] = t[c];
    }
  }
  glm::dvec3 Normal(int i) const
  {
    return glm::dvec3(this->UnitN[0][i], this->UnitN[1][i], this->UnitN[2][i]);
  }
  glm::dvec3 Tangent(int i) const
  {
    return glm::dvec3(this->UnitT[0][i], this->UnitT[1][i], this->UnitT[2][i]);
  }
};

namespace detail
{
/// Whether v is finite and its largest component needs no rescaling (NormalizeExponent 0).
VTK_ALWAYS_INLINE bool InNormalizeRange(const glm::dvec3& v)
{
  const glm::dvec3 a = glm::abs(v);
  return (a.x <= NormalizeMaximum) & (a.y <= NormalizeMaximum) & (a.z <= NormalizeMaximum) &
    ((a.x >= NormalizeMinimum) | (a.y >= NormalizeMinimum) | (a.z >= NormalizeMinimum));
}

/// The common-case pass of ComputePointBlock; Normalize a template argument so that the loop
/// has no branch.
template<bool Normalize>
VTK_ALWAYS_INLINE void ComputeCommonPointBlock(PointBlock& b, int count)
{
  for (int i = 0; i < count; ++i)
  {
    const glm::dvec3 stored(b.N[0][i], b.N[1][i], b.N[2][i]);
    const glm::dvec3 t(b.T[0][i], b.T[1][i], b.T[2][i]);
    const glm::dvec3 n = Normalize ? Unit(stored) : stored;
    bool usable = false;
    const glm::dvec3 unit = UnitPerpendicular(n, t, usable);
    const bool rareNormal = Normalize && !InNormalizeRange(stored);
    const bool rareTangent = !InNormalizeRange(t);
    b.Rare[i] = (rareNormal | !usable | rareTangent) ? 1.0 : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      b.UnitN[c][i] = n[c];
      b.UnitT[c][i] = unit[c];
    }
  }
}
} // namespace detail

/**
 * For the first `count` points of a block: the unit normal (SafeNormalize when `normalize`, else
 * N as it is) and PerpendicularTangent of T against it, bit for bit: a plain loop over the common
 * case (finite vectors whose largest components need no rescaling, tangents not parallel to the
 * normal) that the compiler vectorizes, then the functions themselves for the other points.
 */
VTK_ALWAYS_INLINE void ComputePointBlock(PointBlock& b, int count, bool normalize)
{
  if (normalize)
  {
    detail::ComputeCommonPointBlock<true>(b, count);
  }
  else
  {
    detail::ComputeCommonPointBlock<false>(b, count);
  }
  for (int i = 0; i < count; ++i)
  {
    if (b.Rare[i] == 0.0)
    {
      continue;
    }
    const glm::dvec3 stored(b.N[0][i], b.N[1][i], b.N[2][i]);
    const glm::dvec3 n = normalize ? SafeNormalize(stored) : stored;
    const glm::dvec3 t = PerpendicularTangent(n, glm::dvec3(b.T[0][i], b.T[1][i], b.T[2][i]));
    for (int c = 0; c < 3; ++c)
    {
      b.UnitN[c][i] = n[c];
      b.UnitT[c][i] = t[c];
    }
  }
}

} // namespace vtkNormalMapping

#endif
