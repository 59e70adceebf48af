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

/// Lanes::GatherXYZ (float xyz into float lanes) or GatherXYZDouble (into double lanes), with the
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
  Lanes::template GatherXYZDouble<Guarded>(xyz, ids, count, out);
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

/// The lane types for scalar type S, float (Lanes::F and its mask M) or double (Lanes::D and DM),
/// and the constants of single::Angle or AngleFromSineCosine: the code both precisions share
/// calls Lanes' operations, overloaded for both. (Keyed on the scalar type: a vector type as a
/// template argument loses its attributes.)
template<typename S>
struct LaneTypes;

template<>
struct LaneTypes<float>
{
  using V = Lanes::F;
  using M = Lanes::M;
  static constexpr float TanPiOver8 = single::TanPiOver8, PiOver4 = single::PiOver4,
                         PiOver2 = single::PiOver2, Pi = single::Pi;
};

template<>
struct LaneTypes<double>
{
  using V = Lanes::D;
  using M = Lanes::DM;
  static constexpr double TanPiOver8 = detail::TanPiOver8, PiOver4 = detail::PiOver4,
                          PiOver2 = detail::PiOver2, Pi = detail::Pi;
};

/// (x0 y0 + x1 y1) + x2 y2, as single::Dot and glm::dot, in the lanes of scalar type S.
template<typename S>
inline typename LaneTypes<S>::V DotOf(const typename LaneTypes<S>::V* x,
  const typename LaneTypes<S>::V* y)
{
  using L = Lanes;
  return L::Add(L::Add(L::Mul(x[0], y[0]), L::Mul(x[1], y[1])), L::Mul(x[2], y[2]));
}
inline Lanes::F LanesDot(const Lanes::F* x, const Lanes::F* y)
{
  return DotOf<float>(x, y);
}
inline Lanes::D LanesDot(const Lanes::D* x, const Lanes::D* y)
{
  return DotOf<double>(x, y);
}

/// x0 x0 + x1 x1.
template<typename S>
inline typename LaneTypes<S>::V Dot2Of(const typename LaneTypes<S>::V* x)
{
  using L = Lanes;
  return L::Add(L::Mul(x[0], x[0]), L::Mul(x[1], x[1]));
}
inline Lanes::F LanesDot2(const Lanes::F* x)
{
  return Dot2Of<float>(x);
}
inline Lanes::D LanesDot2(const Lanes::D* x)
{
  return Dot2Of<double>(x);
}

/// The lanes where v's largest component is in [2^-400, 2^400] (so normalizing v rescales nothing,
/// see NormalizeExponent; false for NaN).
inline unsigned LanesUsable(const Lanes::D* v)
{
  using L = Lanes;
  const Lanes::D m = L::Max(L::Max(L::Abs(v[0]), L::Abs(v[1])), L::Abs(v[2]));
  return L::Bits(L::And(L::Ge(m, L::Set(0x1p-400)), L::Le(m, L::Set(0x1p400))));
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

/// atan of the three reduced arguments of TriangleLanes<float>::Angles: single::AtanOfReduced.
struct AtanFloatLanes
{
  void operator()(const Lanes::F z[3], Lanes::F atanZ[3]) const
  {
    for (int j = 0; j < 3; ++j)
    {
      const Lanes::F x = Lanes::Mul(z[j], z[j]);
      atanZ[j] = AtanLanes(z[j], x, Lanes::Mul(x, x));
    }
  }
};

/// The same for TriangleLanes<double>::Angles: AtanOfReducedDouble, lane by lane with the same
/// operations.
struct AtanDoubleLanes
{
  void operator()(const Lanes::D z[3], Lanes::D atanZ[3]) const
  {
    using L = Lanes;
    using D = Lanes::D;
    const double* c = AtanMinimaxDouble;
    const auto pair = [&](int k, D x) { return L::Add(L::Set(c[k]), L::Mul(L::Set(c[k + 1]), x)); };
    for (int j = 0; j < 3; ++j)
    {
      const D x = L::Mul(z[j], z[j]);
      const D x2 = L::Mul(x, x);
      const D x4 = L::Mul(x2, x2);
      const D x8 = L::Mul(x4, x4);
      const D low = L::Add(pair(0, x), L::Mul(pair(2, x), x2));
      const D high = L::Add(pair(4, x), L::Mul(pair(6, x), x2));
      const D q = L::Add(L::Add(low, L::Mul(high, x4)), L::Mul(pair(8, x), x8));
      atanZ[j] = L::Add(z[j], L::Mul(L::Mul(z[j], x), q));
    }
  }
};

/// A triangle kernel's lanes up to the weights: edges, winding normal, unit tangent and the lane
/// masks, as both precisions compute them (TriangleLanes::Solve), in float or double lanes.
template<typename S>
struct TriangleLanes
{
  using L = Lanes;
  using O = LaneTypes<S>;
  using V = typename O::V;
  V E1[3], E2[3], E3[3];
  V Normal[3];          ///< e1 x e2, the winding normal
  V TwiceArea2;         ///< |e1 x e2|^2
  V Tangent[3];         ///< unit
  unsigned Vector;      ///< the lanes the vector code takes; the others go to ScalarTriangle
  unsigned Usable;      ///< the lanes with a frame
  unsigned DetPositive; ///< the lanes whose UV determinant is positive

  /**
   * ComputeTriangleFrame's solve (single::ComputeTriangle's for float) for positions p[corner][xyz]
   * and texture coordinates uv[corner][uv]: lanes whose largest edge or UV delta component is
   * outside [safeMinimum, safeMaximum] or not finite are left to the scalar kernel; a lane has a
   * frame when its area is above tolP2 (the squared position tolerance) times the longest edge
   * squared squared, its UV area above tolUV times the longest UV edge squared, and its tangent is
   * finite and not zero.
   */
  VTK_TANGENT_BATCH_ALWAYS_INLINE void Solve(const V p[3][3],
    const V uv[3][2],
    S safeMinimum,
    S safeMaximum,
    S tolP2,
    S tolUV)
  {
    const V zero = L::Set(S(0));
    V d1[2], d2[2], d3[2];
    V maxE = zero, sumE = zero, maxUV = zero, sumUV = zero;
    for (int d = 0; d < 3; ++d)
    {
      this->E1[d] = L::Sub(p[1][d], p[0][d]);
      this->E2[d] = L::Sub(p[2][d], p[0][d]);
      this->E3[d] = L::Sub(this->E2[d], this->E1[d]);
      maxE = L::Max(maxE, L::Max(L::Abs(this->E1[d]), L::Abs(this->E2[d])));
      sumE = L::Add(sumE, L::Add(this->E1[d], this->E2[d]));
    }
    for (int d = 0; d < 2; ++d)
    {
      d1[d] = L::Sub(uv[1][d], uv[0][d]);
      d2[d] = L::Sub(uv[2][d], uv[0][d]);
      d3[d] = L::Sub(d2[d], d1[d]);
      maxUV = L::Max(maxUV, L::Max(L::Abs(d1[d]), L::Abs(d2[d])));
      sumUV = L::Add(sumUV, L::Add(d1[d], d2[d]));
    }
    // Every component finite (a sum of finite numbers can overflow: then the scalar kernel
    // decides) and both largest components in the safe range.
    const V lo = L::Set(safeMinimum), hi = L::Set(safeMaximum);
    auto vector = L::And(L::Finite(sumE), L::Finite(sumUV));
    vector = L::And(vector, L::And(L::Ge(maxE, lo), L::Le(maxE, hi)));
    vector = L::And(vector, L::And(L::Ge(maxUV, lo), L::Le(maxUV, hi)));
    this->Vector = L::Bits(vector);

    const V* e1 = this->E1;
    const V* e2 = this->E2;
    V* n = this->Normal;
    n[0] = L::Sub(L::Mul(e1[1], e2[2]), L::Mul(e2[1], e1[2]));
    n[1] = L::Sub(L::Mul(e1[2], e2[0]), L::Mul(e2[2], e1[0]));
    n[2] = L::Sub(L::Mul(e1[0], e2[1]), L::Mul(e2[0], e1[1]));
    this->TwiceArea2 = LanesDot(n, n);
    const V longest2 = L::Max(L::Max(LanesDot(e1, e1), LanesDot(e2, e2)), LanesDot(E3, E3));
    const auto posOK = L::Gt(this->TwiceArea2, L::Mul(L::Mul(L::Set(tolP2), longest2), longest2));
    const V det = L::Sub(L::Mul(d1[0], d2[1]), L::Mul(d2[0], d1[1]));
    const V longestUV2 = L::Max(L::Max(LanesDot2(d1), LanesDot2(d2)), LanesDot2(d3));
    const auto uvOK = L::Gt(L::Abs(det), L::Mul(L::Set(tolUV), longestUV2));
    const auto flip = L::Lt(det, zero);
    V t[3];
    for (int d = 0; d < 3; ++d)
    {
      t[d] = L::NegateWhere(flip, L::Sub(L::Mul(d2[1], e1[d]), L::Mul(d1[1], e2[d])));
    }
    const V tLength = L::Sqrt(LanesDot(t, t));
    const auto tOK = L::And(L::Gt(tLength, zero), L::Finite(tLength));
    const V inverse = L::Div(L::Set(S(1)), tLength);
    for (int d = 0; d < 3; ++d)
    {
      this->Tangent[d] = L::Mul(t[d], inverse);
    }
    this->Usable = L::Bits(L::And(L::And(posOK, uvOK), tOK));
    this->DetPositive = L::Bits(L::Gt(det, zero));
  }

  /**
   * The corner angles (single::Angle, or AngleFromSineCosine for double), from the sine |e1 x e2|
   * and each corner's cosine term; `atan(z, out)` gives atan of the three reduced arguments.
   */
  template<typename Atan>
  VTK_TANGENT_BATCH_ALWAYS_INLINE void Angles(Atan&& atan, V angle[3]) const
  {
    using M = typename O::M;
    const V zero = L::Set(S(0));
    const V sine = L::Sqrt(this->TwiceArea2);
    const V c[3] = { LanesDot(E1, E2), L::Negate(LanesDot(E1, E3)), LanesDot(E2, E3) };
    M steep[3], positive[3];
    V z[3], base[3], atanZ[3];
    for (int j = 0; j < 3; ++j)
    {
      const V ac = L::Abs(c[j]);
      steep[j] = L::Gt(sine, ac);
      const V num = L::Select(steep[j], ac, sine);
      const V den = L::Select(steep[j], sine, ac);
      positive[j] = L::Gt(den, zero);
      // One division either way: (num - den) / (num + den) is (z - 1) / (z + 1) for num / den.
      const M reduce = L::Gt(num, L::Mul(L::Set(O::TanPiOver8), den));
      z[j] =
        L::Div(L::Select(reduce, L::Sub(num, den), num), L::Select(reduce, L::Add(num, den), den));
      base[j] = L::Keep(reduce, L::Set(O::PiOver4));
    }
    atan(z, atanZ);
    for (int j = 0; j < 3; ++j)
    {
      V a = L::Add(base[j], atanZ[j]);
      a = L::Select(steep[j], L::Sub(L::Set(O::PiOver2), a), a);
      a = L::Select(L::Lt(c[j], zero), L::Sub(L::Set(O::Pi), a), a);
      angle[j] = L::Keep(positive[j], a);
    }
  }

  /// Stores the lanes' frames and weights w as triangles [i, i + Count) of the batch, with their
  /// orientations (+1 or -1 where the frame is usable, else 0); then the lanes the vector
  /// code does not take, with the scalar kernel.
  template<int Count, typename PT, typename UT, typename NT>
  void Write(const BatchInput<PT, UT, NT>& in, FrameBatch& b, int i, const V w[3]) const
  {
    for (int d = 0; d < 3; ++d)
    {
      L::Store(b.Tangent[d] + i, this->Tangent[d]);
      L::Store(b.Normal[d] + i, this->Normal[d]);
      L::Store(b.Weight[d] + i, w[d]);
    }
    b.SetOrientations(i, Count, this->Usable, this->DetPositive);
    constexpr unsigned all = (1u << Count) - 1;
    for (unsigned rest = ~this->Vector & all; rest != 0; rest &= rest - 1)
    {
      ScalarTriangle(in, b, i + LowestBit(rest));
    }
  }
};

/// The weights of `in.Weights` for the solved lanes r; `atan` as for TriangleLanes::Angles.
template<typename S, typename PT, typename UT, typename NT, typename Atan>
VTK_TANGENT_BATCH_ALWAYS_INLINE inline void WeightLanes(const BatchInput<PT, UT, NT>& in,
  const TriangleLanes<S>& r,
  Atan&& atan,
  typename LaneTypes<S>::V w[3])
{
  using L = Lanes;
  if (in.Weights == BatchWeights::Angle)
  {
    r.Angles(atan, w);
  }
  else if (in.Weights == BatchWeights::Area)
  {
    w[0] = w[1] = w[2] = L::Mul(L::Set(S(0.5)), L::Sqrt(r.TwiceArea2));
  }
  else
  {
    w[0] = w[1] = w[2] = L::Set(S(1));
  }
}

/// single::ComputeTriangle for triangles [i, i + Lanes::Count), and with float normals their
/// corners' sides too (see SidesLanes).
template<typename NT>
void ComputeLanes(const BatchInput<float, float, NT>& in, FrameBatch& b, int i)
{
  using L = Lanes;
  using F = typename L::F;
  constexpr int count = L::Count;

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
  TriangleLanes<float> r;
  const float tolP = static_cast<float>(in.Tolerance.Position);
  r.Solve(p,
    uv,
    single::SafeMinimum,
    single::SafeMaximum,
    tolP * tolP,
    static_cast<float>(in.Tolerance.UV));
  F w[3];
  WeightLanes(in, r, AtanFloatLanes{}, w);
  r.template Write<count>(in, b, i, w);
  if constexpr (std::is_same<NT, float>::value)
  {
    // The sides, as SidesLanes computes them: float normals gathered like the positions, the dot
    // product with the winding normal in double. Lanes the scalar kernel took, and lanes whose
    // product is zero or not finite when there are stand-in normals, go to ScalarSide.
    using D = typename L::D;
    constexpr int half = L::DoubleCount;
    constexpr unsigned all = (1u << count) - 1;
    D nLow[3], nHigh[3];
    for (int d = 0; d < 3; ++d)
    {
      L::Widen(r.Normal[d], nLow[d], nHigh[d]);
    }
    const unsigned negativeOrientation = r.Usable & ~r.DetPositive;
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
      const D dotLow = LanesDot(mLow, nLow), dotHigh = LanesDot(mHigh, nHigh);
      const unsigned negative = L::NegativeBits(dotLow) | (L::NegativeBits(dotHigh) << half);
      unsigned minus = (negative ^ negativeOrientation) & r.Usable & all;
      unsigned scalar = ~r.Vector & all;
      if (in.Fallback)
      {
        scalar |= ~(L::NonZeroFiniteBits(dotLow) | (L::NonZeroFiniteBits(dotHigh) << half)) & all;
      }
      for (; scalar != 0; scalar &= scalar - 1)
      {
        const int l = LowestBit(scalar);
        minus = ScalarSide(in, b, i + l, ids[l]) < 0 ? (minus | (1u << l)) : (minus & ~(1u << l));
      }
      b.SetSides(k, i, count, minus);
    }
  }
}

/// ComputeBatchTriangle for triangles [i, i + Lanes::DoubleCount) of the double-precision path
/// (any input but float positions with float texture coordinates), lane by lane with the same
/// operations. The sides are SidesLanes' work.
template<typename PT, typename UT, typename NT>
void ComputeDoubleLanes(const BatchInput<PT, UT, NT>& in, FrameBatch& b, int i)
{
  using L = Lanes;
  using D = typename L::D;
  constexpr int count = L::DoubleCount;

  D p[3][3], uv[3][2];
  const int nc = in.UVComponents;
  // The 32-byte loads of double positions must not read past the last point.
  const bool guarded = !IdsBelow<count>(b, i, in.NumberOfPoints - 1);
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType* ids = b.Ids[k] + i;
    GatherLanes(guarded, in.Points, ids, in.NumberOfPoints, p[k]);
    if constexpr (std::is_same<UT, double>::value)
    {
      if (nc == 2)
      {
        L::GatherUVDouble(in.UVs, ids, uv[k][0], uv[k][1]);
        continue;
      }
    }
    uv[k][0] = L::GatherDouble(in.UVs, nc, ids, 0);
    uv[k][1] = nc > 1 ? L::GatherDouble(in.UVs, nc, ids, 1) : L::Set(0.0);
  }
  TriangleLanes<double> r;
  r.Solve(p,
    uv,
    SafeMinimum,
    SafeMaximum,
    in.Tolerance.Position * in.Tolerance.Position,
    in.Tolerance.UV);
  D w[3];
  WeightLanes(in, r, AtanDoubleLanes{}, w);
  r.template Write<count>(in, b, i, w);
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
    n[d] = L::Load(b.Normal[d] + i);
  }
  const bool guarded = !IdsBelow<count>(b, i, in.NumberOfPoints - 1);
  const unsigned framed = static_cast<unsigned>(b.Framed >> i) & all;
  const unsigned negativeOrientation = static_cast<unsigned>(b.Mirrored >> i) & framed;
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType* ids = b.Ids[k] + i;
    D m[3];
    GatherLanes(guarded, in.Normals, ids, in.NumberOfPoints, m);
    const D dot = LanesDot(m, n);
    const unsigned negative = L::NegativeBits(dot);
    // side < 0 where the dot product's sign and the orientation's differ (orientation 0: 0).
    unsigned minus = (negative ^ negativeOrientation) & framed;
    if (in.Fallback)
    {
      for (unsigned unsure = ~L::NonZeroFiniteBits(dot) & all; unsure != 0; unsure &= unsure - 1)
      {
        const int l = LowestBit(unsure);
        const int side = ScalarSide(in, b, i + l, ids[l]);
        minus = side < 0 ? (minus | (1u << l)) : (minus & ~(1u << l));
      }
    }
    b.SetSides(k, i, count, minus);
  }
}

/**
 * The frames of points [p, p + Lanes::DoubleCount) of the filter's finish, as its scalar code
 * computes and writes them (SafeNormalize, OrthonormalizeTangent, WriteFrame), for the points
 * with one handedness whose normal and tangent sum are in the range where normalizing rescales
 * nothing. Writes every lane's side byte (PointSum::Sides) and, unless no lane is done, every
 * lane's tangent, sign and (when bOut) bitangent, whole vectors at a time; returns the lanes it
 * did not do, whose output is not meaningful yet: the caller's scalar code must write it (or a
 * later pass does).
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
  const D length = L::Sqrt(LanesDot(m, m));
  for (int d = 0; d < 3; ++d)
  {
    n[d] = L::Div(m[d], length);
  }
  const D along = LanesDot(n, t);
  for (int d = 0; d < 3; ++d)
  {
    perp[d] = L::Sub(t[d], L::Mul(along, n[d]));
  }
  const D perp2 = LanesDot(perp, perp);
  const unsigned ok = L::Bits(L::Gt(perp2, L::Mul(L::Set(1e-18), LanesDot(t, t))));
  const unsigned done = (plus | minus) & usable & ok;
  if (done == 0)
  {
    return all;
  }
  const D perpLength = L::Sqrt(perp2);
  for (int d = 0; d < 3; ++d)
  {
    unit[d] = L::Div(perp[d], perpLength);
  }
  L::StoreXYZ(tOut + 3 * p, unit);
  L::StoreSigns(sOut + p, minus);
  if (bOut)
  {
    // sign * cross(n, t), as glm computes the cross product; the sign is exact.
    const auto flip = L::MaskFromBits(minus);
    const D bitangent[3] = { L::NegateWhere(
                               flip, L::Sub(L::Mul(n[1], unit[2]), L::Mul(unit[1], n[2]))),
      L::NegateWhere(flip, L::Sub(L::Mul(n[2], unit[0]), L::Mul(unit[2], n[0]))),
      L::NegateWhere(flip, L::Sub(L::Mul(n[0], unit[1]), L::Mul(unit[0], n[1]))) };
    L::StoreXYZ(bOut + 3 * p, bitangent);
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
