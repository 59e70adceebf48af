// The batch kernels written once for any SIMD width (private; no include guard on purpose).
//
// vtkTangentFrameBatch.h includes this file once per instruction set, inside a namespace that
// defines `Lanes` (the vector type, its masks and operations) and under a pragma that compiles
// everything here for that instruction set. Every kernel performs the IEEE operations of its
// scalar counterpart in the same order, lane by lane: Lanes must round each operation on its
// own (no fused multiply-add), and the scalar code for special lanes is called, never inlined
// (ScalarTriangle, ScalarSide), so that every instruction set gives the same bits.

/// Whether every corner id of triangles [i, i + N) is below `limit`.
template<int N>
VTK_TANGENT_BATCH_ALWAYS_INLINE inline bool IdsBelow(const FrameBatch& b, int i, vtkIdType limit)
{
  bool below = true;
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType* ids = b.Ids[k] + i;
    if constexpr (sizeof(vtkIdType) == sizeof(std::int64_t))
    {
      below = below && Lanes::Below(reinterpret_cast<const std::int64_t*>(ids), N, limit);
    }
    else
    {
      below = below && *std::max_element(ids, ids + N) < limit;
    }
  }
  return below;
}

/// Lanes::GatherXYZ (float xyz into float lanes) or GatherNormals (into double lanes), with the
/// load guard at the array's last point when `guarded`.
template<bool Guarded>
VTK_TANGENT_BATCH_ALWAYS_INLINE inline void GatherLanes(const float* xyz,
  const vtkIdType* ids,
  vtkIdType count,
  Lanes::F out[3])
{
  Lanes::template GatherXYZ<Guarded>(xyz, ids, count, out);
}
template<bool Guarded, typename NT>
VTK_TANGENT_BATCH_ALWAYS_INLINE inline void GatherLanes(const NT* xyz,
  const vtkIdType* ids,
  vtkIdType count,
  Lanes::D out[3])
{
  Lanes::template GatherNormals<Guarded>(xyz, ids, count, out);
}
template<typename T, typename V>
VTK_TANGENT_BATCH_ALWAYS_INLINE inline void GatherLanes(bool guarded,
  const T* xyz,
  const vtkIdType* ids,
  vtkIdType count,
  V out[3])
{
  if (guarded)
  {
    GatherLanes<true>(xyz, ids, count, out);
  }
  else
  {
    GatherLanes<false>(xyz, ids, count, out);
  }
}

/// (x0 y0 + x1 y1) + x2 y2, as single::Dot.
inline Lanes::F LanesDot(const Lanes::F* x, const Lanes::F* y)
{
  return Lanes::Add(
    Lanes::Add(Lanes::Mul(x[0], y[0]), Lanes::Mul(x[1], y[1])), Lanes::Mul(x[2], y[2]));
}

/// x0 x0 + x1 x1.
inline Lanes::F LanesDot2(const Lanes::F* x)
{
  return Lanes::Add(Lanes::Mul(x[0], x[0]), Lanes::Mul(x[1], x[1]));
}

/// (x0 y0 + x1 y1) + x2 y2 in double, as glm::dot.
inline Lanes::D LanesDotDouble(const Lanes::D* x, const Lanes::D* y)
{
  return Lanes::AddDouble(
    Lanes::AddDouble(Lanes::MulDouble(x[0], y[0]), Lanes::MulDouble(x[1], y[1])),
    Lanes::MulDouble(x[2], y[2]));
}

/// The lanes where v's largest component is in [2^-400, 2^400] (so normalizing v rescales nothing,
/// see NormalizeExponent; false for NaN).
inline unsigned LanesUsable(const Lanes::D* v)
{
  using L = Lanes;
  const Lanes::D m =
    L::MaxDouble(L::MaxDouble(L::AbsDouble(v[0]), L::AbsDouble(v[1])), L::AbsDouble(v[2]));
  return L::BitsDouble(
    L::AndDouble(L::GeDouble(m, L::SetDouble(0x1p-400)), L::LeDouble(m, L::SetDouble(0x1p400))));
}

/// single::AtanOfReduced, lane by lane with the same operations.
inline Lanes::F AtanLanes(Lanes::F z, Lanes::F x, Lanes::F x2)
{
  using L = Lanes;
  const float* c = single::AtanMinimax;
  const Lanes::F low = L::Add(L::Set(c[0]), L::Mul(L::Set(c[1]), x));
  const Lanes::F high =
    L::Add(L::Add(L::Set(c[2]), L::Mul(L::Set(c[3]), x)), L::Mul(x2, L::Set(c[4])));
  const Lanes::F p = L::Add(low, L::Mul(x2, high));
  return L::Add(z, L::Mul(L::Mul(z, x), p));
}

/// single::ComputeTriangle for triangles [i, i + Lanes::Count), and with float normals their
/// corners' sides too (see SidesLanes).
template<typename NT>
void ComputeLanes(const BatchInput<float, float, NT>& in, FrameBatch& b, int i)
{
  using L = Lanes;
  using F = typename L::F;
  using M = typename L::M;
  constexpr int count = L::Count;
  const F zero = L::Zero();

  F p[3][3], uv[3][2];
  const int nc = in.UVComponents;
  // The 16-byte loads must not read past the last point: guarded only where it is in the lanes.
  const bool guarded = !IdsBelow<count>(b, i, in.NumberOfPoints - 1);
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType* ids = b.Ids[k] + i;
    for (int l = 0; in.PrefetchSums && l < count; ++l)
    {
      PrefetchForWriting(in.PrefetchSums + ids[l]);
    }
    GatherLanes(guarded, in.Points, ids, in.NumberOfPoints, p[k]);
    if (nc == 2)
    {
      L::GatherUV(in.UVs, ids, uv[k][0], uv[k][1]);
      continue;
    }
    alignas(64) float u[2][count];
    for (int l = 0; l < count; ++l)
    {
      const float* x = in.UVs + nc * ids[l];
      u[0][l] = x[0];
      u[1][l] = nc > 1 ? x[1] : 0.0f;
    }
    uv[k][0] = L::Load(u[0]);
    uv[k][1] = L::Load(u[1]);
  }
  F e1[3], e2[3], e3[3], d1[2], d2[2], d3[2];
  F maxE = zero, sumE = zero, maxUV = zero, sumUV = zero;
  for (int d = 0; d < 3; ++d)
  {
    e1[d] = L::Sub(p[1][d], p[0][d]);
    e2[d] = L::Sub(p[2][d], p[0][d]);
    e3[d] = L::Sub(e2[d], e1[d]);
    maxE = L::Max(maxE, L::Max(L::Abs(e1[d]), L::Abs(e2[d])));
    sumE = L::Add(sumE, L::Add(e1[d], e2[d]));
  }
  for (int d = 0; d < 2; ++d)
  {
    d1[d] = L::Sub(uv[1][d], uv[0][d]);
    d2[d] = L::Sub(uv[2][d], uv[0][d]);
    d3[d] = L::Sub(d2[d], d1[d]);
    maxUV = L::Max(maxUV, L::Max(L::Abs(d1[d]), L::Abs(d2[d])));
    sumUV = L::Add(sumUV, L::Add(d1[d], d2[d]));
  }
  const F lo = L::Set(single::SafeMinimum), hi = L::Set(single::SafeMaximum);
  M vector = L::And(L::Finite(sumE), L::Finite(sumUV));
  vector = L::And(vector, L::And(L::Ge(maxE, lo), L::Le(maxE, hi)));
  vector = L::And(vector, L::And(L::Ge(maxUV, lo), L::Le(maxUV, hi)));
  const unsigned vectorLanes = L::Bits(vector);

  F n[3];
  n[0] = L::Sub(L::Mul(e1[1], e2[2]), L::Mul(e2[1], e1[2]));
  n[1] = L::Sub(L::Mul(e1[2], e2[0]), L::Mul(e2[2], e1[0]));
  n[2] = L::Sub(L::Mul(e1[0], e2[1]), L::Mul(e2[0], e1[1]));
  const F twiceArea2 = LanesDot(n, n);
  const F longest2 = L::Max(L::Max(LanesDot(e1, e1), LanesDot(e2, e2)), LanesDot(e3, e3));
  const float tolP = static_cast<float>(in.Tolerance.Position);
  const M posOK = L::Gt(twiceArea2, L::Mul(L::Mul(L::Set(tolP * tolP), longest2), longest2));
  const F det = L::Sub(L::Mul(d1[0], d2[1]), L::Mul(d2[0], d1[1]));
  const F longestUV2 = L::Max(L::Max(LanesDot2(d1), LanesDot2(d2)), LanesDot2(d3));
  const M uvOK =
    L::Gt(L::Abs(det), L::Mul(L::Set(static_cast<float>(in.Tolerance.UV)), longestUV2));
  const M flip = L::Lt(det, zero);
  F t[3];
  for (int d = 0; d < 3; ++d)
  {
    t[d] = L::NegateWhere(flip, L::Sub(L::Mul(d2[1], e1[d]), L::Mul(d1[1], e2[d])));
  }
  const F tLength = L::Sqrt(LanesDot(t, t));
  const M tOK = L::And(L::Gt(tLength, zero), L::Finite(tLength));
  const F inverse = L::Div(L::Set(1.0f), tLength);
  const unsigned okLanes = L::Bits(L::And(L::And(posOK, uvOK), tOK));
  const unsigned detPositive = L::Bits(L::Gt(det, zero));

  F w[3];
  if (in.Weights == BatchWeights::Angle)
  {
    // single::Angle for the three corners, with the same operations.
    const F sine = L::Sqrt(twiceArea2);
    const F c[3] = { LanesDot(e1, e2), L::Negate(LanesDot(e1, e3)), LanesDot(e2, e3) };
    M steep[3], positive[3];
    F z[3], x[3], base[3], atanZ[3];
    for (int j = 0; j < 3; ++j)
    {
      const F ac = L::Abs(c[j]);
      steep[j] = L::Gt(sine, ac);
      const F num = L::Select(steep[j], ac, sine);
      const F den = L::Select(steep[j], sine, ac);
      positive[j] = L::Gt(den, zero);
      const M reduce = L::Gt(num, L::Mul(L::Set(single::TanPiOver8), den));
      z[j] =
        L::Div(L::Select(reduce, L::Sub(num, den), num), L::Select(reduce, L::Add(num, den), den));
      base[j] = L::Keep(reduce, L::Set(single::PiOver4));
      x[j] = L::Mul(z[j], z[j]);
    }
    for (int j = 0; j < 3; ++j)
    {
      atanZ[j] = AtanLanes(z[j], x[j], L::Mul(x[j], x[j]));
    }
    for (int j = 0; j < 3; ++j)
    {
      F a = L::Add(base[j], atanZ[j]);
      a = L::Select(steep[j], L::Sub(L::Set(single::PiOver2), a), a);
      a = L::Select(L::Lt(c[j], zero), L::Sub(L::Set(single::Pi), a), a);
      w[j] = L::Keep(positive[j], a);
    }
  }
  else if (in.Weights == BatchWeights::Area)
  {
    w[0] = w[1] = w[2] = L::Mul(L::Set(0.5f), L::Sqrt(twiceArea2));
  }
  else
  {
    w[0] = w[1] = w[2] = L::Set(1.0f);
  }
  for (int d = 0; d < 3; ++d)
  {
    L::StoreWide(b.Tangent[d] + i, L::Mul(t[d], inverse));
    L::StoreWide(b.Normal[d] + i, n[d]);
    L::StoreWide(b.Weight[d] + i, w[d]);
  }
  // Orientation bytes: 1 or -1 where the frame is usable, else 0. Then the lanes the vector code
  // does not take, with the scalar kernel.
  for (int l = 0; l < count; l += 8)
  {
    const unsigned ok = okLanes >> l;
    const std::uint64_t bytes =
      SpreadBits(ok & (detPositive >> l)) | (SpreadBits(ok & ~(detPositive >> l)) * 0xff);
    std::memcpy(b.Orientation + i + l, &bytes, 8);
  }
  constexpr unsigned all = (1u << count) - 1;
  for (unsigned rest = ~vectorLanes & all; rest != 0; rest &= rest - 1)
  {
    ScalarTriangle(in, b, i + LowestBit(rest));
  }
  if constexpr (std::is_same<NT, float>::value)
  {
    // The sides, as SidesLanes computes them: float normals gathered like the positions, the dot
    // product with the winding normal in double. Lanes the scalar kernel took, and lanes whose
    // product is zero or not finite when there are stand-in normals, go to ScalarSide.
    using D = typename L::D;
    constexpr int half = L::DoubleCount;
    D nLow[3], nHigh[3];
    for (int d = 0; d < 3; ++d)
    {
      L::Widen(n[d], nLow[d], nHigh[d]);
    }
    const unsigned negativeOrientation = okLanes & ~detPositive;
    for (int k = 0; k < 3; ++k)
    {
      const vtkIdType* ids = b.Ids[k] + i;
      F m[3];
      GatherLanes(guarded, in.Normals, ids, in.NumberOfPoints, m);
      D mLow[3], mHigh[3];
      for (int d = 0; d < 3; ++d)
      {
        L::Widen(m[d], mLow[d], mHigh[d]);
      }
      const D dotLow = LanesDotDouble(mLow, nLow), dotHigh = LanesDotDouble(mHigh, nHigh);
      const unsigned negative = L::NegativeBits(dotLow) | (L::NegativeBits(dotHigh) << half);
      unsigned minus = (negative ^ negativeOrientation) & okLanes & all;
      unsigned scalar = ~vectorLanes & all;
      if (in.Fallback)
      {
        scalar |= ~(L::NonZeroFiniteBits(dotLow) | (L::NonZeroFiniteBits(dotHigh) << half)) & all;
      }
      for (; scalar != 0; scalar &= scalar - 1)
      {
        const int l = LowestBit(scalar);
        minus = ScalarSide(in, b, i + l, ids[l]) < 0 ? (minus | (1u << l)) : (minus & ~(1u << l));
      }
      for (int l = 0; l < count; l += 8)
      {
        const std::uint64_t bytes = SpreadBits(minus >> l);
        std::memcpy(b.Side[k] + i + l, &bytes, 8);
      }
    }
  }
}

/// BatchInput::Side for the corners of triangles [i, i + Lanes::DoubleCount), in double.
template<typename PT, typename UT, typename NT>
void SidesLanes(const BatchInput<PT, UT, NT>& in, FrameBatch& b, int i)
{
  using L = Lanes;
  using D = typename L::D;
  constexpr int count = L::DoubleCount;
  constexpr unsigned all = (1u << count) - 1;
  D n[3];
  for (int d = 0; d < 3; ++d)
  {
    n[d] = L::LoadDouble(b.Normal[d] + i);
  }
  const bool guarded = !IdsBelow<count>(b, i, in.NumberOfPoints - 1);
  unsigned negativeOrientation, zeroOrientation;
  ClassifyBytes(b.Orientation + i, count, negativeOrientation, zeroOrientation);
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType* ids = b.Ids[k] + i;
    D m[3];
    GatherLanes(guarded, in.Normals, ids, in.NumberOfPoints, m);
    const D dot = LanesDotDouble(m, n);
    const unsigned negative = L::NegativeBits(dot);
    // side < 0 where the dot product's sign and the orientation's differ (orientation 0: 0).
    unsigned minus = (negative ^ negativeOrientation) & ~zeroOrientation & all;
    if (in.Fallback)
    {
      for (unsigned unsure = ~L::NonZeroFiniteBits(dot) & all; unsure != 0; unsure &= unsure - 1)
      {
        const int l = LowestBit(unsure);
        const int side = ScalarSide(in, b, i + l, ids[l]);
        minus = side < 0 ? (minus | (1u << l)) : (minus & ~(1u << l));
      }
    }
    const std::uint64_t bytes = SpreadBits(minus);
    std::memcpy(b.Side[k] + i, &bytes, count);
  }
}

/**
 * The frames of points [p, p + Lanes::DoubleCount) of the filter's finish, as its scalar code
 * computes and writes them (SafeNormalize, OrthonormalizeTangent, WriteFrame), for the points
 * with one handedness whose normal and tangent sum are in the range where normalizing rescales
 * nothing. Writes every lane's side byte (PointSum::Sides) and, for the lanes it does, tangent,
 * sign and (when bOut) bitangent; returns the lanes it did not do, whose output the caller's
 * scalar code must write (or that a later pass writes).
 */
template<typename NT, typename OutT>
unsigned FinishLanes(const NT* normals,
  vtkIdType numPoints,
  const PointSum* sums,
  unsigned char* sides,
  vtkIdType p,
  OutT* tOut,
  OutT* sOut,
  OutT* bOut)
{
  using L = Lanes;
  using D = typename L::D;
  constexpr int count = L::DoubleCount;
  constexpr unsigned all = (1u << count) - 1;
  D m[3], t[4], n[3], perp[3], unit[3];
  L::GatherSums(sums + p, t);
  unsigned plusBit, minusBit;
  L::LowBits(t[3], plusBit, minusBit);
  const std::uint64_t bytes = SpreadBits(plusBit) | (SpreadBits(minusBit) << 1);
  std::memcpy(sides + p, &bytes, count);
  const unsigned plus = plusBit & ~minusBit, minus = minusBit & ~plusBit;
  if ((plus | minus) == 0)
  {
    return all;
  }
  L::LoadNormalRun(normals, p, numPoints, m);
  const unsigned usable = LanesUsable(m) & LanesUsable(t);
  const D length = L::SqrtDouble(LanesDotDouble(m, m));
  for (int d = 0; d < 3; ++d)
  {
    n[d] = L::DivDouble(m[d], length);
  }
  const D along = LanesDotDouble(n, t);
  for (int d = 0; d < 3; ++d)
  {
    perp[d] = L::SubDouble(t[d], L::MulDouble(along, n[d]));
  }
  const D perp2 = LanesDotDouble(perp, perp);
  const unsigned ok =
    L::BitsDouble(L::GtDouble(perp2, L::MulDouble(L::SetDouble(1e-18), LanesDotDouble(t, t))));
  const unsigned done = (plus | minus) & usable & ok;
  if (done == 0)
  {
    return all;
  }
  const D perpLength = L::SqrtDouble(perp2);
  for (int d = 0; d < 3; ++d)
  {
    unit[d] = L::DivDouble(perp[d], perpLength);
  }
  alignas(64) double frame[3][count];
  const auto write = [&](OutT* out)
  {
    for (int l = 0; l < count; ++l)
    {
      for (int d = 0; d < 3; ++d)
      {
        out[3 * (p + l) + d] = static_cast<OutT>(frame[d][l]);
      }
    }
  };
  if constexpr (std::is_same<OutT, float>::value)
  {
    L::StoreXYZ(tOut + 3 * p, unit);
    L::StoreSigns(sOut + p, minus);
  }
  else
  {
    for (int d = 0; d < 3; ++d)
    {
      L::StoreDouble(frame[d], unit[d]);
    }
    write(tOut);
    for (int l = 0; l < count; ++l)
    {
      sOut[p + l] = static_cast<OutT>(((minus >> l) & 1u) ? -1.0 : 1.0);
    }
  }
  if (bOut)
  {
    // sign * cross(n, t), as glm computes the cross product; the sign is exact.
    const D cross[3] = { L::SubDouble(L::MulDouble(n[1], unit[2]), L::MulDouble(unit[1], n[2])),
      L::SubDouble(L::MulDouble(n[2], unit[0]), L::MulDouble(unit[2], n[0])),
      L::SubDouble(L::MulDouble(n[0], unit[1]), L::MulDouble(unit[0], n[1])) };
    for (int d = 0; d < 3; ++d)
    {
      L::StoreDouble(frame[d], cross[d]);
    }
    for (int l = 0; l < count; ++l)
    {
      for (int d = 0; ((minus >> l) & 1u) && d < 3; ++d)
      {
        frame[d][l] = -frame[d][l];
      }
    }
    write(bOut);
  }
  return all & ~done;
}

/// The number of points [0, count) whose normal IsUsableNormal rejects (zero or non-finite),
/// Lanes::Count points at a time.
inline vtkIdType CountUnusableNormals(const float* normals, vtkIdType count)
{
  using L = Lanes;
  using F = typename L::F;
  constexpr int lanes = L::Count;
  alignas(64) vtkIdType ids[lanes];
  for (int l = 0; l < lanes; ++l)
  {
    ids[l] = l;
  }
  vtkIdType unusable = 0;
  vtkIdType p = 0;
  // Plain 16-byte loads while the last point is not in the lanes.
  for (; p + lanes < count; p += lanes)
  {
    F n[3];
    L::template GatherXYZ<false>(normals, ids, count, n);
    const F a[3] = { L::Abs(n[0]), L::Abs(n[1]), L::Abs(n[2]) };
    const F largest = L::Max(L::Max(a[0], a[1]), a[2]);
    const F limit = L::Set(FLT_MAX);
    // Finite (false for NaN) and not all zero.
    const unsigned usable = L::Bits(L::And(L::And(L::Le(a[0], limit), L::Le(a[1], limit)),
      L::And(L::Le(a[2], limit), L::Gt(largest, L::Zero()))));
    unusable += lanes - __builtin_popcount(usable);
    for (int l = 0; l < lanes; ++l)
    {
      ids[l] += lanes;
    }
  }
  for (; p < count; ++p)
  {
    const float* n = normals + 3 * p;
    unusable += IsUsableNormal(glm::dvec3(n[0], n[1], n[2])) ? 0 : 1;
  }
  return unusable;
}
