// SPDX-License-Identifier: BSD-3-Clause
// MikkTSpace-compatible tangent kernel. Written from the behaviour description in
// shared/docs/MIKKTSPACE.md; see vtkMikkTSpaceKernel.h for the contract.
//
// Pipeline (every phase except welding and GWA orientation adoption is parallel):
//  1. Weld points: 32-bit hash of the 8 float bit patterns (-0 normalised to +0), radix sort,
//     exact comparison within equal hashes; the welded id of a point is the smallest point id
//     with equal values. Points with a NaN never weld: each face corner using one gets its
//     own id.
//  2. Faces -> triangles (quad diagonal rule, fans), degeneracy, per-triangle frame
//     (det, Os, Ot, orientation, group-with-any), quad orientation forcing. Runs of 8 triangle
//     faces are set up 8 lanes at a time with AVX2.
//  3. Counting sort of the corners of non-degenerate triangles by welded id ("fans").
//  4. (only if group-with-any triangles exist) sequential replay of the reference's group
//     flood at vertices that touch such triangles, which fixes their adopted orientation.
//  5. Per welded vertex: edge pairing (the reference's rule, restricted to the edges around
//     the vertex), groups = same-orientation edge-connected components, projected directions
//     and corner angles (8 corners at a time with AVX2, 4 with SSE; the acos 8 at a time with
//     AVX-512), angle-weighted accumulation in ascending triangle order, subgroup test, write
//     corner frames. A fan that is one group passing the quick subgroup test (the common
//     case) takes a short path.
//  6. Per face: corners written by several triangles (quad diagonals, fan corners) are
//     merged with the reference's pairwise average in group creation order; degenerate
//     triangles copy; unreached or non-finite corners get the default frame (skipped when
//     no corner can be in that state).
//
// Triangle order here is the input order; the reference's "good triangle" order is that order
// with degenerate triangles removed, so every order-dependent rule (group seeds, accumulation
// order, non-manifold edge pairing, first good corner for degenerate copies) is unchanged.

#include "vtkMikkTSpaceKernel.h"

#include "vtkNormalMappingHugePages.h"
#include "vtkNormalMappingPrivate.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <utility>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define VTK_MIKK_SSE2 1
#endif

// GCC/clang on x86-64: an AVX2 version of the per-member math (8 lanes), chosen at run time.
// It uses the same IEEE operations lane by lane (no FMA: target "avx2" does not enable it).
#if defined(VTK_MIKK_SSE2) && defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define VTK_MIKK_AVX2 1
#define VTK_MIKK_AVX2_FN __attribute__((target("avx2")))
// AVX-512 only for the double-precision acos (8 lanes instead of 4), also chosen at run time.
#define VTK_MIKK_AVX512_FN __attribute__((target("avx2,avx512f")))
#endif

// The reference evaluates every float expression with separate roundings. Fused multiply-add
// changes results by up to ~2e-7; clang contracts by default when FMA is available.
#if defined(__clang__)
#pragma clang fp contract(off)
#endif

namespace vtkNormalMapping
{
namespace mikk
{
namespace
{
using Idx = int32_t;

constexpr float kFltMin = 1.17549435e-38f; // FLT_MIN, the reference's NotZero threshold

// Triangle flags
constexpr uint8_t kDegenerate = 1;
constexpr uint8_t kDead = 2; // face skipped (bad ids)
constexpr uint8_t kGWA = 4;  // group with any: no direction contribution, never seeds
constexpr uint8_t kOrient = 8;
constexpr uint8_t kOneDegenQuad = 16;
constexpr uint8_t kMulti0 = 32; // corner i's face corner is written by several triangles
constexpr uint8_t kExcluded = kDegenerate | kDead;

//------------------------------------------------------------------------------
// Float vector helpers, evaluated exactly as the reference (left-to-right sums, no FMA).
struct V3
{
  float x, y, z;
};
inline V3 Sub(const V3& a, const V3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline V3 Add(const V3& a, const V3& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
inline V3 Scale(const V3& v, float s)
{
  return { v.x * s, v.y * s, v.z * s };
}
inline float Dot(const V3& a, const V3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline bool NotZero(float f)
{
  return std::fabs(f) > kFltMin;
}
inline bool VNotZero(const V3& v)
{
  return NotZero(v.x) || NotZero(v.y) || NotZero(v.z);
}
inline V3 Normalize(const V3& v)
{
  return Scale(v, 1.0f / std::sqrt(Dot(v, v)));
}
inline bool Veq(const V3& a, const V3& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
// v - n (n.v), normalised if not (numerically) zero
inline V3 ProjectNormalize(const V3& v, const V3& n)
{
  V3 r = Sub(v, Scale(n, Dot(n, v)));
  if (VNotZero(r))
  {
    r = Normalize(r);
  }
  return r;
}
inline bool Finite(float f)
{
  return std::isfinite(f);
}

//------------------------------------------------------------------------------
// Uninitialised array for large temporaries. On Linux, large blocks are mapped 2 MB-aligned
// with MADV_HUGEPAGE: first-touch page faults are a large part of the run time otherwise
// (~100 MB of temporaries per million triangles, 4 KB pages).
constexpr size_t kHugePage = vtkNormalMapping::detail::HugePageBytes;
using vtkNormalMapping::detail::AdviseHugePages;
using vtkNormalMapping::detail::ParallelFor;

// Bump allocator for the smaller temporaries of one call: 4 MB chunks mapped 2 MB-aligned with
// MADV_HUGEPAGE, so that a small mesh's temporaries fault in as a few huge pages instead of
// hundreds of 4 KB pages (page faults were ~15 % of the run time on 65K triangles).
class Arena
{
public:
  Arena() = default;
  Arena(const Arena&) = delete;
  Arena& operator=(const Arena&) = delete;
  ~Arena()
  {
    for (const auto& c : this->Chunks)
    {
#if defined(__linux__)
      munmap(c.first, c.second);
#else
      std::free(c.first);
#endif
    }
  }
  void* Take(size_t bytes)
  {
    bytes = (bytes + 63) & ~size_t(63);
    if (bytes > this->Left)
    {
      this->NewChunk(std::max(kChunk, bytes));
    }
    void* p = this->Cur;
    this->Cur += bytes;
    this->Left -= bytes;
    return p;
  }

private:
  static constexpr size_t kChunk = size_t(4) << 20;
  void NewChunk(size_t bytes)
  {
#if defined(__linux__)
    bytes = (bytes + kHugePage - 1) & ~(kHugePage - 1);
    const size_t mapBytes = bytes + kHugePage;
    void* map = mmap(nullptr, mapBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (map == MAP_FAILED)
    {
      throw std::bad_alloc();
    }
    this->Chunks.emplace_back(map, mapBytes);
    const uintptr_t aligned = (reinterpret_cast<uintptr_t>(map) + kHugePage - 1) & ~(kHugePage - 1);
    madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
    this->Cur = reinterpret_cast<char*>(aligned);
#else
    void* p = std::malloc(bytes + 64);
    if (!p)
    {
      throw std::bad_alloc();
    }
    this->Chunks.emplace_back(p, bytes + 64);
    this->Cur = reinterpret_cast<char*>((reinterpret_cast<uintptr_t>(p) + 63) & ~uintptr_t(63));
#endif
    this->Left = bytes;
  }
  std::vector<std::pair<void*, size_t>> Chunks;
  char* Cur = nullptr;
  size_t Left = 0;
};

template<typename T>
class Buffer
{
public:
  Buffer() = default;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() { this->Release(); }

  // Blocks below 4 MB come from the arena if one is given (freed with it).
  void Allocate(size_t n, Arena* arena = nullptr)
  {
    this->Release();
    const size_t bytes = std::max<size_t>(1, n * sizeof(T));
    if (arena && bytes < 2 * kHugePage)
    {
      this->Ptr = static_cast<T*>(arena->Take(bytes));
      this->FromArena = true;
      this->N = n;
      return;
    }
#if defined(__linux__)
    if (bytes >= 2 * kHugePage)
    {
      const size_t mapBytes = bytes + kHugePage;
      void* map =
        mmap(nullptr, mapBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (map != MAP_FAILED)
      {
        const uintptr_t aligned =
          (reinterpret_cast<uintptr_t>(map) + kHugePage - 1) & ~(kHugePage - 1);
        madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
        this->Map = map;
        this->MapBytes = mapBytes;
        this->Ptr = reinterpret_cast<T*>(aligned);
        this->N = n;
        return;
      }
    }
#endif
    this->Ptr = static_cast<T*>(std::malloc(bytes));
    if (!this->Ptr)
    {
      throw std::bad_alloc();
    }
    this->N = n;
  }
  void Assign(size_t n, const T& value, Arena* arena = nullptr)
  {
    this->Allocate(n, arena);
    std::fill(this->Ptr, this->Ptr + n, value);
  }
  void Release()
  {
    if (this->FromArena)
    {
      this->Ptr = nullptr;
      this->N = 0;
      this->FromArena = false;
      return;
    }
#if defined(__linux__)
    if (this->Map)
    {
      munmap(this->Map, this->MapBytes);
      this->Map = nullptr;
      this->Ptr = nullptr;
    }
#endif
    std::free(this->Ptr);
    this->Ptr = nullptr;
    this->N = 0;
  }
  void Swap(Buffer& o)
  {
    std::swap(this->Ptr, o.Ptr);
    std::swap(this->N, o.N);
    std::swap(this->Map, o.Map);
    std::swap(this->MapBytes, o.MapBytes);
    std::swap(this->FromArena, o.FromArena);
  }
  T* data()
  {
    return this->Ptr;
  }
  const T* data() const
  {
    return this->Ptr;
  }
  size_t size() const
  {
    return this->N;
  }
  bool empty() const
  {
    return this->N == 0;
  }
  T& operator[](size_t i)
  {
    return this->Ptr[i];
  }
  const T& operator[](size_t i) const
  {
    return this->Ptr[i];
  }
  T* begin()
  {
    return this->Ptr;
  }
  T* end()
  {
    return this->Ptr + this->N;
  }

private:
  T* Ptr = nullptr;
  size_t N = 0;
  void* Map = nullptr;
  size_t MapBytes = 0;
  bool FromArena = false;
};

//------------------------------------------------------------------------------
// acos(double(x)) rounded to float, bit-identical to (float)std::acos((double)x) for every
// float x, about 3x faster than libm on random input.
// acos is evaluated in double from asin(s) = s + s*z*P(z), z = s*s (|x| <= 1/2) or
// z = (1-|x|)/2, s = sqrt(z) (|x| > 1/2), P a degree-8 Chebyshev fit of
// (asin(sqrt z)/sqrt z - 1)/z on [0, 1/4] (fit error 9.2e-13, computed for this file with
// mpmath). Measured against libm over all 2.1e9 floats in [-1, 1]: at most 1676 double ulps
// apart. A float rounding can only differ when the double result lies within that distance of
// a midpoint between two floats; those inputs (13,899 of 2.1e9, found by the 2^13-ulp window
// below, 5x the measured error) are recomputed with libm. Exhaustive check: 0 mismatches.
inline double Select(bool c, double a, double b)
{
  uint64_t ua, ub;
  std::memcpy(&ua, &a, 8);
  std::memcpy(&ub, &b, 8);
  const uint64_t m = uint64_t(0) - uint64_t(c);
  const uint64_t r = (ua & m) | (ub & ~m);
  double d;
  std::memcpy(&d, &r, 8);
  return d;
}
inline double SqrtNonNegative(double v)
{
#ifdef VTK_MIKK_SSE2
  return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_setzero_pd(), _mm_set_sd(v)));
#else
  return std::sqrt(v);
#endif
}
inline float AngleFromCos(float xf)
{
  const double x = xf;
  const double a = std::fabs(x);
  if (!(a <= 1.0)) // NaN (the caller clamps finite values)
  {
    return static_cast<float>(std::acos(x));
  }
  const bool small = a <= 0.5;
  const double zBig = (1.0 - a) * 0.5; // exact
  const double z = Select(small, x * x, zBig);
  const double s = Select(small, a, SqrtNonNegative(zBig));
  const double c8 = 0.02834674523183333, c7 = 0.001067506315036312, c6 = 0.01686409027396012,
               c5 = 0.016902683886393575, c4 = 0.022412417726695433, c3 = 0.030379945210024933,
               c2 = 0.044642906474584965, c1 = 0.07499999953429712, c0 = 0.16666666666738633;
  const double z2 = z * z, z4 = z2 * z2;
  const double p =
    ((c0 + c1 * z) + (c2 + c3 * z) * z2) + (((c4 + c5 * z) + (c6 + c7 * z) * z2) + c8 * z4) * z4;
  const double as = s + s * z * p; // asin(s)
  const double pio2Hi = 1.5707963267948966, pio2Lo = 6.123233995736766e-17;
  const double sgn = std::copysign(1.0, x);
  // |x| <= 1/2: pi/2 - sgn*asin(|x|); x > 1/2: 2 asin(s); x < -1/2: pi - 2 asin(s)
  const double cHi = Select(small, pio2Hi, (1.0 - sgn) * pio2Hi);
  const double cLo = Select(small, pio2Lo, (1.0 - sgn) * pio2Lo);
  const double k = Select(small, -sgn, 2.0 * sgn);
  const double r = cHi + (k * as + cLo);
  uint64_t bits;
  std::memcpy(&bits, &r, 8);
  const uint64_t low = bits & ((uint64_t(1) << 29) - 1); // the 29 bits dropped by rounding
  const uint64_t mid = uint64_t(1) << 28;
  const uint64_t dist = low > mid ? low - mid : mid - low;
  if (dist < (uint64_t(1) << 13))
  {
    return static_cast<float>(std::acos(x));
  }
  return static_cast<float>(r);
}

//------------------------------------------------------------------------------
// Four lanes at a time (SSE): the same IEEE operations as the scalar helpers above, lane by
// lane (sqrt and division are correctly rounded in both), so the results are bit-identical.
#ifdef VTK_MIKK_SSE2
struct V3x4
{
  __m128 x, y, z;
};

inline __m128 Dot4(const V3x4& a, const V3x4& b)
{
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a.x, b.x), _mm_mul_ps(a.y, b.y)), _mm_mul_ps(a.z, b.z));
}

// v - n (n.v), normalised where any component exceeds FLT_MIN in magnitude
inline V3x4 ProjectNormalize4(const V3x4& v, const V3x4& n)
{
  const __m128 d = Dot4(n, v);
  V3x4 r{ _mm_sub_ps(v.x, _mm_mul_ps(n.x, d)),
    _mm_sub_ps(v.y, _mm_mul_ps(n.y, d)),
    _mm_sub_ps(v.z, _mm_mul_ps(n.z, d)) };
  const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 fmin = _mm_set1_ps(kFltMin);
  const __m128 nonZero = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(_mm_and_ps(r.x, absMask), fmin),
                                     _mm_cmpgt_ps(_mm_and_ps(r.y, absMask), fmin)),
    _mm_cmpgt_ps(_mm_and_ps(r.z, absMask), fmin));
  const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(Dot4(r, r)));
  const auto blend = [&](__m128 plain, __m128 scaled)
  { return _mm_or_ps(_mm_and_ps(nonZero, scaled), _mm_andnot_ps(nonZero, plain)); };
  r.x = blend(r.x, _mm_mul_ps(r.x, inv));
  r.y = blend(r.y, _mm_mul_ps(r.y, inv));
  r.z = blend(r.z, _mm_mul_ps(r.z, inv));
  return r;
}

inline __m128d SelectPD(__m128d mask, __m128d a, __m128d b)
{
  return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b));
}

// AngleFromCos for two lanes (inputs already clamped; NaN lanes may give any NaN).
inline __m128 AngleFromCos2(__m128d x, float* out2)
{
  const __m128d signMask = _mm_set1_pd(-0.0);
  const __m128d one = _mm_set1_pd(1.0);
  const __m128d a = _mm_andnot_pd(signMask, x);
  const __m128d small = _mm_cmple_pd(a, _mm_set1_pd(0.5));
  const __m128d zBig = _mm_mul_pd(_mm_sub_pd(one, a), _mm_set1_pd(0.5));
  const __m128d z = SelectPD(small, _mm_mul_pd(x, x), zBig);
  const __m128d s = SelectPD(small, a, _mm_sqrt_pd(zBig));
  const auto c = [](double v) { return _mm_set1_pd(v); };
  const __m128d z2 = _mm_mul_pd(z, z), z4 = _mm_mul_pd(z2, z2);
  const __m128d p01 = _mm_add_pd(c(0.16666666666738633), _mm_mul_pd(c(0.07499999953429712), z));
  const __m128d p23 = _mm_add_pd(c(0.044642906474584965), _mm_mul_pd(c(0.030379945210024933), z));
  const __m128d p45 = _mm_add_pd(c(0.022412417726695433), _mm_mul_pd(c(0.016902683886393575), z));
  const __m128d p67 = _mm_add_pd(c(0.01686409027396012), _mm_mul_pd(c(0.001067506315036312), z));
  const __m128d p = _mm_add_pd(_mm_add_pd(p01, _mm_mul_pd(p23, z2)),
    _mm_mul_pd(
      _mm_add_pd(_mm_add_pd(p45, _mm_mul_pd(p67, z2)), _mm_mul_pd(c(0.02834674523183333), z4)),
      z4));
  const __m128d as = _mm_add_pd(s, _mm_mul_pd(_mm_mul_pd(s, z), p));
  const __m128d sgn = _mm_or_pd(_mm_and_pd(signMask, x), one);
  const __m128d oneMinusSgn = _mm_sub_pd(one, sgn);
  const __m128d cHi =
    SelectPD(small, c(1.5707963267948966), _mm_mul_pd(oneMinusSgn, c(1.5707963267948966)));
  const __m128d cLo =
    SelectPD(small, c(6.123233995736766e-17), _mm_mul_pd(oneMinusSgn, c(6.123233995736766e-17)));
  const __m128d k = SelectPD(small, _mm_xor_pd(sgn, signMask), _mm_mul_pd(c(2.0), sgn));
  const __m128d r = _mm_add_pd(cHi, _mm_add_pd(_mm_mul_pd(k, as), cLo));
  const __m128 f = _mm_cvtpd_ps(r);
  _mm_storel_pi(reinterpret_cast<__m64*>(out2), f);
  // lanes whose 29 dropped bits lie within 2^13 of the rounding midpoint 2^28 (low dwords)
  const __m128i low =
    _mm_and_si128(_mm_castpd_si128(r), _mm_set_epi32(0, 0x1fffffff, 0, 0x1fffffff));
  const __m128i rel = _mm_sub_epi32(low, _mm_set1_epi32((1 << 28) - (1 << 13) + 1));
  const __m128i near = _mm_and_si128(
    _mm_cmpgt_epi32(rel, _mm_set1_epi32(-1)), _mm_cmplt_epi32(rel, _mm_set1_epi32((1 << 14) - 1)));
  const int nearMask = _mm_movemask_ps(_mm_castsi128_ps(near)) & 5;
  if (nearMask)
  {
    double xx[2];
    _mm_storeu_pd(xx, x);
    for (int l = 0; l < 2; ++l)
    {
      if (nearMask & (1 << (2 * l)))
      {
        out2[l] = static_cast<float>(std::acos(xx[l]));
      }
    }
  }
  return f;
}
#endif

//------------------------------------------------------------------------------
// Eight lanes at a time (AVX2), the operations of the SSE versions above in the same order.
#ifdef VTK_MIKK_AVX2
struct V3x8
{
  __m256 x, y, z;
};

VTK_MIKK_AVX2_FN inline __m256 Dot8(const V3x8& a, const V3x8& b)
{
  return _mm256_add_ps(
    _mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)), _mm256_mul_ps(a.z, b.z));
}

// mask ? yes : no per lane, for masks from comparisons (all bits set or clear)
VTK_MIKK_AVX2_FN inline __m256 Blend8(__m256 mask, __m256 yes, __m256 no)
{
  return _mm256_blendv_ps(no, yes, mask);
}

// NotZero and Veq, lane by lane (false for NaN)
VTK_MIKK_AVX2_FN inline __m256 NotZero8(__m256 x)
{
  const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  return _mm256_cmp_ps(_mm256_and_ps(x, absMask), _mm256_set1_ps(kFltMin), _CMP_GT_OQ);
}
VTK_MIKK_AVX2_FN inline __m256 Equal8(const V3x8& a, const V3x8& b)
{
  return _mm256_and_ps(
    _mm256_and_ps(_mm256_cmp_ps(a.x, b.x, _CMP_EQ_OQ), _mm256_cmp_ps(a.y, b.y, _CMP_EQ_OQ)),
    _mm256_cmp_ps(a.z, b.z, _CMP_EQ_OQ));
}

VTK_MIKK_AVX2_FN inline V3x8 ProjectNormalize8(const V3x8& v, const V3x8& n)
{
  const __m256 d = Dot8(n, v);
  V3x8 r{ _mm256_sub_ps(v.x, _mm256_mul_ps(n.x, d)),
    _mm256_sub_ps(v.y, _mm256_mul_ps(n.y, d)),
    _mm256_sub_ps(v.z, _mm256_mul_ps(n.z, d)) };
  const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256 fmin = _mm256_set1_ps(kFltMin);
  const __m256 nonZero =
    _mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(_mm256_and_ps(r.x, absMask), fmin, _CMP_GT_OQ),
                   _mm256_cmp_ps(_mm256_and_ps(r.y, absMask), fmin, _CMP_GT_OQ)),
      _mm256_cmp_ps(_mm256_and_ps(r.z, absMask), fmin, _CMP_GT_OQ));
  const __m256 inv = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(Dot8(r, r)));
  r.x = Blend8(nonZero, _mm256_mul_ps(r.x, inv), r.x);
  r.y = Blend8(nonZero, _mm256_mul_ps(r.y, inv), r.y);
  r.z = Blend8(nonZero, _mm256_mul_ps(r.z, inv), r.z);
  return r;
}

VTK_MIKK_AVX2_FN inline __m256d SelectPD4(__m256d mask, __m256d a, __m256d b)
{
  return _mm256_blendv_pd(b, a, mask);
}

// AngleFromCos2 for four lanes.
VTK_MIKK_AVX2_FN inline void AngleFromCos4(__m256d x, float* out4)
{
  const __m256d signMask = _mm256_set1_pd(-0.0);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d a = _mm256_andnot_pd(signMask, x);
  const __m256d small = _mm256_cmp_pd(a, _mm256_set1_pd(0.5), _CMP_LE_OQ);
  const __m256d zBig = _mm256_mul_pd(_mm256_sub_pd(one, a), _mm256_set1_pd(0.5));
  const __m256d z = SelectPD4(small, _mm256_mul_pd(x, x), zBig);
  const __m256d s = SelectPD4(small, a, _mm256_sqrt_pd(zBig));
  const __m256d z2 = _mm256_mul_pd(z, z), z4 = _mm256_mul_pd(z2, z2);
  const __m256d p01 = _mm256_add_pd(
    _mm256_set1_pd(0.16666666666738633), _mm256_mul_pd(_mm256_set1_pd(0.07499999953429712), z));
  const __m256d p23 = _mm256_add_pd(
    _mm256_set1_pd(0.044642906474584965), _mm256_mul_pd(_mm256_set1_pd(0.030379945210024933), z));
  const __m256d p45 = _mm256_add_pd(
    _mm256_set1_pd(0.022412417726695433), _mm256_mul_pd(_mm256_set1_pd(0.016902683886393575), z));
  const __m256d p67 = _mm256_add_pd(
    _mm256_set1_pd(0.01686409027396012), _mm256_mul_pd(_mm256_set1_pd(0.001067506315036312), z));
  const __m256d p = _mm256_add_pd(_mm256_add_pd(p01, _mm256_mul_pd(p23, z2)),
    _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(p45, _mm256_mul_pd(p67, z2)),
                    _mm256_mul_pd(_mm256_set1_pd(0.02834674523183333), z4)),
      z4));
  const __m256d as = _mm256_add_pd(s, _mm256_mul_pd(_mm256_mul_pd(s, z), p));
  // The constants of the SSE version, (1 - sgn) pio2, -sgn and 2 sgn (sgn = +-1 with the sign
  // of x), are exact: chosen by the sign bit of x instead of computed.
  const __m256d pio2Hi = _mm256_set1_pd(1.5707963267948966);
  const __m256d pio2Lo = _mm256_set1_pd(6.123233995736766e-17);
  const __m256d cHi = SelectPD4(small,
    pio2Hi,
    _mm256_blendv_pd(_mm256_setzero_pd(), _mm256_set1_pd(2 * 1.5707963267948966), x));
  const __m256d cLo = SelectPD4(small,
    pio2Lo,
    _mm256_blendv_pd(_mm256_setzero_pd(), _mm256_set1_pd(2 * 6.123233995736766e-17), x));
  const __m256d k = SelectPD4(small,
    _mm256_blendv_pd(_mm256_set1_pd(-1.0), one, x),
    _mm256_blendv_pd(_mm256_set1_pd(2.0), _mm256_set1_pd(-2.0), x));
  const __m256d r = _mm256_add_pd(cHi, _mm256_add_pd(_mm256_mul_pd(k, as), cLo));
  _mm_storeu_ps(out4, _mm256_cvtpd_ps(r));
  // lanes whose 29 dropped bits lie within 2^13 of the rounding midpoint 2^28 (low dwords)
  const __m256i low = _mm256_and_si256(
    _mm256_castpd_si256(r), _mm256_set1_epi64x(static_cast<long long>(0x1fffffff)));
  const __m256i rel = _mm256_sub_epi32(low, _mm256_set1_epi32((1 << 28) - (1 << 13) + 1));
  const __m256i near = _mm256_and_si256(_mm256_cmpgt_epi32(rel, _mm256_set1_epi32(-1)),
    _mm256_cmpgt_epi32(_mm256_set1_epi32((1 << 14) - 1), rel));
  const int nearMask = _mm256_movemask_ps(_mm256_castsi256_ps(near)) & 0x55;
  if (nearMask)
  {
    double xx[4];
    _mm256_storeu_pd(xx, x);
    for (int l = 0; l < 4; ++l)
    {
      if (nearMask & (1 << (2 * l)))
      {
        out4[l] = static_cast<float>(std::acos(xx[l]));
      }
    }
  }
}

// Stores x, y, z at row, row + stride, row + 2 stride.
VTK_MIKK_AVX2_FN inline void Store8(float* row, size_t stride, const V3x8& v)
{
  _mm256_storeu_ps(row, v.x);
  _mm256_storeu_ps(row + stride, v.y);
  _mm256_storeu_ps(row + 2 * stride, v.z);
}

// The 3 floats at base + stride * ids[l], l = 0..7, as 8 lanes. (Scalar loads: faster than
// AVX2 gather instructions on the AMD EPYC this was measured on.)
VTK_MIKK_AVX2_FN inline V3x8 Load3x8(const float* base, const Idx* ids, size_t stride)
{
  const float* q[8];
  for (int l = 0; l < 8; ++l)
  {
    q[l] = base + stride * size_t(ids[l]);
  }
  return V3x8{ _mm256_setr_ps(
                 q[0][0], q[1][0], q[2][0], q[3][0], q[4][0], q[5][0], q[6][0], q[7][0]),
    _mm256_setr_ps(q[0][1], q[1][1], q[2][1], q[3][1], q[4][1], q[5][1], q[6][1], q[7][1]),
    _mm256_setr_ps(q[0][2], q[1][2], q[2][2], q[3][2], q[4][2], q[5][2], q[6][2], q[7][2]) };
}
// The 2 floats at base + 2 * ids[l], l = 0..7, as 8 lanes.
VTK_MIKK_AVX2_FN inline void Load2x8(const float* base, const Idx* ids, __m256& u, __m256& v)
{
  const float* q[8];
  for (int l = 0; l < 8; ++l)
  {
    q[l] = base + 2 * size_t(ids[l]);
  }
  u = _mm256_setr_ps(q[0][0], q[1][0], q[2][0], q[3][0], q[4][0], q[5][0], q[6][0], q[7][0]);
  v = _mm256_setr_ps(q[0][1], q[1][1], q[2][1], q[3][1], q[4][1], q[5][1], q[6][1], q[7][1]);
}

bool HaveAVX2()
{
  static const bool have = __builtin_cpu_supports("avx2") != 0;
  return have;
}

bool HaveAVX512()
{
  static const bool have = HaveAVX2() && __builtin_cpu_supports("avx512f") != 0;
  return have;
}

// Double-precision arithmetic for AngleFromCos8 with the rounding mode in the instruction:
// the compiler cannot fuse these into FMA (AVX-512F has 512-bit FMA, and GCC contracts plain
// a * b + c by default), so every operation rounds as in the SSE and AVX2 versions.
constexpr int kNearest = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
VTK_MIKK_AVX512_FN inline __m512d MulPD8(__m512d a, __m512d b)
{
  return _mm512_mul_round_pd(a, b, kNearest);
}
VTK_MIKK_AVX512_FN inline __m512d AddPD8(__m512d a, __m512d b)
{
  return _mm512_add_round_pd(a, b, kNearest);
}
VTK_MIKK_AVX512_FN inline __m512d SubPD8(__m512d a, __m512d b)
{
  return _mm512_sub_round_pd(a, b, kNearest);
}

// AngleFromCos4 for 8 lanes with AVX-512: the same double operations in the same order (masks
// instead of blends).
VTK_MIKK_AVX512_FN inline void AngleFromCos8(__m512d x, float* out8)
{
  const __m512d one = _mm512_set1_pd(1.0);
  const __m512d a = _mm512_castsi512_pd(
    _mm512_and_epi64(_mm512_castpd_si512(x), _mm512_set1_epi64(0x7fffffffffffffffLL)));
  const __mmask8 small = _mm512_cmp_pd_mask(a, _mm512_set1_pd(0.5), _CMP_LE_OQ);
  const __mmask8 negative = _mm512_test_epi64_mask(
    _mm512_castpd_si512(x), _mm512_set1_epi64(static_cast<long long>(0x8000000000000000ULL)));
  const __m512d zBig = MulPD8(SubPD8(one, a), _mm512_set1_pd(0.5));
  const __m512d z = _mm512_mask_blend_pd(small, zBig, MulPD8(x, x));
  const __m512d s = _mm512_mask_blend_pd(small, _mm512_sqrt_pd(zBig), a);
  const __m512d z2 = MulPD8(z, z), z4 = MulPD8(z2, z2);
  const __m512d p01 =
    AddPD8(_mm512_set1_pd(0.16666666666738633), MulPD8(_mm512_set1_pd(0.07499999953429712), z));
  const __m512d p23 =
    AddPD8(_mm512_set1_pd(0.044642906474584965), MulPD8(_mm512_set1_pd(0.030379945210024933), z));
  const __m512d p45 =
    AddPD8(_mm512_set1_pd(0.022412417726695433), MulPD8(_mm512_set1_pd(0.016902683886393575), z));
  const __m512d p67 =
    AddPD8(_mm512_set1_pd(0.01686409027396012), MulPD8(_mm512_set1_pd(0.001067506315036312), z));
  const __m512d p = AddPD8(AddPD8(p01, MulPD8(p23, z2)),
    MulPD8(
      AddPD8(AddPD8(p45, MulPD8(p67, z2)), MulPD8(_mm512_set1_pd(0.02834674523183333), z4)), z4));
  const __m512d as = AddPD8(s, MulPD8(MulPD8(s, z), p));
  const __m512d zero = _mm512_setzero_pd();
  const __m512d cHi = _mm512_mask_blend_pd(small,
    _mm512_mask_blend_pd(negative, zero, _mm512_set1_pd(2 * 1.5707963267948966)),
    _mm512_set1_pd(1.5707963267948966));
  const __m512d cLo = _mm512_mask_blend_pd(small,
    _mm512_mask_blend_pd(negative, zero, _mm512_set1_pd(2 * 6.123233995736766e-17)),
    _mm512_set1_pd(6.123233995736766e-17));
  const __m512d k = _mm512_mask_blend_pd(small,
    _mm512_mask_blend_pd(negative, _mm512_set1_pd(2.0), _mm512_set1_pd(-2.0)),
    _mm512_mask_blend_pd(negative, _mm512_set1_pd(-1.0), one));
  const __m512d r = AddPD8(cHi, AddPD8(MulPD8(k, as), cLo));
  _mm256_storeu_ps(out8, _mm512_cvtpd_ps(r));
  // lanes whose 29 dropped bits lie within 2^13 of the rounding midpoint 2^28
  const __m512i rel =
    _mm512_sub_epi64(_mm512_and_epi64(_mm512_castpd_si512(r), _mm512_set1_epi64(0x1fffffff)),
      _mm512_set1_epi64((1 << 28) - (1 << 13) + 1));
  const __mmask8 near = _mm512_cmp_epi64_mask(rel, _mm512_setzero_si512(), _MM_CMPINT_NLT) &
    _mm512_cmp_epi64_mask(rel, _mm512_set1_epi64((1 << 14) - 1), _MM_CMPINT_LT);
  if (near)
  {
    double xx[8];
    _mm512_storeu_pd(xx, x);
    for (int l = 0; l < 8; ++l)
    {
      if (near & (1 << l))
      {
        out8[l] = static_cast<float>(std::acos(xx[l]));
      }
    }
  }
}

// The angle row of members [0, count8) from the cosines stored there.
VTK_MIKK_AVX512_FN void AnglesAVX512(float* math, size_t count8, size_t blockFloats, size_t row)
{
  for (size_t j = 0; j < count8; j += 8)
  {
    float* angle = math + (j / 8) * blockFloats + row;
    AngleFromCos8(_mm512_cvtps_pd(_mm256_loadu_ps(angle)), angle);
  }
}
#endif

//------------------------------------------------------------------------------
struct Frame
{
  V3 S, T; // tangent and bitangent directions
  float MagS, MagT;
};

// Frame of a corner whose face corner is written by several triangles.
struct SideFrame
{
  Frame F;
  Idx Key; // seed corner of the group (group creation order); -1: not written
  uint8_t Orient;
};

// The reference's average of two frames written to one face corner.
inline Frame AvgFrame(const Frame& a, const Frame& b)
{
  if (a.MagS == b.MagS && a.MagT == b.MagT && Veq(a.S, b.S) && Veq(a.T, b.T))
  {
    return a;
  }
  Frame r;
  r.MagS = 0.5f * (a.MagS + b.MagS);
  r.MagT = 0.5f * (a.MagT + b.MagT);
  r.S = Add(a.S, b.S);
  r.T = Add(a.T, b.T);
  if (VNotZero(r.S))
  {
    r.S = Normalize(r.S);
  }
  if (VNotZero(r.T))
  {
    r.T = Normalize(r.T);
  }
  return r;
}

inline uint32_t FloatBits(float f)
{
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

inline uint64_t Mix64(uint64_t h)
{
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

// Hash of a point's 8 values for welding: equal values (with -0 == +0) give equal hashes.
// Mix64 of the sum of value bits times odd constants (independent multiplies). nan: some value
// is a NaN.
inline uint64_t HashPoint(const float* p, const float* n, const float* uv, bool& nan)
{
#ifdef VTK_MIKK_SSE2
  const __m128i a = _mm_castps_si128(_mm_setr_ps(p[0], p[1], p[2], n[0]));
  const __m128i b = _mm_castps_si128(_mm_setr_ps(n[1], n[2], uv[0], uv[1]));
  const __m128i absMask = _mm_set1_epi32(0x7fffffff);
  const __m128i absA = _mm_and_si128(a, absMask), absB = _mm_and_si128(b, absMask);
  const __m128i inf = _mm_set1_epi32(0x7f800000);
  nan =
    _mm_movemask_epi8(_mm_or_si128(_mm_cmpgt_epi32(absA, inf), _mm_cmpgt_epi32(absB, inf))) != 0;
  // -0 -> +0
  const __m128i zero = _mm_setzero_si128();
  const __m128i ua = _mm_andnot_si128(_mm_cmpeq_epi32(absA, zero), a);
  const __m128i ub = _mm_andnot_si128(_mm_cmpeq_epi32(absB, zero), b);
  // 32 x 32 -> 64-bit products of lanes 0, 2 and (shifted) 1, 3
  const __m128i k0 = _mm_set_epi32(0, int(0x85ebca77), 0, int(0x9e3779b1));
  const __m128i k1 = _mm_set_epi32(0, int(0xc2b2ae3d), 0, int(0x27d4eb2f));
  const __m128i k2 = _mm_set_epi32(0, int(0x165667b1), 0, int(0xd3a2646d));
  const __m128i k3 = _mm_set_epi32(0, int(0xfd7046c5), 0, int(0xb55a4f09));
  const __m128i sum =
    _mm_add_epi64(_mm_add_epi64(_mm_mul_epu32(ua, k0), _mm_mul_epu32(_mm_srli_epi64(ua, 32), k1)),
      _mm_add_epi64(_mm_mul_epu32(ub, k2), _mm_mul_epu32(_mm_srli_epi64(ub, 32), k3)));
  uint64_t lanes[2];
  _mm_storeu_si128(reinterpret_cast<__m128i*>(lanes), sum);
  return Mix64(lanes[0] + lanes[1]);
#else
  static constexpr uint64_t kOdd[8] = {
    0x9e3779b1, 0x27d4eb2f, 0x85ebca77, 0xc2b2ae3d, 0xd3a2646d, 0xb55a4f09, 0x165667b1, 0xfd7046c5
  };
  const float values[8] = { p[0], p[1], p[2], n[0], n[1], n[2], uv[0], uv[1] };
  uint32_t maxAbs = 0;
  uint64_t h = 0;
  for (int j = 0; j < 8; ++j)
  {
    const uint32_t u = FloatBits(values[j]), a = u & 0x7fffffffu;
    maxAbs = std::max(maxAbs, a);
    h += uint64_t(a ? u : 0u) * kOdd[j]; // -0 hashed as +0
  }
  nan = maxAbs > 0x7f800000u;
  return Mix64(h);
#endif
}

//------------------------------------------------------------------------------
struct Kernel
{
  // input
  const MeshInput& In;
  Idx NumPoints = 0;
  Idx NumSlots = 0;
  const long long* Off = nullptr;
  const long long* Conn = nullptr;
  int NumBlocks = 1; // parallel blocks for the fan counting sort

  Arena Pool; // declared before every Buffer that may use it

  // welding
  Buffer<Idx> Rep; // welded id of a point, -1 if it contains a NaN
  bool AnyNaNPoint = false;
  bool UseAVX2 = false;                        // the CPU has AVX2
  bool UseAVX512 = false;                      // and AVX-512 (acos only)
  std::atomic<bool> FinishScanNeeded{ false }; // see Compute
  Idx NumVerts = 0;

  // triangles
  static constexpr long long kFaceChunk = 4096;
  long long NumFaceChunks = 0;
  std::vector<Idx> ChunkTriBase;
  Idx NumTris = 0;
  bool IdentitySlots = false; // all faces are triangles, offsets 3f: slot of corner c is c
  bool AnyMulti = false;      // some face has more than 3 corners
  Buffer<Idx> TriSlot;        // 3 per triangle (unless IdentitySlots): face corner index
  Buffer<Idx> TriWeld;        // 3 per triangle: welded vertex id
  Buffer<V3> TriDir;          // 2 per triangle: sign(det) Os/|Os|, sign(det) Ot/|Ot|
  Buffer<float> TriMag;       // 2 per triangle (only if AnyMulti): |Os|/|det|, |Ot|/|det|
  Buffer<uint8_t> TriFlags;
  long long NumDegenerate = 0, NumGWA = 0, NumSkipped = 0, NumInvalid = 0;

  // fans: corners (3t+i) of non-degenerate triangles, grouped by welded id, ascending
  Buffer<Idx> FanStart;
  Buffer<Idx> Fan;

  Buffer<SideFrame> Side; // 3 per triangle if AnyMulti
  CornerFrame* Out = nullptr;

  explicit Kernel(const MeshInput& in)
    : In(in)
  {
  }

  V3 Pos(Idx p) const
  {
    const float* q = In.Positions + 3 * size_t(p);
    return { q[0], q[1], q[2] };
  }
  V3 Nrm(Idx p) const
  {
    const float* q = In.Normals + 3 * size_t(p);
    return { q[0], q[1], q[2] };
  }
  // point holding the values of a welded vertex
  Idx PointOfWeld(Idx w) const { return w < NumPoints ? w : static_cast<Idx>(Conn[w - NumPoints]); }
  Idx WeldOf(Idx point, Idx slot) const
  {
    const Idx r = Rep[size_t(point)];
    return r >= 0 ? r : NumPoints + slot;
  }
  Idx SlotOf(Idx corner) const { return IdentitySlots ? corner : TriSlot[size_t(corner)]; }

  /// Whether face offsets [b, e) are usable: inside the connectivity and in order.
  bool FaceInRange(long long b, long long e) const { return b >= 0 && e >= b && e <= NumSlots; }
  /// Whether a face gives triangles (e - b - 2 of them): in range, with at least 3 corners.
  bool FaceHasTriangles(long long b, long long e) const { return FaceInRange(b, e) && e - b >= 3; }
  /// Calls visit(b, e, t) for each face of chunk c that gives triangles, in order: [b, e) are
  /// its offsets and t its first triangle (triangles are numbered in face order).
  template<typename Visit>
  void ForEachTriangulatedFace(long long c, Visit&& visit) const
  {
    Idx t = ChunkTriBase[size_t(c)];
    const long long fe = std::min(In.NumberOfFaces, (c + 1) * kFaceChunk);
    for (long long f = c * kFaceChunk; f < fe; ++f)
    {
      const long long b = Off[f], e = Off[f + 1];
      if (this->FaceHasTriangles(b, e))
      {
        visit(b, e, t);
        t += Idx(e - b - 2);
      }
    }
  }

  void Weld();
  void BuildTriangles();
  void SetupTriangle(Idx t, const Idx slots[3], const Idx pts[3], float& det);
#ifdef VTK_MIKK_AVX2
  bool SetupTriangles8(Idx t, long long b);
#endif
  void BuildFans();
  void AdoptGroupWithAnyOrientation();
  void ProcessVertices();
  void MergeMultiWriters();
  void CopyDegenerates();
  void Finish(Result& res);
};

//------------------------------------------------------------------------------
// Welding. Each point gets a 32-bit hash of its 8 values (-0 hashed as +0); a stable LSD
// radix sort groups equal hashes, in ascending point order. Within a run of equal hashes the
// first point of every class of equal values (==) is its representative: the smallest id.
void Kernel::Weld()
{
  const Idx np = NumPoints;
  Rep.Allocate(size_t(np), &Pool); // every entry is set below
  Buffer<uint64_t> keys;
  keys.Allocate(size_t(np), &Pool); // hash << 32 | point id
  const float* P = In.Positions;
  const float* N = In.Normals;
  const float* U = In.TCoords;
  vtkSMPThreadLocal<unsigned char> sawNaN;
  ParallelFor(np,
    16384,
    [&](vtkIdType b, vtkIdType e)
    {
      unsigned char& nanFlag = sawNaN.Local();
      for (vtkIdType p = b; p < e; ++p)
      {
        bool nan;
        const uint64_t h = HashPoint(P + 3 * p, N + 3 * p, U + 2 * p, nan);
        keys[size_t(p)] = (h & 0xffffffff00000000ULL) | uint64_t(uint32_t(p));
        Rep[size_t(p)] = nan ? -1 : 0; // 0: not assigned yet
        if (nan)
        {
          nanFlag = 1;
        }
      }
    });
  for (unsigned char f : sawNaN)
  {
    AnyNaNPoint = AnyNaNPoint || f;
  }
  // LSD radix sort on the 32 hash bits, 11 + 11 + 10 bits
  {
    Buffer<uint64_t> tmp;
    tmp.Allocate(keys.size(), &Pool);
    const int shifts[3] = { 32, 43, 54 };
    std::vector<Idx> count(2048);
    for (int pass = 0; pass < 3; ++pass)
    {
      const int sh = shifts[pass];
      std::fill(count.begin(), count.end(), 0);
      for (uint64_t k : keys)
      {
        ++count[size_t((k >> sh) & 2047)];
      }
      Idx sum = 0;
      for (Idx& c : count)
      {
        const Idx n = c;
        c = sum;
        sum += n;
      }
      for (uint64_t k : keys)
      {
        tmp[size_t(count[size_t((k >> sh) & 2047)]++)] = k;
      }
      keys.Swap(tmp);
    }
  }
  auto equalValues = [&](size_t a, size_t b)
  {
    return P[3 * a] == P[3 * b] && P[3 * a + 1] == P[3 * b + 1] && P[3 * a + 2] == P[3 * b + 2] &&
      N[3 * a] == N[3 * b] && N[3 * a + 1] == N[3 * b + 1] && N[3 * a + 2] == N[3 * b + 2] &&
      U[2 * a] == U[2 * b] && U[2 * a + 1] == U[2 * b + 1];
  };
  std::vector<Idx> heads; // class representatives within the current run
  const size_t n = keys.size();
  for (size_t r0 = 0; r0 < n;)
  {
    const uint64_t hash = keys[r0] >> 32;
    size_t r1 = r0 + 1;
    while (r1 < n && (keys[r1] >> 32) == hash)
    {
      ++r1;
    }
    if (r1 - r0 == 1)
    {
      const Idx p = Idx(uint32_t(keys[r0]));
      if (Rep[size_t(p)] >= 0)
      {
        Rep[size_t(p)] = p;
      }
    }
    else
    {
      heads.clear();
      for (size_t j = r0; j < r1; ++j)
      {
        const Idx p = Idx(uint32_t(keys[j]));
        if (Rep[size_t(p)] < 0)
        {
          continue;
        }
        Idx rep = p;
        for (Idx h : heads)
        {
          if (equalValues(size_t(h), size_t(p)))
          {
            rep = h;
            break;
          }
        }
        if (rep == p)
        {
          heads.push_back(p);
        }
        Rep[size_t(p)] = rep;
      }
    }
    r0 = r1;
  }
}

//------------------------------------------------------------------------------
// Flags, directions and determinant of triangle t (reference: degenerate test, InitTriInfo).
void Kernel::SetupTriangle(Idx t, const Idx slots[3], const Idx pts[3], float& det)
{
  for (int i = 0; i < 3; ++i)
  {
    if (!IdentitySlots)
    {
      TriSlot[3 * size_t(t) + i] = slots[i];
    }
    TriWeld[3 * size_t(t) + i] = WeldOf(pts[i], slots[i]);
  }
  const V3 p0 = Pos(pts[0]), p1 = Pos(pts[1]), p2 = Pos(pts[2]);
  V3 dirS{ 0, 0, 0 }, dirT{ 0, 0, 0 };
  float magS = 0, magT = 0;
  det = 0;
  uint8_t flags = kGWA;
  if (Veq(p0, p1) || Veq(p0, p2) || Veq(p1, p2))
  {
    flags = kDegenerate;
  }
  else
  {
    const float* U = In.TCoords;
    const float u0 = U[2 * size_t(pts[0])], v0 = U[2 * size_t(pts[0]) + 1];
    const float t21x = U[2 * size_t(pts[1])] - u0;
    const float t21y = U[2 * size_t(pts[1]) + 1] - v0;
    const float t31x = U[2 * size_t(pts[2])] - u0;
    const float t31y = U[2 * size_t(pts[2]) + 1] - v0;
    const V3 d1 = Sub(p1, p0);
    const V3 d2 = Sub(p2, p0);
    det = t21x * t31y - t21y * t31x;
    const V3 os = Sub(Scale(d1, t31y), Scale(d2, t21y));
    const V3 ot = Add(Scale(d1, -t31x), Scale(d2, t21x));
    if (det > 0)
    {
      flags |= kOrient;
    }
    if (NotZero(det))
    {
      const float absDet = std::fabs(det);
      const float lenS = std::sqrt(Dot(os, os));
      const float lenT = std::sqrt(Dot(ot, ot));
      const float sgn = (flags & kOrient) ? 1.0f : -1.0f;
      if (NotZero(lenS))
      {
        dirS = Scale(os, sgn / lenS);
      }
      if (NotZero(lenT))
      {
        dirT = Scale(ot, sgn / lenT);
      }
      magS = lenS / absDet;
      magT = lenT / absDet;
      if (NotZero(magS) && NotZero(magT))
      {
        flags = uint8_t(flags & ~kGWA);
      }
    }
  }
  TriDir[2 * size_t(t)] = dirS;
  TriDir[2 * size_t(t) + 1] = dirT;
  if (AnyMulti)
  {
    TriMag[2 * size_t(t)] = magS;
    TriMag[2 * size_t(t) + 1] = magT;
  }
  TriFlags[size_t(t)] = flags;
}

#ifdef VTK_MIKK_AVX2
//------------------------------------------------------------------------------
// SetupTriangle for the 8 triangles t..t+7 made of 8 consecutive 3-corner faces with the face
// corners b..b+23, eight lanes at a time: the same IEEE operations lane by lane, so the same
// bits. Returns false, having written nothing, if a point id is outside [0, NumPoints).
VTK_MIKK_AVX2_FN bool Kernel::SetupTriangles8(Idx t, long long b)
{
  const long long* conn = Conn + b;
  {
    const __m256i zero = _mm256_setzero_si256();
    const __m256i limit = _mm256_set1_epi64x(NumPoints);
    __m256i ok = _mm256_set1_epi64x(-1);
    for (int q = 0; q < 6; ++q)
    {
      const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(conn + 4 * q));
      // 0 <= id < NumPoints, on 64 bits
      ok = _mm256_and_si256(
        ok, _mm256_andnot_si256(_mm256_cmpgt_epi64(zero, ids), _mm256_cmpgt_epi64(limit, ids)));
    }
    if (!_mm256_testc_si256(ok, _mm256_set1_epi64x(-1)))
    {
      return false;
    }
  }
  alignas(32) int32_t pid[3][8];
  const Idx slot0 = Idx(b);
  for (int j = 0; j < 8; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      const Idx slot = slot0 + 3 * j + i;
      const Idx pt = Idx(conn[3 * j + i]);
      pid[i][j] = pt;
      TriWeld[3 * size_t(t) + size_t(3 * j + i)] = WeldOf(pt, slot);
      if (!IdentitySlots)
      {
        TriSlot[3 * size_t(t) + size_t(3 * j + i)] = slot;
      }
    }
  }
  const float* P = In.Positions;
  const float* U = In.TCoords;
  V3x8 p[3];
  __m256 u[3], v[3];
  for (int i = 0; i < 3; ++i)
  {
    p[i] = Load3x8(P, pid[i], 3);
    Load2x8(U, pid[i], u[i], v[i]);
  }
  const __m256 degenerate =
    _mm256_or_ps(_mm256_or_ps(Equal8(p[0], p[1]), Equal8(p[0], p[2])), Equal8(p[1], p[2]));
  const __m256 t21x = _mm256_sub_ps(u[1], u[0]), t21y = _mm256_sub_ps(v[1], v[0]);
  const __m256 t31x = _mm256_sub_ps(u[2], u[0]), t31y = _mm256_sub_ps(v[2], v[0]);
  const V3x8 d1{
    _mm256_sub_ps(p[1].x, p[0].x), _mm256_sub_ps(p[1].y, p[0].y), _mm256_sub_ps(p[1].z, p[0].z)
  };
  const V3x8 d2{
    _mm256_sub_ps(p[2].x, p[0].x), _mm256_sub_ps(p[2].y, p[0].y), _mm256_sub_ps(p[2].z, p[0].z)
  };
  const __m256 det = _mm256_sub_ps(_mm256_mul_ps(t21x, t31y), _mm256_mul_ps(t21y, t31x));
  // os = d1 t31y - d2 t21y, ot = d1 (-t31x) + d2 t21x
  const __m256 negT31x = _mm256_xor_ps(t31x, _mm256_set1_ps(-0.0f));
  const V3x8 os{ _mm256_sub_ps(_mm256_mul_ps(d1.x, t31y), _mm256_mul_ps(d2.x, t21y)),
    _mm256_sub_ps(_mm256_mul_ps(d1.y, t31y), _mm256_mul_ps(d2.y, t21y)),
    _mm256_sub_ps(_mm256_mul_ps(d1.z, t31y), _mm256_mul_ps(d2.z, t21y)) };
  const V3x8 ot{ _mm256_add_ps(_mm256_mul_ps(d1.x, negT31x), _mm256_mul_ps(d2.x, t21x)),
    _mm256_add_ps(_mm256_mul_ps(d1.y, negT31x), _mm256_mul_ps(d2.y, t21x)),
    _mm256_add_ps(_mm256_mul_ps(d1.z, negT31x), _mm256_mul_ps(d2.z, t21x)) };
  const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256 orient = _mm256_cmp_ps(det, _mm256_setzero_ps(), _CMP_GT_OQ);
  const __m256 live = _mm256_andnot_ps(degenerate, NotZero8(det)); // lanes with a frame
  const __m256 absDet = _mm256_and_ps(det, absMask);
  const __m256 lenS = _mm256_sqrt_ps(Dot8(os, os));
  const __m256 lenT = _mm256_sqrt_ps(Dot8(ot, ot));
  const __m256 sgn = Blend8(orient, _mm256_set1_ps(1.0f), _mm256_set1_ps(-1.0f));
  const __m256 useS = _mm256_and_ps(live, NotZero8(lenS));
  const __m256 useT = _mm256_and_ps(live, NotZero8(lenT));
  const __m256 qS = _mm256_div_ps(sgn, lenS), qT = _mm256_div_ps(sgn, lenT);
  const __m256 magS = _mm256_and_ps(live, _mm256_div_ps(lenS, absDet));
  const __m256 magT = _mm256_and_ps(live, _mm256_div_ps(lenT, absDet));
  const __m256 good = _mm256_and_ps(live, _mm256_and_ps(NotZero8(magS), NotZero8(magT)));
  alignas(32) float out[8][8]; // dirS xyz, dirT xyz, magS, magT
  _mm256_store_ps(out[0], _mm256_and_ps(useS, _mm256_mul_ps(os.x, qS)));
  _mm256_store_ps(out[1], _mm256_and_ps(useS, _mm256_mul_ps(os.y, qS)));
  _mm256_store_ps(out[2], _mm256_and_ps(useS, _mm256_mul_ps(os.z, qS)));
  _mm256_store_ps(out[3], _mm256_and_ps(useT, _mm256_mul_ps(ot.x, qT)));
  _mm256_store_ps(out[4], _mm256_and_ps(useT, _mm256_mul_ps(ot.y, qT)));
  _mm256_store_ps(out[5], _mm256_and_ps(useT, _mm256_mul_ps(ot.z, qT)));
  _mm256_store_ps(out[6], magS);
  _mm256_store_ps(out[7], magT);
  for (int j = 0; j < 8; ++j)
  {
    TriDir[2 * size_t(t + j)] = V3{ out[0][j], out[1][j], out[2][j] };
    TriDir[2 * size_t(t + j) + 1] = V3{ out[3][j], out[4][j], out[5][j] };
  }
  if (AnyMulti)
  {
    for (int j = 0; j < 8; ++j)
    {
      TriMag[2 * size_t(t + j)] = out[6][j];
      TriMag[2 * size_t(t + j) + 1] = out[7][j];
    }
  }
  // degenerate: kDegenerate; else kGWA unless good, plus kOrient if det > 0
  const __m256i flagsOk =
    _mm256_or_si256(_mm256_andnot_si256(_mm256_castps_si256(good), _mm256_set1_epi32(kGWA)),
      _mm256_and_si256(_mm256_castps_si256(orient), _mm256_set1_epi32(kOrient)));
  const __m256i flags = _mm256_castps_si256(Blend8(
    degenerate, _mm256_castsi256_ps(_mm256_set1_epi32(kDegenerate)), _mm256_castsi256_ps(flagsOk)));
  const __m128i w16 =
    _mm_packus_epi32(_mm256_castsi256_si128(flags), _mm256_extracti128_si256(flags, 1));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(TriFlags.data() + t), _mm_packus_epi16(w16, w16));
  return true;
}
#endif

//------------------------------------------------------------------------------
void Kernel::BuildTriangles()
{
  const long long nf = In.NumberOfFaces;
  NumFaceChunks = (nf + kFaceChunk - 1) / kFaceChunk;
  ChunkTriBase.assign(size_t(NumFaceChunks) + 1, 0);
  std::vector<uint8_t> chunkIdentity(size_t(NumFaceChunks), 1),
    chunkMulti(size_t(NumFaceChunks), 0);
  ParallelFor(NumFaceChunks,
    1,
    [&](vtkIdType cb, vtkIdType ce)
    {
      for (vtkIdType c = cb; c < ce; ++c)
      {
        const long long fb = c * kFaceChunk, fe = std::min(nf, (c + 1) * kFaceChunk);
        // the common layout first: every face a triangle at offset 3f (a loop without
        // branches); then each face has one triangle
        bool identity = 3 * fe <= NumSlots;
        for (long long f = fb; f <= fe; ++f)
        {
          identity &= Off[f] == 3 * f;
        }
        long long sum = identity ? fe - fb : 0;
        bool multi = false;
        for (long long f = fb; f < fe && !identity; ++f)
        {
          const long long b = Off[f], e = Off[f + 1];
          if (!this->FaceHasTriangles(b, e))
          {
            continue;
          }
          sum += e - b - 2;
          multi = multi || e - b > 3;
        }
        ChunkTriBase[size_t(c) + 1] = Idx(sum); // total bounded by NumSlots
        chunkIdentity[size_t(c)] = identity;
        chunkMulti[size_t(c)] = multi;
      }
    });
  IdentitySlots = true;
  for (long long c = 0; c < NumFaceChunks; ++c)
  {
    ChunkTriBase[size_t(c) + 1] += ChunkTriBase[size_t(c)];
    IdentitySlots = IdentitySlots && chunkIdentity[size_t(c)];
    AnyMulti = AnyMulti || chunkMulti[size_t(c)];
  }
  NumTris = ChunkTriBase[size_t(NumFaceChunks)];
  if (!IdentitySlots)
  {
    TriSlot.Allocate(3 * size_t(NumTris), &Pool);
  }
  TriWeld.Allocate(3 * size_t(NumTris), &Pool);
  TriDir.Allocate(2 * size_t(NumTris), &Pool);
  if (AnyMulti)
  {
    TriMag.Allocate(2 * size_t(NumTris), &Pool);
  }
  TriFlags.Allocate(size_t(NumTris), &Pool);

  struct Stats
  {
    long long Degenerate = 0, GWA = 0, Skipped = 0, Invalid = 0;
  };
  std::vector<Stats> stats(static_cast<size_t>(NumFaceChunks));
  const float* U = In.TCoords;
  const long long np = NumPoints;
#ifdef VTK_MIKK_AVX2
  const bool simd8 = UseAVX2;
#endif
  ParallelFor(NumFaceChunks,
    1,
    [&](vtkIdType cb, vtkIdType ce)
    {
      for (vtkIdType c = cb; c < ce; ++c)
      {
        Stats st;
        Idx t = ChunkTriBase[size_t(c)];
        const long long fe = std::min(nf, (c + 1) * kFaceChunk);
        for (long long f = c * kFaceChunk; f < fe; ++f)
        {
          const long long b = Off[f], e = Off[f + 1];
#ifdef VTK_MIKK_AVX2
          if (simd8 && f + 8 <= fe && b >= 0 && Off[f + 8] == b + 24 && b + 24 <= NumSlots)
          {
            // 8 faces of 3 corners each, consecutive in the connectivity?
            bool run = true;
            for (int j = 1; j < 8; ++j)
            {
              run = run && Off[f + j] == b + 3 * j;
            }
            if (run && SetupTriangles8(t, b))
            {
              t += 8;
              f += 7;
              continue;
            }
          }
#endif
          if (!this->FaceInRange(b, e))
          {
            ++st.Invalid;
            continue;
          }
          const long long n = e - b;
          if (n < 3)
          {
            ++st.Skipped;
            continue;
          }
          bool valid = true;
          for (long long k = b; k < e; ++k)
          {
            valid = valid && Conn[k] >= 0 && Conn[k] < np;
          }
          if (!valid)
          {
            ++st.Invalid;
            for (long long k = 0; k < n - 2; ++k, ++t)
            {
              TriFlags[size_t(t)] = kDead;
              for (int i = 0; i < 3; ++i)
              {
                if (!IdentitySlots)
                {
                  TriSlot[3 * size_t(t) + i] = Idx(b);
                }
                TriWeld[3 * size_t(t) + i] = 0;
              }
              TriDir[2 * size_t(t)] = TriDir[2 * size_t(t) + 1] = V3{ 0, 0, 0 };
            }
            continue;
          }
          const Idx base = Idx(b);
          if (n == 3)
          {
            const Idx slots[3] = { base, base + 1, base + 2 };
            const Idx pts[3] = { Idx(Conn[b]), Idx(Conn[b + 1]), Idx(Conn[b + 2]) };
            float det;
            SetupTriangle(t, slots, pts, det);
            ++t;
          }
          else if (n == 4)
          {
            const Idx q[4] = { Idx(Conn[b]), Idx(Conn[b + 1]), Idx(Conn[b + 2]), Idx(Conn[b + 3]) };
            // shorter UV diagonal, position diagonal on an exact tie (0-2 unless 1-3 shorter)
            const float du02 = U[2 * size_t(q[2])] - U[2 * size_t(q[0])];
            const float dv02 = U[2 * size_t(q[2]) + 1] - U[2 * size_t(q[0]) + 1];
            const float du13 = U[2 * size_t(q[3])] - U[2 * size_t(q[1])];
            const float dv13 = U[2 * size_t(q[3]) + 1] - U[2 * size_t(q[1]) + 1];
            const float uv02 = du02 * du02 + dv02 * dv02;
            const float uv13 = du13 * du13 + dv13 * dv13;
            bool diag02;
            if (uv02 < uv13)
            {
              diag02 = true;
            }
            else if (uv13 < uv02)
            {
              diag02 = false;
            }
            else
            {
              const V3 e02 = Sub(Pos(q[2]), Pos(q[0]));
              const V3 e13 = Sub(Pos(q[3]), Pos(q[1]));
              diag02 = !(Dot(e13, e13) < Dot(e02, e02));
            }
            const int la[3] = { 0, 1, diag02 ? 2 : 3 };
            const int lb[3] = { diag02 ? 0 : 1, 2, 3 };
            const Idx sa[3] = { base + la[0], base + la[1], base + la[2] };
            const Idx sb[3] = { base + lb[0], base + lb[1], base + lb[2] };
            const Idx pa[3] = { q[la[0]], q[la[1]], q[la[2]] };
            const Idx pb[3] = { q[lb[0]], q[lb[1]], q[lb[2]] };
            float detA, detB;
            SetupTriangle(t, sa, pa, detA);
            SetupTriangle(t + 1, sb, pb, detB);
            uint8_t& fa = TriFlags[size_t(t)];
            uint8_t& fb = TriFlags[size_t(t) + 1];
            const bool degA = (fa & kDegenerate) != 0, degB = (fb & kDegenerate) != 0;
            if (degA != degB)
            {
              fa |= kOneDegenQuad;
              fb |= kOneDegenQuad;
            }
            else if (!degA && ((fa ^ fb) & kOrient))
            {
              // force both triangles of the quad to the same orientation
              const bool firstWins = (fb & kGWA) || std::fabs(detA) >= std::fabs(detB);
              uint8_t& dst = firstWins ? fb : fa;
              const uint8_t src = firstWins ? fa : fb;
              dst = uint8_t((dst & ~kOrient) | (src & kOrient));
            }
            // diagonal corners are written by both triangles:
            // 0-2: (0,1,2) corners 0,2 and (0,2,3) corners 0,1
            // 1-3: (0,1,3) corners 1,2 and (1,2,3) corners 0,2
            const uint8_t m0 = kMulti0, m1 = uint8_t(kMulti0 << 1), m2 = uint8_t(kMulti0 << 2);
            fa |= diag02 ? uint8_t(m0 | m2) : uint8_t(m1 | m2);
            fb |= diag02 ? uint8_t(m0 | m1) : uint8_t(m0 | m2);
            t += 2;
          }
          else
          {
            // fan (0, k+1, k+2)
            for (long long k = 0; k < n - 2; ++k, ++t)
            {
              const Idx slots[3] = { base, Idx(base + k + 1), Idx(base + k + 2) };
              const Idx pts[3] = { Idx(Conn[b]), Idx(Conn[b + k + 1]), Idx(Conn[b + k + 2]) };
              float det;
              SetupTriangle(t, slots, pts, det);
              uint8_t m = kMulti0;
              if (k >= 1)
              {
                m |= uint8_t(kMulti0 << 1);
              }
              if (k <= n - 4)
              {
                m |= uint8_t(kMulti0 << 2);
              }
              TriFlags[size_t(t)] |= m;
            }
          }
        }
        // count after the quad rules (flags are final for this chunk)
        for (Idx u = ChunkTriBase[size_t(c)]; u < t; ++u)
        {
          const uint8_t fl = TriFlags[size_t(u)];
          st.Degenerate += (fl & kDegenerate) ? 1 : 0;
          st.GWA += ((fl & (kExcluded | kGWA)) == kGWA) ? 1 : 0;
        }
        stats[size_t(c)] = st;
      }
    });
  for (const Stats& st : stats)
  {
    NumDegenerate += st.Degenerate;
    NumGWA += st.GWA;
    NumSkipped += st.Skipped;
    NumInvalid += st.Invalid;
  }
}

//------------------------------------------------------------------------------
// Counting sort of the corners of non-degenerate triangles by welded id. Triangles are split
// in NumBlocks contiguous blocks with their own counters, so the fill is parallel and every
// fan lists its corners in ascending order whatever the number of blocks.
void Kernel::BuildFans()
{
  NumVerts = NumPoints + (AnyNaNPoint ? NumSlots : 0);
  const size_t nv = size_t(NumVerts);
  const Idx nt = NumTris;
  const int nb = std::max(1, std::min(NumBlocks, int(nt / 4096) + 1));
  Buffer<Idx> counts;
  counts.Assign(size_t(nb) * nv, 0, &Pool);
  // Both passes visit the included triangles of each block in order, with the block's row of
  // `counts` (first the counts, then the running write positions). Plain local pointers: the
  // compiler need not reload them after every store.
  const uint8_t* const flags = TriFlags.data();
  const Idx* const weld = TriWeld.data();
  Idx* const countData = counts.data();
  auto forEachBlockTriangle = [&](const auto& visit)
  {
    ParallelFor(nb,
      1,
      [&](vtkIdType bb, vtkIdType be)
      {
        for (vtkIdType blk = bb; blk < be; ++blk)
        {
          const Idx t0 = Idx((long long)nt * blk / nb);
          const Idx t1 = Idx((long long)nt * (blk + 1) / nb);
          Idx* const row = countData + size_t(blk) * nv;
          for (Idx t = t0; t < t1; ++t)
          {
            if (!(flags[t] & kExcluded))
            {
              visit(row, weld + 3 * size_t(t), t);
            }
          }
        }
      });
  };
  forEachBlockTriangle(
    [](Idx* cnt, const Idx* w, Idx)
    {
      ++cnt[w[0]];
      ++cnt[w[1]];
      ++cnt[w[2]];
    });
  FanStart.Allocate(nv + 1, &Pool);
  Idx sum = 0;
  for (size_t v = 0; v < nv; ++v)
  {
    FanStart[v] = sum;
    for (int blk = 0; blk < nb; ++blk)
    {
      Idx& c = counts[size_t(blk) * nv + v];
      const Idx n = c;
      c = sum;
      sum += n;
    }
  }
  FanStart[nv] = sum;
  Fan.Allocate(size_t(sum), &Pool);
  Idx* const fan = Fan.data();
  forEachBlockTriangle(
    [fan](Idx* pos, const Idx* w, Idx t)
    {
      const Idx w0 = w[0], w1 = w[1], w2 = w[2];
      fan[pos[w0]++] = 3 * t;
      fan[pos[w1]++] = 3 * t + 1;
      fan[pos[w2]++] = 3 * t + 2;
    });
}

//------------------------------------------------------------------------------
// Fan members of a block of consecutive welded vertices (their corners are contiguous in
// Fan): per-member topology, the point and triangle ids CornerMath reads, and its results.
// Member indices are relative to the block; Link values are relative to the member's own
// vertex.
struct FanScratch
{
  struct Entry
  {
    Idx X;      // other vertex of the edge
    Idx Member; // fan member (relative to the vertex)
    uint8_t In; // 0: edge v->X (the member's edge i), 1: edge X->v (its edge i-1)
  };
  enum Row
  {
    Sx,
    Sy,
    Sz,
    Tx,
    Ty,
    Tz,
    Angle,
    Unused, // pads a block to 64 floats
    NumRows
  };
  // Math layout: blocks of kLanes members, each block NumRows rows of kLanes floats, so that
  // one member's values are at constant offsets and CornerMath stores whole rows.
  static constexpr size_t kLanes = 8;
  size_t Capacity = 0; // a multiple of kLanes
  // C: corner 3t+i of the member; X, Y: welded ids of the next and previous corner
  std::vector<Idx> C, X, Y, Link, Comp, Order, Stack, CompStart;
  // CornerMath input: triangle, point of the vertex, points of X and Y (only if some point
  // has a NaN, else X and Y are the points)
  std::vector<Idx> Tri, PV, PX, PY;
  std::vector<uint8_t> Flags;
  std::vector<float> Math; // CornerMath output: projected directions Tp, Bp and corner angle
  std::vector<Entry> Entries;
  std::vector<uint8_t> Paired;
  std::vector<Idx> SubList, SubStart, Members;
  std::vector<Frame> SubFrames;

  void Reserve(size_t k)
  {
    if (k <= Capacity)
    {
      return;
    }
    Capacity = std::max<size_t>(k + k / 2, 64);
    Capacity = (Capacity + kLanes - 1) & ~(kLanes - 1);
    C.resize(Capacity);
    X.resize(Capacity + 8); // PairEdges reads 8 members
    Y.resize(Capacity + 8);
    Tri.resize(Capacity);
    PV.resize(Capacity);
    PX.resize(Capacity);
    PY.resize(Capacity);
    Link.resize(2 * Capacity + 16); // PairEdges may clear 8 members' links
    Comp.resize(Capacity);
    Order.resize(Capacity);
    Stack.resize(Capacity + 1);
    Flags.resize(Capacity);
    Math.assign(NumRows * Capacity, 0.0f);
  }
  /// Member m's value of row 0; that of row r is at + r * kLanes.
  float* Lane(size_t m) { return Math.data() + (m / kLanes) * (NumRows * kLanes) + m % kLanes; }
  const float* Lane(size_t m) const
  {
    return Math.data() + (m / kLanes) * (NumRows * kLanes) + m % kLanes;
  }
  static V3 Get(const float* lane, int row)
  {
    const float* r = lane + size_t(row) * kLanes;
    return { r[0], r[kLanes], r[2 * kLanes] };
  }
  static void Set(float* lane, int row, const V3& v)
  {
    float* r = lane + size_t(row) * kLanes;
    r[0] = v.x;
    r[kLanes] = v.y;
    r[2 * kLanes] = v.z;
  }
  V3 Get(int row, size_t m) const { return Get(this->Lane(m), row); }
  void Set(int row, size_t m, const V3& v) { Set(this->Lane(m), row, v); }
  Idx TriOf(size_t m) const { return C[m] / 3; }
};

// Flags of all triangles of a fan or-ed (Any) and and-ed (All) together.
struct VertexFlags
{
  uint8_t Any = 0, All = 0xff;
};

// Members of vertex v (its fan), stored from block member o on: corner, triangle flags and the
// welded ids of the next (X) and previous (Y) corner of the triangle. With WithMath also the
// ids CornerMath reads: triangle, point of v and points of X and Y. Returns the fan's flags.
template<bool WithMath>
VertexFlags GatherMembers(const Kernel& K, Idx v, FanScratch& s, size_t o, Idx k)
{
  VertexFlags vf;
  const Idx* fan = &K.Fan[size_t(K.FanStart[size_t(v)])];
  const uint8_t* triFlags = K.TriFlags.data();
  const Idx* triWeld = K.TriWeld.data();
  Idx* cs = s.C.data() + o;
  Idx* xs = s.X.data() + o;
  Idx* ys = s.Y.data() + o;
  Idx* ts = s.Tri.data() + o;
  uint8_t* fs = s.Flags.data() + o;
  // offsets from corner 3t+i to corner 3t+(i+1)%3 and to 3t+(i+2)%3
  static constexpr int kToNext[3] = { 1, 1, -2 };
  static constexpr int kToPrev[3] = { 2, -1, -1 };
  for (Idx m = 0; m < k; ++m)
  {
    const Idx c = fan[m];
    const Idx t = c / 3, i = c - 3 * t;
    const uint8_t fl = triFlags[t];
    vf.Any = uint8_t(vf.Any | fl);
    vf.All = uint8_t(vf.All & fl);
    cs[m] = c;
    fs[m] = fl;
    xs[m] = triWeld[c + kToNext[i]];
    ys[m] = triWeld[c + kToPrev[i]];
    if (WithMath)
    {
      ts[m] = t;
    }
  }
  if (WithMath)
  {
    std::fill(s.PV.data() + o, s.PV.data() + o + k, K.PointOfWeld(v));
    if (K.AnyNaNPoint)
    {
      for (Idx m = 0; m < k; ++m)
      {
        s.PX[o + size_t(m)] = K.PointOfWeld(xs[m]);
        s.PY[o + size_t(m)] = K.PointOfWeld(ys[m]);
      }
    }
  }
  return vf;
}

inline Idx LowestSetBit(unsigned v) // v != 0
{
#if defined(__GNUC__) || defined(__clang__)
  return Idx(__builtin_ctz(v));
#else
  Idx i = 0;
  for (; !(v & 1u); v >>= 1)
  {
    ++i;
  }
  return i;
#endif
}

// Pairing of the k members from block member o: Link[2(o+m)] = member across m's edge
// v->next, Link[2(o+m)+1] = member across prev->v, -1 if none. The reference pairs the
// half-edges of one undirected edge in triangle order, each unpaired one with the first later
// unpaired one of opposite direction. All half-edges of an edge (v, x) are in the fan of v, so
// the rule can be evaluated locally. Fast path: at most one half-edge per direction.
#ifdef VTK_MIKK_AVX2
// The fast path of PairEdges for k <= 8 members in one AVX2 register; false if some edge has
// more than one half-edge in a direction (links then incomplete).
VTK_MIKK_AVX2_FN bool PairSmallAVX2(const Idx* X, const Idx* Y, Idx* link, Idx k)
{
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(link), _mm256_set1_epi32(-1));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(link + 8), _mm256_set1_epi32(-1));
  const __m256i xs = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(X));
  const __m256i ys = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(Y));
  const unsigned valid = (1u << k) - 1;
  for (Idx m = 0; m < k; ++m)
  {
    const __m256i x = _mm256_set1_epi32(X[m]);
    const unsigned in =
      unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(ys, x)))) & valid;
    if (in == 0)
    {
      continue;
    }
    const unsigned out =
      unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(xs, x)))) & valid;
    if ((in & (in - 1)) || (out & (out - 1)))
    {
      return false;
    }
    const Idx partner = Idx(__builtin_ctz(in));
    link[2 * m] = partner;
    link[2 * partner + 1] = m;
  }
  return true;
}
#endif

void PairEdges(FanScratch& s, size_t o, Idx k, bool avx2)
{
  const Idx* X = s.X.data() + o;
  const Idx* Y = s.Y.data() + o;
  Idx* link = s.Link.data() + 2 * o;
#ifdef VTK_MIKK_AVX2
  if (avx2 && k <= 8 && PairSmallAVX2(X, Y, link, k))
  {
    return;
  }
#else
  (void)avx2;
#endif
  std::fill(link, link + 2 * size_t(k), -1);
  bool simple = k <= 24;
#ifdef VTK_MIKK_SSE2
  if (k <= 8)
  {
    // the same test with 8 lanes (X and Y are readable up to member o + 8, see Reserve)
    const __m128i x0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(X));
    const __m128i x1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(X + 4));
    const __m128i y0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(Y));
    const __m128i y1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(Y + 4));
    const int valid = (1 << k) - 1;
    const auto lanes = [valid](__m128i a, __m128i b, __m128i v)
    {
      return (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(a, v))) |
               (_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(b, v))) << 4)) &
        valid;
    };
    for (Idx m = 0; m < k; ++m)
    {
      const __m128i x = _mm_set1_epi32(X[m]);
      const int in = lanes(y0, y1, x);
      if (in == 0)
      {
        continue;
      }
      const int out = lanes(x0, x1, x);
      if ((in & (in - 1)) || (out & (out - 1)))
      {
        simple = false;
        break;
      }
      const Idx partner = LowestSetBit(unsigned(in));
      link[2 * m] = partner;
      link[2 * partner + 1] = m;
    }
    if (simple)
    {
      return;
    }
  }
#endif
  for (Idx m = 0; m < k && simple; ++m)
  {
    const Idx x = X[m];
    int nIn = 0, nOut = 0;
    Idx partner = -1;
    for (Idx q = 0; q < k; ++q)
    {
      if (Y[q] == x)
      {
        ++nIn;
        partner = q;
      }
      nOut += X[q] == x;
    }
    if (nIn == 0)
    {
      continue;
    }
    if (nIn > 1 || nOut > 1)
    {
      simple = false;
      break;
    }
    link[2 * m] = partner;
    link[2 * partner + 1] = m;
  }
  if (simple)
  {
    return;
  }
  // general case: sort half-edges by (other vertex, member), pair greedily per edge
  std::fill(link, link + 2 * size_t(k), -1);
  s.Entries.resize(2 * size_t(k));
  for (Idx m = 0; m < k; ++m)
  {
    s.Entries[2 * size_t(m)] = { X[m], m, 0 };
    s.Entries[2 * size_t(m) + 1] = { Y[m], m, 1 };
  }
  std::sort(s.Entries.begin(),
    s.Entries.end(),
    [](const FanScratch::Entry& a, const FanScratch::Entry& b)
    { return a.X < b.X || (a.X == b.X && a.Member < b.Member); });
  const size_t ne = s.Entries.size();
  s.Paired.assign(ne, 0);
  for (size_t r0 = 0; r0 < ne;)
  {
    size_t r1 = r0 + 1;
    while (r1 < ne && s.Entries[r1].X == s.Entries[r0].X)
    {
      ++r1;
    }
    for (size_t a = r0; a < r1; ++a)
    {
      if (s.Paired[a])
      {
        continue;
      }
      for (size_t j = a + 1; j < r1; ++j)
      {
        if (!s.Paired[j] && s.Entries[j].In != s.Entries[a].In)
        {
          s.Paired[a] = s.Paired[j] = 1;
          const auto& ea = s.Entries[a];
          const auto& ej = s.Entries[j];
          link[2 * ea.Member + ea.In] = ej.Member;
          link[2 * ej.Member + ej.In] = ea.Member;
          break;
        }
      }
    }
    r0 = r1;
  }
}

//------------------------------------------------------------------------------
// The reference builds groups sequentially; the first group reaching a group-with-any (GWA)
// triangle that has no group yet gives it its orientation. Replay exactly that, restricted to
// vertices whose fan contains a GWA triangle (only those floods can reach one). Afterwards the
// groups everywhere are the same-orientation edge-connected components of each fan.
void Kernel::AdoptGroupWithAnyOrientation()
{
  const Idx nt = NumTris;
  std::vector<uint8_t> gwaVertex(size_t(NumVerts), 0);
  for (Idx t = 0; t < nt; ++t)
  {
    if ((TriFlags[size_t(t)] & (kExcluded | kGWA)) == kGWA)
    {
      for (int i = 0; i < 3; ++i)
      {
        gwaVertex[size_t(TriWeld[3 * size_t(t) + i])] = 1;
      }
    }
  }
  std::vector<uint8_t> assigned(3 * size_t(nt), 0);
  std::vector<Idx> stack;
  FanScratch s;
  for (Idx t = 0; t < nt; ++t)
  {
    if (TriFlags[size_t(t)] & (kExcluded | kGWA))
    {
      continue;
    }
    for (int i = 0; i < 3; ++i)
    {
      const Idx c = 3 * t + i;
      const Idx v = TriWeld[size_t(c)];
      if (!gwaVertex[size_t(v)] || assigned[size_t(c)])
      {
        continue;
      }
      const Idx* fan = &Fan[size_t(FanStart[size_t(v)])];
      const Idx k = FanStart[size_t(v) + 1] - FanStart[size_t(v)];
      s.Reserve(size_t(k));
      GatherMembers<false>(*this, v, s, 0, k);
      PairEdges(s, 0, k, UseAVX2);
      const Idx seed = Idx(std::lower_bound(fan, fan + k, c) - fan);
      const uint8_t orient = TriFlags[size_t(t)] & kOrient;
      assigned[size_t(c)] = 1;
      stack.assign(1, seed);
      while (!stack.empty())
      {
        const Idx m = stack.back();
        stack.pop_back();
        for (int side = 0; side < 2; ++side)
        {
          const Idx q = s.Link[2 * size_t(m) + side];
          if (q < 0)
          {
            continue;
          }
          const Idx cq = fan[q];
          if (assigned[size_t(cq)])
          {
            continue;
          }
          const Idx tq = cq / 3;
          uint8_t& fq = TriFlags[size_t(tq)];
          if ((fq & kGWA) && !assigned[3 * size_t(tq)] && !assigned[3 * size_t(tq) + 1] &&
            !assigned[3 * size_t(tq) + 2])
          {
            fq = uint8_t((fq & ~kOrient) | orient);
          }
          if ((fq & kOrient) != orient)
          {
            continue;
          }
          assigned[size_t(cq)] = 1;
          stack.push_back(q);
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
// Projected directions (Tp, Bp) and corner angle of every member, as in the reference's
// EvalTspace: n = vertex normal, Tp, Bp = the triangle's directions projected on the plane
// perpendicular to n and normalised, e1 = p_prev - p, e2 = p_next - p likewise, angle =
// acos(clamp(e1.e2)). Results for members of group-with-any triangles are computed but never
// used.

// Inputs of member j: directions, edges and normal (S, T, e1, e2, n).
struct CornerInputs
{
  V3 In[5];
};
inline CornerInputs LoadCornerInputs(const Kernel& K, const FanScratch& s, size_t j)
{
  const Idx t = s.Tri[j], pv = s.PV[j];
  const Idx px = K.AnyNaNPoint ? s.PX[j] : s.X[j];
  const Idx py = K.AnyNaNPoint ? s.PY[j] : s.Y[j];
  const V3 p = K.Pos(pv);
  return { { K.TriDir[2 * size_t(t)],
    K.TriDir[2 * size_t(t) + 1],
    Sub(K.Pos(py), p),
    Sub(K.Pos(px), p),
    K.Nrm(pv) } };
}

#ifdef VTK_MIKK_AVX2
VTK_MIKK_AVX2_FN inline V3x8 Sub8(const V3x8& a, const V3x8& b)
{
  return V3x8{ _mm256_sub_ps(a.x, b.x), _mm256_sub_ps(a.y, b.y), _mm256_sub_ps(a.z, b.z) };
}

// Members [0, count8), count8 a multiple of 8.
VTK_MIKK_AVX2_FN void CornerMathAVX2(const Kernel& K, FanScratch& s, size_t count8)
{
  const bool avx512 = K.UseAVX512;
  constexpr size_t L = FanScratch::kLanes;
  static_assert(L == 8, "one AVX2 register per block row");
  const float* dir = reinterpret_cast<const float*>(K.TriDir.data()); // 6 floats per triangle
  const float* P = K.In.Positions;
  const float* N = K.In.Normals;
  const Idx* px = K.AnyNaNPoint ? s.PX.data() : s.X.data();
  const Idx* py = K.AnyNaNPoint ? s.PY.data() : s.Y.data();
  for (size_t j = 0; j < count8; j += 8)
  {
    const Idx* tri = s.Tri.data() + j;
    const Idx* pv = s.PV.data() + j;
    const V3x8 nn = Load3x8(N, pv, 3);
    const V3x8 p = Load3x8(P, pv, 3);
    float* blk = s.Lane(j);
    Store8(blk + FanScratch::Sx * L, L, ProjectNormalize8(Load3x8(dir, tri, 6), nn));
    Store8(blk + FanScratch::Tx * L, L, ProjectNormalize8(Load3x8(dir + 3, tri, 6), nn));
    const V3x8 e1 = ProjectNormalize8(Sub8(Load3x8(P, py + j, 3), p), nn);
    const V3x8 e2 = ProjectNormalize8(Sub8(Load3x8(P, px + j, 3), p), nn);
    // clamp to [-1, 1] with the operand order of the SSE version (NaN stays NaN)
    const __m256 cosA =
      _mm256_max_ps(_mm256_set1_ps(-1.0f), _mm256_min_ps(_mm256_set1_ps(1.0f), Dot8(e1, e2)));
    float* angle = blk + FanScratch::Angle * L;
    if (avx512)
    {
      _mm256_storeu_ps(angle, cosA); // AnglesAVX512 below
    }
    else
    {
      AngleFromCos4(_mm256_cvtps_pd(_mm256_castps256_ps128(cosA)), angle);
      AngleFromCos4(_mm256_cvtps_pd(_mm256_extractf128_ps(cosA, 1)), angle + 4);
    }
  }
  if (avx512)
  {
    AnglesAVX512(s.Math.data(), count8, FanScratch::NumRows * L, FanScratch::Angle * L);
  }
}
#endif

// Members [0, count); members up to the next multiple of kLanes must have valid ids (the
// caller pads them).
void CornerMath(const Kernel& K, FanScratch& s, size_t count)
{
  constexpr size_t L = FanScratch::kLanes;
#ifdef VTK_MIKK_AVX2
  if (K.UseAVX2)
  {
    CornerMathAVX2(K, s, (count + L - 1) & ~(L - 1));
    return;
  }
#endif
#ifdef VTK_MIKK_SSE2
  for (size_t j = 0; j < count; j += 4)
  {
    CornerInputs in[4];
    for (size_t l = 0; l < 4; ++l)
    {
      in[l] = LoadCornerInputs(K, s, j + l);
    }
    const auto load = [&in](int q)
    {
      return V3x4{ _mm_setr_ps(in[0].In[q].x, in[1].In[q].x, in[2].In[q].x, in[3].In[q].x),
        _mm_setr_ps(in[0].In[q].y, in[1].In[q].y, in[2].In[q].y, in[3].In[q].y),
        _mm_setr_ps(in[0].In[q].z, in[1].In[q].z, in[2].In[q].z, in[3].In[q].z) };
    };
    float* blk = s.Lane(j); // 4 lanes of a block
    const auto store = [blk](int row, const V3x4& v)
    {
      float* r = blk + row * L;
      _mm_storeu_ps(r, v.x);
      _mm_storeu_ps(r + L, v.y);
      _mm_storeu_ps(r + 2 * L, v.z);
    };
    const V3x4 nn = load(4);
    store(FanScratch::Sx, ProjectNormalize4(load(0), nn));
    store(FanScratch::Tx, ProjectNormalize4(load(1), nn));
    const V3x4 e1 = ProjectNormalize4(load(2), nn);
    const V3x4 e2 = ProjectNormalize4(load(3), nn);
    // clamp to [-1, 1]; min/max return their second operand for NaN, which keeps NaN
    const __m128 cosA = _mm_max_ps(_mm_set1_ps(-1.0f), _mm_min_ps(_mm_set1_ps(1.0f), Dot4(e1, e2)));
    float* angle = blk + FanScratch::Angle * L;
    AngleFromCos2(_mm_cvtps_pd(cosA), angle);
    AngleFromCos2(_mm_cvtps_pd(_mm_movehl_ps(cosA, cosA)), angle + 2);
  }
#else
  for (size_t j = 0; j < count; ++j)
  {
    const CornerInputs in = LoadCornerInputs(K, s, j);
    const V3& n = in.In[4];
    const V3 e1 = ProjectNormalize(in.In[2], n);
    const V3 e2 = ProjectNormalize(in.In[3], n);
    s.Set(FanScratch::Sx, j, ProjectNormalize(in.In[0], n));
    s.Set(FanScratch::Tx, j, ProjectNormalize(in.In[1], n));
    float cosA = Dot(e1, e2);
    cosA = cosA > 1 ? 1 : (cosA < -1 ? -1 : cosA);
    s.Lane(j)[FanScratch::Angle * L] = AngleFromCos(cosA);
  }
#endif
}

//------------------------------------------------------------------------------
struct VertexWorker
{
  Kernel& K;
  vtkSMPThreadLocal<FanScratch> Scratch;
  static constexpr Idx kBlock = 64; // vertices per math batch

  explicit VertexWorker(Kernel& k)
    : K(k)
  {
  }

  bool SameFace(Idx ta, Idx tb) const
  {
    if (ta == tb)
    {
      return true;
    }
    // triangles of one face share a face corner; different faces never do
    Idx a[3], b[3];
    for (int i = 0; i < 3; ++i)
    {
      a[i] = K.SlotOf(3 * ta + i);
      b[i] = K.SlotOf(3 * tb + i);
    }
    for (int i = 0; i < 3; ++i)
    {
      if (a[i] == b[0] || a[i] == b[1] || a[i] == b[2])
      {
        return true;
      }
    }
    return false;
  }

  // Angle-weighted average over the non-GWA block members listed (ascending triangle order).
  // Only the tangent S reaches the output of a corner written by one triangle; the bitangent
  // and the magnitudes matter only where several triangles write one face corner (AvgFrame),
  // so they are accumulated only if the mesh has such corners (AnyMulti).
  Frame Eval(const FanScratch& s, const Idx* members, size_t count) const
  {
    return K.AnyMulti ? EvalMembers<true>(
                          s, [members](size_t j) { return size_t(members[j]); }, count)
                      : EvalMembers<false>(
                          s, [members](size_t j) { return size_t(members[j]); }, count);
  }
  // The same over the consecutive block members o..o+count-1.
  Frame EvalRange(const FanScratch& s, size_t o, size_t count) const
  {
    return K.AnyMulti ? EvalMembers<true>(
                          s, [o](size_t j) { return o + j; }, count)
                      : EvalMembers<false>(
                          s, [o](size_t j) { return o + j; }, count);
  }
  template<bool Full, typename MemberOf>
  Frame EvalMembers(const FanScratch& s, MemberOf memberOf, size_t count) const
  {
    Frame r{ { 0, 0, 0 }, { 0, 0, 0 }, 0, 0 };
    float angleSum = 0;
    for (size_t j = 0; j < count; ++j)
    {
      const size_t m = memberOf(j);
      if (s.Flags[m] & kGWA)
      {
        continue;
      }
      const float* lane = s.Lane(m);
      const float a = lane[FanScratch::Angle * FanScratch::kLanes];
      r.S = Add(r.S, Scale(FanScratch::Get(lane, FanScratch::Sx), a));
      if (Full)
      {
        r.T = Add(r.T, Scale(FanScratch::Get(lane, FanScratch::Tx), a));
        const Idx t = s.TriOf(m);
        r.MagS += a * K.TriMag[2 * size_t(t)];
        r.MagT += a * K.TriMag[2 * size_t(t) + 1];
        angleSum += a;
      }
    }
    if (VNotZero(r.S))
    {
      r.S = Normalize(r.S);
    }
    if (Full)
    {
      if (VNotZero(r.T))
      {
        r.T = Normalize(r.T);
      }
      if (angleSum > 0)
      {
        r.MagS /= angleSum;
        r.MagT /= angleSum;
      }
    }
    return r;
  }

  void Write(const FanScratch& s, size_t m, const Frame& f, uint8_t orient, Idx key) const
  {
    const Idx c = s.C[m];
    const Idx i = c - 3 * (c / 3);
    if (s.Flags[m] & (kMulti0 << i))
    {
      SideFrame& sf = K.Side[size_t(c)];
      sf.F = f;
      sf.Key = key;
      sf.Orient = orient;
    }
    else
    {
      CornerFrame& o = K.Out[size_t(K.SlotOf(c))];
      o.Tangent[0] = f.S.x;
      o.Tangent[1] = f.S.y;
      o.Tangent[2] = f.S.z;
      o.Sign = orient ? 1.0f : -1.0f;
    }
  }

  // Fast path of Resolve: all k members in one group (one orientation, edge-connected, no GWA
  // triangle) whose directions pass the sub-group quick test (see Resolve). Returns false,
  // having written nothing, if that does not hold.
  bool ResolveOneGroup(const FanScratch& s, size_t o, Idx k) const
  {
    const uint8_t orient = s.Flags[o] & kOrient;
    const V3 t0 = s.Get(FanScratch::Sx, o), b0 = s.Get(FanScratch::Tx, o);
    if (K.AnyMulti)
    {
      for (size_t j = o; j < o + size_t(k); ++j)
      {
        const float* lane = s.Lane(j);
        if (!(Dot(t0, FanScratch::Get(lane, FanScratch::Sx)) > 0.01f &&
              Dot(b0, FanScratch::Get(lane, FanScratch::Tx)) > 0.01f))
        {
          return false;
        }
      }
      const Frame f = EvalRange(s, o, size_t(k));
      for (size_t j = o; j < o + size_t(k); ++j)
      {
        Write(s, j, f, orient, s.C[o]);
      }
      return true;
    }
    // the quick test and EvalMembers<false> in one pass
    V3 sum{ 0, 0, 0 };
    for (size_t j = o; j < o + size_t(k); ++j)
    {
      const float* lane = s.Lane(j);
      const V3 tp = FanScratch::Get(lane, FanScratch::Sx);
      if (!(Dot(t0, tp) > 0.01f && Dot(b0, FanScratch::Get(lane, FanScratch::Tx)) > 0.01f))
      {
        return false;
      }
      sum = Add(sum, Scale(tp, lane[FanScratch::Angle * FanScratch::kLanes]));
    }
    if (VNotZero(sum))
    {
      sum = Normalize(sum);
    }
    if (!(Finite(sum.x) && Finite(sum.y) && Finite(sum.z)))
    {
      K.FinishScanNeeded.store(true, std::memory_order_relaxed); // Finish replaces them
    }
    const CornerFrame frame = { { sum.x, sum.y, sum.z }, orient ? 1.0f : -1.0f };
    const Idx* cs = s.C.data() + o;
    if (K.IdentitySlots)
    {
      for (Idx m = 0; m < k; ++m)
      {
        K.Out[size_t(cs[m])] = frame;
      }
    }
    else
    {
      for (Idx m = 0; m < k; ++m)
      {
        K.Out[size_t(K.TriSlot[size_t(cs[m])])] = frame;
      }
    }
    return true;
  }

  // Groups of vertex v (block members o..o+k-1, math done) and their frames.
  void Resolve(FanScratch& s, size_t o, Idx k, VertexFlags vf) const
  {
    PairEdges(s, o, k, K.UseAVX2);
    const Idx* link = s.Link.data() + 2 * o;
    const uint8_t* flags = s.Flags.data() + o;
    Idx* comp = s.Comp.data() + o;
    Idx* order = s.Order.data() + o; // block member indices ordered by (component, triangle)
    Idx* stack = s.Stack.data();
    // components: same orientation, edge-connected around v
    Idx numComps = 0;
    // common case: one orientation and one chain or cycle of edge neighbours (links are
    // symmetric, link[2a] == b <=> link[2b+1] == a, so walking both ways from member 0 visits
    // exactly its component)
    if (!((vf.Any ^ vf.All) & kOrient))
    {
      Idx visited = 1;
      Idx m = link[0];
      while (m > 0 && visited <= k)
      {
        ++visited;
        m = link[2 * m];
      }
      if (m != 0)
      {
        for (m = link[1]; m >= 0 && visited <= k; m = link[2 * m + 1])
        {
          ++visited;
        }
      }
      numComps = visited == k ? 1 : 0;
      if (numComps == 1 && !(vf.Any & kGWA) && ResolveOneGroup(s, o, k))
      {
        return;
      }
    }
    // the general path may leave corners unwritten or non-finite: Finish must look
    K.FinishScanNeeded.store(true, std::memory_order_relaxed);
    const bool oneChain = numComps == 1;
    if (!oneChain)
    {
      std::fill(comp, comp + k, -1);
    }
    for (Idx m = 0; m < k && !oneChain; ++m)
    {
      if (comp[m] >= 0)
      {
        continue;
      }
      const uint8_t orient = flags[m] & kOrient;
      const Idx id = numComps++;
      comp[m] = id;
      Idx top = 0;
      stack[top++] = m;
      while (top > 0)
      {
        const Idx q = stack[--top];
        for (int side = 0; side < 2; ++side)
        {
          const Idx r = link[2 * q + side];
          if (r >= 0 && comp[r] < 0 && (flags[r] & kOrient) == orient)
          {
            comp[r] = id;
            stack[top++] = r;
          }
        }
      }
    }
    if (numComps == 1)
    {
      for (Idx m = 0; m < k; ++m)
      {
        order[m] = Idx(o) + m;
      }
      s.CompStart.assign({ 0, k });
    }
    else
    {
      s.CompStart.assign(size_t(numComps) + 1, 0);
      for (Idx m = 0; m < k; ++m)
      {
        ++s.CompStart[size_t(comp[m]) + 1];
      }
      for (Idx g = 0; g < numComps; ++g)
      {
        s.CompStart[size_t(g) + 1] += s.CompStart[size_t(g)];
      }
      for (Idx g = 0; g < numComps; ++g)
      {
        stack[g] = s.CompStart[size_t(g)];
      }
      for (Idx m = 0; m < k; ++m)
      {
        order[stack[comp[m]]++] = Idx(o) + m;
      }
    }
    for (Idx g = 0; g < numComps; ++g)
    {
      const Idx* members = order + s.CompStart[size_t(g)];
      const size_t count = size_t(s.CompStart[size_t(g) + 1] - s.CompStart[size_t(g)]);
      size_t first = ~size_t(0);
      for (size_t j = 0; j < count; ++j)
      {
        if (!(s.Flags[size_t(members[j])] & kGWA))
        {
          first = size_t(members[j]);
          break;
        }
      }
      if (first == ~size_t(0))
      {
        continue; // only GWA triangles: never seeded, corners stay default
      }
      const Idx key = s.C[first];
      const uint8_t orient = s.Flags[first] & kOrient;
      // Sub-groups (threshold cos = -1): two non-GWA triangles of different faces are split
      // only if their projected directions have cos <= -1 (or NaN). Quick sufficient test:
      // every member within 89.4 degrees of the first one (cos > 0.01) keeps every pair below
      // 179 degrees, i.e. cos > -0.9998, far from -1 even with float rounding (~1e-6).
      const V3 t0 = s.Get(FanScratch::Sx, first), b0 = s.Get(FanScratch::Tx, first);
      bool single = true;
      for (size_t j = 0; j < count && single; ++j)
      {
        const size_t m = size_t(members[j]);
        if (s.Flags[m] & kGWA)
        {
          continue;
        }
        single =
          Dot(t0, s.Get(FanScratch::Sx, m)) > 0.01f && Dot(b0, s.Get(FanScratch::Tx, m)) > 0.01f;
      }
      if (single)
      {
        const Frame f = Eval(s, members, count);
        for (size_t j = 0; j < count; ++j)
        {
          Write(s, size_t(members[j]), f, orient, key);
        }
      }
      else
      {
        GeneralSubgroups(s, members, count, orient, key);
      }
    }
  }

  // The reference's sub-group construction: the member list of triangle f is every member t
  // with (either GWA) or (same face) or (cosS > -1 and cosT > -1); equal lists share a frame.
  void GeneralSubgroups(FanScratch& s,
    const Idx* members,
    size_t count,
    uint8_t orient,
    Idx key) const
  {
    s.SubList.clear();
    s.SubStart.assign(1, 0);
    s.SubFrames.clear();
    for (size_t a = 0; a < count; ++a)
    {
      const size_t mf = size_t(members[a]);
      const Idx tf = s.TriOf(mf);
      const bool gwaF = (s.Flags[mf] & kGWA) != 0;
      s.Members.clear();
      for (size_t j = 0; j < count; ++j)
      {
        const size_t mt = size_t(members[j]);
        const bool any = gwaF || (s.Flags[mt] & kGWA);
        bool join = any || SameFace(tf, s.TriOf(mt));
        if (!join)
        {
          const float cosS = Dot(s.Get(FanScratch::Sx, mf), s.Get(FanScratch::Sx, mt));
          const float cosT = Dot(s.Get(FanScratch::Tx, mf), s.Get(FanScratch::Tx, mt));
          join = cosS > -1.0f && cosT > -1.0f;
        }
        if (join)
        {
          s.Members.push_back(Idx(mt));
        }
      }
      // look for an identical list
      size_t found = s.SubFrames.size();
      for (size_t g = 0; g < s.SubFrames.size(); ++g)
      {
        const size_t b = size_t(s.SubStart[g]), e = size_t(s.SubStart[g + 1]);
        if (e - b == s.Members.size() &&
          std::equal(s.Members.begin(), s.Members.end(), s.SubList.begin() + long(b)))
        {
          found = g;
          break;
        }
      }
      if (found == s.SubFrames.size())
      {
        s.SubFrames.push_back(Eval(s, s.Members.data(), s.Members.size()));
        s.SubList.insert(s.SubList.end(), s.Members.begin(), s.Members.end());
        s.SubStart.push_back(Idx(s.SubList.size()));
      }
      Write(s, mf, s.SubFrames[found], orient, key);
    }
  }

  void operator()(vtkIdType b, vtkIdType e)
  {
    FanScratch& s = this->Scratch.Local();
    for (Idx vb = Idx(b); vb < Idx(e); vb += kBlock)
    {
      const Idx ve = std::min(Idx(e), vb + kBlock);
      const Idx f0 = K.FanStart[size_t(vb)];
      const size_t total = size_t(K.FanStart[size_t(ve)] - f0);
      if (total == 0)
      {
        continue;
      }
      const size_t padded = (total + FanScratch::kLanes - 1) & ~(FanScratch::kLanes - 1);
      s.Reserve(padded);
      VertexFlags vertexFlags[kBlock];
      for (Idx v = vb; v < ve; ++v)
      {
        const Idx k = K.FanStart[size_t(v) + 1] - K.FanStart[size_t(v)];
        if (k > 0)
        {
          vertexFlags[v - vb] = GatherMembers<true>(K, v, s, size_t(K.FanStart[size_t(v)] - f0), k);
        }
      }
      // CornerMath reads whole blocks: the padding members get valid ids (member 0's)
      for (size_t j = total; j < padded; ++j)
      {
        s.Tri[j] = s.Tri[0];
        s.PV[j] = s.PV[0];
        s.X[j] = s.X[0];
        s.Y[j] = s.Y[0];
        s.PX[j] = s.PX[0];
        s.PY[j] = s.PY[0];
      }
      CornerMath(K, s, total);
      for (Idx v = vb; v < ve; ++v)
      {
        const Idx k = K.FanStart[size_t(v) + 1] - K.FanStart[size_t(v)];
        if (k > 0)
        {
          Resolve(s, size_t(K.FanStart[size_t(v)] - f0), k, vertexFlags[v - vb]);
        }
      }
    }
  }
};

void Kernel::ProcessVertices()
{
  if (AnyMulti)
  {
    Side.Assign(3 * size_t(NumTris), SideFrame{ {}, -1, 0 }, &Pool);
  }
  VertexWorker worker(*this);
  ParallelFor(NumVerts, 4 * VertexWorker::kBlock, worker);
}

//------------------------------------------------------------------------------
// Face corners written by several triangles: the reference's pairwise average, applied in
// group creation order (then triangle order); the sign is that of the last group.
void Kernel::MergeMultiWriters()
{
  ParallelFor(NumFaceChunks,
    1,
    [&](vtkIdType cb, vtkIdType ce)
    {
      struct Contribution
      {
        Idx Slot, Key, Corner;
      };
      std::vector<Contribution> list;
      for (vtkIdType c = cb; c < ce; ++c)
      {
        this->ForEachTriangulatedFace(c,
          [&](long long b, long long e, Idx t)
          {
            const Idx nTri = Idx(e - b - 2);
            if (nTri == 1 || (TriFlags[size_t(t)] & kDead))
            {
              return;
            }
            list.clear();
            for (Idx u = t; u < t + nTri; ++u)
            {
              for (int i = 0; i < 3; ++i)
              {
                const Idx corner = 3 * u + i;
                if ((TriFlags[size_t(u)] & (kMulti0 << i)) && Side[size_t(corner)].Key >= 0)
                {
                  list.push_back({ SlotOf(corner), Side[size_t(corner)].Key, corner });
                }
              }
            }
            std::sort(list.begin(),
              list.end(),
              [](const Contribution& x, const Contribution& y)
              {
                return x.Slot < y.Slot ||
                  (x.Slot == y.Slot && (x.Key < y.Key || (x.Key == y.Key && x.Corner < y.Corner)));
              });
            for (size_t r0 = 0; r0 < list.size();)
            {
              size_t r1 = r0 + 1;
              Frame fr = Side[size_t(list[r0].Corner)].F;
              uint8_t orient = Side[size_t(list[r0].Corner)].Orient;
              while (r1 < list.size() && list[r1].Slot == list[r0].Slot)
              {
                const SideFrame& sf = Side[size_t(list[r1].Corner)];
                fr = AvgFrame(fr, sf.F);
                orient = sf.Orient;
                ++r1;
              }
              CornerFrame& o = Out[size_t(list[r0].Slot)];
              o.Tangent[0] = fr.S.x;
              o.Tangent[1] = fr.S.y;
              o.Tangent[2] = fr.S.z;
              o.Sign = orient ? 1.0f : -1.0f;
              r0 = r1;
            }
          });
      }
    });
}

//------------------------------------------------------------------------------
// Degenerate triangles copy the frame of the first good corner with the same welded vertex;
// in a quad with one degenerate triangle the corner missing from the good triangle copies the
// good triangle's corner with the same position. Sources are always corners of good
// triangles, which this pass never writes.
void Kernel::CopyDegenerates()
{
  ParallelFor(NumFaceChunks,
    1,
    [&](vtkIdType cb, vtkIdType ce)
    {
      std::vector<uint8_t> covered;
      for (vtkIdType c = cb; c < ce; ++c)
      {
        this->ForEachTriangulatedFace(c,
          [&](long long b, long long e, Idx t)
          {
            const long long n = e - b;
            const Idx nTri = Idx(n - 2);
            bool anyDegenerate = false;
            for (Idx u = t; u < t + nTri; ++u)
            {
              anyDegenerate = anyDegenerate || (TriFlags[size_t(u)] & kDegenerate);
            }
            if (!anyDegenerate || (TriFlags[size_t(t)] & kDead))
            {
              return;
            }
            if (n == 4 && (TriFlags[size_t(t)] & kOneDegenQuad))
            {
              const Idx good = (TriFlags[size_t(t)] & kDegenerate) ? t + 1 : t;
              const Idx gs[3] = { SlotOf(3 * good), SlotOf(3 * good + 1), SlotOf(3 * good + 2) };
              Idx missing = Idx(b);
              while (missing == gs[0] || missing == gs[1] || missing == gs[2])
              {
                ++missing;
              }
              const V3 dst = Pos(Idx(Conn[missing]));
              for (int i = 0; i < 3; ++i)
              {
                if (Veq(Pos(Idx(Conn[gs[i]])), dst))
                {
                  Out[size_t(missing)] = Out[size_t(gs[i])];
                  break;
                }
              }
              return;
            }
            if (n > 4)
            {
              covered.assign(size_t(n), 0);
              for (Idx u = t; u < t + nTri; ++u)
              {
                if (!(TriFlags[size_t(u)] & kDegenerate))
                {
                  for (int i = 0; i < 3; ++i)
                  {
                    covered[size_t(SlotOf(3 * u + i) - b)] = 1;
                  }
                }
              }
            }
            for (Idx u = t; u < t + nTri; ++u)
            {
              if (!(TriFlags[size_t(u)] & kDegenerate))
              {
                continue;
              }
              for (int i = 0; i < 3; ++i)
              {
                const Idx slot = SlotOf(3 * u + i);
                if (n > 4 && covered[size_t(slot - b)])
                {
                  continue;
                }
                const Idx w = TriWeld[3 * size_t(u) + i];
                if (FanStart[size_t(w) + 1] > FanStart[size_t(w)])
                {
                  const Idx src = SlotOf(Fan[size_t(FanStart[size_t(w)])]);
                  Out[size_t(slot)] = Out[size_t(src)];
                }
              }
            }
          });
      }
    });
}

//------------------------------------------------------------------------------
void Kernel::Finish(Result& res)
{
  const size_t ns = size_t(NumSlots);
  const size_t chunk = 65536;
  const size_t numChunks = (ns + chunk - 1) / chunk;
  std::vector<long long> defaults(numChunks, 0), nonFinite(numChunks, 0);
  CornerFrame* out = Out;
  ParallelFor(vtkIdType(numChunks),
    1,
    [&](vtkIdType cb, vtkIdType ce)
    {
      for (vtkIdType c = cb; c < ce; ++c)
      {
        long long nd = 0, nn = 0;
        const size_t e = std::min(ns, size_t(c + 1) * chunk);
        for (size_t s = size_t(c) * chunk; s < e; ++s)
        {
          CornerFrame& o = out[s];
#ifdef VTK_MIKK_SSE2
          {
            // quick test: no lane Inf/NaN and Sign != 0
            const __m128 v = _mm_loadu_ps(o.Tangent);
            const __m128i expMask = _mm_set1_epi32(0x7f800000);
            const __m128i e = _mm_and_si128(_mm_castps_si128(v), expMask);
            const int special = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(e, expMask))) |
              (_mm_movemask_ps(_mm_cmpeq_ps(v, _mm_setzero_ps())) & 8);
            if (!special)
            {
              continue;
            }
          }
#endif
          if (o.Sign == 0.0f)
          {
            o = DefaultCornerFrame;
            ++nd;
          }
          else if (!(Finite(o.Tangent[0]) && Finite(o.Tangent[1]) && Finite(o.Tangent[2])))
          {
            o = DefaultCornerFrame;
            ++nd;
            ++nn;
          }
        }
        defaults[size_t(c)] = nd;
        nonFinite[size_t(c)] = nn;
      }
    });
  for (size_t c = 0; c < numChunks; ++c)
  {
    res.NumberOfDefaultCorners += defaults[c];
    res.NumberOfNonFiniteCorners += nonFinite[c];
  }
}

//------------------------------------------------------------------------------
std::atomic<InstructionSet> MaximumInstructionSet{ InstructionSet::AVX512 };

// The best instruction set up to `maximum` that the CPU and this build have.
InstructionSet UsableInstructionSet(InstructionSet maximum)
{
#ifdef VTK_MIKK_AVX2
  if (maximum >= InstructionSet::AVX512 && HaveAVX512())
  {
    return InstructionSet::AVX512;
  }
  if (maximum >= InstructionSet::AVX2 && HaveAVX2())
  {
    return InstructionSet::AVX2;
  }
#else
  (void)maximum;
#endif
  return InstructionSet::Baseline;
}

//------------------------------------------------------------------------------
Result Compute(const MeshInput& in, const std::function<bool(double)>& progress)
{
  Result res;
  auto aborted = [&](double p)
  {
    if (progress && progress(p))
    {
      res.Aborted = true;
      std::fill(res.Corners.begin(), res.Corners.end(), DefaultCornerFrame);
      res.NumberOfDefaultCorners = static_cast<long long>(res.Corners.size());
      return true;
    }
    return false;
  };
  if (in.NumberOfFaces <= 0 || !in.FaceOffsets)
  {
    return res;
  }
  const long long numSlots = std::max(0LL, in.FaceOffsets[in.NumberOfFaces]);
  // Sign 0 marks a corner not written yet (see Finish)
  res.Corners.reserve(size_t(numSlots));
  AdviseHugePages(res.Corners.data(), size_t(numSlots) * sizeof(CornerFrame));
  // value-initialisation (all +0) compiles to memset, unlike resize(n, value)
  res.Corners.resize(size_t(numSlots));
  const long long limit = std::numeric_limits<Idx>::max() - 16;
  const long long numPoints = std::max(0LL, in.NumberOfPoints);
  if (numSlots > limit / 3 || numPoints > limit - 3 * numSlots)
  {
    res.TooLarge = true;
    std::fill(res.Corners.begin(), res.Corners.end(), DefaultCornerFrame);
    res.NumberOfDefaultCorners = numSlots;
    return res;
  }
  if (numSlots == 0)
  {
    // Only faces without corners: nothing to compute, and their (empty) connectivity may be a
    // null pointer, which is no reason to call them invalid.
    res.NumberOfSkippedFaces = in.NumberOfFaces;
    return res;
  }
  if (!in.FaceConnectivity || !in.Positions || !in.Normals || !in.TCoords)
  {
    std::fill(res.Corners.begin(), res.Corners.end(), DefaultCornerFrame);
    res.NumberOfDefaultCorners = numSlots;
    res.NumberOfInvalidFaces = in.NumberOfFaces;
    return res;
  }

  Kernel K(in);
  K.NumPoints = Idx(numPoints);
  K.NumSlots = Idx(numSlots);
  K.Off = in.FaceOffsets;
  K.Conn = in.FaceConnectivity;
  K.Out = res.Corners.data();
  K.NumBlocks = std::min(8, vtkNormalMapping::detail::UsableThreads());
#ifdef VTK_MIKK_AVX2
  const InstructionSet isa = UsableInstructionSet(MaximumInstructionSet.load());
  K.UseAVX2 = isa >= InstructionSet::AVX2;
  K.UseAVX512 = isa >= InstructionSet::AVX512;
#endif

  if (aborted(0.0))
  {
    return res;
  }
  K.Weld();
  if (aborted(0.15))
  {
    return res;
  }
  K.BuildTriangles();
  if (aborted(0.4))
  {
    return res;
  }
  K.BuildFans();
  if (aborted(0.5))
  {
    return res;
  }
  if (K.NumGWA > 0)
  {
    K.AdoptGroupWithAnyOrientation();
  }
  K.ProcessVertices();
  if (aborted(0.9))
  {
    return res;
  }
  if (K.AnyMulti)
  {
    K.MergeMultiWriters();
  }
  if (K.NumDegenerate > 0)
  {
    K.CopyDegenerates();
  }
  // Finish looks for corners left unwritten (Sign 0) or non-finite. There are none if every
  // vertex took the fast path with a finite frame and no triangle was degenerate, GWA, dead or
  // part of a larger face, and no face was skipped.
  if (K.FinishScanNeeded.load() || K.NumDegenerate > 0 || K.NumGWA > 0 || K.NumSkipped > 0 ||
    K.NumInvalid > 0 || K.AnyMulti)
  {
    K.Finish(res);
  }
  res.NumberOfDegenerateTriangles = K.NumDegenerate;
  res.NumberOfGroupWithAnyTriangles = K.NumGWA;
  res.NumberOfSkippedFaces = K.NumSkipped;
  res.NumberOfInvalidFaces = K.NumInvalid;
  if (progress)
  {
    progress(1.0);
  }
  return res;
}

} // namespace

//------------------------------------------------------------------------------
InstructionSet CurrentInstructionSet()
{
  return UsableInstructionSet(MaximumInstructionSet.load());
}

InstructionSet LimitInstructionSet(InstructionSet maximum)
{
  MaximumInstructionSet.store(maximum);
  return UsableInstructionSet(maximum);
}

//------------------------------------------------------------------------------
Result ComputeMikkTSpace(const MeshInput& in,
  int numThreads,
  const std::function<bool(double progress)>& progressAndAbort)
{
  if (numThreads > 0)
  {
    // VTK 9.1's TBB backend ignores a LocalScope whose thread count equals that of the previous
    // LocalScope (the second of two consecutive 1-thread scopes runs on all threads). Entering
    // a scope with a different count first makes the requested one take effect every time.
    Result res;
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ numThreads == 1 ? 2 : 1 },
      [&]()
      {
        vtkSMPTools::LocalScope(
          vtkSMPTools::Config{ numThreads }, [&]() { res = Compute(in, progressAndAbort); });
      });
    return res;
  }
  return Compute(in, progressAndAbort);
}

} // namespace mikk
} // namespace vtkNormalMapping
