/**
 * @file   vtkTangentFrameBatch.h
 * @brief  ComputeTriangleFrame and the corner weights for many triangles at once (private).
 *
 * vtkPolyDataTangentFrames collects the triangles of a stretch of cells in a FrameBatch and
 * computes their frames here, with the best code the CPU has (chosen at run time, see BatchCode
 * and mikk::LimitInstructionSet): float input 16 triangles per AVX-512 instruction or 8 per AVX2
 * one, double input 4 per AVX2 instruction, or one at a time. All give the bits of the scalar
 * kernels: the vector code (written once for every width in vtkTangentFrameLanes.h) performs the
 * same IEEE operations in the same order lane by lane with no fused multiply-add (target "avx2"
 * has none; the AVX-512 arithmetic has its rounding in the instruction, which is never fused),
 * and hands every triangle whose edges or UV deltas are outside the safe range of
 * RescaleExponent (or non-finite, or zero) to the scalar kernel.
 */
#ifndef vtkTangentFrameBatch_h
#define vtkTangentFrameBatch_h

#include "vtkTangentFrameKernels.h"
#include "vtkType.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define VTK_TANGENT_BATCH_AVX2 1
#define VTK_TANGENT_BATCH_AVX2_FN __attribute__((target("avx2")))
#define VTK_TANGENT_BATCH_AVX2_INLINE __attribute__((target("avx2"), always_inline))
#define VTK_TANGENT_BATCH_NOINLINE __attribute__((noinline))
#define VTK_TANGENT_BATCH_ALWAYS_INLINE __attribute__((always_inline))
#endif

#if defined(__clang__)
#pragma clang fp contract(off)
#endif

namespace vtkNormalMapping
{
namespace detail
{

/// What the weights of a batch are.
enum class BatchWeights
{
  One,   ///< every corner weighs 1 (Unweighted)
  Area,  ///< the triangle's area at each corner (AreaWeighted)
  Angle, ///< the interior angle at each corner (AngleWeighted)
};

/// The index of the lowest set bit of x != 0.
inline int LowestBit64(std::uint64_t x)
{
#if defined(__GNUC__) || defined(__clang__)
  return __builtin_ctzll(x);
#else
  int i = 0;
  for (; (x & 1u) == 0; x >>= 1)
  {
    ++i;
  }
  return i;
#endif
}

/// Triangles and, once computed, their frames and corner weights (structure of arrays), with one
/// bit per triangle for its orientation and for each corner's side. Aligned to a cache line: each
/// block of threads fills its own batch, and adjacent batches must not share a line.
struct alignas(64) FrameBatch
{
  static constexpr int Capacity = 64;
  int Size = 0;
  /// Some triangle may have a corner that the block filling the batch does not own (see
  /// ScatterTarget); clear: the block owns every corner, and the scatter need not ask.
  bool Shared = false;
  vtkIdType Ids[3][Capacity];
  double Tangent[3][Capacity];
  double Normal[3][Capacity];
  double Weight[3][Capacity];
  /// Bit i: triangle i has a frame (orientation +1 or -1; without one, 0).
  std::uint64_t Framed = 0;
  /// Bit i: triangle i's orientation is -1 (where Framed).
  std::uint64_t Mirrored = 0;
  /// Bit i of Minus[k]: corner k of triangle i goes to its point's handedness -1 (see
  /// BatchInput::Side); clear: +1.
  std::uint64_t Minus[3] = { 0, 0, 0 };

  void Add(const vtkIdType* tri)
  {
    this->Ids[0][this->Size] = tri[0];
    this->Ids[1][this->Size] = tri[1];
    this->Ids[2][this->Size] = tri[2];
    ++this->Size;
  }
  bool Full() const { return this->Size == Capacity; }

  /// 1, -1, or 0 for a triangle without a frame.
  int Orientation(int i) const
  {
    return ((this->Framed >> i) & 1u) == 0 ? 0 : (((this->Mirrored >> i) & 1u) != 0 ? -1 : 1);
  }
  void SetOrientation(int i, int orientation)
  {
    SetBits(this->Framed, i, 1, orientation != 0 ? 1u : 0u);
    SetBits(this->Mirrored, i, 1, orientation < 0 ? 1u : 0u);
  }
  /// The orientations of triangles [i, i + count): `framed` lanes have one, positive where
  /// `positive`.
  void SetOrientations(int i, int count, unsigned framed, unsigned positive)
  {
    SetBits(this->Framed, i, count, framed);
    SetBits(this->Mirrored, i, count, framed & ~positive);
  }
  /// 0 for handedness +1, 1 for -1 (the index of the corner's sum).
  int Side(int k, int i) const { return static_cast<int>((this->Minus[k] >> i) & 1u); }
  /// The sides of corner k of triangles [i, i + count): -1 where `minus`.
  void SetSides(int k, int i, int count, unsigned minus)
  {
    SetBits(this->Minus[k], i, count, minus);
  }
  /// Bit i for each triangle i < Size with a frame.
  std::uint64_t FramedTriangles() const { return this->Framed & this->Triangles(); }
  /// Bit i for each triangle i < Size without one.
  std::uint64_t UnframedTriangles() const { return ~this->Framed & this->Triangles(); }

private:
  /// Bits [0, Size).
  std::uint64_t Triangles() const
  {
    return this->Size == Capacity ? ~std::uint64_t{ 0 } : (std::uint64_t{ 1 } << this->Size) - 1;
  }
  /// Bits [i, i + count) of `word` (count <= 32) set to those of `bits`.
  static void SetBits(std::uint64_t& word, int i, int count, unsigned bits)
  {
    const std::uint64_t mask = ((std::uint64_t{ 1 } << count) - 1) << i;
    word = (word & ~mask) | ((static_cast<std::uint64_t>(bits) << i) & mask);
  }
};

struct PointSum; // below

/// Raw inputs of the batch kernels: xyz positions, texture coordinates with `UVComponents`
/// components (1: v = 0), point normals of any length, and unit stand-ins for points whose
/// normal is zero or non-finite (or null).
template<typename PT, typename UT, typename NT>
struct BatchInput
{
  const PT* Points;
  const UT* UVs;
  int UVComponents;
  const NT* Normals;
  const double* Fallback;
  DegeneracyTolerance Tolerance;
  BatchWeights Weights;
  /// The number of points (the vector code reads 16 bytes at a point's xyz except at the last
  /// one); 0 when not known: then every point is read element by element.
  vtkIdType NumberOfPoints = 0;
  /// Where the batch's corners will be added (ScatterTarget::Sums), or null: ComputeBatch then
  /// prefetches each corner's entry for writing while it computes the frames, so that the scatter
  /// finds them in cache. The lane kernels do it next to their position loads, whose ids they
  /// share.
  const PointSum* PrefetchSums = nullptr;

  /// The handedness a triangle with winding normal (x, y, z) and the given orientation gives at
  /// point p: CornerSign without normalizing the point's normal (only the sign of the dot
  /// product matters). A zero or non-finite product uses the stand-in when there is one; when
  /// that fails too the triangle's orientation is kept.
  int Side(double x, double y, double z, int orientation, vtkIdType p) const
  {
    const NT* n = this->Normals + 3 * p;
    double d = n[0] * x + n[1] * y + n[2] * z;
    if (!(d != 0.0 && std::isfinite(d)) && this->Fallback)
    {
      const double* g = this->Fallback + 3 * p;
      d = g[0] * x + g[1] * y + g[2] * z;
    }
    return d < 0.0 ? -orientation : orientation;
  }
};

/// Triangle i of the batch with the scalar kernel.
template<typename PT, typename UT, typename NT>
void ComputeBatchTriangle(const BatchInput<PT, UT, NT>& in, FrameBatch& b, int i)
{
  glm::dvec3 p[3];
  glm::dvec2 uv[3];
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType id = b.Ids[k][i];
    const PT* x = in.Points + 3 * id;
    p[k] = glm::dvec3(x[0], x[1], x[2]);
    const UT* u = in.UVs + in.UVComponents * id;
    uv[k] = glm::dvec2(u[0], in.UVComponents > 1 ? static_cast<double>(u[1]) : 0.0);
  }
  double angles[3] = { 1.0, 1.0, 1.0 };
  const bool angle = in.Weights == BatchWeights::Angle;
  const bool area = in.Weights == BatchWeights::Area;
  const TriangleFrame f = ComputeTriangleFrame(
    p[0], p[1], p[2], uv[0], uv[1], uv[2], in.Tolerance, area, angle ? angles : nullptr);
  for (int c = 0; c < 3; ++c)
  {
    b.Tangent[c][i] = f.Tangent[c];
    b.Normal[c][i] = f.Normal[c];
    b.Weight[c][i] = area ? f.Area : angles[c];
  }
  b.SetOrientation(i, f.Orientation);
}

/**
 * The single-precision path, for float positions and texture coordinates: the same frame as
 * ComputeTriangleFrame computed in float, 16 triangles per AVX-512 instruction or 8 per AVX2 one
 * (vtkTangentFrameLanes.h). Its results
 * differ from the double-precision kernel by float rounding (measured in
 * TestTangentFrameKernels: 1.1e-5 degrees at most on random triangles), of the order of the
 * rounding of the float coordinates themselves. Triangles whose largest edge or UV-delta
 * component is outside [2^-20, 2^20] (where products of four of them could leave float's normal
 * range), non-finite or zero go to the double-precision kernel instead.
 */
namespace single
{
constexpr float SafeMinimum = 0x1p-20f;
constexpr float SafeMaximum = 0x1p20f;
/// atan(z) = z + z x P(x) with x = z^2 on |z| <= tan(pi/8): the coefficients of P, a minimax fit
/// of degree 4 (Remez exchange on the relative error of atan) whose relative error is below
/// 1.2e-9, a hundredth of float's rounding. Half the terms the Taylor series needs for that.
constexpr float AtanMinimax[5] = { -0.3333331865670004f,
  0.19998533167927611f,
  -0.1424297113319538f,
  0.10581485579681649f,
  -0.060332417009767229f };
constexpr float TanPiOver8 = 0.41421356237309504880f;
constexpr float PiOver4 = 0.78539816339744830962f;
constexpr float PiOver2 = 1.5707963267948966192f;
constexpr float Pi = 3.14159265358979323846f;

/// z + z x P(x) (see AtanMinimax), with x2 = x^2: P in Estrin's order, whose chain of dependent
/// operations is half as long as Horner's. The lane kernels (AtanLanes) perform the same
/// operations.
inline float AtanOfReduced(float z, float x, float x2)
{
  const float* c = AtanMinimax;
  const float low = c[0] + c[1] * x;
  const float high = (c[2] + c[3] * x) + x2 * c[4];
  const float p = low + x2 * high;
  return z + (z * x) * p;
}

/// atan2(s, c) for s >= 0, in float: one division (the reduction to |z| <= tan(pi/8) is folded
/// into it) and AtanOfReduced.
inline float Angle(float s, float c)
{
  const float ac = std::abs(c);
  const bool steep = s > ac;
  const float num = steep ? ac : s;
  const float den = steep ? s : ac;
  const bool reduce = num > TanPiOver8 * den;
  const float z = (reduce ? num - den : num) / (reduce ? num + den : den);
  const float x = z * z;
  const float atanZ = AtanOfReduced(z, x, x * x);
  float angle = (reduce ? PiOver4 : 0.0f) + atanZ;
  angle = steep ? PiOver2 - angle : angle;
  angle = c < 0.0f ? Pi - angle : angle;
  return den > 0.0f ? angle : 0.0f;
}

inline float Dot(const float a[3], const float b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Triangle i of the batch in float, or with the double kernel outside the safe range.
template<typename NT>
void ComputeTriangle(const BatchInput<float, float, NT>& in, FrameBatch& b, int i)
{
  float p[3][3], uv[3][2];
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType id = b.Ids[k][i];
    for (int d = 0; d < 3; ++d)
    {
      p[k][d] = in.Points[3 * id + d];
    }
    const float* u = in.UVs + in.UVComponents * id;
    uv[k][0] = u[0];
    uv[k][1] = in.UVComponents > 1 ? u[1] : 0.0f;
  }
  float e1[3], e2[3], e3[3], d1[2], d2[2], d3[2];
  float maxE = 0.0f, sumE = 0.0f, maxUV = 0.0f, sumUV = 0.0f;
  for (int d = 0; d < 3; ++d)
  {
    e1[d] = p[1][d] - p[0][d];
    e2[d] = p[2][d] - p[0][d];
    e3[d] = e2[d] - e1[d];
    maxE = std::max(maxE, std::max(std::abs(e1[d]), std::abs(e2[d])));
    sumE = sumE + (e1[d] + e2[d]);
  }
  for (int d = 0; d < 2; ++d)
  {
    d1[d] = uv[1][d] - uv[0][d];
    d2[d] = uv[2][d] - uv[0][d];
    d3[d] = d2[d] - d1[d];
    maxUV = std::max(maxUV, std::max(std::abs(d1[d]), std::abs(d2[d])));
    sumUV = sumUV + (d1[d] + d2[d]);
  }
  if (!(std::isfinite(sumE) && std::isfinite(sumUV) && maxE >= SafeMinimum && maxE <= SafeMaximum &&
        maxUV >= SafeMinimum && maxUV <= SafeMaximum))
  {
    ComputeBatchTriangle(in, b, i);
    return;
  }
  const float n[3] = {
    e1[1] * e2[2] - e2[1] * e1[2], e1[2] * e2[0] - e2[2] * e1[0], e1[0] * e2[1] - e2[0] * e1[1]
  };
  const float twiceArea2 = Dot(n, n);
  const float longest2 = std::max(std::max(Dot(e1, e1), Dot(e2, e2)), Dot(e3, e3));
  const float tolP = static_cast<float>(in.Tolerance.Position);
  const bool posOK = twiceArea2 > ((tolP * tolP) * longest2) * longest2;
  const float det = d1[0] * d2[1] - d2[0] * d1[1];
  const float longestUV2 =
    std::max(std::max(d1[0] * d1[0] + d1[1] * d1[1], d2[0] * d2[0] + d2[1] * d2[1]),
      d3[0] * d3[0] + d3[1] * d3[1]);
  const bool uvOK = std::abs(det) > static_cast<float>(in.Tolerance.UV) * longestUV2;
  float t[3];
  for (int d = 0; d < 3; ++d)
  {
    t[d] = d2[1] * e1[d] - d1[1] * e2[d];
    t[d] = det < 0.0f ? -t[d] : t[d];
  }
  const float tLength = std::sqrt(Dot(t, t));
  const bool tOK = tLength > 0.0f && std::isfinite(tLength);
  const float inverse = 1.0f / tLength;
  float w[3] = { 1.0f, 1.0f, 1.0f };
  if (in.Weights == BatchWeights::Angle)
  {
    const float sine = std::sqrt(twiceArea2);
    w[0] = Angle(sine, Dot(e1, e2));
    w[1] = Angle(sine, -Dot(e1, e3));
    w[2] = Angle(sine, Dot(e2, e3));
  }
  else if (in.Weights == BatchWeights::Area)
  {
    w[0] = w[1] = w[2] = 0.5f * std::sqrt(twiceArea2);
  }
  for (int d = 0; d < 3; ++d)
  {
    b.Tangent[d][i] = t[d] * inverse;
    b.Normal[d][i] = n[d];
    b.Weight[d][i] = w[d];
  }
  b.SetOrientation(i, posOK && uvOK && tOK ? (det > 0.0f ? 1 : -1) : 0);
}
} // namespace single

/// A hint to fetch the cache line at p for writing; nothing where the compiler has no such hint.
inline void PrefetchForWriting(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p, 1);
#else
  (void)p;
#endif
}

/// The handednesses a point's corners have (with a positive weight): bit 0 for +1, bit 1 for -1.
/// Both bits: a conflict (a mirror seam); none: a fallback point, which vtkPolyDataTangentFrames
/// then marks FallbackMark.
constexpr unsigned char PlusSide = 1, MinusSide = 2, BothSides = 3, FallbackMark = 4;

/// The bits of 1.0, or-ed into every non-zero PointSum::Marks: read as a double (the vector scatter
/// adds zero to the marks' lane with the sums' additions, then ors the mark in) the marks are then
/// never subnormal, and adding zero leaves their bits as they are.
constexpr std::int64_t MarkBase = 0x3ff0000000000000LL;

/// The mark of a corner on `side` (0: handedness +1, 1: -1) with weight w: MarkBase with PlusSide
/// or MinusSide when w > 0, else 0.
inline std::int64_t CornerMark(int side, double w)
{
  return w > 0.0 ? MarkBase | (std::int64_t{ PlusSide } << side) : 0;
}

/**
 * Per point, in one 32-byte line (the scatter reads and writes it once per corner): the or of its
 * corners' marks (CornerMark), then the weighted sum of its triangles' tangents (x, y, z), both
 * handednesses together. The marks come first so that the vector scatter can load a corner's mark
 * into the low lane of a zeroed register (avx2::ScatterCorners).
 */
struct alignas(32) PointSum
{
  /// The or of the corners' CornerMarks. FillFallbacks reuses it as a count.
  std::int64_t Marks;
  double Sum[3];

  glm::dvec3 Tangent() const { return glm::dvec3(this->Sum[0], this->Sum[1], this->Sum[2]); }
  /// PlusSide, MinusSide, BothSides, or 0 for a point without a marked corner.
  unsigned char Sides() const { return static_cast<unsigned char>(this->Marks & BothSides); }
};

/**
 * Bit b set for each block b, of `blocks` (a power of two), that owns one of the `count` ids:
 * (id >> ownerShift) & (blocks - 1) == b (see ScatterTarget). No check of the ids; a negative id
 * is read as unsigned. Branch-free, but scalar for 64-bit ids: the baseline instruction set has no
 * variable 64-bit shift (avx512::OwnerBits does eight at a time).
 */
template<typename IdT>
inline std::uint64_t ScalarOwnerBits(const IdT* ids, vtkIdType count, int blocks, int ownerShift)
{
  const std::uint64_t mask = static_cast<std::uint64_t>(blocks - 1);
  std::uint64_t bits = 0;
  for (vtkIdType j = 0; j < count; ++j)
  {
    const std::uint64_t id = static_cast<std::uint64_t>(static_cast<std::int64_t>(ids[j]));
    bits |= std::uint64_t{ 1 } << ((id >> ownerShift) & mask);
  }
  return bits;
}

/**
 * Where a batch's corners are added: per point, a PointSum. Only corners whose point `Block` owns
 * are added: points are dealt to `Blocks` (a power of two) in runs of 2^OwnerShift ids, round
 * robin.
 */
struct ScatterTarget
{
  PointSum* Sums;
  int Blocks;
  int Block;
  int OwnerShift;

  bool Owns(vtkIdType p) const
  {
    return static_cast<int>((p >> this->OwnerShift) & (this->Blocks - 1)) == this->Block;
  }
};

/// How the ordered scan deals points to blocks: `Blocks` (a power of two) in runs of
/// 2^OwnerShift consecutive ids, round robin (see ScatterTarget).
struct ScanBlocks
{
  int Blocks;
  int OwnerShift;

  /// Runs of 2^MaxShift ids for large meshes: few triangles straddle two runs (each owner computes
  /// such a triangle). With 2^12 it was a quarter of a 1000-point-wide grid's; 2^13 and 2^14
  /// measured the same on the 1M-triangle torus, and 2^16 no better.
  static constexpr int MaxShift = 14;
  /// Runs of at least 1,024 ids, for small meshes: below, a run is a few rows of a grid and most
  /// triangles would be computed twice.
  static constexpr int MinShift = 10;

  /**
   * One block with one thread (nothing computed twice). With several, four blocks per thread, so
   * that a thread done with its blocks of a batch takes those still waiting and a slower vCPU
   * holds a batch up less, but no more blocks than runs; and runs shortened (down to 2^MinShift)
   * until there are two per wanted block, so that meshes of a few thousand points are shared out
   * too. Measured with two threads on the torus (2-vCPU VM, median Update, one thread in
   * parentheses): 1M triangles 12.5 ms with 8 blocks against 14.8 with 2 (14.3; 4, 16 and 32
   * blocks were slower than 8); 100K triangles 0.78 ms with 4 blocks in runs of 2^12 against
   * 0.92 with the 2 blocks in runs of 2^14 that runs of a fixed length allowed (1.22); 16K
   * triangles 0.19 ms against 0.26 with one block (0.25); 6K triangles 0.11 against 0.18 with one
   * block (0.13).
   */
  static ScanBlocks Choose(vtkIdType numPoints, int threads)
  {
    ScanBlocks s{ 1, MaxShift };
    if (threads <= 1)
    {
      return s;
    }
    const vtkIdType wanted = std::min<vtkIdType>(64, 4 * static_cast<vtkIdType>(threads));
    while (s.OwnerShift > MinShift && (numPoints >> s.OwnerShift) < 2 * wanted)
    {
      --s.OwnerShift;
    }
    const vtkIdType limit = std::min(wanted, numPoints >> s.OwnerShift);
    while (2 * static_cast<vtkIdType>(s.Blocks) <= limit)
    {
      s.Blocks *= 2;
    }
    return s;
  }
};

/// Adds the corners of the batch's triangles that have a frame, in order.
inline void ScatterBatchScalar(const FrameBatch& b, const ScatterTarget& s)
{
  for (std::uint64_t framed = b.FramedTriangles(); framed != 0; framed &= framed - 1)
  {
    const int i = LowestBit64(framed);
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType p = b.Ids[k][i];
      if (s.Owns(p))
      {
        const double w = b.Weight[k][i];
        PointSum& sum = s.Sums[p];
        sum.Sum[0] += w * b.Tangent[0][i];
        sum.Sum[1] += w * b.Tangent[1][i];
        sum.Sum[2] += w * b.Tangent[2][i];
        sum.Marks |= CornerMark(b.Side(k, i), w);
      }
    }
  }
}

#ifdef VTK_TANGENT_BATCH_AVX2
namespace avx2
{
using V = __m256d;

/// The CornerMark of every corner of the batch's triangles [0, Size), four at a time (meaningless
/// at triangles without a frame, which the scatter skips).
VTK_TANGENT_BATCH_AVX2_FN inline void CornerMarks(const FrameBatch& b,
  std::int64_t marks[3][FrameBatch::Capacity])
{
  const __m256i lane = _mm256_setr_epi64x(0, 1, 2, 3);
  const __m256i one = _mm256_set1_epi64x(1);
  const __m256i base = _mm256_set1_epi64x(MarkBase);
  for (int k = 0; k < 3; ++k)
  {
    int i = 0;
    for (; i + 4 <= b.Size; i += 4)
    {
      const __m256i positive = _mm256_castpd_si256(
        _mm256_cmp_pd(_mm256_loadu_pd(b.Weight[k] + i), _mm256_setzero_pd(), _CMP_GT_OQ));
      const __m256i side = _mm256_and_si256(
        _mm256_srlv_epi64(_mm256_set1_epi64x(static_cast<long long>(b.Minus[k] >> i)), lane), one);
      // PlusSide << side is side + 1.
      const __m256i mark = _mm256_or_si256(base, _mm256_add_epi64(side, one));
      _mm256_store_si256(
        reinterpret_cast<__m256i*>(marks[k] + i), _mm256_and_si256(mark, positive));
    }
    for (; i < b.Size; ++i)
    {
      marks[k][i] = CornerMark(b.Side(k, i), b.Weight[k][i]);
    }
  }
}

/**
 * ScatterBatchScalar with one read-modify-write of the 32-byte PointSum per corner: the same
 * additions in lanes 1-3, zero added to lane 0 (the marks: weights are finite, so w * 0 is +0),
 * then the corner's mark or-ed into lane 0. The marks of the whole batch come first, from vector
 * compares (CornerMarks). Against picking each corner's mark from a table of lane-3 rows and
 * blending it in (the code before), alternating the two libraries in one process on the 1M
 * torus: 0.94-0.96 of the time per Update on one thread, 0.96 on two, 0.98 with AVX2 only; the
 * scatter's instructions per corner went from about 15 to 9. `EveryPoint`: the target has one
 * block, which owns every point.
 */
template<bool EveryPoint>
VTK_TANGENT_BATCH_AVX2_FN void ScatterCorners(const FrameBatch& b, const ScatterTarget& s)
{
  alignas(32) std::int64_t marks[3][FrameBatch::Capacity];
  CornerMarks(b, marks);
  // In a local: the stores through `sum` could alias s.Sums, which would be read again per corner.
  PointSum* const sums = s.Sums;
  for (std::uint64_t framed = b.FramedTriangles(); framed != 0; framed &= framed - 1)
  {
    const int i = LowestBit64(framed);
    const V t = _mm256_setr_pd(0.0, b.Tangent[0][i], b.Tangent[1][i], b.Tangent[2][i]);
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType p = b.Ids[k][i];
      if (EveryPoint || s.Owns(p))
      {
        double* sum = reinterpret_cast<double*>(sums + p);
        const V added =
          _mm256_add_pd(_mm256_load_pd(sum), _mm256_mul_pd(_mm256_set1_pd(b.Weight[k][i]), t));
        const V mark = _mm256_castsi256_pd(_mm256_setr_epi64x(marks[k][i], 0, 0, 0));
        _mm256_store_pd(sum, _mm256_or_pd(added, mark));
      }
    }
  }
}

VTK_TANGENT_BATCH_AVX2_FN inline void ScatterBatch(const FrameBatch& b, const ScatterTarget& s)
{
  if (s.Blocks == 1 || !b.Shared)
  {
    ScatterCorners<true>(b, s);
  }
  else
  {
    ScatterCorners<false>(b, s);
  }
}
} // namespace avx2

/// ComputeBatchTriangle and BatchInput::Side for the lane kernels' special lanes, never inlined
/// into them: compiled for the baseline instruction set, they cannot be fused into FMA however the
/// kernels' instruction set is.
template<typename PT, typename UT, typename NT>
VTK_TANGENT_BATCH_NOINLINE void ScalarTriangle(const BatchInput<PT, UT, NT>& in,
  FrameBatch& b,
  int i)
{
  ComputeBatchTriangle(in, b, i);
}
template<typename PT, typename UT, typename NT>
VTK_TANGENT_BATCH_NOINLINE int ScalarSide(const BatchInput<PT, UT, NT>& in,
  const FrameBatch& b,
  int i,
  vtkIdType p)
{
  return in.Side(b.Normal[0][i], b.Normal[1][i], b.Normal[2][i], b.Orientation(i), p);
}

/// Byte l of the result is bit l of x (l < 8), as 0 or 1: a bit mask to bytes without a loop.
inline std::uint64_t SpreadBits(unsigned x)
{
  // x in every byte, byte l keeps bit l; adding 0x7f carries exactly the non-zero bytes into
  // their bit 7, and no byte into the next.
  const std::uint64_t y =
    (static_cast<std::uint64_t>(x & 0xffu) * 0x0101010101010101ULL) & 0x8040201008040201ULL;
  return ((y + 0x7f7f7f7f7f7f7f7fULL) >> 7) & 0x0101010101010101ULL;
}

/// The index of the lowest set bit of x != 0.
inline int LowestBit(unsigned x)
{
  return __builtin_ctz(x);
}

// The lane kernels (vtkTangentFrameLanes.h), once per instruction set. Everything between a
// push and its pop is compiled for that instruction set, the templates' instances included.
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
namespace avx2
{
/// Eight float lanes (F), four double lanes (D); each operation is overloaded for both, so that
/// code written once serves both precisions (LaneTypes). AVX2 has no FMA, so nothing is fused.
struct Lanes
{
  static constexpr int Count = 8;
  static constexpr int DoubleCount = 4;
  using F = __m256;
  using M = __m256; // all ones in the lanes where true
  using D = __m256d;

  static F Zero() { return _mm256_setzero_ps(); }
  static F Set(float x) { return _mm256_set1_ps(x); }
  static F Load(const float* x) { return _mm256_loadu_ps(x); }
  static F Add(F x, F y) { return _mm256_add_ps(x, y); }
  static F Sub(F x, F y) { return _mm256_sub_ps(x, y); }
  static F Mul(F x, F y) { return _mm256_mul_ps(x, y); }
  static F Div(F x, F y) { return _mm256_div_ps(x, y); }
  static F Sqrt(F x) { return _mm256_sqrt_ps(x); }
  static F Max(F x, F y) { return _mm256_max_ps(x, y); }
  static F Abs(F x) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x); }
  static F Negate(F x) { return _mm256_xor_ps(x, _mm256_set1_ps(-0.0f)); }
  static F NegateWhere(M m, F x)
  {
    return _mm256_xor_ps(x, _mm256_and_ps(m, _mm256_set1_ps(-0.0f)));
  }
  static M Gt(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_GT_OQ); }
  static M Ge(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_GE_OQ); }
  static M Le(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_LE_OQ); }
  static M Lt(F x, F y) { return _mm256_cmp_ps(x, y, _CMP_LT_OQ); }
  static M Finite(F x) { return Le(Abs(x), _mm256_set1_ps(FLT_MAX)); }
  static M And(M x, M y) { return _mm256_and_ps(x, y); }
  /// m ? x : y
  static F Select(M m, F x, F y) { return _mm256_blendv_ps(y, x, m); }
  /// m ? x : 0
  static F Keep(M m, F x) { return _mm256_and_ps(m, x); }
  static unsigned Bits(M m) { return static_cast<unsigned>(_mm256_movemask_ps(m)); }

  /// Whether 64-bit ids[0..n) (n a multiple of 4, ids >= 0) are all below `limit`.
  static bool Below(const std::int64_t* ids, int n, std::int64_t limit)
  {
    // The sign bit of every id - limit, and-ed.
    const __m256i l = _mm256_set1_epi64x(limit);
    __m256i below = _mm256_set1_epi64x(-1);
    for (int j = 0; j < n; j += 4)
    {
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids + j));
      below = _mm256_and_si256(below, _mm256_sub_epi64(v, l));
    }
    return _mm256_movemask_pd(_mm256_castsi256_pd(below)) == 0xf;
  }

  /// x, y, z and the next float of point `id` of an array of `count` xyz points: one 16-byte load,
  /// or, when Guarded, element by element at the array's last point (count 0: always).
  template<bool Guarded>
  static __m128 LoadPoint(const float* xyz, vtkIdType id, vtkIdType count)
  {
    const float* q = xyz + 3 * id;
    return !Guarded || id + 1 < count ? _mm_loadu_ps(q) : _mm_setr_ps(q[0], q[1], q[2], 0.0f);
  }
  /// Rows r[0..4) transposed; the first three columns out.
  static void Transpose(const __m128 r[4], __m128 out[3])
  {
    const __m128 low01 = _mm_unpacklo_ps(r[0], r[1]), low23 = _mm_unpacklo_ps(r[2], r[3]);
    const __m128 high01 = _mm_unpackhi_ps(r[0], r[1]), high23 = _mm_unpackhi_ps(r[2], r[3]);
    out[0] = _mm_movelh_ps(low01, low23);
    out[1] = _mm_movehl_ps(low23, low01);
    out[2] = _mm_movelh_ps(high01, high23);
  }
  /// The x, y and z of four points.
  template<bool Guarded>
  static void GatherFour(const float* xyz, const vtkIdType* ids, vtkIdType count, __m128 out[3])
  {
    const __m128 r[4] = { LoadPoint<Guarded>(xyz, ids[0], count),
      LoadPoint<Guarded>(xyz, ids[1], count),
      LoadPoint<Guarded>(xyz, ids[2], count),
      LoadPoint<Guarded>(xyz, ids[3], count) };
    Transpose(r, out);
  }
  template<bool Guarded>
  static void GatherXYZ(const float* xyz, const vtkIdType* ids, vtkIdType count, F out[3])
  {
    __m128 low[3], high[3];
    GatherFour<Guarded>(xyz, ids, count, low);
    GatherFour<Guarded>(xyz, ids + 4, count, high);
    for (int d = 0; d < 3; ++d)
    {
      out[d] = _mm256_insertf128_ps(_mm256_castps128_ps256(low[d]), high[d], 1);
    }
  }
  /// u and v of 8 points of a two-component array: one 8-byte load per point.
  static void GatherUV(const float* uv, const vtkIdType* ids, F& u, F& v)
  {
    __m128 pairs[4]; // (u, v) of points 2h and 2h + 1
    for (int h = 0; h < 4; ++h)
    {
      const __m128 low =
        _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(uv + 2 * ids[2 * h]));
      pairs[h] = _mm_loadh_pi(low, reinterpret_cast<const __m64*>(uv + 2 * ids[2 * h + 1]));
    }
    const int evens = _MM_SHUFFLE(2, 0, 2, 0), odds = _MM_SHUFFLE(3, 1, 3, 1);
    u = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_shuffle_ps(pairs[0], pairs[1], evens)),
      _mm_shuffle_ps(pairs[2], pairs[3], evens),
      1);
    v = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_shuffle_ps(pairs[0], pairs[1], odds)),
      _mm_shuffle_ps(pairs[2], pairs[3], odds),
      1);
  }
  /// The lanes widened to double, stored at out[0..8).
  static void Store(double* out, F x)
  {
    _mm256_storeu_pd(out, _mm256_cvtps_pd(_mm256_castps256_ps128(x)));
    _mm256_storeu_pd(out + 4, _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1)));
  }

  /// The four xyz triples v[0..3) as floats, interleaved into out[0..12) with three stores.
  static void StoreXYZ(float* out, const __m256d v[3])
  {
    const __m128 x = _mm256_cvtpd_ps(v[0]), y = _mm256_cvtpd_ps(v[1]), z = _mm256_cvtpd_ps(v[2]);
    const __m128 xy01 = _mm_unpacklo_ps(x, y);                                   // x0 y0 x1 y1
    const __m128 xy23 = _mm_unpackhi_ps(x, y);                                   // x2 y2 x3 y3
    const __m128 z0x1 = _mm_shuffle_ps(z, x, _MM_SHUFFLE(1, 1, 0, 0));           // z0 z0 x1 x1
    const __m128 y1z1 = _mm_shuffle_ps(y, z, _MM_SHUFFLE(1, 1, 1, 1));           // y1 y1 z1 z1
    const __m128 z2x3 = _mm_shuffle_ps(z, x, _MM_SHUFFLE(3, 3, 2, 2));           // z2 z2 x3 x3
    const __m128 y3z3 = _mm_shuffle_ps(y, z, _MM_SHUFFLE(3, 3, 3, 3));           // y3 y3 z3 z3
    _mm_storeu_ps(out, _mm_shuffle_ps(xy01, z0x1, _MM_SHUFFLE(2, 0, 1, 0)));     // x0 y0 z0 x1
    _mm_storeu_ps(out + 4, _mm_shuffle_ps(y1z1, xy23, _MM_SHUFFLE(1, 0, 2, 0))); // y1 z1 x2 y2
    _mm_storeu_ps(out + 8, _mm_shuffle_ps(z2x3, y3z3, _MM_SHUFFLE(2, 0, 2, 0))); // z2 x3 y3 z3
  }
  /// The same in double: Thirds undone (a permute per component, two blends per store).
  static void StoreXYZ(double* out, const __m256d v[3])
  {
    const __m256d x = _mm256_permute4x64_pd(v[0], 0x6c);                            // x0 x3 x2 x1
    const __m256d y = _mm256_permute4x64_pd(v[1], 0xb1);                            // y1 y0 y3 y2
    const __m256d z = _mm256_permute4x64_pd(v[2], 0xc6);                            // z2 z1 z0 z3
    _mm256_storeu_pd(out, _mm256_blend_pd(_mm256_blend_pd(x, y, 0x2), z, 0x4));     // x0 y0 z0 x1
    _mm256_storeu_pd(out + 4, _mm256_blend_pd(_mm256_blend_pd(x, y, 0x9), z, 0x2)); // y1 z1 x2 y2
    _mm256_storeu_pd(out + 8, _mm256_blend_pd(_mm256_blend_pd(x, y, 0x4), z, 0x9)); // z2 x3 y3 z3
  }
  /// The lanes l < 4 where bit l of `bits` is set.
  static __m256d MaskFromBits(unsigned bits)
  {
    const __m256i bit = _mm256_setr_epi64x(1, 2, 4, 8);
    return _mm256_castsi256_pd(
      _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(bits), bit), bit));
  }
  /// out[l] = -1 where bit l of minus is set, else 1, for l < 4.
  static void StoreSigns(float* out, unsigned minus)
  {
    const __m128i bit = _mm_setr_epi32(1, 2, 4, 8);
    const __m128i set =
      _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(static_cast<int>(minus)), bit), bit);
    _mm_storeu_ps(out, _mm_blendv_ps(_mm_set1_ps(1.0f), _mm_set1_ps(-1.0f), _mm_castsi128_ps(set)));
  }
  static void StoreSigns(double* out, unsigned minus)
  {
    _mm256_storeu_pd(
      out, _mm256_blendv_pd(_mm256_set1_pd(1.0), _mm256_set1_pd(-1.0), MaskFromBits(minus)));
  }

  using DM = __m256d; // all ones in the lanes where true
  static D Set(double x) { return _mm256_set1_pd(x); }
  static D Sub(D x, D y) { return _mm256_sub_pd(x, y); }
  static D Div(D x, D y) { return _mm256_div_pd(x, y); }
  static D Sqrt(D x) { return _mm256_sqrt_pd(x); }
  static D Max(D x, D y) { return _mm256_max_pd(x, y); }
  static D Abs(D x) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x); }
  static DM Gt(D x, D y) { return _mm256_cmp_pd(x, y, _CMP_GT_OQ); }
  static DM Ge(D x, D y) { return _mm256_cmp_pd(x, y, _CMP_GE_OQ); }
  static DM Le(D x, D y) { return _mm256_cmp_pd(x, y, _CMP_LE_OQ); }
  static DM And(DM x, DM y) { return _mm256_and_pd(x, y); }
  static unsigned Bits(DM m) { return static_cast<unsigned>(_mm256_movemask_pd(m)); }
  /// x, y and z of the four PointSums s[0..4), and their Marks (as bits).
  static void GatherSums(const PointSum* s, D out[4])
  {
    D r[4];
    for (int j = 0; j < 4; ++j)
    {
      r[j] = _mm256_load_pd(reinterpret_cast<const double*>(s + j));
    }
    // Lanes: the marks, then x, y and z.
    D columns[4];
    TransposeDouble(r, columns);
    out[0] = columns[1];
    out[1] = columns[2];
    out[2] = columns[3];
    out[3] = columns[0];
  }
  /// Rows r[0..4) of four doubles transposed: out[c] holds column c.
  static void TransposeDouble(const D r[4], D out[4])
  {
    const D xz01 = _mm256_unpacklo_pd(r[0], r[1]), yw01 = _mm256_unpackhi_pd(r[0], r[1]);
    const D xz23 = _mm256_unpacklo_pd(r[2], r[3]), yw23 = _mm256_unpackhi_pd(r[2], r[3]);
    out[0] = _mm256_permute2f128_pd(xz01, xz23, 0x20);
    out[1] = _mm256_permute2f128_pd(yw01, yw23, 0x20);
    out[2] = _mm256_permute2f128_pd(xz01, xz23, 0x31);
    out[3] = _mm256_permute2f128_pd(yw01, yw23, 0x31);
  }
  /// The lanes whose bits have bit 0 set (`first`) and bit 1 set (`second`).
  static void LowBits(D bits, unsigned& first, unsigned& second)
  {
    const __m256i x = _mm256_castpd_si256(bits);
    first =
      static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_slli_epi64(x, 63))));
    second =
      static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_slli_epi64(x, 62))));
  }
  static void Widen(F x, D& low, D& high)
  {
    low = _mm256_cvtps_pd(_mm256_castps256_ps128(x));
    high = _mm256_cvtps_pd(_mm256_extractf128_ps(x, 1));
  }
  static D Load(const double* x) { return _mm256_loadu_pd(x); }
  static void Store(double* out, D x) { _mm256_storeu_pd(out, x); }
  static D Add(D x, D y) { return _mm256_add_pd(x, y); }
  static D Mul(D x, D y) { return _mm256_mul_pd(x, y); }
  static DM Lt(D x, D y) { return _mm256_cmp_pd(x, y, _CMP_LT_OQ); }
  static DM Finite(D x) { return Le(Abs(x), _mm256_set1_pd(DBL_MAX)); }
  /// m ? x : y
  static D Select(DM m, D x, D y) { return _mm256_blendv_pd(y, x, m); }
  /// m ? x : 0
  static D Keep(DM m, D x) { return _mm256_and_pd(m, x); }
  static D Negate(D x) { return _mm256_xor_pd(x, _mm256_set1_pd(-0.0)); }
  static D NegateWhere(DM m, D x)
  {
    return _mm256_xor_pd(x, _mm256_and_pd(m, _mm256_set1_pd(-0.0)));
  }
  /// Component d of the points ids[0..4) of an array of any type with `stride` components each,
  /// in double.
  template<typename T>
  static D GatherDouble(const T* x, int stride, const vtkIdType* ids, int d)
  {
    return _mm256_setr_pd(static_cast<double>(x[stride * ids[0] + d]),
      static_cast<double>(x[stride * ids[1] + d]),
      static_cast<double>(x[stride * ids[2] + d]),
      static_cast<double>(x[stride * ids[3] + d]));
  }
  static unsigned NegativeBits(D x)
  {
    return static_cast<unsigned>(
      _mm256_movemask_pd(_mm256_cmp_pd(x, _mm256_setzero_pd(), _CMP_LT_OQ)));
  }
  static unsigned NonZeroFiniteBits(D x)
  {
    const D a = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    const D ok = _mm256_and_pd(_mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_GT_OQ),
      _mm256_cmp_pd(a, _mm256_set1_pd(DBL_MAX), _CMP_LE_OQ));
    return static_cast<unsigned>(_mm256_movemask_pd(ok));
  }
  /// The x, y and z of 4 points of a float or double xyz array of `count` points, in double.
  template<bool Guarded>
  static void GatherXYZDouble(const float* n, const vtkIdType* ids, vtkIdType count, D out[3])
  {
    __m128 f[3];
    GatherFour<Guarded>(n, ids, count, f);
    for (int d = 0; d < 3; ++d)
    {
      out[d] = _mm256_cvtps_pd(f[d]);
    }
  }
  /// Double: element by element.
  template<bool Guarded>
  static void GatherXYZDouble(const double* xyz, const vtkIdType* ids, vtkIdType, D out[3])
  {
    for (int d = 0; d < 3; ++d)
    {
      out[d] = GatherDouble(xyz, 3, ids, d);
    }
  }
  /// The same with one 32-byte load per point (element by element at the array's last point when
  /// Guarded) and a transpose: slower here than the element loads above (0.90-0.91 against
  /// 0.93-0.94 of VTK's filter's speed on the 1M double torus, AVX2 only), faster for AVX-512's
  /// eight lanes (1.30-1.33 against 1.24-1.30), which use it.
  template<bool Guarded>
  static void GatherRowsDouble(const double* xyz, const vtkIdType* ids, vtkIdType count, D out[3])
  {
    D r[4], columns[4];
    for (int j = 0; j < 4; ++j)
    {
      const double* q = xyz + 3 * ids[j];
      r[j] =
        !Guarded || ids[j] + 1 < count ? _mm256_loadu_pd(q) : _mm256_setr_pd(q[0], q[1], q[2], 0.0);
    }
    TransposeDouble(r, columns);
    for (int d = 0; d < 3; ++d)
    {
      out[d] = columns[d];
    }
  }
  /// u and v of 4 points of a two-component double array: one 16-byte load per point.
  static void GatherUVDouble(const double* uv, const vtkIdType* ids, D& u, D& v)
  {
    const auto pair = [&](int l) { return _mm_loadu_pd(uv + 2 * ids[l]); };
    const D even = _mm256_insertf128_pd(_mm256_castpd128_pd256(pair(0)), pair(2), 1);
    const D odd = _mm256_insertf128_pd(_mm256_castpd128_pd256(pair(1)), pair(3), 1);
    u = _mm256_unpacklo_pd(even, odd);
    v = _mm256_unpackhi_pd(even, odd);
  }
  /// The normals of points [p, p + 4) of an array of `count` points, in double.
  static void LoadNormalRun(const float* n, vtkIdType p, vtkIdType count, D out[3])
  {
    const vtkIdType ids[4] = { p, p + 1, p + 2, p + 3 };
    if (p + 4 >= count)
    {
      GatherXYZDouble<true>(n, ids, count, out);
    }
    else
    {
      GatherXYZDouble<false>(n, ids, count, out);
    }
  }
  /// The same for double normals: three loads of exactly their 12 doubles, then Thirds.
  static void LoadNormalRun(const double* n, vtkIdType p, vtkIdType count, D out[3])
  {
    if (p + 4 > count)
    {
      const vtkIdType ids[4] = { p, p + 1, p + 2, p + 3 };
      GatherXYZDouble<true>(n, ids, count, out);
      return;
    }
    const double* q = n + 3 * p;
    const D x[3] = { _mm256_loadu_pd(q), _mm256_loadu_pd(q + 4), _mm256_loadu_pd(q + 8) };
    Thirds(x, out);
  }
  /// Component k of four interleaved triples x[0..3) (12 lanes) into out[k]: lanes k, k + 3,
  /// k + 6, k + 9. Per component two blends gather its lanes, and a permute orders them.
  static void Thirds(const D x[3], D out[3])
  {
    // x[0] = (a0 b0 c0 a1), x[1] = (b1 c1 a2 b2), x[2] = (c2 a3 b3 c3).
    out[0] = _mm256_permute4x64_pd(
      _mm256_blend_pd(_mm256_blend_pd(x[0], x[1], 0x4), x[2], 0x2), 0x6c); // a0 a3 a2 a1
    out[1] = _mm256_permute4x64_pd(
      _mm256_blend_pd(_mm256_blend_pd(x[0], x[1], 0x9), x[2], 0x4), 0xb1); // b1 b0 b3 b2
    out[2] = _mm256_permute4x64_pd(
      _mm256_blend_pd(_mm256_blend_pd(x[0], x[1], 0x2), x[2], 0x9), 0xc6); // c2 c1 c0 c3
  }
};
#include "vtkTangentFrameLanes.h"

/**
 * Appends the n triangles of `ids` (three 64-bit ids each) to the batch, which has room, if every
 * id is in [0, numPoints); else appends nothing and returns false. Four triangles a step: three
 * 256-bit loads, a range test and Lanes::Thirds put the interleaved ids into b.Ids.
 */
inline bool TakeTriangles(const std::int64_t* ids, int n, std::int64_t numPoints, FrameBatch& b)
{
  // An id is in range when id - numPoints is negative and id is not: the sign bit of
  // (id - numPoints) & ~id, and-ed over all ids.
  const __m256i limit = _mm256_set1_epi64x(numPoints);
  __m256i inRange = _mm256_set1_epi64x(-1);
  int t = 0;
  for (; t + 4 <= n; t += 4)
  {
    const std::int64_t* from = ids + 3 * t;
    __m256d x[3], corners[3];
    for (int j = 0; j < 3; ++j)
    {
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(from + 4 * j));
      inRange = _mm256_and_si256(inRange, _mm256_andnot_si256(v, _mm256_sub_epi64(v, limit)));
      x[j] = _mm256_castsi256_pd(v);
    }
    Lanes::Thirds(x, corners);
    for (int k = 0; k < 3; ++k)
    {
      _mm256_storeu_pd(reinterpret_cast<double*>(b.Ids[k] + b.Size + t), corners[k]);
    }
  }
  bool tailInRange = true;
  for (; t < n; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t id = ids[3 * t + k];
      tailInRange =
        tailInRange && static_cast<std::uint64_t>(id) < static_cast<std::uint64_t>(numPoints);
      b.Ids[k][b.Size + t] = id;
    }
  }
  if (!tailInRange || _mm256_movemask_pd(_mm256_castsi256_pd(inRange)) != 0xf)
  {
    return false;
  }
  b.Size += n;
  return true;
}
} // namespace avx2
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,avx512f"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,avx512f")
#endif
namespace avx512
{
/// Sixteen float lanes, eight double lanes. AVX-512F has fused multiply-add and
/// compilers may fuse a separate multiply and add into it, so the arithmetic uses the forms with
/// the rounding in the instruction (round to nearest, as everywhere), which are never fused.
struct Lanes
{
  static constexpr int Count = 16;
  static constexpr int DoubleCount = 8;
  static constexpr int Nearest = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
  using F = __m512;
  using M = __mmask16;
  using D = __m512d;

  static F Zero() { return _mm512_setzero_ps(); }
  static F Set(float x) { return _mm512_set1_ps(x); }
  static F Load(const float* x) { return _mm512_loadu_ps(x); }
  static F Add(F x, F y) { return _mm512_add_round_ps(x, y, Nearest); }
  static F Sub(F x, F y) { return _mm512_sub_round_ps(x, y, Nearest); }
  static F Mul(F x, F y) { return _mm512_mul_round_ps(x, y, Nearest); }
  static F Div(F x, F y) { return _mm512_div_round_ps(x, y, Nearest); }
  static F Sqrt(F x) { return _mm512_sqrt_round_ps(x, Nearest); }
  static F Max(F x, F y) { return _mm512_max_ps(x, y); }
  static F Bitwise(__m512i x) { return _mm512_castsi512_ps(x); }
  static F Abs(F x)
  {
    return Bitwise(_mm512_and_si512(_mm512_castps_si512(x), _mm512_set1_epi32(0x7fffffff)));
  }
  static F Negate(F x)
  {
    return Bitwise(_mm512_xor_si512(_mm512_castps_si512(x), _mm512_set1_epi32(INT_MIN)));
  }
  static F NegateWhere(M m, F x)
  {
    const __m512i bits = _mm512_castps_si512(x);
    return Bitwise(_mm512_mask_xor_epi32(bits, m, bits, _mm512_set1_epi32(INT_MIN)));
  }
  static M Gt(F x, F y) { return _mm512_cmp_ps_mask(x, y, _CMP_GT_OQ); }
  static M Ge(F x, F y) { return _mm512_cmp_ps_mask(x, y, _CMP_GE_OQ); }
  static M Le(F x, F y) { return _mm512_cmp_ps_mask(x, y, _CMP_LE_OQ); }
  static M Lt(F x, F y) { return _mm512_cmp_ps_mask(x, y, _CMP_LT_OQ); }
  static M Finite(F x) { return Le(Abs(x), _mm512_set1_ps(FLT_MAX)); }
  static M And(M x, M y) { return static_cast<M>(x & y); }
  /// m ? x : y
  static F Select(M m, F x, F y) { return _mm512_mask_blend_ps(m, y, x); }
  /// m ? x : 0
  static F Keep(M m, F x) { return _mm512_maskz_mov_ps(m, x); }
  static unsigned Bits(M m) { return m; }

  /// Whether 64-bit ids[0..n) (n a multiple of 8, ids >= 0) are all below `limit`.
  static bool Below(const std::int64_t* ids, int n, std::int64_t limit)
  {
    const __m512i l = _mm512_set1_epi64(limit);
    __m512i below = _mm512_set1_epi64(-1);
    for (int j = 0; j < n; j += 8)
    {
      below = _mm512_and_si512(below, _mm512_sub_epi64(_mm512_loadu_si512(ids + j), l));
    }
    return _mm512_cmplt_epi64_mask(below, _mm512_setzero_si512()) == 0xff;
  }

  /// The x, y and z of 16 points: point 4c + r goes to 128-bit lane c of row r, and a transpose
  /// within the lanes puts point l in lane l.
  template<bool Guarded>
  static void GatherXYZ(const float* xyz, const vtkIdType* ids, vtkIdType count, F out[3])
  {
    F r[4];
    for (int j = 0; j < 4; ++j)
    {
      r[j] = _mm512_castps128_ps512(avx2::Lanes::LoadPoint<Guarded>(xyz, ids[j], count));
      r[j] = _mm512_insertf32x4(r[j], avx2::Lanes::LoadPoint<Guarded>(xyz, ids[4 + j], count), 1);
      r[j] = _mm512_insertf32x4(r[j], avx2::Lanes::LoadPoint<Guarded>(xyz, ids[8 + j], count), 2);
      r[j] = _mm512_insertf32x4(r[j], avx2::Lanes::LoadPoint<Guarded>(xyz, ids[12 + j], count), 3);
    }
    const F low01 = _mm512_unpacklo_ps(r[0], r[1]), low23 = _mm512_unpacklo_ps(r[2], r[3]);
    const F high01 = _mm512_unpackhi_ps(r[0], r[1]), high23 = _mm512_unpackhi_ps(r[2], r[3]);
    out[0] = _mm512_shuffle_ps(low01, low23, _MM_SHUFFLE(1, 0, 1, 0));
    out[1] = _mm512_shuffle_ps(low01, low23, _MM_SHUFFLE(3, 2, 3, 2));
    out[2] = _mm512_shuffle_ps(high01, high23, _MM_SHUFFLE(1, 0, 1, 0));
  }
  /// u and v of 16 points of a two-component array: one 8-byte load per point, then the even and
  /// odd floats of the 32 picked out.
  static void GatherUV(const float* uv, const vtkIdType* ids, F& u, F& v)
  {
    const auto pair = [&](int l)
    {
      const __m128 low =
        _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(uv + 2 * ids[l]));
      return _mm_loadh_pi(low, reinterpret_cast<const __m64*>(uv + 2 * ids[l + 1]));
    };
    F halves[2];
    for (int half = 0; half < 2; ++half)
    {
      const int l = 8 * half;
      halves[half] = _mm512_castps128_ps512(pair(l));
      halves[half] = _mm512_insertf32x4(halves[half], pair(l + 2), 1);
      halves[half] = _mm512_insertf32x4(halves[half], pair(l + 4), 2);
      halves[half] = _mm512_insertf32x4(halves[half], pair(l + 6), 3);
    }
    const __m512i evens =
      _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odds = _mm512_add_epi32(evens, _mm512_set1_epi32(1));
    u = _mm512_permutex2var_ps(halves[0], evens, halves[1]);
    v = _mm512_permutex2var_ps(halves[0], odds, halves[1]);
  }
  static void Store(double* out, F x)
  {
    const __m512d bits = _mm512_castps_pd(x);
    _mm512_storeu_pd(out, _mm512_cvtps_pd(_mm512_castps512_ps256(x)));
    _mm512_storeu_pd(out + 8, _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(bits, 1))));
  }

  using DM = __mmask8;
  static D Set(double x) { return _mm512_set1_pd(x); }
  static D Sub(D x, D y) { return _mm512_sub_round_pd(x, y, Nearest); }
  static D Div(D x, D y) { return _mm512_div_round_pd(x, y, Nearest); }
  static D Sqrt(D x) { return _mm512_sqrt_round_pd(x, Nearest); }
  static D Max(D x, D y) { return _mm512_max_pd(x, y); }
  static D Abs(D x) { return _mm512_abs_pd(x); }
  static DM Gt(D x, D y) { return _mm512_cmp_pd_mask(x, y, _CMP_GT_OQ); }
  static DM Ge(D x, D y) { return _mm512_cmp_pd_mask(x, y, _CMP_GE_OQ); }
  static DM Le(D x, D y) { return _mm512_cmp_pd_mask(x, y, _CMP_LE_OQ); }
  static DM And(DM x, DM y) { return static_cast<DM>(x & y); }
  static unsigned Bits(DM m) { return m; }
  /// x, y and z of the eight PointSums s[0..8), and their Marks (as bits).
  static void GatherSums(const PointSum* s, D out[4])
  {
    __m256d low[4], high[4];
    avx2::Lanes::GatherSums(s, low);
    avx2::Lanes::GatherSums(s + 4, high);
    for (int d = 0; d < 4; ++d)
    {
      out[d] = _mm512_insertf64x4(_mm512_castpd256_pd512(low[d]), high[d], 1);
    }
  }
  /// The lanes whose bits have bit 0 set (`first`) and bit 1 set (`second`).
  static void LowBits(D bits, unsigned& first, unsigned& second)
  {
    const __m512i x = _mm512_castpd_si512(bits);
    first = _mm512_test_epi64_mask(x, _mm512_set1_epi64(1));
    second = _mm512_test_epi64_mask(x, _mm512_set1_epi64(2));
  }
  /// The eight xyz triples v[0..3) as floats, interleaved into out[0..24): two permutes pick
  /// them from (x | y) and z, and two stores write them.
  static void StoreXYZ(float* out, const D v[3])
  {
    const __m512d x = _mm512_castps_pd(_mm512_castps256_ps512(_mm512_cvtpd_ps(v[0])));
    const __m512 xy =
      _mm512_castpd_ps(_mm512_insertf64x4(x, _mm256_castps_pd(_mm512_cvtpd_ps(v[1])), 1));
    const __m512 z = _mm512_castps256_ps512(_mm512_cvtpd_ps(v[2]));
    // Output float i is component i % 3 of point i / 3: x at index p, y at 8 + p, z at 16 + p.
    const __m512i first = _mm512_setr_epi32(0, 8, 16, 1, 9, 17, 2, 10, 18, 3, 11, 19, 4, 12, 20, 5);
    const __m512i second = _mm512_setr_epi32(13, 21, 6, 14, 22, 7, 15, 23, 0, 0, 0, 0, 0, 0, 0, 0);
    _mm512_storeu_ps(out, _mm512_permutex2var_ps(xy, first, z));
    _mm256_storeu_ps(out + 16, _mm512_castps512_ps256(_mm512_permutex2var_ps(xy, second, z)));
  }
  /// out[l] = -1 where bit l of minus is set, else 1, for l < 8.
  static void StoreSigns(float* out, unsigned minus)
  {
    const __m512 signs = _mm512_mask_blend_ps(
      static_cast<__mmask16>(minus), _mm512_set1_ps(1.0f), _mm512_set1_ps(-1.0f));
    _mm256_storeu_ps(out, _mm512_castps512_ps256(signs));
  }
  static void StoreSigns(double* out, unsigned minus)
  {
    _mm512_storeu_pd(out,
      _mm512_mask_blend_pd(
        static_cast<__mmask8>(minus), _mm512_set1_pd(1.0), _mm512_set1_pd(-1.0)));
  }
  /// The eight xyz triples in double, interleaved into out[0..24): avx2::Lanes::StoreXYZ per half.
  static void StoreXYZ(double* out, const D v[3])
  {
    __m256d low[3], high[3];
    for (int d = 0; d < 3; ++d)
    {
      low[d] = _mm512_castpd512_pd256(v[d]);
      high[d] = _mm512_extractf64x4_pd(v[d], 1);
    }
    avx2::Lanes::StoreXYZ(out, low);
    avx2::Lanes::StoreXYZ(out + 12, high);
  }
  /// The lanes l < 8 where bit l of `bits` is set.
  static DM MaskFromBits(unsigned bits) { return static_cast<DM>(bits); }
  static void Widen(F x, D& low, D& high)
  {
    low = _mm512_cvtps_pd(_mm512_castps512_ps256(x));
    high = _mm512_cvtps_pd(_mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(x), 1)));
  }
  static D Load(const double* x) { return _mm512_loadu_pd(x); }
  static void Store(double* out, D x) { _mm512_storeu_pd(out, x); }
  static D Add(D x, D y) { return _mm512_add_round_pd(x, y, Nearest); }
  static D Mul(D x, D y) { return _mm512_mul_round_pd(x, y, Nearest); }
  static DM Lt(D x, D y) { return _mm512_cmp_pd_mask(x, y, _CMP_LT_OQ); }
  static DM Finite(D x) { return Le(Abs(x), _mm512_set1_pd(DBL_MAX)); }
  /// m ? x : y
  static D Select(DM m, D x, D y) { return _mm512_mask_blend_pd(m, y, x); }
  /// m ? x : 0
  static D Keep(DM m, D x) { return _mm512_maskz_mov_pd(m, x); }
  static D Negate(D x) { return NegateWhere(0xff, x); }
  static D NegateWhere(DM m, D x)
  {
    const __m512i bits = _mm512_castpd_si512(x);
    return _mm512_castsi512_pd(_mm512_mask_xor_epi64(bits, m, bits, _mm512_set1_epi64(INT64_MIN)));
  }
  /// Component d of the points ids[0..8) of an array of any type with `stride` components each,
  /// in double.
  template<typename T>
  static D GatherDouble(const T* x, int stride, const vtkIdType* ids, int d)
  {
    const auto at = [&](int l) { return static_cast<double>(x[stride * ids[l] + d]); };
    return _mm512_setr_pd(at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7));
  }
  static unsigned NegativeBits(D x)
  {
    return _mm512_cmp_pd_mask(x, _mm512_setzero_pd(), _CMP_LT_OQ);
  }
  static unsigned NonZeroFiniteBits(D x)
  {
    const D a = _mm512_abs_pd(x);
    return _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ) &
      _mm512_cmp_pd_mask(a, _mm512_set1_pd(DBL_MAX), _CMP_LE_OQ);
  }
  /// The x, y and z of 8 points of a float or double xyz array of `count` points, in double.
  template<bool Guarded>
  static void GatherXYZDouble(const float* n, const vtkIdType* ids, vtkIdType count, D out[3])
  {
    __m256 f[3];
    avx2::Lanes::GatherXYZ<Guarded>(n, ids, count, f);
    for (int d = 0; d < 3; ++d)
    {
      out[d] = _mm512_cvtps_pd(f[d]);
    }
  }
  /// Double: avx2::Lanes::GatherRowsDouble for each half.
  template<bool Guarded>
  static void GatherXYZDouble(const double* xyz, const vtkIdType* ids, vtkIdType count, D out[3])
  {
    __m256d low[3], high[3];
    avx2::Lanes::GatherRowsDouble<Guarded>(xyz, ids, count, low);
    avx2::Lanes::GatherRowsDouble<Guarded>(xyz, ids + 4, count, high);
    for (int d = 0; d < 3; ++d)
    {
      out[d] = _mm512_insertf64x4(_mm512_castpd256_pd512(low[d]), high[d], 1);
    }
  }
  /// u and v of 8 points of a two-component double array: one 16-byte load per point.
  static void GatherUVDouble(const double* uv, const vtkIdType* ids, D& u, D& v)
  {
    // Points 2j and 2j + 1 to 128-bit lane j of `even` and `odd` (AVX-512F inserts, as floats).
    const auto pair = [&](int l) { return _mm_castpd_ps(_mm_loadu_pd(uv + 2 * ids[l])); };
    __m512 even = _mm512_castps128_ps512(pair(0)), odd = _mm512_castps128_ps512(pair(1));
    even = _mm512_insertf32x4(even, pair(2), 1);
    odd = _mm512_insertf32x4(odd, pair(3), 1);
    even = _mm512_insertf32x4(even, pair(4), 2);
    odd = _mm512_insertf32x4(odd, pair(5), 2);
    even = _mm512_insertf32x4(even, pair(6), 3);
    odd = _mm512_insertf32x4(odd, pair(7), 3);
    u = _mm512_unpacklo_pd(_mm512_castps_pd(even), _mm512_castps_pd(odd));
    v = _mm512_unpackhi_pd(_mm512_castps_pd(even), _mm512_castps_pd(odd));
  }
  /// The normals of points [p, p + 8) (all in the array), in double: two loads of exactly their
  /// 24 floats and a permute per component.
  static void LoadNormalRun(const float* normals, vtkIdType p, vtkIdType, D out[3])
  {
    const float* n = normals + 3 * p;
    const __m512 low = _mm512_loadu_ps(n);
    const __m512 high = _mm512_castps256_ps512(_mm256_loadu_ps(n + 16));
    for (int d = 0; d < 3; ++d)
    {
      // Component d of point l is float 3 l + d: indices 16 and up pick from `high`.
      const __m512i index = _mm512_setr_epi32(
        d, 3 + d, 6 + d, 9 + d, 12 + d, 15 + d, 18 + d, 21 + d, 0, 0, 0, 0, 0, 0, 0, 0);
      out[d] = _mm512_cvtps_pd(_mm512_castps512_ps256(_mm512_permutex2var_ps(low, index, high)));
    }
  }
  /// Lanes k, k + 3, ..., k + 21 (k < 3) of the 24 64-bit lanes of x[0..3): component k of
  /// eight interleaved triples. Two permutes: first from x[0] and x[1] (lanes 0-15), then the
  /// rest from x[2].
  static __m512i Thirds(const __m512i x[3], int k)
  {
    alignas(64) static constexpr std::int64_t fromFirstTwo[3][8] = {
      { 0, 3, 6, 9, 12, 15, 0, 0 }, { 1, 4, 7, 10, 13, 0, 0, 0 }, { 2, 5, 8, 11, 14, 0, 0, 0 }
    };
    alignas(64) static constexpr std::int64_t fromThird[3][8] = {
      { 0, 1, 2, 3, 4, 5, 10, 13 }, { 0, 1, 2, 3, 4, 8, 11, 14 }, { 0, 1, 2, 3, 4, 9, 12, 15 }
    };
    const __m512i firstTwo =
      _mm512_permutex2var_epi64(x[0], _mm512_load_si512(fromFirstTwo[k]), x[1]);
    return _mm512_permutex2var_epi64(firstTwo, _mm512_load_si512(fromThird[k]), x[2]);
  }
  /// The same for double normals: three loads, Thirds per component.
  static void LoadNormalRun(const double* normals, vtkIdType p, vtkIdType, D out[3])
  {
    const double* n = normals + 3 * p;
    const __m512i x[3] = { _mm512_castpd_si512(_mm512_loadu_pd(n)),
      _mm512_castpd_si512(_mm512_loadu_pd(n + 8)),
      _mm512_castpd_si512(_mm512_loadu_pd(n + 16)) };
    for (int d = 0; d < 3; ++d)
    {
      out[d] = _mm512_castsi512_pd(Thirds(x, d));
    }
  }
};
#include "vtkTangentFrameLanes.h"

/**
 * Appends the n triangles of `ids` (three 64-bit ids each) to the batch, which has room, if every
 * id is in [0, numPoints); else appends nothing and returns false. Eight triangles a step: three
 * 512-bit loads, a range test and Lanes::Thirds per corner put the interleaved ids into b.Ids.
 */
inline bool TakeTriangles(const std::int64_t* ids, int n, std::int64_t numPoints, FrameBatch& b)
{
  const __m512i limit = _mm512_set1_epi64(numPoints);
  __mmask8 inRange = 0xff;
  int t = 0;
  for (; t + 8 <= n; t += 8)
  {
    const std::int64_t* from = ids + 3 * t;
    const __m512i x[3] = {
      _mm512_loadu_si512(from), _mm512_loadu_si512(from + 8), _mm512_loadu_si512(from + 16)
    };
    // Unsigned: a negative id is huge.
    inRange &= _mm512_cmplt_epu64_mask(x[0], limit) & _mm512_cmplt_epu64_mask(x[1], limit) &
      _mm512_cmplt_epu64_mask(x[2], limit);
    for (int k = 0; k < 3; ++k)
    {
      _mm512_storeu_si512(b.Ids[k] + b.Size + t, Lanes::Thirds(x, k)); // corner k
    }
  }
  for (; t < n; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t id = ids[3 * t + k];
      inRange &= static_cast<std::uint64_t>(id) < static_cast<std::uint64_t>(numPoints) ? 0xff : 0;
      b.Ids[k][b.Size + t] = id;
    }
  }
  if (inRange != 0xff)
  {
    return false;
  }
  b.Size += n;
  return true;
}

/**
 * Bit b set for each block b, of `blocks` (a power of two), that owns one of the `count` 64-bit
 * ids: ScalarOwnerBits, eight ids per step (the rest through ScalarOwnerBits).
 */
inline std::uint64_t OwnerBits(const std::int64_t* ids, int count, int blocks, int ownerShift)
{
  const __m512i mask = _mm512_set1_epi64(blocks - 1);
  const __m512i one = _mm512_set1_epi64(1);
  const __m128i shift = _mm_cvtsi32_si128(ownerShift);
  __m512i bits = _mm512_setzero_si512();
  int j = 0;
  for (; j + 8 <= count; j += 8)
  {
    const __m512i owner =
      _mm512_and_si512(_mm512_srl_epi64(_mm512_loadu_si512(ids + j), shift), mask);
    bits = _mm512_or_si512(bits, _mm512_sllv_epi64(one, owner));
  }
  return static_cast<std::uint64_t>(_mm512_reduce_or_epi64(bits)) |
    ScalarOwnerBits(ids + j, count - j, blocks, ownerShift);
}
} // namespace avx512
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif

/// The code ComputeBatch runs: the scalar kernels, or the lane kernels with AVX2 (8 float or 4
/// double lanes) or AVX-512 (16 float or 8 double lanes). Every one gives the same bits.
enum class BatchCode
{
  Scalar = 0,
  AVX2 = 1,
  AVX512 = 2,
};

/// Frames, weights and sides of every triangle in the batch, with `code` (the caller checked that
/// the CPU has it). Float positions and texture coordinates take the single-precision path,
/// anything else the double-precision kernel (ComputeDoubleLanes).
template<typename PT, typename UT, typename NT>
void ComputeBatch(const BatchInput<PT, UT, NT>& in, FrameBatch& b, BatchCode code)
{
  int i = 0;
  constexpr bool useFloat = std::is_same<PT, float>::value && std::is_same<UT, float>::value;
  // Triangles [0, sided) have their sides already (the float lanes with float normals).
  int sided = 0;
#ifdef VTK_TANGENT_BATCH_AVX2
  if constexpr (useFloat)
  {
    for (; code == BatchCode::AVX512 && i + 16 <= b.Size; i += 16)
    {
      avx512::ComputeLanes(in, b, i);
    }
    for (; code >= BatchCode::AVX2 && i + 8 <= b.Size; i += 8)
    {
      avx2::ComputeLanes(in, b, i);
    }
    sided = std::is_same<NT, float>::value ? i : 0;
  }
#endif
  // The triangles the lane kernels did not prefetch for: the rest of the float path, every
  // triangle of the double path.
  for (int k = 0; in.PrefetchSums && k < 3; ++k)
  {
    for (int j = i; j < b.Size; ++j)
    {
      PrefetchForWriting(in.PrefetchSums + b.Ids[k][j]);
    }
  }
#ifdef VTK_TANGENT_BATCH_AVX2
  if constexpr (!useFloat)
  {
    for (; code == BatchCode::AVX512 && i + 8 <= b.Size; i += 8)
    {
      avx512::ComputeDoubleLanes(in, b, i);
    }
    for (; code >= BatchCode::AVX2 && i + 4 <= b.Size; i += 4)
    {
      avx2::ComputeDoubleLanes(in, b, i);
    }
  }
#endif
  for (; i < b.Size; ++i)
  {
    if constexpr (useFloat)
    {
      single::ComputeTriangle(in, b, i);
    }
    else
    {
      ComputeBatchTriangle(in, b, i);
    }
  }
  i = sided;
#ifdef VTK_TANGENT_BATCH_AVX2
  for (; code == BatchCode::AVX512 && i + 8 <= b.Size; i += 8)
  {
    avx512::SidesLanes(in, b, i);
  }
  for (; code >= BatchCode::AVX2 && i + 4 <= b.Size; i += 4)
  {
    avx2::SidesLanes(in, b, i);
  }
#else
  (void)code;
#endif
  for (; i < b.Size; ++i)
  {
    const int orientation = b.Orientation(i);
    for (int k = 0; k < 3; ++k)
    {
      const int side =
        in.Side(b.Normal[0][i], b.Normal[1][i], b.Normal[2][i], orientation, b.Ids[k][i]);
      b.SetSides(k, i, 1, side < 0 ? 1u : 0u);
    }
  }
}

/// Adds the batch to `s` (see ScatterTarget); `vector`: use AVX2. Sums must be 32-byte aligned.
inline void ScatterBatch(const FrameBatch& b, const ScatterTarget& s, bool vector)
{
#ifdef VTK_TANGENT_BATCH_AVX2
  if (vector)
  {
    avx2::ScatterBatch(b, s);
    return;
  }
#else
  (void)vector;
#endif
  ScatterBatchScalar(b, s);
}

/// The best code this build and CPU have for ComputeBatch and the finish (FinishLanes); the
/// scatter uses AVX2 whenever it is at least that.
inline BatchCode BestBatchCode()
{
#ifdef VTK_TANGENT_BATCH_AVX2
  if (__builtin_cpu_supports("avx2") == 0)
  {
    return BatchCode::Scalar;
  }
  return __builtin_cpu_supports("avx512f") != 0 ? BatchCode::AVX512 : BatchCode::AVX2;
#else
  return BatchCode::Scalar;
#endif
}

} // namespace detail
} // namespace vtkNormalMapping

#endif
