// Unit tests of the tangent-frame kernels, called directly without a pipeline.
#include "vtkNormalMappingHugePages.h"
#include "vtkTangentFrameBatch.h"
#include "vtkTangentFrameKernels.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i)
  {
    const glm::dvec3 a(d(rng), d(rng), d(rng)), b(d(rng), d(rng), d(rng)),
      c(d(rng), d(rng), d(rng));
    double angles[3];
    ComputeCornerAngles(a, b, c, angles);
    // Three angles, each within FastAngleMatchesAtan2's 1.5e-15 rad, and two roundings of the sum
    // (half an ulp of pi, 2.2e-16, each). Measured: 4.4e-16 at most.
    EXPECT_NEAR(angles[0] + angles[1] + angles[2], Pi, 3 * 1.5e-15 + 2 * 2.2e-16);
  }
  double angles[3];
  ComputeCornerAngles({ 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, angles);
  EXPECT_EQ(angles[0] + angles[1] + angles[2], 0.0);
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

TEST(TangentFrameKernels, FastAngleMatchesAtan2)
{
  // The minimax polynomial's relative error is below 3.6e-17 (AtanMinimaxDouble), 5.7e-17 rad at
  // pi / 2; each of the division, the polynomial's final addition and the reflections
  // (pi / 4 +, pi / 2 -, pi -) rounds by at most half an ulp of a result below pi (2.2e-16): about
  // 1.0e-15 in all, bounded with 50% to spare. Measured: 4.4e-16 (one ulp of pi). The Taylor series
  // this replaced had 2e-12.
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

TEST(TangentFrameKernels, FrameAnglesMatchCornerAngles)
{
  // The angles ComputeTriangleFrame can return are those of ComputeCornerAngles (the same
  // formula on the same rescaled edges, so the same bits), for any triangle that is not
  // degenerate in position, and zero for one that is.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i)
  {
    const glm::dvec3 a(d(rng), d(rng), d(rng)), b(d(rng), d(rng), d(rng)),
      c(d(rng), d(rng), d(rng));
    double fromFrame[3], direct[3];
    ComputeTriangleFrame(
      a, b, c, { 0, 0 }, { 1, 0 }, { 0, 1 }, DegeneracyTolerance(), false, fromFrame);
    ComputeCornerAngles(a, b, c, direct);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(fromFrame[k], direct[k]);
    }
  }
  double angles[3] = { 9, 9, 9 };
  ComputeTriangleFrame({ 0, 0, 0 },
    { 1, 0, 0 },
    { 2, 0, 0 },
    { 0, 0 },
    { 1, 0 },
    { 0, 1 },
    DegeneracyTolerance(),
    false,
    angles);
  EXPECT_EQ(angles[0] + angles[1] + angles[2], 0.0);
}

namespace
{
/// A batch of random triangles (positions and UVs in [-1, 1], every eighth one degenerate in
/// UV, one with a NaN, one scaled out of the single-precision range), in float and in double.
struct RandomBatch
{
  static constexpr int Triangles = detail::FrameBatch::Capacity;
  std::vector<float> P, U, N;
  std::vector<double> Pd, Ud, Nd;

  explicit RandomBatch(unsigned seed)
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> d(-1.0f, 1.0f);
    P.resize(9 * Triangles);
    U.resize(6 * Triangles);
    N.resize(9 * Triangles);
    for (auto& x : P)
    {
      x = d(rng);
    }
    for (auto& x : U)
    {
      x = d(rng);
    }
    for (auto& x : N)
    {
      x = d(rng);
    }
    for (int t = 0; t < Triangles; t += 8)
    {
      U[6 * t + 4] = U[6 * t + 2] = U[6 * t]; // u0 = u1 = u2: zero UV area
    }
    P[9 * 5 + 4] = std::numeric_limits<float>::quiet_NaN();
    for (int k = 0; k < 9; ++k)
    {
      P[9 * 11 + k] *= 1e-9f; // edges below 2^-20: the double kernel takes it
    }
    Pd.assign(P.begin(), P.end());
    Ud.assign(U.begin(), U.end());
    Nd.assign(N.begin(), N.end());
  }

  template<typename T>
  detail::FrameBatch Compute(const std::vector<T>& p,
    const std::vector<T>& u,
    const std::vector<T>& n,
    detail::BatchCode code) const
  {
    detail::FrameBatch b;
    for (vtkIdType t = 0; t < Triangles; ++t)
    {
      const vtkIdType tri[3] = { 3 * t, 3 * t + 1, 3 * t + 2 };
      b.Add(tri);
    }
    // With the number of points, so that the vector code's 16-byte loads run (all but the last
    // point's).
    const detail::BatchInput<T, T, T> in{ p.data(),
      u.data(),
      2,
      n.data(),
      nullptr,
      DegeneracyTolerance(),
      detail::BatchWeights::Angle,
      static_cast<vtkIdType>(p.size() / 3) };
    detail::ComputeBatch(in, b, code);
    return b;
  }
};

/// Whether two computed batches agree bit for bit in everything the scatter reads: orientations,
/// and the frames, weights and sides of triangles that have a frame (the rest is not read).
bool SameBits(const detail::FrameBatch& a, const detail::FrameBatch& b)
{
  if (a.Size != b.Size)
  {
    return false;
  }
  for (int i = 0; i < a.Size; ++i)
  {
    if (a.Orientation(i) != b.Orientation(i))
    {
      return false;
    }
    for (int k = 0; a.Orientation(i) != 0 && k < 3; ++k)
    {
      if (std::memcmp(&a.Tangent[k][i], &b.Tangent[k][i], sizeof(double)) != 0 ||
        std::memcmp(&a.Normal[k][i], &b.Normal[k][i], sizeof(double)) != 0 ||
        std::memcmp(&a.Weight[k][i], &b.Weight[k][i], sizeof(double)) != 0 ||
        a.Side(k, i) != b.Side(k, i))
      {
        return false;
      }
    }
  }
  return true;
}
}

/// The batch codes this build and CPU can run, scalar first.
std::vector<detail::BatchCode> BatchCodes()
{
  std::vector<detail::BatchCode> codes;
  for (int c = 0; c <= static_cast<int>(detail::BestBatchCode()); ++c)
  {
    codes.push_back(static_cast<detail::BatchCode>(c));
  }
  return codes;
}

TEST(TangentFrameKernels, BatchVectorAndScalarGiveTheSameBits)
{
  // The AVX2 and AVX-512 code performs the scalar kernels' IEEE operations lane by lane (float and
  // double paths), so the whole batch must match bit for bit, special triangles included.
  const std::vector<detail::BatchCode> codes = BatchCodes();
  if (codes.size() < 2)
  {
    GTEST_SKIP() << "this CPU (or build) has no AVX2: only the scalar batch code runs";
  }
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const RandomBatch r(seed);
    const detail::FrameBatch f = r.Compute(r.P, r.U, r.N, detail::BatchCode::Scalar);
    const detail::FrameBatch d = r.Compute(r.Pd, r.Ud, r.Nd, detail::BatchCode::Scalar);
    for (size_t c = 1; c < codes.size(); ++c)
    {
      EXPECT_TRUE(SameBits(r.Compute(r.P, r.U, r.N, codes[c]), f))
        << "float, seed " << seed << ", code " << c;
      EXPECT_TRUE(SameBits(r.Compute(r.Pd, r.Ud, r.Nd, codes[c]), d))
        << "double, seed " << seed << ", code " << c;
    }
  }
}

TEST(TangentFrameKernels, ScatterSumsAndMarksEveryCornerOnce)
{
  // A batch whose 64 triangles share 10 points, with triangles without a frame and zero weights:
  // points 0-2 have only +1 corners, 3-5 only -1 corners, 6-8 both, 9 only zero weights. Expected
  // per point: the sums added in batch order (the scalar scatter's
  // operations) and the or of the marks of its corners with a positive weight. The vector scatter
  // must give the same bits, with one block or with the points dealt to two, for the full batch
  // and for batches of 61 and 3 triangles (the vector code takes the marks four corners at a time:
  // a tail of one, and a batch that is all tail).
  constexpr int numPoints = 10;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  detail::FrameBatch b;
  for (int i = 0; i < detail::FrameBatch::Capacity; ++i)
  {
    const vtkIdType tri[3] = { i % numPoints, (3 * i + 1) % numPoints, (7 * i + 2) % numPoints };
    b.Add(tri);
    b.SetOrientation(i, i % 9 == 0 ? 0 : (i % 4 == 0 ? -1 : 1));
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType p = tri[k];
      b.Tangent[k][i] = d(rng);
      b.Weight[k][i] = p == 9 || (i + k) % 7 == 0 ? 0.0 : std::abs(d(rng));
      b.SetSides(k, i, 1, p < 3 ? 0u : (p < 6 ? 1u : static_cast<unsigned>((i / 10) % 2)));
    }
  }
  for (int size : { detail::FrameBatch::Capacity, 61, 3 })
  {
    b.Size = size;
    std::vector<detail::PointSum> expected(numPoints, detail::PointSum{});
    for (int i = 0; i < b.Size; ++i)
    {
      for (int k = 0; b.Orientation(i) != 0 && k < 3; ++k)
      {
        detail::PointSum& e = expected[b.Ids[k][i]];
        for (int c = 0; c < 3; ++c)
        {
          e.Sum[c] += b.Weight[k][i] * b.Tangent[c][i];
        }
        if (b.Weight[k][i] > 0.0)
        {
          e.Marks |= detail::MarkBase | (b.Side(k, i) == 0 ? detail::PlusSide : detail::MinusSide);
        }
      }
    }
    // The full batch must reach every kind of mark, or the comparison proves less than it says.
    std::set<unsigned char> kinds;
    for (const detail::PointSum& e : expected)
    {
      kinds.insert(e.Sides());
    }
    if (size == detail::FrameBatch::Capacity)
    {
      ASSERT_EQ(kinds.size(), 4u); // 0, PlusSide, MinusSide, BothSides
    }
    const bool vector = detail::BestBatchCode() >= detail::BatchCode::AVX2;
    for (bool useVector : { false, vector })
    {
      for (int blocks : { 1, 2 })
      {
        std::vector<detail::PointSum> sums(numPoints, detail::PointSum{});
        // With two blocks, each owns some corners of the batch's triangles: the batch says so.
        b.Shared = blocks > 1;
        for (int block = 0; block < blocks; ++block)
        {
          detail::ScatterBatch(
            b, detail::ScatterTarget{ sums.data(), blocks, block, 0 }, useVector);
        }
        EXPECT_EQ(
          0, std::memcmp(sums.data(), expected.data(), sizeof(detail::PointSum) * numPoints))
          << "vector " << useVector << ", blocks " << blocks << ", size " << size;
      }
    }
  }
}

TEST(TangentFrameKernels, HugePageReservationRoundsUpOnlyWhenCheap)
{
  using detail::HugePageBytes;
  using detail::HugePageReservation;
  // Rounded up to whole 2 MiB pages when that adds at most an eighth: the 1M-triangle torus'
  // sums with their side bytes (501,501 points: 16.5 MB), and blocks of the size of its float
  // tangents and signs.
  EXPECT_EQ(HugePageReservation((501501u + 15672u) * 32), 8 * HugePageBytes);
  EXPECT_EQ(HugePageReservation(501501u * 12), 3 * HugePageBytes);
  EXPECT_EQ(HugePageReservation(501501u * 4), HugePageBytes);
  EXPECT_EQ(HugePageReservation(HugePageBytes), HugePageBytes);
  // One page: rounded from 8/9 of it on (the eighth of the array's own size).
  const std::size_t edge = (8 * HugePageBytes + 8) / 9;
  EXPECT_EQ(HugePageReservation(edge), HugePageBytes);
  // Else left as it is: 0.5 MB would become 2 MiB, 9/8 of a page 2 pages.
  EXPECT_EQ(HugePageReservation(501501u), 501501u);
  EXPECT_EQ(HugePageReservation(edge - 1), edge - 1);
  EXPECT_EQ(HugePageReservation(9 * HugePageBytes / 8), 9 * HugePageBytes / 8);
  EXPECT_EQ(HugePageReservation(0), 0u);
}

TEST(TangentFrameKernels, ScanBlocksShareOutMeshesOfEverySize)
{
  using detail::ScanBlocks;
  // One thread: one block, which owns every point, whatever the size.
  for (vtkIdType n : { vtkIdType(0), vtkIdType(5000), vtkIdType(1) << 40 })
  {
    const ScanBlocks s = ScanBlocks::Choose(n, 1);
    EXPECT_EQ(s.Blocks, 1);
  }
  // Two threads on the benchmark's tori (about one point per two triangles): the 1M-triangle one in
  // runs of 2^14 as before; smaller ones in shorter runs, so that they are shared out at all
  // (with runs of a fixed 2^14, 50K points made 3 runs and 2 blocks, 32K points one).
  const auto expectChoice = [](vtkIdType n, int threads, int blocks, int shift)
  {
    const ScanBlocks s = ScanBlocks::Choose(n, threads);
    EXPECT_EQ(s.Blocks, blocks) << n << " points, " << threads << " threads";
    EXPECT_EQ(s.OwnerShift, shift) << n << " points, " << threads << " threads";
  };
  expectChoice(501501, 2, 8, 14);
  expectChoice(50086, 2, 8, 11);
  expectChoice(3200, 2, 2, 10);
  expectChoice(1000, 2, 1, 10);
  expectChoice(36000, 8, 32, 10);
  // The rule's invariants over sizes from 0 to 2^26 points and any thread count: a power of two
  // up to 64 and four per thread, never more blocks than runs, runs within the bounds and only
  // shortened while there are fewer than two per wanted block, and more points never fewer
  // blocks.
  for (int threads : { 2, 3, 4, 8, 16, 64, 1000 })
  {
    const vtkIdType wanted = std::min(64, 4 * threads);
    int previous = 1;
    for (vtkIdType n = 0; n <= (vtkIdType(1) << 26); n = n < 16 ? n + 1 : n + n / 7)
    {
      const ScanBlocks s = ScanBlocks::Choose(n, threads);
      SCOPED_TRACE(std::to_string(n) + " points, " + std::to_string(threads) + " threads");
      ASSERT_GE(s.Blocks, 1);
      EXPECT_EQ(s.Blocks & (s.Blocks - 1), 0);
      EXPECT_LE(s.Blocks, wanted);
      EXPECT_GE(s.OwnerShift, ScanBlocks::MinShift);
      EXPECT_LE(s.OwnerShift, ScanBlocks::MaxShift);
      const vtkIdType runs = n >> s.OwnerShift;
      EXPECT_TRUE(s.Blocks == 1 || s.Blocks <= runs);
      // The largest power of two within both limits: twice as many would exceed one.
      EXPECT_TRUE(2 * s.Blocks > std::min(wanted, runs));
      if (s.OwnerShift < ScanBlocks::MaxShift)
      {
        EXPECT_LT(n >> (s.OwnerShift + 1), 2 * wanted);
      }
      EXPECT_GE(s.Blocks, previous);
      previous = s.Blocks;
    }
  }
}

TEST(TangentFrameKernels, SinglePrecisionAngleIsWithinTwoAndAHalfRoundings)
{
  // single::Angle (the float corner angle of AngleWeighted) against atan2 in double, over every
  // direction and 60 binary orders of magnitude. Its error: the division that reduces the argument
  // rounds once, the minimax polynomial is within 1.2e-9 (a hundredth of float's epsilon) and its
  // float evaluation rounds about once more, and the final add of pi/4, pi/2 or pi once more.
  // 2e7 random pairs measured at most 1.72 FLT_EPSILON relative; 2.5 leaves room for other
  // seeds without hiding a wrong coefficient (without the last one it measures 80).
  using vtkNormalMapping::detail::single::Angle;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> direction(0.0, M_PI), exponent(-30.0, 30.0);
  double worst = 0.0;
  for (int i = 0; i < 1000000; ++i)
  {
    const double a = direction(rng), r = std::exp2(exponent(rng));
    const float s = static_cast<float>(r * std::sin(a)), c = static_cast<float>(r * std::cos(a));
    const double exact = std::atan2(static_cast<double>(s), static_cast<double>(c));
    worst = std::max(worst, std::abs(Angle(s, c) - exact) / (exact * FLT_EPSILON));
  }
  EXPECT_LT(worst, 2.5);
  // The axes and the empty corner exactly.
  EXPECT_EQ(Angle(0.0f, 2.0f), 0.0f);
  EXPECT_EQ(Angle(3.0f, 0.0f), static_cast<float>(M_PI / 2));
  EXPECT_EQ(Angle(0.0f, -2.0f), static_cast<float>(M_PI));
  EXPECT_EQ(Angle(0.0f, 0.0f), 0.0f);
}

TEST(TangentFrameKernels, SinglePrecisionPathAgreesWithTheDoubleKernel)
{
  // Float positions and UVs are computed in float: each operation rounds to 2^-24 relative, and
  // a tangent is a few dozen operations deep, so directions agree to ~1e-6 rad; near-degenerate
  // random triangles amplify it. Measured on these seeds: 1.1e-5 degrees and 2.1e-7 relative for
  // the angle weights. Bounds: 1e-4 degrees and 1e-6 relative. Orientation and sides must agree.
  for (unsigned seed : { 1u, 2u, 3u })
  {
    const RandomBatch r(seed);
    for (detail::BatchCode code : BatchCodes())
    {
      const detail::FrameBatch f = r.Compute(r.P, r.U, r.N, code);
      const detail::FrameBatch d = r.Compute(r.Pd, r.Ud, r.Nd, detail::BatchCode::Scalar);
      int frames = 0;
      for (int i = 0; i < f.Size; ++i)
      {
        ASSERT_EQ(f.Orientation(i), d.Orientation(i)) << "triangle " << i;
        if (d.Orientation(i) == 0)
        {
          continue;
        }
        ++frames;
        const glm::dvec3 tf(f.Tangent[0][i], f.Tangent[1][i], f.Tangent[2][i]);
        const glm::dvec3 td(d.Tangent[0][i], d.Tangent[1][i], d.Tangent[2][i]);
        EXPECT_LT(AngleBetween(tf, td) * 180.0 / Pi, 1e-4) << "triangle " << i;
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(f.Weight[k][i], d.Weight[k][i], 1e-6 * d.Weight[k][i]) << "triangle " << i;
          EXPECT_EQ(f.Side(k, i), d.Side(k, i)) << "triangle " << i;
        }
      }
      // 64 triangles, 8 degenerate in UV and one with a NaN: the rest have frames.
      EXPECT_EQ(frames, detail::FrameBatch::Capacity - 9);
    }
  }
}

#ifdef VTK_TANGENT_BATCH_AVX2
namespace
{
/// The filter's scalar frame of a point with one handedness (vtkPolyDataTangentFrames' Finish,
/// WriteFrame): what FinishLanes must give bit for bit.
template<typename NT, typename OutT>
void ScalarFrame(const NT* normal, const detail::PointSum& sum, bool minus, OutT out[7])
{
  const glm::dvec3 n = SafeNormalize(glm::dvec3(normal[0], normal[1], normal[2]));
  const glm::dvec3 t = PerpendicularTangent(n, sum.Tangent());
  const double sign = minus ? -1.0 : 1.0;
  const glm::dvec3 b = sign * glm::cross(n, t);
  for (int c = 0; c < 3; ++c)
  {
    out[c] = static_cast<OutT>(t[c]);
    out[4 + c] = static_cast<OutT>(b[c]);
  }
  out[3] = static_cast<OutT>(sign);
}

/// FinishLanes (`count` points a call) against ScalarFrame on points with normals and sums over a
/// wide range of scales, parallel sums, zero normals, NaN sums and every kind of handedness mark;
/// and the side bytes it writes against PointSum::Sides.
template<typename NT, typename OutT, typename Finish>
void CheckFinishLanes(int count, Finish finish)
{
  constexpr int numPoints = 256; // the last call includes the last point (element-wise loads)
  const bool wide = std::is_same<NT, double>::value;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<NT> normals(3 * numPoints);
  std::vector<detail::PointSum> sums(numPoints);
  std::vector<unsigned char> sides(numPoints, detail::FallbackMark);
  for (int i = 0; i < numPoints; ++i)
  {
    // Double normals and all sums: 2^-300 .. 2^300; float normals: 2^-60 .. 2^60.
    const double scale = std::ldexp(1.0, wide ? (i % 7) * 100 - 300 : (i % 7) * 20 - 60);
    for (int c = 0; c < 3; ++c)
    {
      normals[3 * i + c] = static_cast<NT>(d(rng) / scale);
      sums[i].Sum[c] = i % 5 == 0 ? normals[3 * i + c] * scale * scale // parallel to the normal
                                  : d(rng) * (wide ? scale : 1.0 / scale);
    }
    if (i % 17 == 0)
    {
      std::fill(normals.begin() + 3 * i, normals.begin() + 3 * i + 3, NT(0));
    }
    if (i % 19 == 0)
    {
      sums[i].Sum[1] = std::numeric_limits<double>::quiet_NaN();
    }
    const unsigned char side = i % 11 == 0
      ? 0
      : (i % 13 == 0 ? detail::BothSides : (i % 2 ? detail::PlusSide : detail::MinusSide));
    sums[i].Marks = side == 0 ? 0 : detail::MarkBase | side;
  }
  std::vector<OutT> t(3 * numPoints), s(numPoints), b(3 * numPoints);
  int done = 0;
  for (int p = 0; p + count <= numPoints; p += count)
  {
    const unsigned rest =
      finish(normals.data(), numPoints, sums.data(), sides.data(), p, t.data(), s.data(), b.data());
    for (int l = 0; l < count; ++l)
    {
      const int i = p + l;
      ASSERT_EQ(sides[i], sums[i].Sides()) << i;
      if ((rest >> l) & 1u)
      {
        continue;
      }
      ++done;
      ASSERT_TRUE(sides[i] == detail::PlusSide || sides[i] == detail::MinusSide) << i;
      OutT expected[7];
      ScalarFrame(normals.data() + 3 * i, sums[i], sides[i] == detail::MinusSide, expected);
      const OutT got[7] = {
        t[3 * i], t[3 * i + 1], t[3 * i + 2], s[i], b[3 * i], b[3 * i + 1], b[3 * i + 2]
      };
      EXPECT_EQ(0, std::memcmp(expected, got, sizeof(got))) << "point " << i;
    }
  }
  // Every point with one handedness, a usable normal and a sum with a perpendicular part is done
  // by the lanes: about 3/5 of these.
  EXPECT_GT(done, numPoints / 2);
}
}

TEST(TangentFrameKernels, LanesCountUnusableNormalsAsIsUsableNormalDoes)
{
  if (detail::BestBatchCode() == detail::BatchCode::Scalar)
  {
    GTEST_SKIP() << "this CPU (or build) has no AVX2: only the scalar count runs";
  }
  // Normals that are zero, +-0, NaN, +-Inf in one component, denormal or huge, at every position
  // (the lanes, the tail, the last point), for every count up to a few lane widths.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> kind(0, 9);
  const float specials[] = { 0.0f,
    -0.0f,
    std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity(),
    std::numeric_limits<float>::denorm_min(),
    std::numeric_limits<float>::max() };
  for (int count = 0; count <= 70; ++count)
  {
    std::vector<float> n(3 * count, 0.5f);
    vtkIdType expected = 0;
    for (int p = 0; p < count; ++p)
    {
      const int k = kind(rng);
      if (k < 3)
      {
        n[3 * p] = n[3 * p + 1] = n[3 * p + 2] = k == 0 ? 0.0f : -0.0f; // zero (k == 2: -0)
      }
      else if (k < 8)
      {
        n[3 * p + (k % 3)] = specials[k - 1]; // NaN, +-Inf, denormal, largest
      }
      expected += IsUsableNormal(glm::dvec3(n[3 * p], n[3 * p + 1], n[3 * p + 2])) ? 0 : 1;
    }
    EXPECT_EQ(detail::avx2::CountUnusableNormals(n.data(), count), expected) << count;
    if (detail::BestBatchCode() == detail::BatchCode::AVX512)
    {
      EXPECT_EQ(detail::avx512::CountUnusableNormals(n.data(), count), expected) << count;
    }
  }
}

TEST(TangentFrameKernels, FinishLanesGiveTheBitsOfTheScalarFinish)
{
  if (detail::BestBatchCode() == detail::BatchCode::Scalar)
  {
    GTEST_SKIP() << "this CPU (or build) has no AVX2: only the scalar finish runs";
  }
  CheckFinishLanes<float, float>(4, detail::avx2::FinishLanes<float, float>);
  CheckFinishLanes<double, double>(4, detail::avx2::FinishLanes<double, double>);
  CheckFinishLanes<double, float>(4, detail::avx2::FinishLanes<double, float>);
  if (detail::BestBatchCode() == detail::BatchCode::AVX512)
  {
    CheckFinishLanes<float, float>(8, detail::avx512::FinishLanes<float, float>);
    CheckFinishLanes<double, double>(8, detail::avx512::FinishLanes<double, double>);
    CheckFinishLanes<float, double>(8, detail::avx512::FinishLanes<float, double>);
  }
}

TEST(TangentFrameKernels, LanesTakeTrianglesDeinterleaveAndRejectBadIds)
{
  if (detail::BestBatchCode() != detail::BatchCode::AVX512)
  {
    GTEST_SKIP() << "this CPU (or build) has no AVX-512: the filter takes runs with scalar code";
  }
  constexpr std::int64_t numPoints = 1000;
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::int64_t> id(0, numPoints - 1);
  // Runs shorter than, equal to and longer than a step of eight, after an empty or part-filled
  // batch; whole when every id is in range, refused (batch size unchanged) when one is not,
  // wherever it is: a step's first, second or third vector, or the tail.
  for (int first : { 0, 5 })
  {
    for (int n : { 0, 1, 7, 8, 9, 17, 59 })
    {
      if (first + n > detail::FrameBatch::Capacity)
      {
        continue;
      }
      std::vector<std::int64_t> ids(3 * n);
      for (auto& x : ids)
      {
        x = id(rng);
      }
      detail::FrameBatch b;
      b.Size = first;
      ASSERT_TRUE(detail::avx512::TakeTriangles(ids.data(), n, numPoints, b));
      ASSERT_EQ(b.Size, first + n);
      for (int t = 0; t < n; ++t)
      {
        for (int k = 0; k < 3; ++k)
        {
          ASSERT_EQ(b.Ids[k][first + t], ids[3 * t + k]) << "n " << n << " triangle " << t;
        }
      }
      for (int bad = 0; bad < 3 * n; ++bad)
      {
        for (std::int64_t value : { numPoints, std::int64_t{ -1 }, INT64_MIN })
        {
          std::vector<std::int64_t> hostile = ids;
          hostile[bad] = value;
          b.Size = first;
          EXPECT_FALSE(detail::avx512::TakeTriangles(hostile.data(), n, numPoints, b))
            << "n " << n << " bad id at " << bad << ": " << value;
          EXPECT_EQ(b.Size, first);
        }
      }
    }
  }
}

TEST(TangentFrameKernels, LanesOwnerBitsMatchTheOwnerRule)
{
  if (detail::BestBatchCode() != detail::BatchCode::AVX512)
  {
    GTEST_SKIP() << "this CPU (or build) has no AVX-512: the filter finds owners with scalar code";
  }
  // Every block count the filter uses (powers of two up to 64), owner runs of the longest and
  // shortest lengths the filter uses and a shorter one, ids anywhere (negative and huge ones
  // included: ids are not checked here), and counts with and without a tail shorter than a step of
  // eight, each id alone in its run so that a missed id is a missed bit.
  std::mt19937 rng(7);
  for (int shift : { 3, detail::ScanBlocks::MinShift, detail::ScanBlocks::MaxShift })
  {
    for (int blocks = 1; blocks <= 64; blocks *= 2)
    {
      for (int count : { 0, 1, 7, 8, 9, 30, 54, 192 })
      {
        for (int trial = 0; trial < 20; ++trial)
        {
          std::vector<std::int64_t> ids(count);
          std::uint64_t expected = 0;
          for (int j = 0; j < count; ++j)
          {
            const std::int64_t run = static_cast<std::int64_t>(rng() % 200);
            ids[j] = trial == 0 && j == count - 1
              ? std::int64_t{ -1 }
              : (run << shift) + static_cast<std::int64_t>(rng() % (1u << shift));
            expected |= std::uint64_t{ 1 } << ((static_cast<std::uint64_t>(ids[j]) >> shift) &
                          static_cast<std::uint64_t>(blocks - 1));
          }
          EXPECT_EQ(detail::avx512::OwnerBits(ids.data(), count, blocks, shift), expected)
            << "shift " << shift << " blocks " << blocks << " count " << count;
          // Each id's own bit, alone: the single-id runs the tail and the steps both see.
          for (int j = 0; j < count; ++j)
          {
            const std::uint64_t own = std::uint64_t{ 1 }
              << ((static_cast<std::uint64_t>(ids[j]) >> shift) &
                   static_cast<std::uint64_t>(blocks - 1));
            ASSERT_EQ(detail::avx512::OwnerBits(ids.data() + j, 1, blocks, shift), own);
          }
        }
      }
    }
  }
}
#endif
