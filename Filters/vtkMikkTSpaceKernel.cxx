// SPDX-License-Identifier: BSD-3-Clause
// MikkTSpace-compatible tangent kernel, written from a description of the reference
// mikktspace.c's behaviour; see vtkMikkTSpaceKernel.h for the contract.
//
// Phases (parallel with vtkSMPTools unless noted):
//  1. Weld points: a hash of the 8 values per point (parallel), a radix sort by hash and an
//     exact comparison within equal hashes (sequential) give every point the smallest point id
//     with equal values (==, so -0 == +0). Points with a NaN never weld: each face corner using
//     one gets its own welded id.
//  2. Faces -> triangles: a count of the triangles per chunk of faces (sequential), then the
//     quad diagonal rule, fans, degeneracy, per-triangle frame, quad orientation forcing.
//  3. Counting sort (sequential) of the corners of non-degenerate triangles by welded id: the
//     "fan" of every welded vertex, in ascending corner order.
//  4. Only if zero-UV-area ("group with any", GWA) triangles exist: sequential replay of the
//     reference's group flood at the vertices touching them, which fixes their orientation.
//  5. Per welded vertex: edge pairing, groups (same-orientation edge-connected components of
//     the fan), projected directions and corner angles, angle-weighted sums in ascending
//     triangle order, sub-groups, corner frames.
//  6. Per face: corners written by several triangles (quad diagonals, fan corners) take the
//     reference's pairwise average; degenerate triangles copy; unreached or non-finite corners
//     get the default frame.
//
// Triangle order is the input order; the reference's "good triangle" order is that order with
// degenerate triangles removed, so every order-dependent rule (group seeds, accumulation order,
// edge pairing, first good corner for degenerate copies) is unchanged.

#include "vtkMikkTSpaceKernel.h"

#include "vtkNormalMappingMultiversioning.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <tuple>

// The reference rounds every float operation separately; a fused multiply-add changes results
// in the last bits. The build adds -ffp-contract=off for GCC and Clang (GCC ignores the STDC
// pragma); the pragma covers other compilers.
#if defined(_MSC_VER) && !defined(__clang__)
#pragma fp_contract(off)
#elif !defined(__GNUC__) || defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#endif

namespace vtkNormalMapping
{
namespace mikk
{
namespace
{
using Idx = int32_t;

constexpr float kFltMin = std::numeric_limits<float>::min(); // the reference's NotZero bound

// Triangle flags
constexpr uint8_t kDegenerate = 1; // two equal corner positions
constexpr uint8_t kDead = 2;       // face skipped (bad ids)
constexpr uint8_t kGWA = 4;        // group with any: no direction contribution, never seeds
constexpr uint8_t kOrient = 8;     // positive UV orientation
constexpr uint8_t kMulti0 = 32;    // (kMulti0 << i): corner i's face corner has several writers
constexpr uint8_t kExcluded = kDegenerate | kDead;

//------------------------------------------------------------------------------
bool NotZero(float f)
{
  return std::fabs(f) > kFltMin;
}

// Float vector, evaluated as the reference does (left-to-right sums, every operation rounded).
struct V3
{
  float x, y, z;
  static V3 At(const float* a, size_t i) { return { a[3 * i], a[3 * i + 1], a[3 * i + 2] }; }
  V3 operator+(const V3& b) const { return { x + b.x, y + b.y, z + b.z }; }
  V3 operator-(const V3& b) const { return { x - b.x, y - b.y, z - b.z }; }
  V3 operator*(float s) const { return { x * s, y * s, z * s }; }
  bool operator==(const V3& b) const { return x == b.x && y == b.y && z == b.z; }
  float Dot(const V3& b) const { return x * b.x + y * b.y + z * b.z; }
  bool NotZero() const { return mikk::NotZero(x) || mikk::NotZero(y) || mikk::NotZero(z); }
  bool Finite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
  // v / |v|, unless v is (numerically) zero
  V3 Normalized() const { return NotZero() ? *this * (1.0f / std::sqrt(Dot(*this))) : *this; }
};

//------------------------------------------------------------------------------
// Tangent and bitangent directions with their magnitudes: a triangle corner's contribution,
// or a group's angle-weighted average.
struct Frame
{
  V3 S, T;
  float MagS, MagT;
};

// Frame of a triangle corner whose face corner has several writers, kept until they merge.
struct PendingFrame
{
  Frame F;
  Idx Seed; // seed corner of the group (group creation order); -1: not written
  uint8_t Orient;
};

// The reference's average of two frames written to one face corner.
Frame Average(const Frame& a, const Frame& b)
{
  if (a.MagS == b.MagS && a.MagT == b.MagT && a.S == b.S && a.T == b.T)
  {
    return a;
  }
  return { (a.S + b.S).Normalized(),
    (a.T + b.T).Normalized(),
    0.5f * (a.MagS + b.MagS),
    0.5f * (a.MagT + b.MagT) };
}

CornerFrame ToCornerFrame(const V3& tangent, uint8_t orient)
{
  return { { tangent.x, tangent.y, tangent.z }, orient ? 1.0f : -1.0f };
}

//------------------------------------------------------------------------------
// One member of a welded vertex's fan: a corner of a non-degenerate triangle at that vertex.
struct Member
{
  Idx Corner;     // 3 t + i
  Idx Next, Prev; // welded ids of the triangle's next and previous corner
  Idx Link[2];    // member across the edge vertex->Next, across Prev->vertex; -1: none
  Idx Group;      // same-orientation edge-connected component
  uint8_t Flags;  // of the triangle
  // The triangle's directions projected on the vertex's tangent plane and normalised
  // (CornerMath), its magnitudes, and the corner angle (0 for GWA members, which never
  // contribute).
  V3 S, T;
  float MagS, MagT, Angle;
};

// Per-thread scratch of the vertex phase (and of the sequential FloodGroup).
struct Scratch
{
  std::vector<Member> Members; // the fan of the vertex at hand
  std::vector<uint64_t> Edges; // half-edges of PairEdges
  std::vector<float> XYZ;      // vectors to project, see CornerMath
  std::vector<Idx> Order, Stack;
  // GeneralSubgroups: the non-GWA members of a group, the members one list leaves out and those
  // it keeps, and the frame of each sub-group by the members its list leaves out
  std::vector<Idx> Contributors, LeftOut, Kept;
  std::map<std::vector<Idx>, Frame> Subgroups;
};

// PairEdges for a small fan: each member's unpaired half-edges take the first later unpaired
// half-edge of opposite direction.
void PairEdgesByScan(std::vector<Member>& m)
{
  for (size_t j = 0; j < m.size(); ++j)
  {
    for (int side = 0; side < 2; ++side)
    {
      const Idx x = side == 0 ? m[j].Next : m[j].Prev;
      for (size_t q = j + 1; q < m.size() && m[j].Link[side] < 0; ++q)
      {
        Member& b = m[q];
        if ((side == 0 ? b.Prev : b.Next) == x && b.Link[1 - side] < 0)
        {
          m[j].Link[side] = Idx(q);
          b.Link[1 - side] = Idx(j);
        }
      }
    }
  }
}

// Links the members' half-edges as the reference pairs them: the half-edges of one undirected
// edge (vertex, x), in triangle order, each unpaired one with the first later unpaired one of
// opposite direction. All half-edges of an edge at the vertex are in its fan, so the rule is
// evaluated locally. A small fan scans the later members. A large one (a polygon of thousands
// of corners fan-triangulated around its first) pairs in O(k log k): its half-edges are sorted by
// (x, member), and each edge's are swept with a queue of the unpaired ones so far; those share
// one direction, so a half-edge of the other direction pairs with the oldest of them.
void PairEdges(std::vector<Member>& m, std::vector<uint64_t>& halfEdges)
{
  constexpr size_t kScanLimit = 32;
  for (Member& a : m)
  {
    a.Link[0] = a.Link[1] = -1;
  }
  if (m.size() <= kScanLimit)
  {
    PairEdgesByScan(m);
    return;
  }
  halfEdges.clear();
  for (size_t j = 0; j < m.size(); ++j)
  {
    // side 0: the half-edge vertex->Next; side 1: Prev->vertex
    halfEdges.push_back(uint64_t(m[j].Next) << 32 | j << 1);
    halfEdges.push_back(uint64_t(m[j].Prev) << 32 | j << 1 | 1);
  }
  std::sort(halfEdges.begin(), halfEdges.end());
  uint64_t* h = halfEdges.data();
  for (size_t b = 0, e; b < halfEdges.size(); b = e)
  {
    const uint64_t x = h[b] >> 32;
    size_t head = b, tail = b; // the queue, kept in place of the half-edges swept
    for (e = b; e < halfEdges.size() && h[e] >> 32 == x; ++e)
    {
      if (head < tail && ((h[head] ^ h[e]) & 1))
      {
        const Idx i = Idx(uint32_t(h[head]) >> 1), j = Idx(uint32_t(h[e]) >> 1);
        const int side = int(h[head++] & 1);
        m[size_t(i)].Link[side] = j;
        m[size_t(j)].Link[1 - side] = i;
      }
      else
      {
        h[tail++] = h[e];
      }
    }
  }
}

//------------------------------------------------------------------------------
// The 8 values of point p, and whether one is a NaN.
bool LoadPoint(const MeshInput& in, Idx p, float (&values)[8])
{
  std::copy_n(in.Positions + 3 * size_t(p), 3, values);
  std::copy_n(in.Normals + 3 * size_t(p), 3, values + 3);
  std::copy_n(in.TCoords + 2 * size_t(p), 2, values + 6);
  return std::any_of(values, values + 8, [](float v) { return std::isnan(v); });
}

// 32-bit hash of a point's value bit patterns, -0 as +0 (equal values give equal hashes).
uint32_t HashPoint(const float (&values)[8])
{
  static constexpr uint64_t kOdd[8] = {
    0x9e3779b1, 0x27d4eb2f, 0x85ebca77, 0xc2b2ae3d, 0xd3a2646d, 0xb55a4f09, 0x165667b1, 0xfd7046c5
  };
  uint64_t h = 0;
  for (int j = 0; j < 8; ++j)
  {
    uint32_t u;
    std::memcpy(&u, &values[j], 4);
    h += uint64_t((u & 0x7fffffffu) ? u : 0u) * kOdd[j];
  }
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  return uint32_t((h ^ (h >> 33)) >> 32);
}

// Stable LSD radix sort of keys by their upper 32 bits.
void SortByUpperHalf(std::vector<uint64_t>& keys)
{
  std::vector<uint64_t> tmp(keys.size());
  std::vector<size_t> count(2048);
  for (int shift = 32; shift < 64; shift += 11)
  {
    std::fill(count.begin(), count.end(), 0);
    for (const uint64_t k : keys)
    {
      ++count[(k >> shift) & 2047];
    }
    std::exclusive_scan(count.begin(), count.end(), count.begin(), size_t(0));
    for (const uint64_t k : keys)
    {
      tmp[count[(k >> shift) & 2047]++] = k;
    }
    keys.swap(tmp);
  }
}

//------------------------------------------------------------------------------
// f(b, e, local) for ranges [b, e) that cover [0, n), in parallel; local is the calling thread's
// T of `locals`.
template<typename T, typename F>
void ForEachRange(vtkIdType n, vtkIdType grain, vtkSMPThreadLocal<T>& locals, F&& f)
{
  vtkSMPTools::For(0, n, grain, [&](vtkIdType b, vtkIdType e) { f(b, e, locals.Local()); });
}

// The vectors (x[j], y[j], z[j]), j < rows, projected on the plane perpendicular to the unit
// normal n and normalised, in place: a loop the compiler vectorises to the CPU's vector width
// (VTK_NORMALMAPPING_TARGET_CLONES; every width rounds each operation the same).
VTK_NORMALMAPPING_TARGET_CLONES
void ProjectOnTangentPlane(float* x, float* y, float* z, size_t rows, const V3& n)
{
  for (size_t j = 0; j < rows; ++j)
  {
    const V3 w{ x[j], y[j], z[j] };
    const V3 u = (w - n * n.Dot(w)).Normalized();
    x[j] = u.x;
    y[j] = u.y;
    z[j] = u.z;
  }
}

// |v|, and unit = sign v / |v| unless |v| is numerically zero (reference: InitTriInfo).
float SignedUnit(const V3& v, float sign, V3& unit)
{
  const float length = std::sqrt(v.Dot(v));
  if (NotZero(length))
  {
    unit = v * (sign / length);
  }
  return length;
}

// Labels the members of a fan with their groups and returns how many there are. A member has at
// most one link per side and links are symmetric (a.Link[0] == b exactly when b.Link[1] == a),
// so a group is the chain (or cycle) walked both ways from its first member while the
// orientation stays the same.
Idx LabelGroups(std::vector<Member>& m)
{
  Idx numGroups = 0;
  for (Member& a : m)
  {
    a.Group = -1;
  }
  for (Member& a : m)
  {
    if (a.Group >= 0)
    {
      continue;
    }
    a.Group = numGroups++;
    for (int side = 0; side < 2; ++side)
    {
      for (Idx r = a.Link[side];
           r >= 0 && m[size_t(r)].Group < 0 && !((m[size_t(r)].Flags ^ a.Flags) & kOrient);
           r = m[size_t(r)].Link[side])
      {
        m[size_t(r)].Group = a.Group;
      }
    }
  }
  return numGroups;
}

//------------------------------------------------------------------------------
void SetAllDefault(Result& res)
{
  std::fill(res.Corners.begin(), res.Corners.end(), DefaultCornerFrame);
  res.CornerKinds.assign(res.Corners.size(), CornerKind::Default);
  res.NumberOfDefaultCorners = static_cast<long long>(res.Corners.size());
}

// Whether the kernel has faces to work on; when not, `res` is the final result: no faces, too
// many corners or points for 32-bit indices, only empty faces, or missing arrays.
bool CheckInput(const MeshInput& in, Result& res)
{
  if (in.NumberOfFaces <= 0 || !in.FaceOffsets)
  {
    return false;
  }
  const long long numSlots = std::max(0LL, in.FaceOffsets[in.NumberOfFaces]);
  res.Corners.resize(size_t(numSlots)); // Sign 0 marks a corner not written yet (see SetDefaults)
  res.CornerKinds.resize(size_t(numSlots)); // Computed until SetDefaults says otherwise
  const long long limit = std::numeric_limits<Idx>::max() - 16;
  const long long numPoints = std::max(0LL, in.NumberOfPoints);
  if (numSlots > limit / 3 || numPoints > limit - 3 * numSlots)
  {
    res.TooLarge = true;
    SetAllDefault(res);
    return false;
  }
  if (numSlots == 0)
  {
    // only faces without corners: their (empty) connectivity may be a null pointer
    res.NumberOfSkippedFaces = in.NumberOfFaces;
    return false;
  }
  if (!in.FaceConnectivity || !in.Positions || !in.Normals || !in.TCoords)
  {
    SetAllDefault(res);
    res.NumberOfInvalidFaces = in.NumberOfFaces;
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
struct Kernel
{
  const MeshInput& In;
  Result& Res;
  const Idx NumPoints;
  const Idx NumSlots; // face corners
  const long long* const Off;
  const long long* const Conn;
  CornerFrame* const Out;

  // welding
  std::vector<Idx> Rep; // welded id of a point, -1 if it contains a NaN
  bool AnyNaNPoint = false;
  Idx NumVerts = 0;

  // triangles, in face order
  static constexpr long long kFaceChunk = 4096;
  std::vector<Idx> ChunkTriBase; // first triangle of each chunk of faces
  // Per face, 1 where it starts before an earlier face ends (offsets out of order), which makes it
  // invalid: faces never share a face corner. Empty when no face does.
  std::vector<uint8_t> Overlapping;
  Idx NumTris = 0;
  bool AnyMulti = false; // some face has more than 3 corners
  struct Triangle
  {
    V3 S, T; // sign(det) Os/|Os|, sign(det) Ot/|Ot|
    uint8_t Flags;
  };
  // One record per triangle, all the vertex phase reads of it (welded ids come from the points'
  // table, WeldOf). Not value-initialised: the triangle pass writes every record.
  std::unique_ptr<Triangle[]> Tris;
  // Face corner of each triangle corner (3 per triangle); null when every face is a triangle
  // stored in order, whose triangle corner c is face corner c.
  std::unique_ptr<Idx[]> Slots;
  // |Os|/|det| and |Ot|/|det| of each triangle, only when some face has more than 3 corners:
  // they only decide how the several frames written to one face corner merge (Average).
  std::unique_ptr<float[]> Mags;
  long long NumDegenerate = 0, NumGWA = 0, NumSkipped = 0, NumInvalid = 0;

  // fans: corners of non-degenerate triangles grouped by welded id, ascending
  std::vector<Idx> FanStart, Fan;
  std::vector<PendingFrame> Pending; // 3 per triangle if AnyMulti

  // `res.Corners` holds one frame per face corner (CheckInput).
  Kernel(const MeshInput& in, Result& res)
    : In(in)
    , Res(res)
    , NumPoints(Idx(std::max(0LL, in.NumberOfPoints)))
    , NumSlots(Idx(res.Corners.size()))
    , Off(in.FaceOffsets)
    , Conn(in.FaceConnectivity)
    , Out(res.Corners.data())
  {
  }

  V3 Pos(size_t p) const { return V3::At(In.Positions, p); }
  V3 Nrm(size_t p) const { return V3::At(In.Normals, p); }
  float UV(size_t p, int k) const { return In.TCoords[2 * p + size_t(k)]; } // k: 0 u, 1 v
  // point holding the values of a welded vertex
  Idx PointOfWeld(Idx w) const { return w < NumPoints ? w : Idx(Conn[w - NumPoints]); }
  Idx FanSize(Idx v) const { return FanStart[size_t(v) + 1] - FanStart[size_t(v)]; }
  // face corner and welded vertex of triangle corner c = 3 t + i
  Idx SlotOf(Idx c) const { return Slots ? Slots[size_t(c)] : c; }
  std::array<Idx, 3> SlotsOf(Idx t) const
  {
    return { SlotOf(3 * t), SlotOf(3 * t + 1), SlotOf(3 * t + 2) };
  }
  // Welded id of corner c of a triangle that is not dead: its point's, or for a point with a NaN
  // one of its own past the points.
  Idx WeldOf(Idx c) const
  {
    const Idx slot = SlotOf(c);
    const Idx w = Rep[size_t(Conn[slot])];
    return w >= 0 ? w : NumPoints + slot;
  }

  bool FaceInRange(long long b, long long e) const { return b >= 0 && e >= b && e <= NumSlots; }
  bool FaceHasTriangles(long long b, long long e) const { return FaceInRange(b, e) && e - b >= 3; }
  bool Overlaps(long long f) const { return !Overlapping.empty() && Overlapping[size_t(f)]; }
  /// visit(b, e, t) for every face that gives triangles, in parallel over chunks of faces:
  /// [b, e) are its offsets and t its first triangle.
  template<typename Visit>
  void ForEachTriangulatedFace(Visit&& visit) const
  {
    vtkSMPTools::For(0,
      vtkIdType(ChunkTriBase.size() - 1),
      1,
      [&](vtkIdType cb, vtkIdType ce)
      {
        for (vtkIdType c = cb; c < ce; ++c)
        {
          Idx t = ChunkTriBase[size_t(c)];
          const long long fe = std::min(In.NumberOfFaces, (c + 1) * kFaceChunk);
          for (long long f = c * kFaceChunk; f < fe; ++f)
          {
            const long long b = Off[f], e = Off[f + 1];
            if (FaceHasTriangles(b, e) && !Overlaps(f))
            {
              visit(b, e, t);
              t += Idx(e - b - 2);
            }
          }
        }
      });
  }

  // The phases in order, with the progress (fraction done) reported before each; a request to stop
  // leaves every corner at the default frame.
  void Run(const std::function<bool(double)>& progress)
  {
    const std::pair<double, void (Kernel::*)()> phases[] = { { 0.0, &Kernel::Weld },
      { 0.15, &Kernel::BuildTriangles },
      { 0.4, &Kernel::BuildFans },
      { 0.5, &Kernel::ProcessVertices },
      { 0.9, &Kernel::FinishFaces } };
    for (const auto& phase : phases)
    {
      Res.Aborted = progress && progress(phase.first);
      if (Res.Aborted)
      {
        SetAllDefault(Res);
        return;
      }
      (this->*phase.second)();
    }
    Res.NumberOfTriangles = NumTris;
    Res.NumberOfDegenerateTriangles = NumDegenerate;
    Res.NumberOfGroupWithAnyTriangles = NumGWA;
    Res.NumberOfSkippedFaces = NumSkipped;
    Res.NumberOfInvalidFaces = NumInvalid;
    if (progress)
    {
      progress(1.0);
    }
  }

  // Phase 1: points sorted by (hash, id); within a run of equal hashes the first point of every
  // class of equal values (the smallest id) is the welded id of the class.
  void Weld()
  {
    const Idx np = NumPoints;
    Rep.resize(size_t(np));
    std::vector<uint64_t> keys(static_cast<size_t>(np));
    vtkSMPTools::For(0,
      vtkIdType(np),
      16384,
      [&](vtkIdType b, vtkIdType e)
      {
        float values[8];
        for (Idx p = Idx(b); p < Idx(e); ++p)
        {
          Rep[size_t(p)] = LoadPoint(In, p, values) ? -1 : p;
          keys[size_t(p)] = uint64_t(HashPoint(values)) << 32 | uint64_t(p);
        }
      });
    AnyNaNPoint = std::find(Rep.begin(), Rep.end(), -1) != Rep.end();
    SortByUpperHalf(keys);
    std::vector<Idx> heads;
    float values[8], other[8];
    const auto equalValues = [&](Idx h)
    {
      LoadPoint(In, h, other);
      return std::equal(values, values + 8, other);
    };
    for (size_t r0 = 0, r1; r0 < keys.size(); r0 = r1)
    {
      r1 = r0 + 1;
      while (r1 < keys.size() && keys[r1] >> 32 == keys[r0] >> 32)
      {
        ++r1;
      }
      if (r1 - r0 == 1)
      {
        continue; // a hash of its own: nothing to weld
      }
      heads.clear();
      for (size_t j = r0; j < r1; ++j)
      {
        const Idx p = Idx(uint32_t(keys[j]));
        if (Rep[size_t(p)] >= 0)
        {
          LoadPoint(In, p, values);
          const auto head = std::find_if(heads.begin(), heads.end(), equalValues);
          if (head == heads.end())
          {
            heads.push_back(p);
          }
          else
          {
            Rep[size_t(p)] = *head;
          }
        }
      }
    }
  }

  // Phase 2: one sequential pass over the offsets gives the first triangle of each chunk of faces
  // (ChunkTriBase), the faces that give none, and whether any face has more than 3 corners
  // (AnyMulti) or any is not stored as corners (3f, 3f + 1, 3f + 2) (Slots needed); then the
  // triangles are set up in parallel.
  void BuildTriangles()
  {
    bool inOrder = true;
    long long reach = 0; // the end of the faces in range so far
    for (long long f = 0; f < In.NumberOfFaces; ++f)
    {
      if (f % kFaceChunk == 0)
      {
        ChunkTriBase.push_back(NumTris);
      }
      const long long b = Off[f], e = Off[f + 1];
      inOrder = inOrder && b == 3 * f && e == b + 3;
      if (FaceInRange(b, e) && b < reach)
      {
        Overlapping.resize(size_t(In.NumberOfFaces), 0);
        Overlapping[size_t(f)] = 1;
        ++NumInvalid;
        continue;
      }
      reach = FaceInRange(b, e) ? e : reach;
      if (FaceHasTriangles(b, e))
      {
        NumTris += Idx(e - b - 2);
        AnyMulti = AnyMulti || e - b > 3;
      }
      else
      {
        ++(FaceInRange(b, e) ? NumSkipped : NumInvalid);
      }
    }
    ChunkTriBase.push_back(NumTris);
    Tris.reset(new Triangle[size_t(NumTris)]);
    Slots.reset(inOrder ? nullptr : new Idx[3 * size_t(NumTris)]);
    Mags.reset(AnyMulti ? new float[2 * size_t(NumTris)] : nullptr);
    std::atomic<long long> invalid(0);
    ForEachTriangulatedFace(
      [&](long long b, long long e, Idx t) { invalid += SetupFace(b, e, t); });
    NumInvalid += invalid;
  }

  // The triangles of face [b, e) from triangle t on: one triangle, a quad split on a diagonal
  // (SetupQuad), or a fan (0, k+1, k+2) of a larger polygon; a face with an id outside the points
  // gives dead triangles; returns whether it does.
  bool SetupFace(long long b, long long e, Idx t)
  {
    const Idx base = Idx(b), nTri = Idx(e - b - 2);
    if (!std::all_of(
          Conn + b, Conn + e, [this](long long id) { return id >= 0 && id < NumPoints; }))
    {
      std::fill(Tris.get() + t, Tris.get() + t + nTri, Triangle{ {}, {}, kDead }); // never in a fan
      return true;
    }
    else if (nTri == 1)
    {
      SetupTriangle(t, { base, base + 1, base + 2 });
    }
    else if (nTri == 2)
    {
      SetupQuad(t, base);
    }
    else
    {
      // corner 0 is shared by all the fan's triangles, corners 1 and 2 by neighbours
      for (Idx k = 0; k < nTri; ++k)
      {
        SetupTriangle(t + k, { base, base + k + 1, base + k + 2 });
        Tris[size_t(t) + size_t(k)].Flags |=
          uint8_t(kMulti0 | (k >= 1 ? kMulti0 << 1 : 0) | (k + 1 < nTri ? kMulti0 << 2 : 0));
      }
    }
    return false;
  }

  // The two triangles t, t+1 of the quad with face corners base..base+3, split on the shorter UV
  // diagonal (the position diagonal on an exact tie), and the reference's rule for them: two good
  // triangles of different orientation take the one of the larger UV area (a GWA second triangle
  // always takes the first's).
  void SetupQuad(Idx t, Idx base)
  {
    const long long* q = Conn + base;
    const auto uvLength2 = [this](long long a, long long b)
    {
      const float du = UV(b, 0) - UV(a, 0), dv = UV(b, 1) - UV(a, 1);
      return du * du + dv * dv;
    };
    const float uv02 = uvLength2(q[0], q[2]), uv13 = uvLength2(q[1], q[3]);
    bool diag02 = uv02 < uv13;
    if (!(uv02 < uv13) && !(uv13 < uv02))
    {
      const V3 e02 = Pos(q[2]) - Pos(q[0]), e13 = Pos(q[3]) - Pos(q[1]);
      diag02 = !(e13.Dot(e13) < e02.Dot(e02));
    }
    const float detA = SetupTriangle(t, { base, base + 1, base + (diag02 ? 2 : 3) });
    const float detB = SetupTriangle(t + 1, { base + (diag02 ? 0 : 1), base + 2, base + 3 });
    uint8_t& fa = Tris[size_t(t)].Flags;
    uint8_t& fb = Tris[size_t(t) + 1].Flags;
    if (!((fa | fb) & kDegenerate) && ((fa ^ fb) & kOrient))
    {
      const bool firstWins = (fb & kGWA) || std::fabs(detA) >= std::fabs(detB);
      uint8_t& dst = firstWins ? fb : fa;
      const uint8_t src = firstWins ? fa : fb;
      dst = uint8_t((dst & ~kOrient) | (src & kOrient));
    }
    // the diagonal's face corners are written by both triangles:
    // 0-2: (0,1,2) corners 0,2 and (0,2,3) corners 0,1; 1-3: (0,1,3) corners 1,2 and (1,2,3) 0,2
    const uint8_t m0 = kMulti0, m1 = uint8_t(kMulti0 << 1), m2 = uint8_t(kMulti0 << 2);
    fa |= diag02 ? uint8_t(m0 | m2) : uint8_t(m1 | m2);
    fb |= diag02 ? uint8_t(m0 | m1) : uint8_t(m0 | m2);
  }

  // Triangle t with the face corners `slots` (reference: degenerate test, InitTriInfo): its
  // degeneracy, orientation and GWA flags, unit directions and magnitudes. Returns its UV
  // determinant.
  float SetupTriangle(Idx t, const std::array<Idx, 3>& slots)
  {
    if (Slots)
    {
      std::copy(slots.begin(), slots.end(), Slots.get() + 3 * size_t(t));
    }
    const long long a = Conn[slots[0]], b = Conn[slots[1]], c = Conn[slots[2]];
    const V3 p0 = Pos(a), p1 = Pos(b), p2 = Pos(c);
    const float t21x = UV(b, 0) - UV(a, 0), t21y = UV(b, 1) - UV(a, 1);
    const float t31x = UV(c, 0) - UV(a, 0), t31y = UV(c, 1) - UV(a, 1);
    const float det = t21x * t31y - t21y * t31x;
    Triangle& tri = Tris[size_t(t)];
    tri = Triangle{ { 0, 0, 0 }, { 0, 0, 0 }, kDegenerate };
    if (p0 == p1 || p0 == p2 || p1 == p2)
    {
      return det;
    }
    tri.Flags = det > 0 ? uint8_t(kGWA | kOrient) : kGWA;
    float magS = 0, magT = 0;
    if (NotZero(det))
    {
      const V3 d1 = p1 - p0, d2 = p2 - p0;
      const float sign = det > 0 ? 1.0f : -1.0f;
      magS = SignedUnit(d1 * t31y - d2 * t21y, sign, tri.S) / std::fabs(det);
      magT = SignedUnit(d1 * -t31x + d2 * t21x, sign, tri.T) / std::fabs(det);
      if (NotZero(magS) && NotZero(magT))
      {
        tri.Flags = uint8_t(tri.Flags & ~kGWA);
      }
    }
    if (Mags)
    {
      Mags[2 * size_t(t)] = magS;
      Mags[2 * size_t(t) + 1] = magT;
    }
    return det;
  }

  // Phase 3: counting sort of the corners of non-degenerate triangles by welded id; every fan lists
  // its corners in ascending order. Counts the degenerate and GWA triangles.
  void BuildFans()
  {
    NumVerts = NumPoints + (AnyNaNPoint ? NumSlots : 0);
    FanStart.assign(size_t(NumVerts) + 1, 0);
    for (Idx t = 0; t < NumTris; ++t)
    {
      const uint8_t flags = Tris[size_t(t)].Flags;
      NumDegenerate += (flags & kDegenerate) ? 1 : 0;
      NumGWA += (flags & (kExcluded | kGWA)) == kGWA ? 1 : 0;
      if (!(flags & kExcluded))
      {
        for (int i = 0; i < 3; ++i)
        {
          ++FanStart[size_t(WeldOf(3 * t + i)) + 1];
        }
      }
    }
    std::partial_sum(FanStart.begin(), FanStart.end(), FanStart.begin());
    Fan.resize(size_t(FanStart.back()));
    std::vector<Idx> pos(FanStart.begin(), FanStart.end() - 1);
    for (Idx t = 0; t < NumTris; ++t)
    {
      if (!(Tris[size_t(t)].Flags & kExcluded))
      {
        for (int i = 0; i < 3; ++i)
        {
          Fan[size_t(pos[size_t(WeldOf(3 * t + i))]++)] = 3 * t + i;
        }
      }
    }
  }

  // The members of vertex v's fan, linked across shared edges.
  void GatherFan(Idx v, std::vector<Member>& m) const
  {
    const Idx* fan = Fan.data() + FanStart[size_t(v)];
    m.resize(size_t(FanSize(v)));
    for (size_t j = 0; j < m.size(); ++j)
    {
      const Idx c = fan[j], i = c % 3;
      m[j].Corner = c;
      m[j].Next = WeldOf(c - i + (i + 1) % 3);
      m[j].Prev = WeldOf(c - i + (i + 2) % 3);
      m[j].Flags = Tris[size_t(c / 3)].Flags;
      m[j].MagS = Mags ? Mags[2 * size_t(c / 3)] : 0.0f;
      m[j].MagT = Mags ? Mags[2 * size_t(c / 3) + 1] : 0.0f;
    }
  }

  // Phases 4 and 5: the orientation of GWA triangles, then every welded vertex with a fan, in
  // parallel.
  void ProcessVertices()
  {
    if (NumGWA > 0)
    {
      AdoptGroupWithAnyOrientation();
    }
    if (AnyMulti)
    {
      Pending.assign(3 * size_t(NumTris), PendingFrame{ {}, -1, 0 });
    }
    vtkSMPThreadLocal<Scratch> scratch;
    ForEachRange(NumVerts,
      1024,
      scratch,
      [this](vtkIdType b, vtkIdType e, Scratch& s)
      {
        for (Idx v = Idx(b); v < Idx(e); ++v)
        {
          if (FanSize(v) > 0)
          {
            ProcessVertex(v, s);
          }
        }
      });
  }

  // The reference builds groups sequentially; the first group reaching a GWA triangle that has
  // no group yet gives it its orientation. This replays that, restricted to vertices whose fan
  // contains a GWA triangle (only their floods can reach one). Afterwards the groups everywhere
  // are the same-orientation edge-connected components of each fan.
  void AdoptGroupWithAnyOrientation()
  {
    const auto flags = [this](Idx c) { return Tris[size_t(c / 3)].Flags & (kExcluded | kGWA); };
    std::vector<uint8_t> gwaVertex(size_t(NumVerts), 0);
    for (Idx c = 0; c < 3 * NumTris; ++c)
    {
      if (flags(c) == kGWA)
      {
        gwaVertex[size_t(WeldOf(c))] = 1;
      }
    }
    // The paired edges of each such vertex's fan (Member::Link per fan position), made once:
    // every flood from one of its corners walks them.
    std::vector<Idx> linkStart(size_t(NumVerts) + 1, 0);
    for (Idx v = 0; v < NumVerts; ++v)
    {
      linkStart[size_t(v) + 1] = linkStart[size_t(v)] + (gwaVertex[size_t(v)] ? FanSize(v) : 0);
    }
    std::vector<std::array<Idx, 2>> links(size_t(linkStart.back()));
    Scratch scratch;
    for (Idx v = 0; v < NumVerts; ++v)
    {
      if (gwaVertex[size_t(v)])
      {
        GatherFan(v, scratch.Members);
        PairEdges(scratch.Members, scratch.Edges);
        for (size_t j = 0; j < scratch.Members.size(); ++j)
        {
          const Member& member = scratch.Members[j];
          links[size_t(linkStart[size_t(v)]) + j] = { member.Link[0], member.Link[1] };
        }
      }
    }
    std::vector<uint8_t> assigned(3 * size_t(NumTris), 0);
    for (Idx c = 0; c < 3 * NumTris; ++c)
    {
      const Idx v = WeldOf(c);
      if (!flags(c) && gwaVertex[size_t(v)] && !assigned[size_t(c)])
      {
        FloodGroup(c, links.data() + linkStart[size_t(v)], assigned, scratch.Stack);
      }
    }
  }

  // The reference's group flood from corner c across the paired edges of its welded vertex's fan
  // (`links`, per fan position), through corners not assigned to a group yet: a GWA triangle none
  // of whose corners has a group takes the seed's orientation, and the flood goes on through
  // corners of that orientation.
  void FloodGroup(Idx c,
    const std::array<Idx, 2>* links,
    std::vector<uint8_t>& assigned,
    std::vector<Idx>& stack)
  {
    const Idx v = WeldOf(c);
    const Idx* fan = Fan.data() + FanStart[size_t(v)];
    const uint8_t orient = Tris[size_t(c / 3)].Flags & kOrient;
    assigned[size_t(c)] = 1;
    stack.assign(1, Idx(std::lower_bound(fan, fan + FanSize(v), c) - fan));
    while (!stack.empty())
    {
      const Idx j = stack.back();
      stack.pop_back();
      for (const Idx q : links[j])
      {
        if (q < 0 || assigned[size_t(fan[q])])
        {
          continue;
        }
        const Idx tq = fan[q] / 3;
        uint8_t& fq = Tris[size_t(tq)].Flags;
        if ((fq & kGWA) && !assigned[3 * size_t(tq)] && !assigned[3 * size_t(tq) + 1] &&
          !assigned[3 * size_t(tq) + 2])
        {
          fq = uint8_t((fq & ~kOrient) | orient);
        }
        if ((fq & kOrient) == orient)
        {
          assigned[size_t(fan[q])] = 1;
          stack.push_back(q);
        }
      }
    }
  }

  // Groups of vertex v and their frames: each group's members, in triangle order, go to
  // ResolveGroup.
  void ProcessVertex(Idx v, Scratch& s)
  {
    std::vector<Member>& m = s.Members;
    GatherFan(v, m);
    PairEdges(m, s.Edges);
    CornerMath(v, s);
    const Idx numGroups = LabelGroups(m);
    // members ordered by (group, triangle)
    s.Order.resize(m.size());
    std::iota(s.Order.begin(), s.Order.end(), 0);
    if (numGroups == 1)
    {
      ResolveGroup(s, s.Order.data(), m.size());
      return;
    }
    std::sort(s.Order.begin(),
      s.Order.end(),
      [&m](Idx a, Idx b)
      { return std::tie(m[size_t(a)].Group, a) < std::tie(m[size_t(b)].Group, b); });
    for (const Idx *b = s.Order.data(), *end = b + m.size(), *e; b != end; b = e)
    {
      e = std::find_if(b, end, [&](Idx j) { return m[size_t(j)].Group != m[size_t(*b)].Group; });
      ResolveGroup(s, b, size_t(e - b));
    }
  }

  // The reference's EvalTspace inputs at vertex v: the triangles' directions and the corners'
  // edges projected on the plane perpendicular to the vertex normal and normalised, and the corner
  // angle acos(e1.e2) (in double, rounded to float, as the reference). The edge to a neighbour is
  // the same for the two members sharing it: a member's edge to Prev is its partner's (Link[1])
  // edge to Next, projected once.
  void CornerMath(Idx v, Scratch& s) const
  {
    const Idx pv = PointOfWeld(v);
    const V3 n = Nrm(pv), p = Pos(pv);
    const size_t k = s.Members.size();
    // The vectors to project, in separate x, y, z arrays so that the projection loop vectorises:
    // [0, k) S of each member, [k, 2k) T, [2k, 3k) the edge to Next, then the edges to Prev of
    // members whose in-edge is unpaired (a paired one is its partner's edge to Next).
    s.XYZ.resize(12 * k);
    float *x = s.XYZ.data(), *y = x + 4 * k, *z = y + 4 * k;
    const auto set = [=](size_t row, const V3& w)
    {
      x[row] = w.x;
      y[row] = w.y;
      z[row] = w.z;
    };
    const auto get = [=](size_t row) { return V3{ x[row], y[row], z[row] }; };
    size_t rows = 3 * k;
    for (size_t j = 0; j < k; ++j)
    {
      const Member& a = s.Members[j];
      const Triangle& tri = Tris[size_t(a.Corner / 3)];
      set(j, tri.S);
      set(k + j, tri.T);
      set(2 * k + j, Pos(PointOfWeld(a.Next)) - p);
      if (a.Link[1] < 0)
      {
        set(rows++, Pos(PointOfWeld(a.Prev)) - p);
      }
    }
    ProjectOnTangentPlane(x, y, z, rows, n);
    // the cosines of all members first, then the acos calls
    for (size_t j = 0, extra = 3 * k; j < k; ++j)
    {
      Member& a = s.Members[j];
      a.S = get(j);
      a.T = get(k + j);
      const float c = get(a.Link[1] >= 0 ? 2 * k + size_t(a.Link[1]) : extra++).Dot(get(2 * k + j));
      a.Angle = c > 1 ? 1 : (c < -1 ? -1 : c); // NaN stays NaN
    }
    for (Member& a : s.Members)
    {
      a.Angle = (a.Flags & kGWA) ? 0.0f : float(std::acos(double(a.Angle)));
    }
  }

  // Frames of one group (members in ascending triangle order). Its seed is the first non-GWA
  // member; a group of GWA triangles only is never seeded and its corners stay default.
  void ResolveGroup(Scratch& s, const Idx* members, size_t count)
  {
    const Idx* seed = std::find_if(
      members, members + count, [&s](Idx j) { return !(s.Members[size_t(j)].Flags & kGWA); });
    if (seed == members + count)
    {
      return;
    }
    const Member& first = s.Members[size_t(*seed)];
    const uint8_t orient = first.Flags & kOrient;
    // Sub-groups (threshold cos = -1) split two non-GWA triangles of different faces only if
    // their projected directions have cos <= -1 (or NaN). A sufficient test that none split:
    // every member within 89.4 degrees of the seed (cos > 0.01), so every pair is within 179
    // degrees (cos > -0.9998, far from -1 even with float rounding).
    const bool single = std::all_of(members,
      members + count,
      [&](Idx j)
      {
        const Member& a = s.Members[size_t(j)];
        return (a.Flags & kGWA) || (first.S.Dot(a.S) > 0.01f && first.T.Dot(a.T) > 0.01f);
      });
    if (!single)
    {
      GeneralSubgroups(s, members, count, orient, first.Corner);
      return;
    }
    const Frame f = Eval(s, members, count);
    for (size_t j = 0; j < count; ++j)
    {
      Write(s.Members[size_t(members[j])], f, orient, first.Corner);
    }
  }

  // Angle-weighted average of the non-GWA members listed, in list order.
  Frame Eval(const Scratch& s, const Idx* members, size_t count) const
  {
    Frame r{};
    float angleSum = 0;
    for (size_t j = 0; j < count; ++j)
    {
      const Member& a = s.Members[size_t(members[j])];
      if (a.Flags & kGWA)
      {
        continue;
      }
      r.S = r.S + a.S * a.Angle;
      r.T = r.T + a.T * a.Angle;
      r.MagS += a.Angle * a.MagS;
      r.MagT += a.Angle * a.MagT;
      angleSum += a.Angle;
    }
    r.S = r.S.Normalized();
    r.T = r.T.Normalized();
    if (angleSum > 0)
    {
      r.MagS /= angleSum;
      r.MagT /= angleSum;
    }
    return r;
  }

  // The reference's sub-groups: the list of member f holds every member t with (either GWA) or
  // (same face) or (cosS > -1 and cosT > -1); equal lists share a frame. A list is thus all the
  // members but some non-GWA members of faces other than f's, and is known by those (LeftOut):
  // f is tested against the non-GWA members of the other faces only. A face's triangles are
  // consecutive, so its members are too.
  void GeneralSubgroups(Scratch& s, const Idx* members, size_t count, uint8_t orient, Idx seed)
  {
    s.Subgroups.clear();
    std::vector<Idx>& c = s.Contributors;
    c.clear();
    std::copy_if(members,
      members + count,
      std::back_inserter(c),
      [&s](Idx j) { return !(s.Members[size_t(j)].Flags & kGWA); });
    const auto triangleOf = [&s](Idx j) { return s.Members[size_t(j)].Corner / 3; };
    // the contributors in [from, to) that the list of f leaves out, to s.LeftOut
    const auto leaveOut = [&s, &c](const Member& f, size_t from, size_t to)
    {
      for (size_t k = from; k < to; ++k)
      {
        const Member& t = s.Members[size_t(c[k])];
        if (!(f.S.Dot(t.S) > -1.0f && f.T.Dot(t.T) > -1.0f))
        {
          s.LeftOut.push_back(c[k]);
        }
      }
    };
    // [b, e): the contributors of one face
    for (size_t b = 0, e; b < c.size(); b = e)
    {
      e = b + 1;
      while (e < c.size() && SameFace(triangleOf(c[b]), triangleOf(c[e])))
      {
        ++e;
      }
      for (size_t i = b; i < e; ++i)
      {
        const Member& f = s.Members[size_t(c[i])];
        s.LeftOut.clear();
        leaveOut(f, 0, b);
        leaveOut(f, e, c.size());
        Write(f, SubgroupFrame(s, members, count), orient, seed);
      }
    }
    // a GWA member's list holds every member
    s.LeftOut.clear();
    for (size_t j = 0; j < count; ++j)
    {
      const Member& m = s.Members[size_t(members[j])];
      if (m.Flags & kGWA)
      {
        Write(m, SubgroupFrame(s, members, count), orient, seed);
      }
    }
  }

  // The frame of the sub-group whose list is the members but s.LeftOut (both ascending), in list
  // order; evaluated once per distinct list.
  const Frame& SubgroupFrame(Scratch& s, const Idx* members, size_t count) const
  {
    auto sub = s.Subgroups.find(s.LeftOut);
    if (sub == s.Subgroups.end())
    {
      s.Kept.clear();
      std::set_difference(
        members, members + count, s.LeftOut.begin(), s.LeftOut.end(), std::back_inserter(s.Kept));
      sub = s.Subgroups.emplace(s.LeftOut, Eval(s, s.Kept.data(), s.Kept.size())).first;
    }
    return sub->second;
  }

  // Triangles of one face share a face corner; different faces never do.
  bool SameFace(Idx ta, Idx tb) const
  {
    const std::array<Idx, 3> a = SlotsOf(ta), b = SlotsOf(tb);
    return ta == tb || std::find_first_of(a.begin(), a.end(), b.begin(), b.end()) != a.end();
  }

  void Write(const Member& m, const Frame& f, uint8_t orient, Idx seed)
  {
    if (m.Flags & (kMulti0 << (m.Corner % 3)))
    {
      Pending[size_t(m.Corner)] = PendingFrame{ f, seed, orient }; // merged in MergeMultiWriters
    }
    else
    {
      Out[size_t(SlotOf(m.Corner))] = ToCornerFrame(f.S, orient);
    }
  }

  // Phase 6: face corners with several writers, those of degenerate triangles, and the default
  // frames.
  void FinishFaces()
  {
    if (AnyMulti)
    {
      MergeMultiWriters();
    }
    if (NumDegenerate > 0)
    {
      CopyDegenerates();
    }
    SetDefaults();
  }

  // Face corners written by several triangles: the reference's pairwise average, applied in
  // group creation order (then triangle order); the sign is that of the last group.
  void MergeMultiWriters()
  {
    // {face corner, group seed, triangle corner} of each frame to merge, sorted in that order
    vtkSMPThreadLocal<std::vector<std::array<Idx, 3>>> lists;
    ForEachTriangulatedFace(
      [&](long long b, long long e, Idx t)
      {
        const Idx nTri = Idx(e - b - 2);
        if (nTri == 1 || (Tris[size_t(t)].Flags & kDead))
        {
          return;
        }
        std::vector<std::array<Idx, 3>>& list = lists.Local();
        list.clear();
        for (Idx corner = 3 * t; corner < 3 * (t + nTri); ++corner)
        {
          if ((Tris[size_t(corner / 3)].Flags & (kMulti0 << (corner % 3))) &&
            Pending[size_t(corner)].Seed >= 0)
          {
            list.push_back({ SlotOf(corner), Pending[size_t(corner)].Seed, corner });
          }
        }
        std::sort(list.begin(), list.end());
        Frame f{};
        for (size_t r = 0; r < list.size(); ++r)
        {
          // the frames merged so far; a face corner keeps its last, complete merge
          const PendingFrame& pf = Pending[size_t(list[r][2])];
          f = r > 0 && list[r - 1][0] == list[r][0] ? Average(f, pf.F) : pf.F;
          Out[size_t(list[r][0])] = ToCornerFrame(f.S, pf.Orient);
        }
      });
  }

  // Degenerate triangles copy the frame of the first good corner with the same welded vertex;
  // in a quad with one degenerate triangle the corner missing from the good triangle copies the
  // good triangle's corner with the same position. Sources are always corners of good
  // triangles, which this pass never writes.
  void CopyDegenerates()
  {
    vtkSMPThreadLocal<std::vector<uint8_t>> coveredSlots;
    ForEachTriangulatedFace(
      [&](long long b, long long e, Idx t)
      {
        const long long n = e - b;
        const Idx nTri = Idx(n - 2);
        const Triangle* tri = Tris.get() + t;
        if ((tri[0].Flags & kDead) ||
          std::none_of(tri, tri + nTri, [](const Triangle& u) { return u.Flags & kDegenerate; }))
        {
          return;
        }
        if (n == 4 && !(tri[0].Flags & tri[1].Flags & kDegenerate))
        {
          // a quad of which exactly one triangle is degenerate
          CopyToQuadCorner(Idx(b), t);
          return;
        }
        // a degenerate fan triangle only fills face corners no good triangle covers
        std::vector<uint8_t>& covered = coveredSlots.Local();
        covered.assign(size_t(n), 0);
        for (Idx corner = 3 * t; corner < 3 * (t + nTri); ++corner)
        {
          covered[size_t(SlotOf(corner) - b)] |= !(Tris[size_t(corner / 3)].Flags & kDegenerate);
        }
        for (Idx corner = 3 * t; corner < 3 * (t + nTri); ++corner)
        {
          const Idx slot = SlotOf(corner);
          const Idx w = WeldOf(corner);
          if ((Tris[size_t(corner / 3)].Flags & kDegenerate) && !covered[size_t(slot - b)] &&
            FanSize(w) > 0)
          {
            Out[size_t(slot)] = Out[size_t(SlotOf(Fan[size_t(FanStart[size_t(w)])]))];
          }
        }
      });
  }

  // In the quad of face corners from b on, split into triangles t and t + 1 of which one is
  // degenerate: the face corner missing from the good triangle copies the frame of the good
  // triangle's corner at the same position, if it has one.
  void CopyToQuadCorner(Idx b, Idx t)
  {
    const std::array<Idx, 3> gs = SlotsOf(t + ((Tris[size_t(t)].Flags & kDegenerate) ? 1 : 0));
    Idx missing = b;
    while (missing == gs[0] || missing == gs[1] || missing == gs[2])
    {
      ++missing;
    }
    const V3 dst = Pos(Conn[missing]);
    const auto src =
      std::find_if(gs.begin(), gs.end(), [&](Idx slot) { return Pos(Conn[slot]) == dst; });
    if (src != gs.end())
    {
      Out[size_t(missing)] = Out[size_t(*src)];
    }
  }

  // Corners never written (Sign 0) or not finite get the default frame; they and the cancelled
  // corners are marked in Res.CornerKinds and counted.
  void SetDefaults()
  {
    struct Counts
    {
      long long Defaults = 0, NonFinite = 0, Cancelled = 0;
    };
    vtkSMPThreadLocal<Counts> counts;
    CornerKind* const kinds = Res.CornerKinds.data();
    ForEachRange(NumSlots,
      65536,
      counts,
      [this, kinds](vtkIdType b, vtkIdType e, Counts& n)
      {
        for (vtkIdType c = b; c < e; ++c)
        {
          CornerFrame& o = Out[c];
          const bool unwritten = o.Sign == 0.0f;
          if (unwritten || !V3{ o.Tangent[0], o.Tangent[1], o.Tangent[2] }.Finite())
          {
            o = DefaultCornerFrame;
            kinds[c] = CornerKind::Default;
            ++n.Defaults;
            n.NonFinite += unwritten ? 0 : 1;
          }
          else if (IsCancelled(o))
          {
            kinds[c] = CornerKind::Cancelled;
            ++n.Cancelled;
          }
        }
      });
    for (const Counts& n : counts)
    {
      Res.NumberOfDefaultCorners += n.Defaults;
      Res.NumberOfNonFiniteCorners += n.NonFinite;
      Res.NumberOfCancelledCorners += n.Cancelled;
    }
  }
};

} // namespace

//------------------------------------------------------------------------------
Result ComputeMikkTSpace(const MeshInput& in, const std::function<bool(double)>& progress)
{
  Result res;
  if (CheckInput(in, res))
  {
    Kernel(in, res).Run(progress);
  }
  return res;
}

} // namespace mikk
} // namespace vtkNormalMapping
