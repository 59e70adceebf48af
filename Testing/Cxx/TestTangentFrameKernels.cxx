// SPDX-License-Identifier: BSD-3-Clause
// Unit tests of the tangent-frame kernels, called directly without a pipeline.
#include "vtkTangentFrameKernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <vector>

using namespace vtkNormalMapping;

namespace
{
const double Pi = std::acos(-1.0);

// The kernels compute in double from exactly representable inputs; a unit vector they return is
// normalized once, so its length is 1 within a few ulps of double.
constexpr double UnitTolerance = 1e-14;

double AngleBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}
}

TEST(TangentFrameKernels, RightTriangleWithIdentityUV)
{
  const TriangleFrame f =
    ComputeTriangleFrame({ 0, 0, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, { 0, 0 }, { 1, 0 }, { 0, 1 });
  EXPECT_EQ(f.Orientation, 1);
  EXPECT_EQ(f.Tangent, glm::dvec3(1, 0, 0)); // exact: no rounding happens on this input
  EXPECT_EQ(SafeNormalize(f.Normal), glm::dvec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(f.Area, 2.0);
}

TEST(TangentFrameKernels, RotatedUVGivesRotatedTangent)
{
  // u = cos(a) x + sin(a) y, v = -sin(a) x + cos(a) y  =>  dP/du = (cos a, sin a, 0).
  for (double a : { 0.1, 1.0, 2.5, -2.0 })
  {
    const auto uv = [a](double x, double y)
    { return glm::dvec2(std::cos(a) * x + std::sin(a) * y, -std::sin(a) * x + std::cos(a) * y); };
    const TriangleFrame f = ComputeTriangleFrame(
      { 0.3, 0.1, 0 }, { 1.2, 0.4, 0 }, { 0.5, 0.9, 0 }, uv(0.3, 0.1), uv(1.2, 0.4), uv(0.5, 0.9));
    ASSERT_EQ(f.Orientation, 1);
    // A handful of roundings on O(1) values: 1e-14 rad is ~50 ulps.
    EXPECT_LT(AngleBetween(f.Tangent, { std::cos(a), std::sin(a), 0 }), 1e-14) << "a=" << a;
  }
}

TEST(TangentFrameKernels, MirroredUVFlipsOrientationAndTangent)
{
  const TriangleFrame f =
    ComputeTriangleFrame({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0 }, { -1, 0 }, { 0, 1 });
  EXPECT_EQ(f.Orientation, -1);
  EXPECT_EQ(f.Tangent, glm::dvec3(-1, 0, 0));
  // The sign at a corner whose normal is +z is -1; with the normal flipped it is +1 (the
  // triangle's winding then disagrees with the shading normal).
  EXPECT_EQ(CornerSign(f, { 0, 0, 1 }), -1);
  EXPECT_EQ(CornerSign(f, { 0, 0, -1 }), 1);
}

TEST(TangentFrameKernels, DegenerateTrianglesHaveNoFrame)
{
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // Zero UV area.
  TriangleFrame f = ComputeTriangleFrame(a, b, c, { 0, 0 }, { 1, 1 }, { 2, 2 });
  EXPECT_EQ(f.Orientation, 0);
  EXPECT_EQ(SafeNormalize(f.Normal), glm::dvec3(0, 0, 1)); // the geometry is still fine
  // Zero area: collinear and repeated points.
  f = ComputeTriangleFrame(a, b, { 2, 0, 0 }, { 0, 0 }, { 1, 0 }, { 0, 1 });
  EXPECT_EQ(f.Orientation, 0);
  EXPECT_EQ(f.Area, 0.0);
  f = ComputeTriangleFrame(a, a, c, { 0, 0 }, { 1, 0 }, { 0, 1 });
  EXPECT_EQ(f.Orientation, 0);
  // Non-finite input anywhere.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ComputeTriangleFrame({ nan, 0, 0 }, b, c, { 0, 0 }, { 1, 0 }, { 0, 1 }).Orientation, 0);
  EXPECT_EQ(ComputeTriangleFrame(a, { inf, 0, 0 }, c, { 0, 0 }, { 1, 0 }, { 0, 1 }).Orientation, 0);
  EXPECT_EQ(ComputeTriangleFrame(a, b, c, { 0, nan }, { 1, 0 }, { 0, 1 }).Orientation, 0);
  EXPECT_EQ(ComputeTriangleFrame(a, b, c, { 0, 0 }, { inf, 0 }, { 0, 1 }).Orientation, 0);
}

TEST(TangentFrameKernels, ToleranceSeparatesNearDegenerateUV)
{
  // A UV triangle whose shape ratio is 1e-20: below any stored precision, degenerate.
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  TriangleFrame f = ComputeTriangleFrame(a, b, c, { 0, 0 }, { 1, 0 }, { 0.5, 1e-20 });
  EXPECT_EQ(f.Orientation, 0);
  // Shape ratio 1e-3: a thin but honest UV triangle keeps its frame.
  f = ComputeTriangleFrame(a, b, c, { 0, 0 }, { 1, 0 }, { 0.5, 1e-3 });
  EXPECT_NE(f.Orientation, 0);
  EXPECT_NEAR(glm::length(f.Tangent), 1.0, UnitTolerance);
}

TEST(TangentFrameKernels, ScaleInvariantWithoutOverflow)
{
  const glm::dvec3 p[3] = { { 0.1, 0.2, 0.3 }, { 1.1, 0.25, 0.2 }, { 0.4, 1.3, 0.5 } };
  const glm::dvec2 uv[3] = { { 0.1, 0.7 }, { 0.8, 0.6 }, { 0.3, 0.05 } };
  const TriangleFrame ref = ComputeTriangleFrame(p[0], p[1], p[2], uv[0], uv[1], uv[2]);
  ASSERT_NE(ref.Orientation, 0);
  // Power-of-two scales are exact, and the kernel either rescales by powers of two (outside
  // [2^-160, 2^160]) or computes with no product leaving the normal range: bit-identical
  // directions. (Normal has no particular length: it scales with the positions inside the range.)
  for (int e : { -1000, -300, -100, -30, 30, 100, 300, 1000 })
  {
    const double sp = std::ldexp(1.0, e);
    const double su = std::ldexp(1.0, -e / 3);
    const TriangleFrame f =
      ComputeTriangleFrame(sp * p[0], sp * p[1], sp * p[2], su * uv[0], su * uv[1], su * uv[2]);
    EXPECT_EQ(f.Tangent, ref.Tangent) << "2^" << e;
    EXPECT_EQ(SafeNormalize(f.Normal), SafeNormalize(ref.Normal)) << "2^" << e;
  }
  // Decimal scales round the inputs: identical to a few ulps (1e-15 rad).
  for (double sp : { 1e-30, 1e-10, 1e10, 1e30 })
  {
    for (double su : { 1e-10, 1e10 })
    {
      const TriangleFrame f =
        ComputeTriangleFrame(sp * p[0], sp * p[1], sp * p[2], su * uv[0], su * uv[1], su * uv[2]);
      ASSERT_NE(f.Orientation, 0);
      EXPECT_LT(AngleBetween(f.Tangent, ref.Tangent), 1e-15 * 8) << sp << " " << su;
      EXPECT_TRUE(std::isfinite(f.Area) && f.Area > 0.0);
    }
  }
}

TEST(TangentFrameKernels, CornerAnglesSumToPi)
{
  // The interior angles ComputeTriangleFrame returns, on triangles of every shape; zero on
  // triangles that are degenerate in position (coincident or collinear corners).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const auto cornerAngles =
    [](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double angles[3]) {
      ComputeTriangleFrame(a, b, c, { 0, 0 }, { 1, 0 }, { 0, 1 }, DegeneracyTolerance(), angles);
    };
  for (int i = 0; i < 1000; ++i)
  {
    const glm::dvec3 a(d(rng), d(rng), d(rng)), b(d(rng), d(rng), d(rng)),
      c(d(rng), d(rng), d(rng));
    double angles[3];
    cornerAngles(a, b, c, angles);
    // Three angles, each within FastAngleMatchesAtan2's 1.5e-15 rad, and two roundings of the sum
    // (half an ulp of pi, 2.2e-16, each). Measured: 4.4e-16 at most.
    EXPECT_NEAR(angles[0] + angles[1] + angles[2], Pi, 3 * 1.5e-15 + 2 * 2.2e-16);
  }
  for (const glm::dvec3& far : { glm::dvec3(0, 0, 0), glm::dvec3(2, 0, 0) })
  {
    double angles[3] = { 9, 9, 9 };
    cornerAngles({ 0, 0, 0 }, { 1, 0, 0 }, far, angles);
    EXPECT_EQ(angles[0] + angles[1] + angles[2], 0.0);
  }
}

TEST(TangentFrameKernels, FallbackTangentIsUnitAndPerpendicular)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> d;
  std::vector<glm::dvec3> normals = {
    { 0, 0, 1 }, { 0, 0, -1 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, -1 + 1e-17 }
  };
  for (int i = 0; i < 1000; ++i)
  {
    normals.push_back(SafeNormalize({ d(rng), d(rng), d(rng) }));
  }
  for (const glm::dvec3& n : normals)
  {
    const glm::dvec3 t = FallbackTangent(n);
    // Duff et al.'s basis is exact in exact arithmetic; in double it is within ~1e-15.
    EXPECT_NEAR(glm::length(t), 1.0, 1e-14);
    EXPECT_NEAR(glm::dot(t, n), 0.0, 1e-14);
  }
  EXPECT_EQ(FallbackTangent(glm::dvec3(0.0)), glm::dvec3(1, 0, 0));
}

TEST(TangentFrameKernels, OrthonormalizeTangent)
{
  glm::dvec3 out(7.0);
  EXPECT_TRUE(OrthonormalizeTangent({ 0, 0, 1 }, { 3, 0, 4 }, out));
  EXPECT_EQ(out, glm::dvec3(1, 0, 0));
  // Parallel to the normal, zero, non-finite: refused, output untouched.
  out = glm::dvec3(7.0);
  EXPECT_FALSE(OrthonormalizeTangent({ 0, 0, 1 }, { 0, 0, 5 }, out));
  EXPECT_FALSE(OrthonormalizeTangent({ 0, 0, 1 }, { 0, 0, 0 }, out));
  EXPECT_FALSE(
    OrthonormalizeTangent({ 0, 0, 1 }, { std::numeric_limits<double>::quiet_NaN(), 0, 0 }, out));
  EXPECT_EQ(out, glm::dvec3(7.0));
  // Huge and tiny inputs.
  EXPECT_TRUE(OrthonormalizeTangent({ 0, 0, 1 }, { 1e300, 1e300, 1e300 }, out));
  EXPECT_NEAR(glm::length(out), 1.0, UnitTolerance);
  EXPECT_TRUE(OrthonormalizeTangent({ 0, 0, 1 }, { 1e-310, 0, 0 }, out));
  EXPECT_EQ(out, glm::dvec3(1, 0, 0));
  // The threshold, |perp| > 1e-9 |t|, at every scale (rescaled or not): 2e-9 of t passes and
  // gives exactly the perpendicular direction, 5e-10 is refused.
  for (double scale : { 1.0, 1e-100, 1e100, 1e-300, 1e300 })
  {
    out = glm::dvec3(7.0);
    EXPECT_TRUE(OrthonormalizeTangent({ 0, 0, 1 }, { 2e-9 * scale, 0, scale }, out)) << scale;
    EXPECT_EQ(out, glm::dvec3(1, 0, 0)) << scale;
    EXPECT_FALSE(OrthonormalizeTangent({ 0, 0, 1 }, { 0, 5e-10 * scale, scale }, out)) << scale;
  }
}

TEST(TangentFrameKernels, SafeNormalize)
{
  EXPECT_EQ(SafeNormalize({ 0, 0, 0 }), glm::dvec3(0.0));
  EXPECT_EQ(SafeNormalize({ std::numeric_limits<double>::infinity(), 0, 0 }), glm::dvec3(0.0));
  EXPECT_EQ(SafeNormalize({ 0, 1e-320, 0 }), glm::dvec3(0, 1, 0));
  EXPECT_NEAR(glm::length(SafeNormalize({ 1e200, 1e200, 0 })), 1.0, UnitTolerance);
}

template<typename T>
void ExpectUsableIsFiniteAndNonZero()
{
  // IsUsableNormal reads the bits of the stored values; it must agree with its definition
  // (every component finite, not all zero) on every combination of zeros of both signs,
  // subnormals, the largest finite values, infinities and NaNs of both signs.
  using Limits = std::numeric_limits<T>;
  const T values[] = { T(0),
    -T(0),
    T(1),
    T(-2.5),
    Limits::denorm_min(),
    -Limits::denorm_min(),
    Limits::min(),
    Limits::max(),
    -Limits::max(),
    Limits::infinity(),
    -Limits::infinity(),
    Limits::quiet_NaN(),
    -Limits::quiet_NaN() };
  int usable = 0;
  for (T x : values)
  {
    for (T y : values)
    {
      for (T z : values)
      {
        const bool expected = std::isfinite(x) && std::isfinite(y) && std::isfinite(z) &&
          !(x == T(0) && y == T(0) && z == T(0));
        EXPECT_EQ(IsUsableNormal(glm::vec<3, T>(x, y, z)), expected) << x << " " << y << " " << z;
        usable += expected ? 1 : 0;
      }
    }
  }
  EXPECT_GT(usable, 0);
}

TEST(TangentFrameKernels, UsableNormalsAreFiniteAndNonZero)
{
  ExpectUsableIsFiniteAndNonZero<float>();
  ExpectUsableIsFiniteAndNonZero<double>();
}

TEST(TangentFrameKernels, FastAngleMatchesAtan2)
{
  // The minimax polynomial's relative error is below 3.6e-17 (AtanMinimax), 5.7e-17 rad at
  // pi / 2; each of the division, the polynomial's final addition and the reflections
  // (pi / 4 +, pi / 2 -, pi -) rounds by at most half an ulp of a result below pi (2.2e-16): about
  // 1.0e-15 in all, bounded with 50% to spare.
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i)
  {
    const double a = Pi * i / 20000.0;
    for (double r : { 1e-300, 1e-3, 1.0, 7.5, 1e300 })
    {
      const double s = r * std::sin(a), c = r * std::cos(a);
      worst = std::max(worst, std::abs(detail::AngleFromSineCosine(s, c) - std::atan2(s, c)));
    }
  }
  EXPECT_LT(worst, 1.5e-15);
  EXPECT_EQ(detail::AngleFromSineCosine(0.0, 0.0), 0.0);
  EXPECT_EQ(detail::AngleFromSineCosine(0.0, -1.0), Pi);
}

TEST(TangentFrameKernels, BlockGivesTheBitsOfComputeTriangleFrame)
{
  // ComputeTriangleBlock computes the common case in a vectorized loop and sends the rest to
  // ComputeTriangleFrame: every triangle, common or not, must come out with the same bits as
  // ComputeTriangleFrame (exact comparison: the same IEEE operations in the same order). The
  // block mixes ordinary triangles with ones that need rescaling, are degenerate in position or
  // in UV, or are not finite, at every position in the block.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const DegeneracyTolerance tol;
  TriangleBlock block;
  for (int round = 0; round < 20; ++round)
  {
    const int count = round == 0 ? TriangleBlock::Size : 1 + static_cast<int>(rng() % 64);
    std::vector<std::array<glm::dvec3, 3>> corners(count);
    std::vector<std::array<glm::dvec2, 3>> uvs(count);
    for (int i = 0; i < count; ++i)
    {
      glm::dvec3* p = corners[i].data();
      glm::dvec2* uv = uvs[i].data();
      for (int k = 0; k < 3; ++k)
      {
        p[k] = glm::dvec3(d(rng), d(rng), d(rng));
        uv[k] = glm::dvec2(d(rng), d(rng));
      }
      switch ((i + round) % 8)
      {
        case 1: // needs rescaling: huge positions
          for (int k = 0; k < 3; ++k)
            p[k] *= 1e300;
          break;
        case 2: // needs rescaling: tiny UV deltas
          for (int k = 0; k < 3; ++k)
            uv[k].x = 0.5 + 1e-60 * uv[k].x;
          break;
        case 3: // collinear corners
          p[2] = 2.0 * p[1] - p[0];
          break;
        case 4: // collapsed texture coordinates
          uv[1] = uv[0];
          break;
        case 5: // not finite
          p[1].x = nan;
          break;
        default:
          break;
      }
      block.SetCorners(i, p, uv);
    }
    for (bool withAngles : { false, true })
    {
      ComputeTriangleBlock(block, count, tol, withAngles);
      for (int i = 0; i < count; ++i)
      {
        const glm::dvec3* p = corners[i].data();
        const glm::dvec2* uv = uvs[i].data();
        double angles[3];
        const TriangleFrame ref =
          ComputeTriangleFrame(p[0], p[1], p[2], uv[0], uv[1], uv[2], tol, angles);
        const TriangleFrame f = block.Frame(i);
        EXPECT_EQ(f.Tangent, ref.Tangent) << "triangle " << i << " of round " << round;
        EXPECT_EQ(f.Normal, ref.Normal) << "triangle " << i << " of round " << round;
        EXPECT_EQ(f.Area, ref.Area) << "triangle " << i << " of round " << round;
        EXPECT_EQ(f.Orientation, ref.Orientation) << "triangle " << i << " of round " << round;
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(block.Angle[k][i], withAngles ? angles[k] : 0.0) << "corner " << k;
        }
      }
    }
  }
}

TEST(TangentFrameKernels, SignedCornerWeightsOfABlockAreThoseOfCornerSignAndCornerWeight)
{
  // SignCornerWeights computes a block's signed corner weights in a vectorized loop: each must
  // have the bits of
  // CornerSign(frame, normal) * CornerWeight(method, area, angle), for every
  // method, with shading normals that agree with the triangle's winding, oppose it, are
  // perpendicular to it or zero, and triangles without a frame (orientation 0).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const DegeneracyTolerance tol;
  TriangleBlock block;
  const int count = TriangleBlock::Size - 3;
  std::vector<std::array<glm::dvec3, 3>> normals(count);
  for (int i = 0; i < count; ++i)
  {
    glm::dvec3 p[3];
    glm::dvec2 uv[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = glm::dvec3(d(rng), d(rng), d(rng));
      uv[k] = glm::dvec2(d(rng), d(rng));
    }
    if (i % 7 == 3)
    {
      uv[2] = uv[1]; // no frame
    }
    block.SetCorners(i, p, uv);
    const glm::dvec3 winding = glm::cross(p[1] - p[0], p[2] - p[0]);
    for (int k = 0; k < 3; ++k)
    {
      const glm::dvec3 other(d(rng), d(rng), d(rng));
      const glm::dvec3 choices[4] = {
        winding + 0.1 * other, -winding + 0.1 * other, glm::cross(winding, other), glm::dvec3(0.0)
      };
      normals[i][k] = choices[(i + k) % 4];
      block.SetCornerNormal(k, i, normals[i][k]);
    }
  }
  for (TangentMethod method :
    { TangentMethod::Unweighted, TangentMethod::AreaWeighted, TangentMethod::AngleWeighted })
  {
    ComputeTriangleBlock(block, count, tol, method == TangentMethod::AngleWeighted);
    SignCornerWeights(block, count, method);
    int negative = 0;
    for (int i = 0; i < count; ++i)
    {
      const TriangleFrame f = block.Frame(i);
      for (int k = 0; k < 3; ++k)
      {
        const double expected =
          CornerSign(f, normals[i][k]) * CornerWeight(method, f.Area, block.Angle[k][i]);
        EXPECT_EQ(block.SignedWeight[k][i], expected)
          << "corner " << k << " of triangle " << i << ", method " << static_cast<int>(method);
        negative += expected < 0.0 ? 1 : 0;
      }
    }
    EXPECT_GT(negative, 0); // both handednesses occur
  }
}

TEST(TangentFrameKernels, PointBlockGivesTheBitsOfSafeNormalizeAndPerpendicularTangent)
{
  // ComputePointBlock computes the common case in a vectorized loop and sends the rest to
  // SafeNormalize and PerpendicularTangent: every point must come out with their bits (exact
  // comparison). The block mixes ordinary points with normals and tangents that need rescaling,
  // are zero or not finite, and tangents parallel to the normal, at every position.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PointBlock block;
  for (int round = 0; round < 20; ++round)
  {
    const int count = round == 0 ? PointBlock::Size : 1 + static_cast<int>(rng() % 64);
    std::vector<glm::dvec3> normals(count), tangents(count);
    for (int i = 0; i < count; ++i)
    {
      glm::dvec3 n(d(rng), d(rng), d(rng));
      glm::dvec3 t(d(rng), d(rng), d(rng));
      switch ((i + round) % 9)
      {
        case 1: // needs rescaling: tiny normal
          n *= 1e-200;
          break;
        case 2: // needs rescaling: huge tangent
          t *= 1e200;
          break;
        case 3: // no tangent
          t = glm::dvec3(0.0);
          break;
        case 4: // tangent along the normal
          t = -3.0 * n;
          break;
        case 5: // not finite
          n.y = nan;
          break;
        case 6: // not finite
          t.z = std::numeric_limits<double>::infinity();
          break;
        case 7: // zero normal
          n = glm::dvec3(0.0);
          break;
        default:
          break;
      }
      normals[i] = n;
      tangents[i] = t;
      block.Set(i, n, t);
    }
    for (bool normalize : { true, false })
    {
      ComputePointBlock(block, count, normalize);
      for (int i = 0; i < count; ++i)
      {
        const glm::dvec3 n = normalize ? SafeNormalize(normals[i]) : normals[i];
        const glm::dvec3 t = PerpendicularTangent(n, tangents[i]);
        // Bitwise: NaN never equals itself, so compare the bytes.
        const glm::dvec3 gotN = block.Normal(i);
        const glm::dvec3 gotT = block.Tangent(i);
        EXPECT_EQ(std::memcmp(&gotN, &n, sizeof(n)), 0)
          << "point " << i << " of round " << round << ", normalize " << normalize;
        EXPECT_EQ(std::memcmp(&gotT, &t, sizeof(t)), 0)
          << "point " << i << " of round " << round << ", normalize " << normalize;
      }
    }
  }
}
