// SPDX-License-Identifier: BSD-3-Clause
// Tests of the MikkTSpace kernel (vtkMikkTSpaceKernel.h): comparison with tangents produced by
// the reference mikktspace.c (shared/data/mikktspace/*.vtp), with the tangents stored in the
// Khronos glTF sample NormalTangentMirrorTest, and unit tests on hand-built meshes.
//
// Shared data location: see NormalMappingTestData.h.

#include "MikkTSpaceKernelMesh.h"
#include "NormalMappingTestData.h"
#include "NormalMappingThreads.h"
#include "vtkMikkTSpaceKernel.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkXMLPolyDataReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace mikk = vtkNormalMapping::mikk;
using namespace NormalMappingTestData;

namespace
{
//------------------------------------------------------------------------------
using Mesh = NormalMappingTesting::KernelMesh;

/// The kernel's result, with vtkSMPTools' default threads or with `threads`.
mikk::Result RunKernel(const Mesh& m, int threads = 0)
{
  if (threads <= 0)
  {
    return mikk::ComputeMikkTSpace(m.Input());
  }
  mikk::Result r;
  NormalMappingTesting::WithThreads(threads, [&]() { r = mikk::ComputeMikkTSpace(m.Input()); });
  return r;
}

bool IsDefault(const mikk::CornerFrame& f)
{
  return f.Tangent[0] == 1.0f && f.Tangent[1] == 0.0f && f.Tangent[2] == 0.0f && f.Sign == -1.0f;
}

bool BitEqual(const mikk::CornerFrame& a, const mikk::CornerFrame& b)
{
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

//------------------------------------------------------------------------------
// Reference data
struct ReferenceMesh
{
  Mesh M;
  std::vector<float> Tangents; // 4 per triangle corner
};

bool LoadReference(const std::string& path, ReferenceMesh& out, std::string& error)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* pd = reader->GetOutput();
  if (!pd || !pd->GetPoints())
  {
    error = "cannot read " + path;
    return false;
  }
  vtkDataArray* normals = pd->GetPointData()->GetArray("Normals");
  vtkDataArray* tcoords = pd->GetPointData()->GetArray("TCoords");
  vtkDataArray* tangents = pd->GetFieldData()->GetArray("CornerTangents");
  if (!normals || !tcoords || !tangents || tangents->GetNumberOfComponents() != 4)
  {
    error = "missing Normals, TCoords or CornerTangents in " + path;
    return false;
  }
  const vtkIdType np = pd->GetNumberOfPoints();
  Mesh& m = out.M;
  m.P.resize(3 * static_cast<size_t>(np));
  m.N.resize(3 * static_cast<size_t>(np));
  m.U.resize(2 * static_cast<size_t>(np));
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3];
    pd->GetPoints()->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      // stored as float32: the double round trip is exact
      m.P[3 * i + k] = static_cast<float>(p[k]);
      m.N[3 * i + k] = static_cast<float>(normals->GetComponent(i, k));
    }
    m.U[2 * i] = static_cast<float>(tcoords->GetComponent(i, 0));
    m.U[2 * i + 1] = static_cast<float>(tcoords->GetComponent(i, 1));
  }
  vtkCellArray* polys = pd->GetPolys();
  vtkIdType npts;
  const vtkIdType* pts;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    if (npts != 3)
    {
      error = "non-triangle cell in " + path;
      return false;
    }
    m.AddFace({ pts[0], pts[1], pts[2] });
  }
  if (tangents->GetNumberOfTuples() != static_cast<vtkIdType>(m.Conn.size()))
  {
    error = "CornerTangents size does not match the triangles in " + path;
    return false;
  }
  out.Tangents.resize(4 * m.Conn.size());
  for (vtkIdType i = 0; i < tangents->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < 4; ++k)
    {
      out.Tangents[4 * i + k] = static_cast<float>(tangents->GetComponent(i, k));
    }
  }
  return true;
}

// Largest angle accepted between our tangent and the reference's, in degrees.
// Both compute the same float expressions in the same order, so they agree bit for bit (the
// measured distribution is all zeros, see docs/mikktspace.md). Legitimate sources of
// difference are compilation details of either side: FMA contraction (measured <= 1.8e-7 per
// component on the reference, MIKKTSPACE.md), a float instead of double acos (<= 1.2e-7) and
// the sign of zero components. Each amounts to a few float ulps of a unit vector, i.e. about
// 1e-7 rad = 6e-6 degrees per ulp; 1e-3 degrees allows ~150 ulps, so it only fails on a real
// algorithmic difference (wrong group, weight or order), which shows as >= ~0.01 degree.
constexpr double kMaxAngleDeg = 1e-3;

// glTF comparison bound, in degrees. The stored tangents come from Blender's MikkTSpace
// rewrite, which weights by a polynomial acos approximation (absolute error ~1e-4 rad per
// weight) instead of libm. A relative weight error e tilts an average of directions spread by
// at most ~90 degrees by less than e * 90 degrees, ~0.005 degrees here; measured max 0.003.
constexpr double kGltfMaxAngleDeg = 0.01;

} // namespace

//------------------------------------------------------------------------------
TEST(MikkTSpaceKernel, MatchesReferenceData)
{
  REQUIRE_SHARED_DATA(dataDir);
  const std::vector<std::string> names = { "sphere_poles",
    "torus",
    "mirror_grid",
    "cylinder_seam",
    "noisy",
    "NormalTangentTest",
    "NormalTangentMirrorTest" };
  int tested = 0;
  for (const std::string& name : names)
  {
    const std::string path = dataDir + "/mikktspace/" + name + ".vtp";
    if (!std::ifstream(path).good())
    {
      ADD_FAILURE() << "missing reference file " << path;
      continue;
    }
    ReferenceMesh ref;
    std::string error;
    ASSERT_TRUE(LoadReference(path, ref, error)) << error;
    const mikk::Result res = RunKernel(ref.M);
    ASSERT_EQ(res.Corners.size(), ref.M.Conn.size());
    Stats st;
    for (size_t c = 0; c < res.Corners.size(); ++c)
    {
      const float* r = &ref.Tangents[4 * c];
      const mikk::CornerFrame& o = res.Corners[c];
      const bool refDefault = r[0] == 1.0f && r[1] == 0.0f && r[2] == 0.0f && r[3] == -1.0f;
      if (refDefault)
      {
        ++st.ReferenceDefaults;
        if (!IsDefault(o))
        {
          ++st.DefaultMismatches;
          ADD_FAILURE() << name << " corner " << c << ": reference default, ours (" << o.Tangent[0]
                        << ", " << o.Tangent[1] << ", " << o.Tangent[2] << ", " << o.Sign << ")";
        }
        continue;
      }
      if (r[3] != o.Sign)
      {
        ++st.SignMismatches;
        ADD_FAILURE() << name << " corner " << c << ": sign " << o.Sign << ", reference " << r[3];
      }
      const double a = AngleDeg(r, o.Tangent);
      st.Angles.push_back(a);
      EXPECT_LE(a, kMaxAngleDeg) << name << " corner " << c << " (triangle " << c / 3 << ")";
    }
    std::printf("[ mikk     ] %-24s corners %7zu  exact %7lld  mean %.3g  p99 %.3g  max %.3g deg"
                "  sign mismatches %lld  reference defaults %lld (mismatched %lld)"
                "  degenerate triangles %lld\n",
      name.c_str(),
      res.Corners.size(),
      st.Exact(),
      st.Mean(),
      st.Quantile(0.99),
      st.Max(),
      st.SignMismatches,
      st.ReferenceDefaults,
      st.DefaultMismatches,
      res.NumberOfDegenerateTriangles);
    ++tested;
  }
  EXPECT_EQ(tested, static_cast<int>(names.size()));
}

//------------------------------------------------------------------------------
// NormalTangentMirrorTest.gltf stores MikkTSpace tangents exported by Blender (TANGENT, vec4).
// glTF UVs run v downward, so glTF tangent = ours on the glTF UVs with the sign negated.
TEST(MikkTSpaceKernel, MatchesGltfStoredTangents)
{
  REQUIRE_SHARED_DATA(dataDir);
  const std::string path = dataDir + "/gltf/NormalTangentMirrorTest/NormalTangentMirrorTest.gltf";
  GltfPrimitive gltf;
  std::string error;
  ASSERT_TRUE(LoadGltfPrimitive(path, gltf, error)) << error;
  const std::vector<double>& pos = gltf.Positions;
  const std::vector<double>& nrm = gltf.Normals;
  const std::vector<double>& uv = gltf.TexCoords;
  const std::vector<double>& tan = gltf.Tangents;
  const std::vector<double>& idx = gltf.Indices;
  ASSERT_FALSE(tan.empty()) << "no TANGENT in " << path;
  ASSERT_EQ(idx.size() % 3, 0u);
  Mesh m;
  m.P.assign(pos.begin(), pos.end()); // float32 values: exact
  m.N.assign(nrm.begin(), nrm.end());
  m.U.assign(uv.begin(), uv.end());
  for (size_t t = 0; t < idx.size(); t += 3)
  {
    m.AddFace({ static_cast<long long>(idx[t]),
      static_cast<long long>(idx[t + 1]),
      static_cast<long long>(idx[t + 2]) });
  }
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), m.Conn.size()) << "a frame for every corner";
  Stats st;
  for (size_t c = 0; c < res.Corners.size(); ++c)
  {
    const size_t v = static_cast<size_t>(m.Conn[c]);
    const float stored[3] = { static_cast<float>(tan[4 * v]),
      static_cast<float>(tan[4 * v + 1]),
      static_cast<float>(tan[4 * v + 2]) };
    const mikk::CornerFrame& o = res.Corners[c];
    if (static_cast<float>(tan[4 * v + 3]) != -o.Sign)
    {
      ++st.SignMismatches;
    }
    st.Angles.push_back(AngleDeg(stored, o.Tangent));
  }
  std::printf(
    "[ mikk     ] glTF NormalTangentMirrorTest corners %zu  mean %.3g  p99 %.3g  max %.3g deg"
    "  sign mismatches %lld\n",
    res.Corners.size(),
    st.Mean(),
    st.Quantile(0.99),
    st.Max(),
    st.SignMismatches);
  EXPECT_EQ(st.SignMismatches, 0);
  EXPECT_LE(st.Max(), kGltfMaxAngleDeg);
}

//------------------------------------------------------------------------------
// Unit tests on hand-built meshes
namespace
{
constexpr std::array<float, 3> kUp = { 0.0f, 0.0f, 1.0f };

// Tolerance for tangents expected to be exact axis vectors: they come out of a normalisation
// of an exactly axis-aligned vector (or a sum of them), so only a 1-ulp error of 1/sqrt is
// possible: 2 ulps of 1.0f = 2.4e-7.
constexpr float kAxisTol = 2.4e-7f;

void ExpectTangent(const mikk::CornerFrame& f,
  float x,
  float y,
  float z,
  float sign,
  const char* what)
{
  EXPECT_NEAR(f.Tangent[0], x, kAxisTol) << what;
  EXPECT_NEAR(f.Tangent[1], y, kAxisTol) << what;
  EXPECT_NEAR(f.Tangent[2], z, kAxisTol) << what;
  EXPECT_EQ(f.Sign, sign) << what;
}

// Non-planar quad with per-point normals; uv chosen by the caller.
Mesh BentQuad(const std::array<std::array<float, 2>, 4>& uv,
  const std::array<std::array<float, 3>, 4>& pos)
{
  Mesh m;
  const std::array<std::array<float, 3>, 4> nrm = { { { -0.2f, -0.1f, 0.974679f },
    { 0.3f, -0.2f, 0.932738f },
    { 0.1f, 0.4f, 0.910494f },
    { -0.3f, 0.2f, 0.932738f } } };
  for (int i = 0; i < 4; ++i)
  {
    m.AddPoint(pos[i], nrm[i], uv[i]);
  }
  return m;
}

// The same points as separate triangles.
Mesh AsTriangles(const Mesh& quad, std::initializer_list<std::array<long long, 3>> tris)
{
  Mesh m = quad;
  m.Offsets = { 0 };
  m.Conn.clear();
  for (const auto& t : tris)
  {
    m.AddFace({ t[0], t[1], t[2] });
  }
  return m;
}

// The corners whose frame is not a unit tangent in the plane z = 0 with sign +1.
int CountNotUnitInPlane(const mikk::Result& r)
{
  int wrong = 0;
  for (const mikk::CornerFrame& f : r.Corners)
  {
    const float length = std::sqrt(
      f.Tangent[0] * f.Tangent[0] + f.Tangent[1] * f.Tangent[1] + f.Tangent[2] * f.Tangent[2]);
    // A float unit vector's length is 1 within a few float roundings.
    wrong += f.Sign == 1.0f && std::abs(length - 1.0f) < 1e-5f && f.Tangent[2] == 0.0f ? 0 : 1;
  }
  return wrong;
}
} // namespace

// Quads split on the shorter UV diagonal; on a UV tie, 1-3 only if its position diagonal is
// strictly shorter. The quad's corners must equal those of the explicitly split triangles.
TEST(MikkTSpaceKernel, QuadSplitRule)
{
  const std::array<std::array<float, 3>, 4> pos = {
    { { 0, 0, 0 }, { 1, 0, 0.3f }, { 1.2f, 1.1f, -0.2f }, { 0, 1, 0.25f } }
  };
  struct Case
  {
    const char* Name;
    std::array<std::array<float, 2>, 4> UV;
    std::array<std::array<float, 3>, 4> Pos;
    bool Diag02;
  };
  // UV diagonals: (a) |uv2-uv0|^2 = 3.25 > |uv3-uv1|^2 = 1.25 -> 1-3;
  // (b) the mirror image -> 0-2; (c) unit square (tie), position 0-2 longer -> 1-3;
  // (d) tie with equal position diagonals -> 0-2.
  const std::vector<Case> cases = {
    { "uv 1-3 shorter", { { { 0, 0 }, { 1, 0 }, { 1.5f, 1 }, { 0.5f, 1 } } }, pos, false },
    { "uv 0-2 shorter", { { { 0.5f, 0 }, { 1.5f, 0 }, { 1, 1 }, { 0, 1 } } }, pos, true },
    { "uv tie, position 1-3 shorter", { { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } } }, pos, false },
    { "uv tie, position tie",
      { { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } } },
      { { { 0, 0, 0 }, { 1, 0, 0.3f }, { 1, 1, 0 }, { 0, 1, 0.3f } } },
      true },
  };
  for (const Case& c : cases)
  {
    Mesh quad = BentQuad(c.UV, c.Pos);
    quad.AddFace({ 0, 1, 2, 3 });
    const Mesh split02 = AsTriangles(quad, { { 0, 1, 2 }, { 0, 2, 3 } });
    const Mesh split13 = AsTriangles(quad, { { 0, 1, 3 }, { 1, 2, 3 } });
    const mikk::Result q = RunKernel(quad);
    const mikk::Result a = RunKernel(split02);
    const mikk::Result b = RunKernel(split13);
    ASSERT_EQ(q.Corners.size(), 4u);
    // quad corner -> corner of the split triangles (face*3 + k)
    const std::array<size_t, 4> map02 = { 0, 1, 2, 5 };
    const std::array<size_t, 4> map13 = { 0, 1, 4, 2 };
    const mikk::Result& expected = c.Diag02 ? a : b;
    const std::array<size_t, 4>& map = c.Diag02 ? map02 : map13;
    const mikk::Result& other = c.Diag02 ? b : a;
    const std::array<size_t, 4>& otherMap = c.Diag02 ? map13 : map02;
    bool differsFromOther = false;
    for (size_t k = 0; k < 4; ++k)
    {
      EXPECT_TRUE(BitEqual(q.Corners[k], expected.Corners[map[k]])) << c.Name << " corner " << k;
      differsFromOther = differsFromOther || !BitEqual(q.Corners[k], other.Corners[otherMap[k]]);
    }
    // the mesh is bent, so the two splits give different tangents: the test can tell them apart
    EXPECT_TRUE(differsFromOther) << c.Name;
  }
}

// A quad whose two triangles have opposite UV orientations takes one orientation for both, the
// reference's rule: that of the triangle with the larger UV area, the first on a tie. Here the
// quad splits on its shorter UV diagonal 0-2 into (0, 1, 2) and (0, 2, 3), whose UV areas are
// equal: every corner takes the first triangle's sign, +1, or -1 with u mirrored.
TEST(MikkTSpaceKernel, QuadOfOppositeOrientationsTakesTheFirstOnATie)
{
  for (const float mirror : { 1.0f, -1.0f })
  {
    Mesh m;
    m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
    m.AddPoint({ 1, 0, 0 }, kUp, { mirror * 0.5f, -1 });
    m.AddPoint({ 1, 1, 0 }, kUp, { mirror * 1, 0 });
    m.AddPoint({ 0, 1, 0 }, kUp, { mirror * 3, -1 });
    m.AddFace({ 0, 1, 2, 3 });
    const mikk::Result res = RunKernel(m);
    ASSERT_EQ(res.Corners.size(), 4u);
    for (size_t k = 0; k < 4; ++k)
    {
      EXPECT_EQ(res.Corners[k].Sign, mirror) << "corner " << k << ", mirror " << mirror;
    }
  }
}

// A quad whose second triangle is "group with any" keeps the first triangle's orientation even
// when the second has the larger UV area (the reference's rule). Split on its shorter UV
// diagonal 0-2: A = (0, 1, 2) is left-handed with UV determinant -0.3; B = (0, 2, 3) has
// collinear positions, so its dP/du vanishes and it groups with any, while its UV determinant
// is +2. A's corners are those of A alone, sign -1; taking B's orientation would make them +1.
TEST(MikkTSpaceKernel, QuadKeepsTheFirstOrientationWhenTheSecondGroupsWithAny)
{
  Mesh quad;
  quad.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  quad.AddPoint({ 1, 0, 0 }, kUp, { 0, 0.6f });
  quad.AddPoint({ 1, 1, 0 }, kUp, { 0.5f, 0.5f });
  quad.AddPoint({ 2, 2, 0 }, kUp, { -3, 1 }); // on the line through points 0 and 2
  quad.AddFace({ 0, 1, 2, 3 });
  const mikk::Result q = RunKernel(quad);
  const mikk::Result a = RunKernel(AsTriangles(quad, { { 0, 1, 2 } }));
  ASSERT_EQ(q.Corners.size(), 4u);
  EXPECT_EQ(q.NumberOfGroupWithAnyTriangles, 1);
  for (size_t k = 0; k < 3; ++k)
  {
    EXPECT_EQ(q.Corners[k].Sign, -1.0f) << "corner " << k;
    EXPECT_TRUE(BitEqual(q.Corners[k], a.Corners[k])) << "corner " << k;
  }
}

// Two triangles sharing an edge, u mirrored about x = 0: opposite signs, no averaging across.
TEST(MikkTSpaceKernel, MirroredPairSigns)
{
  Mesh m;
  const long long l = m.AddPoint({ -1, 0, 0 }, kUp, { 1, 0 });
  const long long c0 = m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  const long long c1 = m.AddPoint({ 0, 1, 0 }, kUp, { 0, 1 });
  const long long r = m.AddPoint({ 1, 0, 0 }, kUp, { 1, 0 });
  m.AddFace({ l, c0, c1 }); // u decreases along +x: tangent -x, bitangent +y = -cross(N,T)
  m.AddFace({ c0, r, c1 }); // u increases along +x: tangent +x, bitangent +y = +cross(N,T)
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), 6u);
  for (int k = 0; k < 3; ++k)
  {
    ExpectTangent(res.Corners[k], -1, 0, 0, -1, "mirrored triangle");
    ExpectTangent(res.Corners[3 + k], 1, 0, 0, 1, "unmirrored triangle");
  }
  EXPECT_EQ(res.NumberOfDefaultCorners, 0);
}

// The kernel welds points whose eight values (position, normal, texture coordinates) are equal,
// as the reference does: -0 equals +0, and points that differ in any value, as the two copies
// of a UV seam do, stay apart. Two triangles side by side, each with its own copies of the shared
// edge's points.
TEST(MikkTSpaceKernel, WeldingComparesEveryValueWithSignedZerosEqual)
{
  // Left: (-1, 0, 0), (0, 0, 0), (0, 1, 0) with UVs (0, 0), (1, 0), (1, 1) (tangent +x). Right:
  // (x0, 0, 0), (1, 0, 0), (0, 1, 0) with the given UVs, x0 being +0 or -0.
  const auto sideBySide = [](const std::array<std::array<float, 2>, 3>& right, float x0)
  {
    Mesh m;
    const std::array<std::array<float, 3>, 6> p = {
      { { -1, 0, 0 }, { 0, 0, 0 }, { 0, 1, 0 }, { x0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }
    };
    const std::array<std::array<float, 2>, 6> uv = {
      { { 0, 0 }, { 1, 0 }, { 1, 1 }, right[0], right[1], right[2] }
    };
    for (size_t i = 0; i < 6; ++i)
    {
      m.AddPoint(p[i], kUp, uv[i]);
    }
    m.AddFace({ 0, 1, 2 });
    m.AddFace({ 3, 4, 5 });
    return RunKernel(m).Corners;
  };
  // A UV seam: the right triangle's texture is turned by 90 degrees (tangent +y). The seam
  // copies differ only in UVs, so every corner keeps its own triangle's frame; welded, the seam
  // corners would average +x and +y.
  const std::vector<mikk::CornerFrame> seam =
    sideBySide({ { { 0, 0 }, { 0, -1 }, { 1, 0 } } }, 0.0f);
  ASSERT_EQ(seam.size(), 6u);
  for (size_t k = 0; k < 3; ++k)
  {
    ExpectTangent(seam[k], 1, 0, 0, 1, "left triangle");
    ExpectTangent(seam[3 + k], 0, 1, 0, 1, "right triangle");
  }
  // The same edge with equal UVs on both sides, and tangents +x and (1, -0.5, 0) / |.|: the seam
  // copies weld and their corners average the two. The right copy of the origin stored as -0
  // must give the same bits as +0.
  const std::array<std::array<float, 2>, 3> continuous = { { { 1, 0 }, { 2, 0.5f }, { 1, 1 } } };
  const std::vector<mikk::CornerFrame> plus = sideBySide(continuous, 0.0f);
  const std::vector<mikk::CornerFrame> minus = sideBySide(continuous, -0.0f);
  ASSERT_EQ(plus.size(), 6u);
  ASSERT_EQ(minus.size(), 6u);
  EXPECT_TRUE(BitEqual(plus[1], plus[3])) << "the welded origin has one frame";
  EXPECT_LT(plus[1].Tangent[1], 0.0f) << "the seam corner averages in the right triangle";
  for (size_t k = 0; k < 6; ++k)
  {
    EXPECT_TRUE(BitEqual(plus[k], minus[k])) << "corner " << k;
  }
}

// A face corner that two triangles of a quad write keeps the first frame only when the two agree
// in direction and in magnitude; otherwise the reference averages and renormalises. Two quads
// over the same four points, in two corner orders: at the diagonal corners of the second quad,
// its triangles' frames have the same directions bit for bit but different magnitudes
// (|dP/du| 1.63 and 0.89), so the reference renormalises their sum, which moves the tangent by
// an ulp. The expected bits are the original mikktspace.c's output (genTangSpaceDefault) for
// this mesh. A merge that compares only the directions keeps the unrenormalised frame there.
TEST(MikkTSpaceKernel, MultiWriterMergeComparesMagnitudes)
{
  Mesh m;
  const long long p0 = m.AddPoint({ 1, 0, 0 }, kUp, { 1.5f, -0.5f });
  const long long p1 = m.AddPoint({ -1, 0, 1 }, kUp, { 0.5f, -1 });
  const long long p2 = m.AddPoint({ 0, -2, 0 }, kUp, { -1, -1 });
  const long long p3 = m.AddPoint({ -2, -2, 0 }, kUp, { -1, -1.5f });
  m.AddFace({ p1, p2, p3, p0 });
  m.AddFace({ p3, p1, p2, p0 });
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), 8u);
  // Every tangent is (-1, 2, 0) / sqrt(5), rounded three ways: x = -y / 2 exactly.
  const float single = 0x1.c9f25cp-1f;      // one writer
  const float equal = 0x1.c9f25ep-1f;       // two writers whose frames agree in every bit
  const float renormalised = 0x1.c9f26p-1f; // two writers whose magnitudes differ
  const std::array<float, 8> y = {
    equal, single, equal, single, renormalised, single, renormalised, single
  };
  for (size_t c = 0; c < 8; ++c)
  {
    const mikk::CornerFrame expected = { { -0.5f * y[c], y[c], 0.0f }, c < 4 ? 1.0f : -1.0f };
    EXPECT_TRUE(BitEqual(res.Corners[c], expected))
      << "corner " << c << ": " << res.Corners[c].Tangent[0] << " " << res.Corners[c].Tangent[1];
  }
}

// Degenerate triangles copy the first good corner with the same welded vertex (or get the
// default); in a quad with one degenerate triangle the missing corner copies the good
// triangle's corner at the same position.
TEST(MikkTSpaceKernel, DegenerateTriangleCopying)
{
  Mesh m;
  const long long a = m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  const long long b = m.AddPoint({ 1, 0, 0 }, kUp, { 1, 0 });
  const long long c = m.AddPoint({ 0, 1, 0 }, kUp, { 0, 1 });
  const long long bDup = m.AddPoint({ 1, 0, 0 }, kUp, { 1, 0 });      // welds with b
  const long long bOther = m.AddPoint({ 1, 0, 0 }, kUp, { 0.5f, 0 }); // b's position, other uv
  const long long lone = m.AddPoint({ 5, 5, 0 }, kUp, { 3, 3 });
  m.AddFace({ a, b, c });         // good: tangent +x, sign +1
  m.AddFace({ c, bDup, bOther }); // degenerate (bDup, bOther same position)
  m.AddFace({ lone, lone, a });   // degenerate
  m.AddFace({ a, b, bOther, c }); // quad: (0,1,2) degenerate, (0,2,3) good (uv 0-2 shorter)
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), 13u);
  EXPECT_EQ(res.NumberOfDegenerateTriangles, 3);
  const mikk::CornerFrame& ta = res.Corners[0];
  const mikk::CornerFrame& tb = res.Corners[1];
  const mikk::CornerFrame& tc = res.Corners[2];
  ExpectTangent(ta, 1, 0, 0, 1, "good triangle");
  EXPECT_TRUE(BitEqual(res.Corners[3], tc)) << "c copies the good triangle's c";
  EXPECT_TRUE(BitEqual(res.Corners[4], tb)) << "bDup welds with b";
  EXPECT_TRUE(BitEqual(res.Corners[5], res.Corners[11]))
    << "bOther's first good corner is in the quad's good triangle";
  EXPECT_TRUE(IsDefault(res.Corners[6])) << "lone has no good corner";
  EXPECT_TRUE(IsDefault(res.Corners[7])) << "lone has no good corner";
  EXPECT_TRUE(BitEqual(res.Corners[8], ta)) << "a copies the good triangle's a";
  // quad: corner 1 (b) is missing from the good triangle (0,2,3) = (a, bOther, c) and copies
  // its corner with b's position, bOther (face corner 2)
  EXPECT_TRUE(BitEqual(res.Corners[10], res.Corners[11]));
  EXPECT_FALSE(IsDefault(res.Corners[11]));
}

// A zero-UV-area ("group with any") triangle X between a right-handed triangle A and a
// left-handed B around a common vertex takes the orientation of the first group reaching it:
// the group created first, i.e. of the triangle listed first.
TEST(MikkTSpaceKernel, GroupWithAnyAdoption)
{
  auto build = [](bool aFirst)
  {
    Mesh m;
    const long long c = m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
    const long long a = m.AddPoint({ 1, 0, 0 }, kUp, { 1, 0 });
    const long long p1 = m.AddPoint({ 1, 1, 0 }, kUp, { 1, 1 });
    const long long p2 = m.AddPoint({ 0, 1, 0 }, kUp, { 2, 2 }); // uv collinear with c, p1
    const long long b = m.AddPoint({ -1, 1, 0 }, kUp, { 1, 0 });
    if (aFirst)
    {
      m.AddFace({ c, a, p1 }); // A: det > 0
      m.AddFace({ c, p2, b }); // B: det < 0
    }
    else
    {
      m.AddFace({ c, p2, b });
      m.AddFace({ c, a, p1 });
    }
    m.AddFace({ c, p1, p2 }); // X: zero UV area
    return m;
  };
  for (bool aFirst : { true, false })
  {
    const mikk::Result res = RunKernel(build(aFirst));
    ASSERT_EQ(res.Corners.size(), 9u);
    EXPECT_EQ(res.NumberOfGroupWithAnyTriangles, 1);
    const size_t faceA = aFirst ? 0 : 3, faceB = aFirst ? 3 : 0;
    EXPECT_EQ(res.Corners[faceA].Sign, 1.0f);
    EXPECT_EQ(res.Corners[faceB].Sign, -1.0f);
    // X = (c, p1, p2): corners 6, 7, 8
    if (aFirst)
    {
      EXPECT_TRUE(BitEqual(res.Corners[6], res.Corners[faceA + 0])) << "X at c joins A";
      EXPECT_TRUE(BitEqual(res.Corners[7], res.Corners[faceA + 2])) << "X at p1 joins A";
      EXPECT_TRUE(IsDefault(res.Corners[8])) << "X at p2: B's group cannot enter";
    }
    else
    {
      EXPECT_TRUE(BitEqual(res.Corners[6], res.Corners[faceB + 0])) << "X at c joins B";
      EXPECT_TRUE(BitEqual(res.Corners[8], res.Corners[faceB + 1])) << "X at p2 joins B";
      EXPECT_TRUE(IsDefault(res.Corners[7])) << "X at p1: A's group cannot enter";
    }
  }
}

// A fan of 2^18 triangles around one centre whose texture orientation alternates (each centre
// corner a group of its own), two of them of zero UV area at the centre: the group replay that
// gives those two their orientation floods once per group, and each flood walks the centre's
// paired edges. They are paired once per fan: pairing the whole fan again for every flood makes
// the time grow with the square of the fan, past ctest's default timeout at this size.
TEST(MikkTSpaceKernel, GroupWithAnyReplayPairsEachFanOnce)
{
  constexpr int k = 1 << 18;
  Mesh m;
  const long long centre = m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  std::vector<long long> ring;
  for (int i = 0; i <= k; ++i)
  {
    const double a = 6.283185307179586 * i / (k + 1);
    // Ring point 5 has the centre's texture coordinates: triangles 4 and 5 have zero UV area.
    const std::array<float, 2> uv = i == 5
      ? std::array<float, 2>{ 0, 0 }
      : (i % 2 ? std::array<float, 2>{ 0.5403023f, 0.84147096f } : std::array<float, 2>{ 1, 0 });
    ring.push_back(m.AddPoint({ float(std::cos(a)), float(std::sin(a)), 0 }, kUp, uv));
  }
  for (int i = 0; i < k; ++i)
  {
    m.AddFace({ centre, ring[i], ring[i + 1] });
  }
  const mikk::Result r = RunKernel(m);
  ASSERT_EQ(r.Corners.size(), static_cast<size_t>(3 * k));
  EXPECT_EQ(r.NumberOfGroupWithAnyTriangles, 2);
  // Triangle i (corner 3 i at the centre) turns the texture one way for even i, the other way for
  // odd i.
  int wrong = 0;
  for (int i = 0; i < k; ++i)
  {
    const float expected = i % 2 ? -1.0f : 1.0f;
    wrong += i == 4 || i == 5 || r.Corners[3 * static_cast<size_t>(i)].Sign == expected ? 0 : 1;
  }
  EXPECT_EQ(wrong, 0);
}

// One polygon of 2^20 corners on a 270-degree arc around its corner 0, with texture coordinates
// z^2 (as complex numbers): its fan triangles keep one orientation (one group at corner 0) while
// their tangents turn by 270 degrees, so no shortcut by direction applies. They all hold face
// corner 0, so every two are of one face and the group is one sub-group: found in one pass over
// the members, where comparing every pair makes the time grow with the square of the polygon,
// past ctest's default timeout at this size.
TEST(MikkTSpaceKernel, LargePolygonIsOneSubgroupAtItsFannedCorner)
{
  constexpr int k = 1 << 20;
  Mesh m;
  std::vector<long long> face = { m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 }) };
  for (int i = 0; i + 1 < k; ++i)
  {
    const double a = 1.5 * 3.141592653589793 * i / (k - 1);
    face.push_back(m.AddPoint({ float(std::cos(a)), float(std::sin(a)), 0 },
      kUp,
      { float(std::cos(2 * a)), float(std::sin(2 * a)) }));
  }
  m.Offsets.push_back(m.Offsets.back() + static_cast<long long>(face.size()));
  m.Conn.insert(m.Conn.end(), face.begin(), face.end());
  const mikk::Result r = RunKernel(m);
  ASSERT_EQ(r.Corners.size(), static_cast<size_t>(k));
  EXPECT_EQ(r.NumberOfDefaultCorners, 0);
  EXPECT_EQ(r.NumberOfCancelledCorners, 0);
  EXPECT_EQ(CountNotUnitInPlane(r), 0);
}

// One polygon of 2^20 corners on a 150-degree arc around its corner 0 and two triangles of other
// faces that continue the arc to 170 degrees, all with texture coordinates z^2: one group at the
// centre whose tangents turn by 170 degrees, so neither the direction shortcut nor the one-face
// case applies. No two members are opposite, so the group is one sub-group and the three face
// corners at the centre get one frame. Each member is compared with the members of the other faces
// only: comparing every pair makes the time grow with the square of the polygon, past ctest's
// default timeout at this size.
TEST(MikkTSpaceKernel, SubgroupsCompareMembersOfDifferentFacesOnly)
{
  constexpr int k = 1 << 20;
  Mesh m;
  const auto ringPoint = [&m](double degrees)
  {
    const double a = degrees * 3.141592653589793 / 180;
    return m.AddPoint({ float(std::cos(a)), float(std::sin(a)), 0 },
      kUp,
      { float(std::cos(2 * a)), float(std::sin(2 * a)) });
  };
  std::vector<long long> face = { m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 }) };
  for (int i = 0; i + 1 < k; ++i)
  {
    face.push_back(ringPoint(150.0 * i / (k - 2)));
  }
  m.Offsets.push_back(m.Offsets.back() + static_cast<long long>(face.size()));
  m.Conn.insert(m.Conn.end(), face.begin(), face.end());
  const long long at160 = ringPoint(160), at170 = ringPoint(170);
  m.AddFace({ face[0], face.back(), at160 });
  m.AddFace({ face[0], at160, at170 });
  const mikk::Result r = RunKernel(m);
  ASSERT_EQ(r.Corners.size(), static_cast<size_t>(k) + 6);
  EXPECT_EQ(r.NumberOfDefaultCorners, 0);
  EXPECT_EQ(r.NumberOfCancelledCorners, 0);
  EXPECT_EQ(CountNotUnitInPlane(r), 0);
  // the centre's face corners: the polygon's corner 0 and the triangles' first corners
  EXPECT_TRUE(BitEqual(r.Corners[0], r.Corners[k]));
  EXPECT_TRUE(BitEqual(r.Corners[0], r.Corners[k + 3]));
}

// A fan of 63 triangles around one centre (more than 32 corners: its edges are paired through a
// sorted index) on the boundary of the square [-8, 8]^2 in exact coordinates, whose texture
// orientation alternates, with ring point 6 at the centre's texture coordinates: triangles 5 and 6
// have zero UV area and take the orientation of triangle 4's group, which reaches them first in the
// reference's flood (positive, where a zero-area triangle is negative by itself). The expected hash
// (FNV-1a over the bits of every corner frame, in corner order) is that of the original
// mikktspace.c's output (genTangSpaceDefault) for this mesh.
TEST(MikkTSpaceKernel, GroupWithAnyFanMatchesTheOriginal)
{
  Mesh m;
  const long long centre = m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  std::vector<long long> ring;
  for (int i = 0; i < 64; ++i)
  {
    // counter-clockwise from (8, -8), one unit per step
    const int side = i / 16, step = i % 16;
    const std::array<int, 4> x = { 8, 8 - step, -8, -8 + step };
    const std::array<int, 4> y = { -8 + step, 8, 8 - step, -8 };
    const std::array<float, 2> uv = i == 6
      ? std::array<float, 2>{ 0, 0 }
      : (i % 2 ? std::array<float, 2>{ 0.5f, 0.75f } : std::array<float, 2>{ 1, 0 });
    ring.push_back(m.AddPoint({ float(x[side]), float(y[side]), 0 }, kUp, uv));
  }
  for (int i = 0; i + 1 < 64; ++i)
  {
    m.AddFace({ centre, ring[i], ring[i + 1] });
  }
  const mikk::Result r = RunKernel(m);
  ASSERT_EQ(r.Corners.size(), 189u);
  EXPECT_EQ(r.NumberOfGroupWithAnyTriangles, 2);
  uint64_t hash = 14695981039346656037ULL;
  for (const mikk::CornerFrame& f : r.Corners)
  {
    for (const float value : { f.Tangent[0], f.Tangent[1], f.Tangent[2], f.Sign })
    {
      uint32_t bits;
      std::memcpy(&bits, &value, sizeof(bits));
      hash = (hash ^ bits) * 1099511628211ULL;
    }
  }
  EXPECT_EQ(hash, 0xb6a7ca0c2dc53627ULL);
  EXPECT_EQ(r.Corners[15].Sign, 1.0f); // triangle 5's corner at the centre
  EXPECT_EQ(r.Corners[18].Sign, 1.0f); // triangle 6's
}

// Within one group, the reference averages a member only with the members whose projected
// directions are not exactly opposite to its own (its sub-group). Five triangles around a centre,
// ring point k at 45k degrees with its texture coordinates at 90k degrees (the map z -> z^2,
// which keeps the orientation), make one group: the first member's dP/du is +x and dP/dv
// (-1, 1), every other member's are within 90 degrees of those, yet the group holds pairs of
// exactly opposite directions (dP/du +y and -y). Each member's sub-group differs, so the five
// corners at the centre differ; averaging the group as a whole, as when every member is close to
// the first, would give them one frame.
TEST(MikkTSpaceKernel, OppositeMembersOfAGroupAreNotAveraged)
{
  const float h = 0.70710677f;
  const std::array<std::array<float, 3>, 8> ring = { { { 1, 0, 0 },
    { h, h, 0 },
    { 0, 1, 0 },
    { -h, h, 0 },
    { -1, 0, 0 },
    { -h, -h, 0 },
    { 0, -1, 0 },
    { h, -h, 0 } } };
  const std::array<std::array<float, 2>, 4> uv = { { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } } };
  Mesh m;
  m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  for (size_t k = 0; k < ring.size(); ++k)
  {
    m.AddPoint(ring[k], kUp, uv[k % 4]);
  }
  for (const long long k : { 7, 0, 1, 5, 6 }) // the triangles between ring points k and k + 1
  {
    m.AddFace({ 0, 1 + k, 1 + (k + 1) % 8 });
  }
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), 15u);
  EXPECT_EQ(res.NumberOfDefaultCorners, 0);
  for (size_t a = 0; a < 15; a += 3)
  {
    for (size_t b = a + 3; b < 15; b += 3)
    {
      EXPECT_FALSE(BitEqual(res.Corners[a], res.Corners[b])) << "centre corners " << a << ", " << b;
    }
  }
}

// Faces with more than 4 corners are fan-triangulated; their corners equal those of the
// explicit fan. Faces with fewer than 3 corners are skipped with default corners.
TEST(MikkTSpaceKernel, FanPolygon)
{
  Mesh m;
  const float r = 1.0f;
  for (int i = 0; i < 6; ++i)
  {
    const float ang = static_cast<float>(i) * 1.04719755f;
    const float x = r * std::cos(ang), y = r * std::sin(ang), z = 0.2f * (i % 2);
    const float nx = -0.1f * x, ny = -0.1f * y;
    const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
    m.AddPoint(
      { x, y, z }, { nx / len, ny / len, 1.0f / len }, { 0.5f + 0.4f * x, 0.5f + 0.3f * y });
  }
  Mesh poly = m;
  poly.AddFace({ 0, 1, 2, 3, 4, 5 });
  poly.AddFace({ 0, 3 }); // skipped
  Mesh fan = m;
  for (long long k = 1; k + 1 < 6; ++k)
  {
    fan.AddFace({ 0, k, k + 1 });
  }
  const mikk::Result p = RunKernel(poly);
  const mikk::Result f = RunKernel(fan);
  ASSERT_EQ(p.Corners.size(), 8u);
  EXPECT_EQ(p.NumberOfSkippedFaces, 1);
  // polygon corner j -> first fan corner using point j
  const std::array<size_t, 6> map = { 0, 1, 2, 5, 8, 11 };
  for (size_t j = 0; j < 6; ++j)
  {
    EXPECT_TRUE(BitEqual(p.Corners[j], f.Corners[map[j]])) << "polygon corner " << j;
    EXPECT_FALSE(IsDefault(p.Corners[j]));
  }
  EXPECT_TRUE(IsDefault(p.Corners[6]) && IsDefault(p.Corners[7]));
  EXPECT_EQ(p.NumberOfDefaultCorners, 2);
}

// A dome of n triangles around an apex (point 0), its texture mirrored in u across x = 0: the
// apex's corners form two groups (one per handedness) only if the fan's edges pair.
Mesh MirroredDome(int n)
{
  Mesh m;
  m.AddPoint({ 0, 0, 1 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  for (int i = 0; i < n; ++i)
  {
    const float a = 6.2831853f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
    const float x = std::cos(a), y = std::sin(a);
    m.AddPoint(
      { x, y, 0.5f }, { 0.6f * x, 0.6f * y, 0.8f }, { 0.5f + 0.4f * std::abs(x), 0.5f + 0.4f * y });
  }
  for (long long i = 0; i < n; ++i)
  {
    m.AddFace({ 0, 1 + i, 1 + (i + 1) % n });
  }
  return m;
}

// The kernel pairs the edges of a small fan by scanning and those of a fan of more than 32
// corners through a sorted index; both give every apex corner of one handedness the same frame,
// the group's, and the two halves different ones. Without pairing each corner keeps its own
// triangle's direction, which differs from its neighbours' on this curved dome.
TEST(MikkTSpaceKernel, LargeAndSmallFansPairTheirEdges)
{
  for (const int n : { 16, 96 })
  {
    const Mesh m = MirroredDome(n);
    const mikk::Result r = RunKernel(m);
    ASSERT_EQ(r.Corners.size(), static_cast<size_t>(3 * n));
    std::array<const mikk::CornerFrame*, 2> first = { nullptr, nullptr };
    int mismatched = 0;
    for (int t = 0; t < n; ++t)
    {
      // The triangles whose both rim points lie on one side of x = 0 have one handedness;
      // the two straddling x = 0 (u's fold) are left out.
      const float x0 = m.P[3 * (1 + t)], x1 = m.P[3 * (1 + (t + 1) % n)];
      if ((x0 < 0) != (x1 < 0))
      {
        continue;
      }
      const mikk::CornerFrame& apex = r.Corners[static_cast<size_t>(3 * t)];
      const mikk::CornerFrame*& group = first[x0 < 0 ? 1 : 0];
      group = group ? group : &apex;
      mismatched += BitEqual(apex, *group) ? 0 : 1;
    }
    ASSERT_TRUE(first[0] && first[1]);
    EXPECT_EQ(mismatched, 0) << n << " triangles";
    EXPECT_NE(first[0]->Sign, first[1]->Sign) << n << " triangles";
  }
}

// Copies [first, first + count) of a star around one apex (point 0): copy i has three triangles
// on one edge (apex, x_i), two along apex->x_i and the third, on the other side, along x_i->apex,
// at different heights, so that each triangle has its own tangent. The reference pairs the third
// with the first (the first later half-edge of opposite direction still unpaired), which groups
// them apart from the second at the apex. The copies share only the apex.
Mesh NonManifoldStar(int first, int count)
{
  // Texture coordinates that follow the height too, so that the triangles' tangents differ on
  // the apex's tangent plane.
  Mesh m;
  m.AddPoint({ 0, 0, 0 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  const auto add = [&](float x, float y, float z)
  {
    return m.AddPoint(
      { x, y, z }, { 0, 0, 1 }, { 0.5f + 0.2f * x + 0.15f * z, 0.5f + 0.2f * y - 0.1f * z });
  };
  for (int i = first; i < first + count; ++i)
  {
    const float a = 6.2831853f * static_cast<float>(i) / 40.0f;
    const float c = std::cos(a), s = std::sin(a);
    const long long x = add(c, s, 0.1f);
    // left of apex->x at two heights, and right of it
    const long long left1 = add(0.6f * c - 0.3f * s, 0.6f * s + 0.3f * c, 0.3f);
    const long long left2 = add(0.4f * c - 0.5f * s, 0.4f * s + 0.5f * c, -0.2f);
    const long long right = add(0.5f * c + 0.4f * s, 0.5f * s - 0.4f * c, 0.4f);
    m.AddFace({ 0, x, left1 });
    m.AddFace({ 0, x, left2 });
    m.AddFace({ x, 0, right });
  }
  return m;
}

// The apex of 12 copies has 36 corners, past the 32 up to which the kernel pairs a fan's edges by
// scanning: it pairs them through a sorted sweep. Each copy alone is paired by scanning. Groups
// of different copies cannot join (they share no edge), so every corner must come out the same,
// bit for bit, either way.
TEST(MikkTSpaceKernel, NonManifoldEdgesPairAlikeInLargeAndSmallFans)
{
  constexpr int copies = 12;
  const mikk::Result all = RunKernel(NonManifoldStar(0, copies));
  ASSERT_EQ(all.Corners.size(), static_cast<size_t>(9 * copies));
  int differing = 0;
  for (int i = 0; i < copies; ++i)
  {
    const mikk::Result one = RunKernel(NonManifoldStar(i, 1));
    ASSERT_EQ(one.Corners.size(), 9u);
    for (size_t c = 0; c < 9; ++c)
    {
      differing += BitEqual(all.Corners[9 * static_cast<size_t>(i) + c], one.Corners[c]) ? 0 : 1;
    }
    // The apex's first and third corners share a group, the second is alone.
    EXPECT_TRUE(BitEqual(one.Corners[0], one.Corners[7])) << "copy " << i;
    EXPECT_FALSE(BitEqual(one.Corners[0], one.Corners[3])) << "copy " << i;
  }
  EXPECT_EQ(differing, 0);
}

/// Four points, ids 0 to 3, the last out of the plane of the others; no faces.
Mesh FourPoints()
{
  Mesh m;
  m.AddPoint({ 0, 0, 0 }, kUp, { 0, 0 });
  m.AddPoint({ 1, 0, 0 }, kUp, { 1, 0 });
  m.AddPoint({ 0, 1, 0 }, kUp, { 0, 1 });
  m.AddPoint({ 1, 1, 0.5f }, kUp, { 1, 1 });
  return m;
}

// Point ids outside [0, NumberOfPoints) skip the face (default corners), leaving the rest of
// the mesh as if the face were absent.
TEST(MikkTSpaceKernel, OutOfRangeIds)
{
  const Mesh m0 = FourPoints();
  Mesh m = m0, clean = m0;
  const long long a = 0, b = 1, c = 2, d = 3;
  clean.AddFace({ a, b, c });
  clean.AddFace({ b, d, c });
  m.AddFace({ a, b, c });
  m.AddFace({ b, 4, c });     // == NumberOfPoints
  m.AddFace({ -1, b, d, c }); // negative
  m.AddFace({ b, d, c });
  m.AddFace({ a, 1LL << 40, c, d, b }); // huge
  const mikk::Result res = RunKernel(m);
  const mikk::Result ref = RunKernel(clean);
  ASSERT_EQ(res.Corners.size(), 18u);
  EXPECT_EQ(res.NumberOfInvalidFaces, 3);
  for (size_t k = 0; k < 3; ++k)
  {
    EXPECT_TRUE(BitEqual(res.Corners[k], ref.Corners[k]));
    EXPECT_TRUE(BitEqual(res.Corners[10 + k], ref.Corners[3 + k]));
  }
  for (size_t k : { 3, 4, 5, 6, 7, 8, 9, 13, 14, 15, 16, 17 })
  {
    EXPECT_TRUE(IsDefault(res.Corners[k])) << "corner " << k;
  }
  EXPECT_EQ(res.NumberOfDefaultCorners, 12);
}

// Offsets out of order can make two faces share face corners, which each face writes on its own
// thread: a face that starts before an earlier one ends is invalid, its corners that no valid
// face holds get the default, and the earlier face keeps its frames.
TEST(MikkTSpaceKernel, FacesThatOverlapEarlierOnesAreInvalid)
{
  const Mesh m0 = FourPoints();
  Mesh m = m0, clean = m0;
  const long long a = 0, b = 1, c = 2, d = 3;
  clean.AddFace({ a, b, c });
  m.Conn = { a, b, c, d, b };
  m.Offsets = { 0, 3, 2, 5 }; // [0, 3), then [3, 2) (out of range) and [2, 5), overlapping [0, 3)
  const mikk::Result res = RunKernel(m);
  const mikk::Result ref = RunKernel(clean);
  ASSERT_EQ(res.Corners.size(), 5u);
  EXPECT_EQ(res.NumberOfInvalidFaces, 2);
  for (size_t k = 0; k < 3; ++k)
  {
    EXPECT_TRUE(BitEqual(res.Corners[k], ref.Corners[k])) << "corner " << k;
  }
  EXPECT_TRUE(IsDefault(res.Corners[3]));
  EXPECT_TRUE(IsDefault(res.Corners[4]));
}

// NaN and Inf anywhere in the input never produce non-finite output.
TEST(MikkTSpaceKernel, NonFiniteInput)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Mesh m;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      m.AddPoint({ float(i), float(j), 0.1f * float((i * j) % 3) },
        kUp,
        { 0.1f * float(i), 0.1f * float(j) });
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const long long p = j * (n + 1) + i;
      if ((i + j) % 2)
      {
        m.AddFace({ p, p + 1, p + n + 2, p + n + 1 });
      }
      else
      {
        m.AddFace({ p, p + 1, p + n + 2 });
        m.AddFace({ p, p + n + 2, p + n + 1 });
      }
    }
  }
  const mikk::Result clean = RunKernel(m);
  EXPECT_EQ(clean.NumberOfNonFiniteCorners, 0);
  m.P[3 * 8 + 0] = nan;
  m.N[3 * 10 + 1] = nan;
  m.U[2 * 17 + 0] = nan;
  m.P[3 * 24 + 2] = inf;
  m.N[3 * 30 + 0] = -inf;
  m.U[2 * 40 + 1] = inf;
  m.P[3 * 45 + 0] = nan; // and a whole NaN point
  m.P[3 * 45 + 1] = nan;
  m.P[3 * 45 + 2] = nan;
  const mikk::Result res = RunKernel(m);
  ASSERT_EQ(res.Corners.size(), clean.Corners.size());
  long long changed = 0;
  for (size_t k = 0; k < res.Corners.size(); ++k)
  {
    const mikk::CornerFrame& f = res.Corners[k];
    ASSERT_TRUE(
      std::isfinite(f.Tangent[0]) && std::isfinite(f.Tangent[1]) && std::isfinite(f.Tangent[2]))
      << "corner " << k;
    ASSERT_TRUE(f.Sign == 1.0f || f.Sign == -1.0f);
    changed += BitEqual(f, clean.Corners[k]) ? 0 : 1;
  }
  EXPECT_GT(res.NumberOfNonFiniteCorners, 0);
  EXPECT_LE(res.NumberOfNonFiniteCorners, res.NumberOfDefaultCorners);
  // only the neighbourhoods of the bad points change
  EXPECT_LT(changed, static_cast<long long>(res.Corners.size()) / 2);
}

namespace
{
// Torus with quads and triangles, a mirrored band, collapsed UVs, degenerate triangles,
// a fan polygon cap row and duplicated faces: exercises every path of the kernel.
// TrianglesOnly: every face a triangle (the kernel sets up runs of 8 triangle faces together);
// Clean: only the mirrored band (no collapsed UVs, degenerate or duplicated faces).
enum class TorusFaces
{
  Mixed,
  TrianglesOnly,
  Clean
};
Mesh MixedTorus(int nu, int nv, TorusFaces faces = TorusFaces::Mixed)
{
  Mesh m;
  const float twoPi = 6.28318531f;
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const float a = twoPi * float(i) / float(nu), b = twoPi * float(j) / float(nv);
      const float ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
      float u = float(i) / float(nu), v = float(j) / float(nv);
      if (i > nu / 2)
      {
        u = 1.0f - u; // mirrored band
      }
      if ((i * 7 + j * 3) % 53 == 0 && faces != TorusFaces::Clean)
      {
        u = v = 0.25f; // collapsed UVs -> group-with-any triangles
      }
      m.AddPoint({ (2 + cb) * ca, (2 + cb) * sa, sb }, { cb * ca, cb * sa, sb }, { u, v });
    }
  }
  auto id = [&](int i, int j) { return static_cast<long long>((j % nv) * nu + (i % nu)); };
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const long long p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1),
                      p01 = id(i, j + 1);
      const int kind = faces == TorusFaces::Mixed ? (i + 3 * j) % 7 : 3;
      if (kind < 3)
      {
        m.AddFace({ p00, p10, p11, p01 });
      }
      else if (kind < 6)
      {
        m.AddFace({ p00, p10, p11 });
        m.AddFace({ p00, p11, p01 });
      }
      else
      {
        m.AddFace({ p00, p10, p11, p01, p00 }); // pentagon with a repeated corner
      }
      if ((i + j) % 11 == 0 && faces != TorusFaces::Clean)
      {
        m.AddFace({ p00, p00, p11 }); // degenerate
      }
      if ((i * j) % 37 == 5 && faces != TorusFaces::Clean)
      {
        m.AddFace({ p00, p10, p11 }); // duplicated face: non-manifold edges
      }
    }
  }
  return m;
}

// n x n grid of triangle pairs with jittered positions, normals and UVs (a fixed pseudo-random
// sequence): corner angles from a few degrees to nearly 180, so every branch of the acos
// evaluation is taken.
Mesh JitteredGrid(int n)
{
  Mesh m;
  unsigned state = 12345u;
  const auto jitter = [&state]()
  {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) - 0.5f; // [-0.5, 0.5)
  };
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const float x = float(i) + 0.9f * jitter(), y = float(j) + 0.9f * jitter();
      const float z = 0.3f * jitter();
      const float nx = 0.2f * jitter(), ny = 0.2f * jitter();
      const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
      m.AddPoint({ x, y, z },
        { nx / len, ny / len, 1.0f / len },
        { (x + 0.3f * jitter()) / float(n), (y + 0.3f * jitter()) / float(n) });
    }
  }
  const auto id = [n](int i, int j) { return static_cast<long long>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      m.AddFace({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.AddFace({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return m;
}
} // namespace

// Identical output for 1, 2 and 8 threads.
TEST(MikkTSpaceKernel, DeterministicAcrossThreadCounts)
{
  const Mesh m = MixedTorus(160, 90);
  std::vector<mikk::Result> results;
  for (int threads : { 1, 2, 8 })
  {
    results.push_back(RunKernel(m, threads));
  }
  EXPECT_GT(results[0].NumberOfDegenerateTriangles, 0);
  EXPECT_GT(results[0].NumberOfGroupWithAnyTriangles, 0);
  for (size_t i = 1; i < results.size(); ++i)
  {
    ASSERT_EQ(results[i].Corners.size(), results[0].Corners.size());
    EXPECT_EQ(0,
      std::memcmp(results[i].Corners.data(),
        results[0].Corners.data(),
        results[0].Corners.size() * sizeof(mikk::CornerFrame)))
      << "run " << i;
    EXPECT_EQ(results[i].NumberOfDefaultCorners, results[0].NumberOfDefaultCorners);
  }
}

// One and two threads give the same bits and counts on the triangle-only and clean tori, on a
// jittered grid (corner angles up to nearly 180 degrees) and on a torus with a NaN normal and a
// NaN position, which reaches the non-finite handling.
TEST(MikkTSpaceKernel, DeterministicOnEveryMeshKind)
{
  std::vector<Mesh> meshes = { MixedTorus(160, 90, TorusFaces::TrianglesOnly),
    MixedTorus(160, 90, TorusFaces::Clean),
    JitteredGrid(120) };
  Mesh withNaN = MixedTorus(40, 20, TorusFaces::TrianglesOnly);
  withNaN.N[3 * 5 + 1] = std::nanf("");
  withNaN.P[3 * 17] = std::nanf("");
  meshes.push_back(withNaN);
  for (size_t k = 0; k < meshes.size(); ++k)
  {
    const mikk::Result expected = RunKernel(meshes[k], 1);
    const mikk::Result r = RunKernel(meshes[k], 2);
    ASSERT_EQ(r.Corners.size(), expected.Corners.size());
    EXPECT_EQ(0,
      std::memcmp(r.Corners.data(),
        expected.Corners.data(),
        expected.Corners.size() * sizeof(mikk::CornerFrame)))
      << "mesh " << k;
    EXPECT_EQ(r.NumberOfDefaultCorners, expected.NumberOfDefaultCorners) << "mesh " << k;
    EXPECT_EQ(r.NumberOfNonFiniteCorners, expected.NumberOfNonFiniteCorners) << "mesh " << k;
    EXPECT_EQ(r.NumberOfDegenerateTriangles, expected.NumberOfDegenerateTriangles);
    EXPECT_EQ(r.NumberOfGroupWithAnyTriangles, expected.NumberOfGroupWithAnyTriangles);
  }
  EXPECT_GT(RunKernel(withNaN).NumberOfNonFiniteCorners, 0);
}

// The callback can stop the computation; it is told the progress.
TEST(MikkTSpaceKernel, ProgressAndAbort)
{
  const Mesh m = MixedTorus(20, 10);
  std::vector<double> seen;
  const mikk::Result full = mikk::ComputeMikkTSpace(m.Input(),
    [&](double p)
    {
      seen.push_back(p);
      return false;
    });
  EXPECT_FALSE(full.Aborted);
  ASSERT_GE(seen.size(), 2u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
  int calls = 0;
  const mikk::Result stopped =
    mikk::ComputeMikkTSpace(m.Input(), [&](double) { return ++calls == 2; });
  EXPECT_TRUE(stopped.Aborted);
  ASSERT_EQ(stopped.Corners.size(), full.Corners.size());
  for (const auto& f : stopped.Corners)
  {
    EXPECT_TRUE(IsDefault(f));
  }
}

TEST(MikkTSpaceKernel, EmptyInput)
{
  Mesh m;
  const mikk::Result res = RunKernel(m);
  EXPECT_TRUE(res.Corners.empty());
  EXPECT_TRUE(res.CornerKinds.empty());
  EXPECT_FALSE(res.Aborted);
}

// CornerKinds tells the corners left at the default, and the cancelled ones, from the computed
// frames, also where a computed frame has the default's bits: on the plane z = x/2 + y/4 with
// normals +z and texture coordinates (x, -y), dP/du projected on the tangent plane is exactly +x
// and the texture is mirrored (sign -1).
TEST(MikkTSpaceKernel, CornerKindsTellDefaultsFromComputedFramesWithTheDefaultBits)
{
  using Kind = mikk::CornerKind;
  Mesh m;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      m.AddPoint({ float(i), float(j), 0.5f * i + 0.25f * j }, kUp, { float(i), -float(j) });
    }
  }
  m.AddFace({ 0, 1, 3, 2 });
  // Zero texture-coordinate area: no group reaches these corners.
  const long long flat = m.AddPoint({ 5, 0, 0 }, kUp, { 0.5f, 0.5f });
  m.AddPoint({ 6, 0, 0 }, kUp, { 0.5f, 0.5f });
  m.AddPoint({ 5, 1, 0 }, kUp, { 0.5f, 0.5f });
  m.AddFace({ flat, flat + 1, flat + 2 });
  // Normals along dP/du = +x: the projected tangents, and so their sum, are zero.
  const std::array<float, 3> x = { 1, 0, 0 };
  const long long along = m.AddPoint({ 10, 0, 0 }, x, { 0, 0 });
  m.AddPoint({ 11, 0, 0 }, x, { 1, 0 });
  m.AddPoint({ 10, 1, 0 }, x, { 0, 1 });
  m.AddFace({ along, along + 1, along + 2 });
  m.AddFace({ 0, 1 }); // skipped
  const mikk::Result res = RunKernel(m);
  const std::vector<Kind> expected = { Kind::Computed,
    Kind::Computed,
    Kind::Computed,
    Kind::Computed,
    Kind::Default,
    Kind::Default,
    Kind::Default,
    Kind::Cancelled,
    Kind::Cancelled,
    Kind::Cancelled,
    Kind::Default,
    Kind::Default };
  ASSERT_EQ(res.Corners.size(), expected.size());
  ASSERT_EQ(res.CornerKinds.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
  {
    EXPECT_EQ(int(res.CornerKinds[k]), int(expected[k])) << "corner " << k;
  }
  for (size_t k = 0; k < 4; ++k)
  {
    EXPECT_TRUE(BitEqual(res.Corners[k], mikk::DefaultCornerFrame)) << "corner " << k;
  }
  EXPECT_EQ(res.NumberOfDefaultCorners, 5);
  EXPECT_EQ(res.NumberOfCancelledCorners, 3);

  // The results that leave every corner at the default say so too.
  const mikk::Result stopped = mikk::ComputeMikkTSpace(m.Input(), [](double) { return true; });
  mikk::MeshInput noNormals = m.Input();
  noNormals.Normals = nullptr;
  for (const mikk::Result& all : { stopped, mikk::ComputeMikkTSpace(noNormals) })
  {
    ASSERT_EQ(all.CornerKinds.size(), expected.size());
    EXPECT_TRUE(std::all_of(
      all.CornerKinds.begin(), all.CornerKinds.end(), [](Kind k) { return k == Kind::Default; }));
  }
  EXPECT_TRUE(stopped.Aborted);
}
