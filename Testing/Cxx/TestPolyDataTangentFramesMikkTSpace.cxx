// SPDX-License-Identifier: BSD-3-Clause
// Tests of vtkPolyDataTangentFrames with Method == MIKKTSPACE, through the pipeline:
// comparison with the reference tangents (shared/data/mikktspace/*.vtp) and with the TANGENT
// attribute of the Khronos glTF sample NormalTangentMirrorTest, splitting, strips, mixed cell
// types, bad input, non-finite input, progress/abort and thread-count independence.
//
// Shared data location: see NormalMappingTestData.h (tests that need it skip without it).

#include "NormalMappingProgress.h"
#include "NormalMappingTestData.h"
#include "NormalMappingThreads.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkTangentFrameKernels.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt64Array.h>
#include <vtkXMLPolyDataReader.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace mikk = vtkNormalMapping::mikk;
using namespace NormalMappingTestData;

namespace
{
//------------------------------------------------------------------------------
// Tolerances

// Filter vs reference, in degrees. The kernel matches the reference bit for bit on these files
// (TestMikkTSpaceKernel) and the filter stores the kernel's float tangent unchanged (float
// output) or widened exactly (double output), so the expected angle is 0. The bound is the
// kernel test's: 1e-3 degrees ~ 150 float ulps of a unit vector, room for compiler differences
// on either side (FMA contraction <= 1.8e-7 per component, float vs double acos <= 1.2e-7),
// while any algorithmic difference (wrong group, weight, order or corner mapping) is >= ~0.01.
constexpr double kMaxAngleDeg = 1e-3;

// Filter vs the glTF file's stored TANGENT, in degrees. Those tangents were exported by
// Blender's MikkTSpace rewrite, which weights by a polynomial acos (~1e-4 rad absolute error per
// weight); a relative weight error e tilts an average of directions spread by at most ~90
// degrees by less than e * 90 degrees, ~0.005 degrees; the kernel measured a 0.003 maximum.
constexpr double kGltfMaxAngleDeg = 0.01;

// Tangents expected to be exact axis vectors come from normalising an exactly axis-aligned sum,
// so at most a 1-ulp error of 1/sqrt: 2 ulps of 1.0f = 2.4e-7.
constexpr double kAxisTol = 2.4e-7;

// |B - sign * cross(N, T)| for the output bitangent: both computed in double from the same
// float values, then rounded once to float (<= 2^-24 relative per component, |B| <= 1):
// 1e-6 is ~16 float ulps of a unit vector.
constexpr double kBitangentTol = 1e-6;

//------------------------------------------------------------------------------
// Building and running

struct TestMesh
{
  std::vector<std::array<float, 3>> P, N;
  std::vector<std::array<float, 2>> U;
  std::vector<std::vector<vtkIdType>> Verts, Lines, Polys, Strips;

  vtkIdType AddPoint(std::array<float, 3> p, std::array<float, 3> n, std::array<float, 2> uv)
  {
    P.push_back(p);
    N.push_back(n);
    U.push_back(uv);
    return static_cast<vtkIdType>(P.size()) - 1;
  }

  vtkSmartPointer<vtkPolyData> Build() const
  {
    auto pd = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    vtkNew<vtkFloatArray> normals, uvs;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    uvs->SetName("TCoords");
    uvs->SetNumberOfComponents(2);
    for (size_t i = 0; i < P.size(); ++i)
    {
      points->InsertNextPoint(P[i].data());
      normals->InsertNextTypedTuple(N[i].data());
      uvs->InsertNextTypedTuple(U[i].data());
    }
    pd->SetPoints(points);
    pd->GetPointData()->SetNormals(normals);
    pd->GetPointData()->SetTCoords(uvs);
    const auto cells = [](const std::vector<std::vector<vtkIdType>>& list)
    {
      vtkNew<vtkCellArray> ca;
      for (const auto& c : list)
      {
        ca->InsertNextCell(static_cast<vtkIdType>(c.size()), c.data());
      }
      return vtkSmartPointer<vtkCellArray>(ca.Get());
    };
    if (!Verts.empty())
    {
      pd->SetVerts(cells(Verts));
    }
    if (!Lines.empty())
    {
      pd->SetLines(cells(Lines));
    }
    if (!Polys.empty())
    {
      pd->SetPolys(cells(Polys));
    }
    if (!Strips.empty())
    {
      pd->SetStrips(cells(Strips));
    }
    return pd;
  }
};

struct FilterRun
{
  vtkSmartPointer<vtkPolyData> Output;
  std::vector<std::string> Errors, Warnings;
  std::vector<double> Progress;
  vtkIdType Conflicts = 0, SplitPoints = 0, Degenerate = 0, DefaultCorners = 0;
};

void CatchMessage(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* run = static_cast<FilterRun*>(clientData);
  const std::string text = callData ? static_cast<const char*>(callData) : "";
  (event == vtkCommand::ErrorEvent ? run->Errors : run->Warnings).push_back(text);
}

FilterRun RunFilter(vtkPolyData* input,
  const std::function<void(vtkPolyDataTangentFrames*)>& setup = {})
{
  FilterRun run;
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetMethodToMikkTSpace();
  filter->SetInputData(input);
  if (setup)
  {
    setup(filter);
  }
  vtkNew<vtkCallbackCommand> messages;
  messages->SetCallback(CatchMessage);
  messages->SetClientData(&run);
  filter->AddObserver(vtkCommand::ErrorEvent, messages);
  filter->AddObserver(vtkCommand::WarningEvent, messages);
  filter->Update();
  run.Output = filter->GetOutput();
  run.Conflicts = filter->GetNumberOfHandednessConflicts();
  run.SplitPoints = filter->GetNumberOfSplitPoints();
  run.Degenerate = filter->GetNumberOfDegenerateTriangles();
  run.DefaultCorners = filter->GetNumberOfFallbackPoints();
  return run;
}

std::string Join(const std::vector<std::string>& messages)
{
  std::string all;
  for (const auto& m : messages)
  {
    all += m + "\n";
  }
  return all;
}

std::vector<vtkIdType> CellIds(vtkCellArray* cells, vtkIdType cell)
{
  vtkNew<vtkIdList> ids;
  cells->GetCellAtId(cell, ids);
  return std::vector<vtkIdType>(ids->begin(), ids->end());
}

/// Output frame of point p as a kernel CornerFrame (float output: exact; double: rounded back,
/// exact too because the doubles are widened floats).
mikk::CornerFrame PointFrame(vtkPolyData* out, vtkIdType p)
{
  vtkDataArray* t = out->GetPointData()->GetArray("Tangents");
  vtkDataArray* s = out->GetPointData()->GetArray("TangentSigns");
  mikk::CornerFrame f{};
  for (int k = 0; k < 3; ++k)
  {
    f.Tangent[k] = static_cast<float>(t->GetComponent(p, k));
  }
  f.Sign = static_cast<float>(s->GetComponent(p, 0));
  return f;
}

bool BitEqual(const mikk::CornerFrame& a, const mikk::CornerFrame& b)
{
  return std::memcmp(&a, &b, sizeof(a)) == 0;
}

bool IsDefault(const mikk::CornerFrame& f)
{
  return BitEqual(f, mikk::DefaultCornerFrame);
}

//------------------------------------------------------------------------------
// The expected per-corner frames, computed here independently of the filter: the kernel run on
// the polygons and on the strip triangles (even j: (j, j+1, j+2), odd: (j+1, j, j+2)); a strip
// corner i takes strip triangle max(0, i - 2), the first one containing it.
struct ExpectedFrames
{
  mikk::Result Kernel;
  std::vector<std::vector<long long>> PolySlot;  // [cell][k] -> kernel corner
  std::vector<std::vector<long long>> StripSlot; // [strip][i] -> kernel corner or -1
};

ExpectedFrames ComputeExpected(vtkPolyData* pd)
{
  ExpectedFrames e;
  const vtkIdType np = pd->GetNumberOfPoints();
  std::vector<float> P(3 * np), N(3 * np), U(2 * np);
  vtkDataArray* normals = pd->GetPointData()->GetNormals();
  vtkDataArray* uvs = pd->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < np; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      P[3 * i + k] = static_cast<float>(pd->GetPoints()->GetData()->GetComponent(i, k));
      N[3 * i + k] = static_cast<float>(normals->GetComponent(i, k));
    }
    U[2 * i] = static_cast<float>(uvs->GetComponent(i, 0));
    U[2 * i + 1] =
      uvs->GetNumberOfComponents() > 1 ? static_cast<float>(uvs->GetComponent(i, 1)) : 0.0f;
  }
  std::vector<long long> offsets{ 0 }, conn;
  for (vtkIdType c = 0; c < pd->GetPolys()->GetNumberOfCells(); ++c)
  {
    std::vector<long long> slots;
    const std::vector<vtkIdType> ids = CellIds(pd->GetPolys(), c);
    for (vtkIdType id : ids)
    {
      // polygons with fewer than 3 points have no frame (-1: not checked)
      slots.push_back(ids.size() < 3 ? -1 : static_cast<long long>(conn.size()));
      conn.push_back(id);
    }
    offsets.push_back(static_cast<long long>(conn.size()));
    e.PolySlot.push_back(slots);
  }
  for (vtkIdType s = 0; s < pd->GetStrips()->GetNumberOfCells(); ++s)
  {
    const std::vector<vtkIdType> ids = CellIds(pd->GetStrips(), s);
    const long long n = static_cast<long long>(ids.size());
    const long long base = static_cast<long long>(conn.size());
    for (long long j = 0; j + 2 < n; ++j)
    {
      const bool odd = (j & 1) != 0;
      conn.push_back(ids[odd ? j + 1 : j]);
      conn.push_back(ids[odd ? j : j + 1]);
      conn.push_back(ids[j + 2]);
      offsets.push_back(static_cast<long long>(conn.size()));
    }
    std::vector<long long> slots;
    for (long long i = 0; i < n; ++i)
    {
      if (n < 3)
      {
        slots.push_back(-1);
        continue;
      }
      const long long j = std::max(0LL, i - 2);
      const int pos = (j & 1) == 0 ? static_cast<int>(i - j) : (i == j + 1 ? 0 : (i == j ? 1 : 2));
      slots.push_back(base + 3 * j + pos);
    }
    e.StripSlot.push_back(slots);
  }
  mikk::MeshInput in;
  in.NumberOfFaces = static_cast<long long>(offsets.size()) - 1;
  in.FaceOffsets = offsets.data();
  in.FaceConnectivity = conn.data();
  in.NumberOfPoints = np;
  in.Positions = P.data();
  in.Normals = N.data();
  in.TCoords = U.data();
  e.Kernel = mikk::ComputeMikkTSpace(in);
  return e;
}

/// The filter's output contract applied to a kernel frame at a point with normal `n` (as given
/// to the kernel), written here from the documentation (vtkPolyDataTangentFrames.h,
/// NumberOfFallbackPoints): a non-unit (cancelled, |length - 1| > 1e-6) tangent becomes
/// (1, 0, 0) made perpendicular to the unit normal; a unit tangent (the default (1, 0, 0)
/// included) with |T.N| > 1e-4 is made perpendicular; anything else is the kernel's frame bit
/// for bit. Signs are kept.
mikk::CornerFrame ContractFrame(const mikk::CornerFrame& f, const float n[3])
{
  const glm::dvec3 unitN = vtkNormalMapping::SafeNormalize(glm::dvec3(n[0], n[1], n[2]));
  const glm::dvec3 t(f.Tangent[0], f.Tangent[1], f.Tangent[2]);
  glm::dvec3 fixedT;
  if (std::abs(glm::length(t) - 1.0) > 1e-6)
  {
    fixedT = vtkNormalMapping::PerpendicularTangent(unitN, glm::dvec3(1, 0, 0));
  }
  else if (std::abs(glm::dot(t, unitN)) > 1e-4)
  {
    fixedT = vtkNormalMapping::PerpendicularTangent(unitN, t);
  }
  else
  {
    return f;
  }
  mikk::CornerFrame out = f;
  for (int k = 0; k < 3; ++k)
  {
    out.Tangent[k] = static_cast<float>(fixedT[k]);
  }
  return out;
}

/// The float normal of point p, as the filter hands it to the kernel.
std::array<float, 3> FloatNormal(vtkPolyData* pd, vtkIdType p)
{
  vtkDataArray* normals = pd->GetPointData()->GetNormals();
  return { static_cast<float>(normals->GetComponent(p, 0)),
    static_cast<float>(normals->GetComponent(p, 1)),
    static_cast<float>(normals->GetComponent(p, 2)) };
}

/// With Splitting on: every output corner carries exactly its own (expected) frame, the cells
/// keep their order and sizes, and a re-pointed corner uses a copy of its input point.
void ExpectCornersCarryOwnFrames(vtkPolyData* in, vtkPolyData* out, bool gltf = false)
{
  const ExpectedFrames e = ComputeExpected(in);
  const vtkIdType np = in->GetNumberOfPoints();
  vtkDataArray* inUV = in->GetPointData()->GetTCoords();
  vtkDataArray* outUV = out->GetPointData()->GetTCoords();
  ASSERT_NE(outUV, nullptr);
  long long wrong = 0;
  for (int which = 0; which < 2; ++which)
  {
    vtkCellArray* inCells = which == 0 ? in->GetPolys() : in->GetStrips();
    vtkCellArray* outCells = which == 0 ? out->GetPolys() : out->GetStrips();
    ASSERT_EQ(inCells->GetNumberOfCells(), outCells->GetNumberOfCells());
    for (vtkIdType c = 0; c < inCells->GetNumberOfCells(); ++c)
    {
      const std::vector<vtkIdType> a = CellIds(inCells, c), b = CellIds(outCells, c);
      ASSERT_EQ(a.size(), b.size()) << "cell " << c;
      for (size_t k = 0; k < a.size(); ++k)
      {
        if (a[k] != b[k])
        {
          ASSERT_GE(b[k], np) << "corner re-pointed to another input point";
          double pa[3], pb[3];
          in->GetPoint(a[k], pa);
          out->GetPoint(b[k], pb);
          EXPECT_TRUE(pa[0] == pb[0] && pa[1] == pb[1] && pa[2] == pb[2]);
          EXPECT_EQ(inUV->GetComponent(a[k], 0), outUV->GetComponent(b[k], 0));
        }
        const long long slot = which == 0 ? e.PolySlot[c][k] : e.StripSlot[c][k];
        if (slot < 0)
        {
          continue;
        }
        mikk::CornerFrame expected =
          ContractFrame(e.Kernel.Corners[static_cast<size_t>(slot)], FloatNormal(in, a[k]).data());
        if (gltf)
        {
          expected.Sign = -expected.Sign;
        }
        if (!BitEqual(PointFrame(out, b[k]), expected) && ++wrong <= 5)
        {
          ADD_FAILURE() << (which == 0 ? "polygon " : "strip ") << c << " corner " << k
                        << " does not carry its own frame";
        }
      }
    }
  }
  EXPECT_EQ(wrong, 0);
}

/// Names (without .vtp) of every file in <shared>/mikktspace, sorted.
std::vector<std::string> ReferenceFiles(const std::string& dataDir)
{
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dataDir + "/mikktspace", error))
  {
    if (entry.path().extension() == ".vtp")
    {
      names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

vtkSmartPointer<vtkPolyData> ReadVtp(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> pd = reader->GetOutput();
  return pd;
}

//------------------------------------------------------------------------------
// Hand-built meshes

/// 3 x 2 points, two unit quads as four triangles, u mirrored about x = 1 (u = |x - 1|), v = y,
/// normals +z. The centre column (points 1 and 4) is shared by both halves.
TestMesh MirroredPair()
{
  TestMesh m;
  for (int y = 0; y < 2; ++y)
  {
    for (int x = 0; x < 3; ++x)
    {
      m.AddPoint({ float(x), float(y), 0.0f },
        { 0.0f, 0.0f, 1.0f },
        { std::fabs(float(x) - 1.0f), float(y) });
    }
  }
  m.Polys = { { 0, 1, 4 }, { 0, 4, 3 }, { 1, 2, 5 }, { 1, 5, 4 } };
  return m;
}

/// A bumpy nx x ny grid with mixed cells: triangles, quads, 6-point polygons (two quads merged)
/// and a 2-point polygon; u mirrored about x = nx / 2, v with a seam row of duplicated points.
TestMesh MixedGrid(int nx, int ny)
{
  TestMesh m;
  const auto height = [](float x, float y)
  { return 0.3f * std::sin(0.7f * x) * std::cos(0.5f * y); };
  std::vector<vtkIdType> id((nx + 1) * (ny + 1));
  for (int y = 0; y <= ny; ++y)
  {
    for (int x = 0; x <= nx; ++x)
    {
      const float fx = float(x), fy = float(y);
      const float dx = 0.21f * std::cos(0.7f * fx) * std::cos(0.5f * fy);
      const float dy = -0.15f * std::sin(0.7f * fx) * std::sin(0.5f * fy);
      const float len = std::sqrt(dx * dx + dy * dy + 1.0f);
      id[y * (nx + 1) + x] = m.AddPoint({ fx, fy, height(fx, fy) },
        { -dx / len, -dy / len, 1.0f / len },
        { 0.1f * std::fabs(fx - 0.5f * float(nx)), 0.1f * fy });
    }
  }
  for (int y = 0; y < ny; ++y)
  {
    for (int x = 0; x < nx; ++x)
    {
      const vtkIdType a = id[y * (nx + 1) + x], b = id[y * (nx + 1) + x + 1],
                      c = id[(y + 1) * (nx + 1) + x + 1], d = id[(y + 1) * (nx + 1) + x];
      const int kind = (x + 2 * y) % 4;
      if (kind == 0)
      {
        m.Polys.push_back({ a, b, c });
        m.Polys.push_back({ a, c, d });
      }
      else if (kind == 1 && x + 1 < nx)
      {
        const vtkIdType b2 = id[y * (nx + 1) + x + 2], c2 = id[(y + 1) * (nx + 1) + x + 2];
        m.Polys.push_back({ a, b, b2, c2, c, d });
        ++x;
      }
      else
      {
        m.Polys.push_back({ a, b, c, d });
      }
    }
  }
  m.Polys.push_back({ id[0], id[1] }); // fewer than 3 points: no frame, must not split
  return m;
}

/// A strip of 2 * (n + 1) points along x (bottom y = 0, top y = 1 alternating), u = |x - 1|,
/// v = y, normals -z (the strip winds clockwise seen from +z). Corners at x = 1 belong to
/// triangles of both mirrored halves.
TestMesh MirroredStrip(int n)
{
  TestMesh m;
  std::vector<vtkIdType> strip;
  for (int x = 0; x <= n; ++x)
  {
    for (int y = 0; y < 2; ++y)
    {
      strip.push_back(m.AddPoint({ float(x), float(y), 0.0f },
        { 0.0f, 0.0f, -1.0f },
        { std::fabs(float(x) - 1.0f), float(y) }));
    }
  }
  m.Strips.push_back(strip);
  return m;
}

/// The mesh with each strip of 3 or more points replaced by its triangles as one-triangle strips,
/// in strip order, every odd one reversed to keep the strip's winding: what the filter cuts a
/// strip into when its triangles need different frames at a corner.
TestMesh WithStripsCut(TestMesh m)
{
  std::vector<std::vector<vtkIdType>> cut;
  for (const std::vector<vtkIdType>& s : m.Strips)
  {
    if (s.size() < 3)
    {
      cut.push_back(s);
    }
    for (size_t j = 0; j + 2 < s.size(); ++j)
    {
      const bool odd = (j & 1) != 0;
      cut.push_back({ s[odd ? j + 1 : j], s[odd ? j : j + 1], s[j + 2] });
    }
  }
  m.Strips = cut;
  return m;
}

/// Torus of nu x nv quads with u mirrored on half of it, some quads split, a band of strips
/// (or, with strips false, quads there too) and a seam; big enough to spread over several
/// threads.
TestMesh BigMixedTorus(int nu, int nv, bool strips = true)
{
  TestMesh m;
  const double R = 2.0, r = 0.6, pi = 3.14159265358979323846;
  const auto at = [&](int i, int j) { return static_cast<vtkIdType>((j % nv) * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i <= nu; ++i)
    {
      const double a = 2 * pi * i / nu, b = 2 * pi * j / nv;
      const double nx = std::cos(a) * std::cos(b), ny = std::sin(a) * std::cos(b), nz = std::sin(b);
      const double u = double(i) / nu;
      m.AddPoint({ float((R + r * std::cos(b)) * std::cos(a)),
                   float((R + r * std::cos(b)) * std::sin(a)),
                   float(r * std::sin(b)) },
        { float(nx), float(ny), float(nz) },
        { float(u < 0.5 ? u : 1.0 - u), float(double(j) / nv) });
    }
  }
  for (int j = 0; j < nv; ++j)
  {
    if (strips && j % 8 == 3)
    {
      std::vector<vtkIdType> strip;
      for (int i = 0; i <= nu; ++i)
      {
        strip.push_back(at(i, j + 1));
        strip.push_back(at(i, j));
      }
      m.Strips.push_back(strip);
      continue;
    }
    for (int i = 0; i < nu; ++i)
    {
      const vtkIdType a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 3 == 0)
      {
        m.Polys.push_back({ a, b, c });
        m.Polys.push_back({ a, c, d });
      }
      else
      {
        m.Polys.push_back({ a, b, c, d });
      }
    }
  }
  return m;
}

template<typename T>
std::vector<T> Values(vtkDataArray* a)
{
  std::vector<T> v;
  if (!a)
  {
    return v;
  }
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    v.push_back(static_cast<T>(a->GetComponent(
      i / a->GetNumberOfComponents(), static_cast<int>(i % a->GetNumberOfComponents()))));
  }
  return v;
}

bool SameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A grid of quads on the plane z = x/2 + y/4, normals +z, texture coordinates (x, -y): dP/du
// projected on the tangent plane is exactly +x and the texture is mirrored, so every corner's
// computed frame has the bits of the kernel's default, (1,0,0) with sign -1.
TestMesh DefaultBitsGrid()
{
  TestMesh m;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      m.AddPoint({ float(i), float(j), 0.5f * float(i) + 0.25f * float(j) },
        { 0, 0, 1 },
        { float(i), -float(j) });
    }
  }
  for (vtkIdType j = 0; j < 2; ++j)
  {
    for (vtkIdType i = 0; i < 2; ++i)
    {
      const vtkIdType p = 3 * j + i;
      m.Polys.push_back({ p, p + 1, p + 4, p + 3 });
    }
  }
  return m;
}

/// Whether the first `count` corners of `r` are computed (not left at the default) and have the
/// default's bits.
::testing::AssertionResult ComputedWithTheDefaultBits(const mikk::Result& r, size_t count)
{
  for (size_t c = 0; c < count; ++c)
  {
    const mikk::CornerFrame& f = r.Corners[c];
    if (r.CornerKinds[c] != mikk::CornerKind::Computed || !IsDefault(f))
    {
      return ::testing::AssertionFailure()
        << "corner " << c << ": kind " << int(r.CornerKinds[c]) << ", (" << f.Tangent[0] << ", "
        << f.Tangent[1] << ", " << f.Tangent[2] << "), sign " << f.Sign;
    }
  }
  return ::testing::AssertionSuccess();
}

} // namespace

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, MatchesReferenceData)
{
  REQUIRE_SHARED_DATA(dataDir);
  const std::vector<std::string> names = ReferenceFiles(dataDir);
  // The files documented in shared/data/README.md must all be there (others are tested too).
  for (const char* known : { "sphere_poles",
         "torus",
         "mirror_grid",
         "cylinder_seam",
         "noisy",
         "NormalTangentTest",
         "NormalTangentMirrorTest" })
  {
    EXPECT_NE(std::find(names.begin(), names.end(), known), names.end())
      << "missing reference file " << dataDir << "/mikktspace/" << known << ".vtp";
  }
  int tested = 0;
  for (const std::string& name : names)
  {
    const std::string path = dataDir + "/mikktspace/" + name + ".vtp";
    vtkSmartPointer<vtkPolyData> input = ReadVtp(path);
    vtkDataArray* ref = input->GetFieldData()->GetArray("CornerTangents");
    ASSERT_TRUE(ref && ref->GetNumberOfComponents() == 4) << path;
    ASSERT_TRUE(input->GetPointData()->GetNormals() && input->GetPointData()->GetTCoords());
    const FilterRun run = RunFilter(input);
    EXPECT_TRUE(run.Errors.empty()) << Join(run.Errors);
    EXPECT_TRUE(run.Warnings.empty()) << Join(run.Warnings);
    vtkPolyData* out = run.Output;
    ASSERT_NE(out->GetPointData()->GetArray("Tangents"), nullptr) << name;
    EXPECT_EQ(out->GetPointData()->GetTangents(), out->GetPointData()->GetArray("Tangents"));
    EXPECT_NE(vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("Tangents")), nullptr);
    EXPECT_EQ(out->GetNumberOfPoints(), input->GetNumberOfPoints() + run.SplitPoints);

    vtkCellArray* polys = out->GetPolys();
    ASSERT_EQ(polys->GetNumberOfCells() * 3, ref->GetNumberOfTuples());
    Stats st;
    long long defaults = 0, changedDefaults = 0;
    for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
    {
      const std::vector<vtkIdType> ids = CellIds(polys, c);
      ASSERT_EQ(ids.size(), 3u);
      for (int k = 0; k < 3; ++k)
      {
        double r[4];
        ref->GetTuple(3 * c + k, r);
        const mikk::CornerFrame o = PointFrame(out, ids[k]);
        if (r[0] == 1 && r[1] == 0 && r[2] == 0 && r[3] == -1)
        {
          // The reference's default frame is not perpendicular to every normal: the filter
          // gives the documented fallback frame instead, which is the default wherever (1,0,0)
          // already is perpendicular to the normal.
          ++defaults;
          const mikk::CornerFrame fallback =
            ContractFrame(mikk::DefaultCornerFrame, FloatNormal(out, ids[k]).data());
          changedDefaults += IsDefault(fallback) ? 0 : 1;
          EXPECT_TRUE(BitEqual(o, fallback))
            << name << " cell " << c << " corner " << k
            << ": reference default, output not the fallback frame";
          continue;
        }
        if (static_cast<float>(r[3]) != o.Sign)
        {
          ++st.SignMismatches;
          ADD_FAILURE() << name << " cell " << c << " corner " << k << ": sign " << o.Sign;
        }
        const float rf[3] = { float(r[0]), float(r[1]), float(r[2]) };
        const double angle = AngleDeg(rf, o.Tangent);
        st.Angles.push_back(angle);
        EXPECT_LE(angle, kMaxAngleDeg) << name << " cell " << c << " corner " << k;
      }
    }
    ExpectCornersCarryOwnFrames(input, out);
    std::printf("[ mikk-flt ] %-24s corners %6zu exact %6lld mean %.3g p99 %.3g max %.3g deg"
                "  sign mismatches %lld  defaults %lld (made perpendicular %lld)  conflicts %lld"
                "  split points %lld"
                "  degenerate %lld\n",
      name.c_str(),
      st.Angles.size() + static_cast<size_t>(defaults),
      st.Exact(),
      st.Mean(),
      st.Quantile(0.99),
      st.Max(),
      st.SignMismatches,
      defaults,
      changedDefaults,
      static_cast<long long>(run.Conflicts),
      static_cast<long long>(run.SplitPoints),
      static_cast<long long>(run.Degenerate));
    ++tested;
  }
  EXPECT_EQ(tested, static_cast<int>(names.size()));
}

//------------------------------------------------------------------------------
// NormalTangentMirrorTest.vtp holds the glTF's positions, normals and TEXCOORD_0 exactly as
// stored (v down; checked below), so GLTFSignConvention on must reproduce the file's TANGENT.
TEST(PolyDataTangentFramesMikkTSpace, MatchesGltfStoredTangents)
{
  REQUIRE_SHARED_DATA(dataDir);
  const std::string gltfPath =
    dataDir + "/gltf/NormalTangentMirrorTest/NormalTangentMirrorTest.gltf";
  GltfPrimitive gltf;
  std::string error;
  ASSERT_TRUE(LoadGltfPrimitive(gltfPath, gltf, error)) << error;
  ASSERT_FALSE(gltf.Tangents.empty()) << "no TANGENT in " << gltfPath;
  vtkSmartPointer<vtkPolyData> input = ReadVtp(dataDir + "/mikktspace/NormalTangentMirrorTest.vtp");
  const vtkIdType np = input->GetNumberOfPoints();
  ASSERT_EQ(static_cast<size_t>(np) * 3, gltf.Positions.size());
  vtkDataArray* uv = input->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_EQ(p[k], gltf.Positions[3 * i + k]) << "point " << i;
    }
    ASSERT_EQ(uv->GetComponent(i, 0), gltf.TexCoords[2 * i]) << "u of point " << i;
    ASSERT_EQ(uv->GetComponent(i, 1), gltf.TexCoords[2 * i + 1]) << "v of point " << i;
  }
  ASSERT_EQ(
    static_cast<size_t>(input->GetPolys()->GetNumberOfConnectivityIds()), gltf.Indices.size());

  const FilterRun run =
    RunFilter(input, [](vtkPolyDataTangentFrames* f) { f->GLTFSignConventionOn(); });
  const FilterRun plain = RunFilter(input);
  vtkPolyData* out = run.Output;
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkCellArray* inPolys = input->GetPolys();
  vtkCellArray* outPolys = out->GetPolys();
  Stats st;
  long long corner = 0;
  for (vtkIdType c = 0; c < inPolys->GetNumberOfCells(); ++c)
  {
    const std::vector<vtkIdType> a = CellIds(inPolys, c), b = CellIds(outPolys, c);
    for (size_t k = 0; k < a.size(); ++k, ++corner)
    {
      ASSERT_EQ(static_cast<double>(a[k]), gltf.Indices[static_cast<size_t>(corner)]);
      const double* stored = &gltf.Tangents[4 * static_cast<size_t>(a[k])];
      const mikk::CornerFrame o = PointFrame(out, b[k]);
      if (static_cast<float>(stored[3]) != o.Sign)
      {
        ++st.SignMismatches;
      }
      const float s[3] = { float(stored[0]), float(stored[1]), float(stored[2]) };
      st.Angles.push_back(AngleDeg(s, o.Tangent));
      // GLTFSignConvention only negates the sign.
      const mikk::CornerFrame q = PointFrame(plain.Output, CellIds(plain.Output->GetPolys(), c)[k]);
      EXPECT_TRUE(q.Sign == -o.Sign && std::memcmp(q.Tangent, o.Tangent, sizeof(q.Tangent)) == 0);
    }
  }
  std::printf("[ mikk-flt ] glTF NormalTangentMirrorTest corners %zu mean %.3g p99 %.3g max %.3g"
              " deg  sign mismatches %lld  split points %lld\n",
    st.Angles.size(),
    st.Mean(),
    st.Quantile(0.99),
    st.Max(),
    st.SignMismatches,
    static_cast<long long>(run.SplitPoints));
  EXPECT_EQ(st.SignMismatches, 0);
  EXPECT_LE(st.Max(), kGltfMaxAngleDeg);
  ExpectCornersCarryOwnFrames(input, out, /*gltf=*/true);
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, SplitsMirrorSeam)
{
  TestMesh m = MirroredPair();
  vtkSmartPointer<vtkPolyData> input = m.Build();
  vtkNew<vtkIntArray> tag; // extra point data: must be copied to the split points
  tag->SetName("Tag");
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    tag->InsertNextValue(static_cast<int>(100 + i));
  }
  input->GetPointData()->AddArray(tag);

  const FilterRun run = RunFilter(input);
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkPolyData* out = run.Output;
  // Points 1 and 4 (the centre column) carry the left (first) frame; each gets one copy.
  EXPECT_EQ(run.Conflicts, 2);
  EXPECT_EQ(run.SplitPoints, 2);
  ASSERT_EQ(out->GetNumberOfPoints(), 8);
  // New points in order of first appearance: corner 0 of cell 2 (point 1), corner 2 of cell 3
  // (point 4).
  const std::vector<std::vector<vtkIdType>> expected = {
    { 0, 1, 4 }, { 0, 4, 3 }, { 6, 2, 5 }, { 6, 5, 7 }
  };
  for (vtkIdType c = 0; c < 4; ++c)
  {
    EXPECT_EQ(CellIds(out->GetPolys(), c), expected[c]) << "cell " << c;
    // u = 1 - x on the left: dP/du = -x, bitangent +y = sign * cross(z, -x) = -sign * y, so
    // sign -1; on the right dP/du = +x, sign +1.
    const bool left = c < 2;
    for (vtkIdType p : CellIds(out->GetPolys(), c))
    {
      const mikk::CornerFrame f = PointFrame(out, p);
      EXPECT_NEAR(f.Tangent[0], left ? -1.0 : 1.0, kAxisTol) << "cell " << c;
      EXPECT_NEAR(f.Tangent[1], 0.0, kAxisTol);
      EXPECT_NEAR(f.Tangent[2], 0.0, kAxisTol);
      EXPECT_EQ(f.Sign, left ? -1.0f : 1.0f) << "cell " << c;
    }
  }
  vtkDataArray* outTag = out->GetPointData()->GetArray("Tag");
  ASSERT_NE(outTag, nullptr);
  EXPECT_EQ(outTag->GetComponent(6, 0), 101);
  EXPECT_EQ(outTag->GetComponent(7, 0), 104);
  double p6[3], p7[3];
  out->GetPoint(6, p6);
  out->GetPoint(7, p7);
  EXPECT_TRUE(p6[0] == 1 && p6[1] == 0 && p7[0] == 1 && p7[1] == 1);
  EXPECT_EQ(out->GetPointData()->GetTCoords()->GetNumberOfTuples(), 8);
  EXPECT_EQ(out->GetPointData()->GetNormals()->GetNumberOfTuples(), 8);
  ExpectCornersCarryOwnFrames(input, out);

  // Splitting off: the same conflicts, no new points, the first corner's frame.
  const FilterRun off = RunFilter(input, [](vtkPolyDataTangentFrames* f) { f->SplittingOff(); });
  EXPECT_EQ(off.Conflicts, 2);
  EXPECT_EQ(off.SplitPoints, 0);
  ASSERT_EQ(off.Output->GetNumberOfPoints(), 6);
  for (vtkIdType c = 0; c < 4; ++c)
  {
    EXPECT_EQ(CellIds(off.Output->GetPolys(), c), m.Polys[c]);
  }
  for (vtkIdType p : { 1, 4 })
  {
    const mikk::CornerFrame f = PointFrame(off.Output, p);
    EXPECT_NEAR(f.Tangent[0], -1.0, kAxisTol);
    EXPECT_EQ(f.Sign, -1.0f);
  }
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, CellOrderAndCornerCorrespondence)
{
  TestMesh m = MixedGrid(12, 9);
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const FilterRun run = RunFilter(input);
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  EXPECT_GT(run.SplitPoints, 0); // the mirror column splits
  EXPECT_EQ(run.Output->GetNumberOfPoints(), input->GetNumberOfPoints() + run.SplitPoints);
  ExpectCornersCarryOwnFrames(input, run.Output);
  // The 2-point polygon has no frame and keeps its ids.
  const vtkIdType last = input->GetPolys()->GetNumberOfCells() - 1;
  EXPECT_EQ(CellIds(run.Output->GetPolys(), last), m.Polys.back());

  // Double output: the same values, widened.
  const FilterRun dbl = RunFilter(input,
    [](vtkPolyDataTangentFrames* f) { f->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION); });
  vtkDataArray* td = dbl.Output->GetPointData()->GetArray("Tangents");
  ASSERT_NE(vtkDoubleArray::SafeDownCast(td), nullptr);
  ASSERT_NE(
    vtkDoubleArray::SafeDownCast(dbl.Output->GetPointData()->GetArray("TangentSigns")), nullptr);
  EXPECT_EQ(Values<double>(td), Values<double>(run.Output->GetPointData()->GetArray("Tangents")));
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, Strips)
{
  TestMesh m = MirroredStrip(3);
  m.Strips.push_back({ 0, 1 }); // fewer than 3 points: no triangle, no frame
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const FilterRun run = RunFilter(input);
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkPolyData* out = run.Output;
  // Strip corners 2 and 3 (x = 1) are in triangles of both halves, whose frames one strip corner
  // cannot carry: the strip is cut into its triangles (one-triangle strips), and points 2 and 3
  // are conflicts split between them. Their first triangle (left half, mirrored) keeps them.
  EXPECT_EQ(run.Conflicts, 2);
  EXPECT_EQ(run.SplitPoints, 2);
  EXPECT_EQ(out->GetNumberOfPoints(), input->GetNumberOfPoints() + 2);
  const vtkSmartPointer<vtkPolyData> cut = WithStripsCut(m).Build();
  ExpectCornersCarryOwnFrames(cut, out);
  // Left half (x < 1, u = 1 - x) with the strip's clockwise winding: T = -x; right: T = +x, also
  // at the copies of points 2 and 3.
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    const mikk::CornerFrame f = PointFrame(out, p);
    const bool left = p < 4;
    EXPECT_NEAR(f.Tangent[0], left ? -1.0 : 1.0, kAxisTol) << "point " << p;
    EXPECT_NE(f.Sign, 0.0f);
  }
  EXPECT_EQ(PointFrame(out, 2).Sign, PointFrame(out, 0).Sign);
  EXPECT_EQ(PointFrame(out, 4).Sign, -PointFrame(out, 0).Sign);
  EXPECT_EQ(PointFrame(out, 8).Sign, PointFrame(out, 4).Sign);

  // The same triangles as polygons give the same frames, bit for bit, split points included.
  TestMesh tris = WithStripsCut(MirroredStrip(3));
  tris.Polys = tris.Strips;
  tris.Strips.clear();
  const FilterRun polyRun = RunFilter(tris.Build());
  ASSERT_EQ(polyRun.Output->GetNumberOfPoints(), out->GetNumberOfPoints());
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    EXPECT_TRUE(BitEqual(PointFrame(out, p), PointFrame(polyRun.Output, p))) << "point " << p;
  }
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, MixedCellTypes)
{
  // Polygons on y in [1, 2], a mirrored strip on y in [0, 1] sharing the points of y = 1, two
  // vertex cells and a line. v runs back down to 0 on y = 2, so the polygons have the opposite
  // handedness of the strip and the points of y = 1 split.
  TestMesh m = MirroredStrip(3);
  std::vector<vtkIdType> top;
  for (int x = 0; x <= 3; ++x)
  {
    top.push_back(m.AddPoint(
      { float(x), 2.0f, 0.0f }, { 0.0f, 0.0f, -1.0f }, { std::fabs(float(x) - 1.0f), 0.0f }));
  }
  for (int x = 0; x < 3; ++x)
  {
    // points of y = 1 are 2x + 1; clockwise seen from +z like the strip
    m.Polys.push_back({ 2 * x + 1, top[x], top[x + 1], 2 * x + 3 });
  }
  m.Verts = { { 0 }, { 5 } };
  m.Lines = { { 0, 2, 4, 6 } };
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const vtkIdType numCells = input->GetNumberOfCells();
  vtkNew<vtkIntArray> cellTag;
  cellTag->SetName("CellTag");
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    cellTag->InsertNextValue(static_cast<int>(7 * c));
  }
  input->GetCellData()->AddArray(cellTag);

  const FilterRun run = RunFilter(input,
    [](vtkPolyDataTangentFrames* f)
    {
      f->ComputeBitangentsOn();
      f->ComputeCellTangentsOn();
    });
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkPolyData* out = run.Output;
  // The strip crosses the mirror seam at x = 1: it is cut into its 6 triangles.
  const vtkSmartPointer<vtkPolyData> cut = WithStripsCut(m).Build();
  ExpectCornersCarryOwnFrames(cut, out);
  // Verts and lines untouched.
  ASSERT_EQ(out->GetVerts()->GetNumberOfCells(), 2);
  EXPECT_EQ(CellIds(out->GetVerts(), 1), std::vector<vtkIdType>{ 5 });
  ASSERT_EQ(out->GetLines()->GetNumberOfCells(), 1);
  EXPECT_EQ(CellIds(out->GetLines(), 0), m.Lines[0]);
  // Strip re-pointed where the polygons (first in corner order) took a point's first frame.
  EXPECT_GT(run.SplitPoints, 0);
  // Cell data passed through, the strip's repeated for each of its triangles; cell tangents:
  // zero for verts/lines, unit and perpendicular to the cell plane (z = 0) for the polygons and
  // the strip's triangles.
  ASSERT_EQ(out->GetNumberOfCells(), numCells + 5);
  std::vector<int> tags = Values<int>(cellTag);
  tags.insert(tags.end(), 5, tags.back());
  EXPECT_EQ(Values<int>(out->GetCellData()->GetArray("CellTag")), tags);
  vtkDataArray* ct = out->GetCellData()->GetTangents();
  ASSERT_NE(ct, nullptr);
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    double t[3];
    ct->GetTuple(c, t);
    if (c < 3) // 2 verts + 1 line
    {
      EXPECT_TRUE(t[0] == 0 && t[1] == 0 && t[2] == 0) << "cell " << c;
    }
    else
    {
      // 1e-6: a unit vector normalised in double and rounded to float (6e-8 per component).
      EXPECT_NEAR(t[0] * t[0] + t[1] * t[1] + t[2] * t[2], 1.0, 1e-6) << "cell " << c;
      EXPECT_NEAR(t[2], 0.0, 1e-6) << "cell " << c;
    }
  }
  // Bitangents = sign * cross(N, T).
  vtkDataArray* bt = out->GetPointData()->GetArray("Bitangents");
  vtkDataArray* nrm = out->GetPointData()->GetNormals();
  ASSERT_NE(bt, nullptr);
  ASSERT_EQ(nrm->GetNumberOfTuples(), out->GetNumberOfPoints());
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    const mikk::CornerFrame f = PointFrame(out, p);
    double n[3], b[3];
    nrm->GetTuple(p, n);
    bt->GetTuple(p, b);
    const double e[3] = { f.Sign * (n[1] * f.Tangent[2] - n[2] * f.Tangent[1]),
      f.Sign * (n[2] * f.Tangent[0] - n[0] * f.Tangent[2]),
      f.Sign * (n[0] * f.Tangent[1] - n[1] * f.Tangent[0]) };
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_NEAR(b[k], e[k], kBitangentTol) << "point " << p;
    }
  }
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, OutOfRangeIdsPassThrough)
{
  TestMesh m = MirroredPair();
  m.Polys.push_back({ 0, 1, 42 });
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const FilterRun run = RunFilter(input);
  ASSERT_EQ(run.Errors.size(), 1u) << Join(run.Errors);
  EXPECT_NE(run.Errors[0].find("outside"), std::string::npos) << run.Errors[0];
  EXPECT_EQ(run.Output->GetNumberOfPoints(), input->GetNumberOfPoints());
  EXPECT_EQ(run.Output->GetPolys()->GetNumberOfCells(), 5);
  EXPECT_EQ(run.Output->GetPointData()->GetArray("Tangents"), nullptr);
  EXPECT_EQ(run.Output->GetPointData()->GetArray("TangentSigns"), nullptr);

  // Decreasing offsets (a malformed cell array): an error, not a crash.
  vtkSmartPointer<vtkPolyData> bad = MirroredPair().Build();
  vtkNew<vtkTypeInt64Array> offsets, conn;
  for (vtkTypeInt64 v : { 0, 4, 2, 6 })
  {
    offsets->InsertNextValue(v);
  }
  for (vtkTypeInt64 v : { 0, 1, 4, 0, 4, 3 })
  {
    conn->InsertNextValue(v);
  }
  vtkNew<vtkCellArray> badPolys;
  badPolys->SetData(offsets, conn);
  bad->SetPolys(badPolys);
  const FilterRun badRun = RunFilter(bad);
  EXPECT_EQ(badRun.Errors.size(), 1u) << Join(badRun.Errors);
  EXPECT_EQ(badRun.Output->GetPointData()->GetArray("Tangents"), nullptr);

  TestMesh s = MirroredStrip(2);
  s.Strips[0].push_back(-3);
  const FilterRun stripRun = RunFilter(s.Build());
  EXPECT_EQ(stripRun.Errors.size(), 1u) << Join(stripRun.Errors);
  EXPECT_EQ(stripRun.Output->GetPointData()->GetArray("Tangents"), nullptr);
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, NonFiniteInputGivesFiniteOutput)
{
  TestMesh m = MixedGrid(8, 6);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  m.P[3][1] = nan;
  m.P[10][0] = inf;
  m.N[20] = { nan, nan, nan };
  m.N[21] = { 0.0f, 0.0f, 0.0f };
  m.U[30][0] = nan;
  m.U[31][1] = -inf;
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const FilterRun run = RunFilter(input,
    [](vtkPolyDataTangentFrames* f)
    {
      f->ComputeBitangentsOn();
      f->ComputeCellTangentsOn();
    });
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkPolyData* out = run.Output;
  for (const char* name : { "Tangents", "TangentSigns", "Bitangents" })
  {
    vtkDataArray* a = out->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    for (double v : Values<double>(a))
    {
      EXPECT_TRUE(std::isfinite(v)) << name;
    }
  }
  for (double v : Values<double>(out->GetPointData()->GetArray("TangentSigns")))
  {
    EXPECT_TRUE(v == 1.0 || v == -1.0);
  }
  for (double v : Values<double>(out->GetCellData()->GetTangents()))
  {
    EXPECT_TRUE(std::isfinite(v));
  }
}

//------------------------------------------------------------------------------
// A mesh whose every triangle has two equal corner positions gets the default frame everywhere,
// and says so, whether the normals come with the input or are computed (the two take different
// routes through the filter).
TEST(PolyDataTangentFramesMikkTSpace, WarnsWhenNoTriangleHasAFrame)
{
  TestMesh m;
  for (int k = 0; k < 4; ++k)
  {
    // a triangle (p, p, q): its first two corners coincide, its texture coordinates do not
    const float x = float(k);
    const vtkIdType a = m.AddPoint({ x, 0.0f, 0.0f }, { 0.0f, 0.0f, 1.0f }, { x, 0.0f });
    const vtkIdType b = m.AddPoint({ x, 0.0f, 0.0f }, { 0.0f, 0.0f, 1.0f }, { x + 0.5f, 0.0f });
    const vtkIdType c = m.AddPoint({ x, 1.0f, 0.0f }, { 0.0f, 0.0f, 1.0f }, { x, 1.0f });
    m.Polys.push_back({ a, b, c });
  }
  for (const bool withNormals : { true, false })
  {
    SCOPED_TRACE(withNormals ? "input normals" : "computed normals");
    vtkSmartPointer<vtkPolyData> input = m.Build();
    if (!withNormals)
    {
      input->GetPointData()->SetNormals(nullptr);
    }
    const FilterRun run = RunFilter(input);
    EXPECT_TRUE(run.Errors.empty()) << Join(run.Errors);
    EXPECT_EQ(run.Degenerate, 4);
    // Computing normals adds a warning of its own.
    EXPECT_EQ(std::count_if(run.Warnings.begin(),
                run.Warnings.end(),
                [](const std::string& w) {
                  return w.find("None of the 4 triangles has a usable frame") != std::string::npos;
                }),
      1)
      << Join(run.Warnings);
  }
}

//------------------------------------------------------------------------------
// The filter's contract for MikkTSpace: finite unit tangents perpendicular to the normal, where
// the kernel (like the reference) gives a zero tangent (cancelled), the default (1,0,0) whatever
// the normal, or a tangent off perpendicular because the normal is not unit.
// Normals a little off unit length, as real files store them: the kernel projects with the
// normal as given, leaving |T.N| of about 2 (|N| - 1) (N.dP/du). Up to 1e-4 the filter keeps
// the kernel's bits (the reference's tangents); beyond, it makes the tangent perpendicular.
TEST(PolyDataTangentFramesMikkTSpace, SlightlyNonUnitNormalsKeepOrCorrectTheKernelFrame)
{
  const float c = 0.6f, z = 0.8f;
  // |N| = 1.005: |T.N| about 0.0075; |N| = 1 + 4e-5: about 4e-5.
  for (const float length : { 1.005f, 1.00004f })
  {
    SCOPED_TRACE(length);
    TestMesh m;
    m.AddPoint({ 0, 0, 0 }, { length * c, 0, length * z }, { 0, 0 });
    m.AddPoint({ 1, 0, 0 }, { length * c, 0, length * z }, { 1, 0 });
    m.AddPoint({ 0, 1, 0 }, { length * c, 0, length * z }, { 0, 1 });
    m.Polys.push_back({ 0, 1, 2 });
    vtkSmartPointer<vtkPolyData> input = m.Build();
    const ExpectedFrames e = ComputeExpected(input);
    const FilterRun run = RunFilter(input, [](vtkPolyDataTangentFrames*) {});
    ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
    vtkDataArray* t = run.Output->GetPointData()->GetTangents();
    for (vtkIdType p = 0; p < 3; ++p)
    {
      const mikk::CornerFrame& k = e.Kernel.Corners[static_cast<size_t>(p)];
      const glm::dvec3 n = glm::normalize(glm::dvec3(c, 0.0, z));
      const double kernelTN =
        std::abs(glm::dot(glm::dvec3(k.Tangent[0], k.Tangent[1], k.Tangent[2]), n));
      glm::dvec3 tv;
      t->GetTuple(p, &tv[0]);
      if (length > 1.001f)
      {
        ASSERT_GT(kernelTN, 1e-3) << "point " << p << ": the kernel's tangent was expected off";
        // Float output: a unit vector rounded to float is perpendicular within ~2e-7.
        EXPECT_NEAR(glm::dot(tv, n), 0.0, 1e-6) << "point " << p;
      }
      else
      {
        ASSERT_GT(kernelTN, 1e-5) << "point " << p << ": the kernel's tangent was expected off";
        EXPECT_TRUE(BitEqual(PointFrame(run.Output, p), k)) << "point " << p;
      }
    }
  }
}

//------------------------------------------------------------------------------
// Cell tangents (docs/filter.md): per polygon or strip, the sum of the kernel frames of its
// faces' computed corners (mikk::CornerKind), made perpendicular to the sum of its faces' cross
// products (fanned from each face's first corner) and normalised; with nothing left to sum, the
// fixed perpendicular FallbackTangent of that normal.
TEST(PolyDataTangentFramesMikkTSpace, CellTangentsSumTheCornerFramesOfEachCell)
{
  TestMesh m;
  // Cell 0: a quad folded along its diagonal, with texture coordinates no affine map gives, so
  // that its corners' frames differ and its two triangles' normals too.
  m.AddPoint({ 0, 0, 0 }, { 0, 0, 1 }, { 0, 0 });
  m.AddPoint({ 4, 0, 0 }, { 0, 0, 1 }, { 4, 0 });
  m.AddPoint({ 2, 1, 0 }, { 0, 0, 1 }, { 2, 1 });
  m.AddPoint({ 0, 1, 0.5f }, { 0, 0, 1 }, { 0, 2 });
  m.Polys.push_back({ 0, 1, 2, 3 });
  // Cell 1: a triangle of zero UV area in a plane whose normal n = (0.48, 0.36, 0.8) has a y
  // component, so that its fallback (Duff et al.'s basis of n) differs from the default (1,0,0)
  // made perpendicular to n. Edges a and n x a.
  const float nx = 0.48f, ny = 0.36f, nz = 0.8f;
  m.AddPoint({ 10, 0, 0 }, { nx, ny, nz }, { 0.5f, 0.5f });
  m.AddPoint({ 10.8f, 0, -0.48f }, { nx, ny, nz }, { 0.5f, 0.5f });
  m.AddPoint({ 10 - 0.1728f, 0.8704f, -0.288f }, { nx, ny, nz }, { 0.5f, 0.5f });
  m.Polys.push_back({ 4, 5, 6 });
  // Cell 2: a strip of two triangles, (7, 8, 9) and (9, 8, 10), one lifted corner.
  m.AddPoint({ 20, 0, 0 }, { 0, 0, 1 }, { 0, 0 });
  m.AddPoint({ 21, 0, 0 }, { 0, 0, 1 }, { 1, 0 });
  m.AddPoint({ 20, 1, 0 }, { 0, 0, 1 }, { 0, 1 });
  m.AddPoint({ 21, 1, 0.3f }, { 0, 0, 1 }, { 1.5f, 1 });
  m.Strips.push_back({ 7, 8, 9, 10 });
  vtkSmartPointer<vtkPolyData> input = m.Build();
  const ExpectedFrames e = ComputeExpected(input);
  // The kernel's faces, as the filter builds them: the polygons, then the strip's triangles.
  const std::vector<std::vector<vtkIdType>> faces = {
    { 0, 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 }, { 9, 8, 10 }
  };
  const std::vector<std::vector<size_t>> cellFaces = { { 0 }, { 1 }, { 2, 3 } };
  ASSERT_EQ(e.Kernel.Corners.size(), 13u);
  for (size_t k = 4; k < 7; ++k)
  {
    ASSERT_TRUE(IsDefault(e.Kernel.Corners[k])) << "corner " << k << " was expected default";
  }
  ASSERT_FALSE(BitEqual(e.Kernel.Corners[0], e.Kernel.Corners[1]));

  const FilterRun run =
    RunFilter(input, [](vtkPolyDataTangentFrames* f) { f->ComputeCellTangentsOn(); });
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  vtkDataArray* cellTangents = run.Output->GetCellData()->GetTangents();
  ASSERT_NE(cellTangents, nullptr);
  ASSERT_EQ(cellTangents->GetNumberOfTuples(), 3);
  size_t corner = 0;
  for (vtkIdType c = 0; c < 3; ++c)
  {
    glm::dvec3 t(0.0), n(0.0);
    for (const size_t f : cellFaces[static_cast<size_t>(c)])
    {
      const std::vector<vtkIdType>& ids = faces[f];
      const auto point = [&](size_t i)
      {
        const std::array<float, 3>& q = m.P[static_cast<size_t>(ids[i])];
        return glm::dvec3(q[0], q[1], q[2]);
      };
      for (size_t i = 0; i < ids.size(); ++i, ++corner)
      {
        const mikk::CornerFrame& k = e.Kernel.Corners[corner];
        if (e.Kernel.CornerKinds[corner] == mikk::CornerKind::Computed)
        {
          t += glm::dvec3(k.Tangent[0], k.Tangent[1], k.Tangent[2]);
        }
      }
      for (size_t i = 1; i + 1 < ids.size(); ++i)
      {
        n += glm::cross(point(i) - point(0), point(i + 1) - point(0));
      }
    }
    const glm::dvec3 expected =
      vtkNormalMapping::PerpendicularTangent(vtkNormalMapping::SafeNormalize(n), t);
    double actual[3];
    cellTangents->GetTuple(c, actual);
    for (int k = 0; k < 3; ++k)
    {
      // Float output: the double result rounded once (6e-8); the sums above add the same terms
      // in the same order as the filter's.
      EXPECT_NEAR(actual[k], expected[k], 1e-6) << "cell " << c << ", component " << k;
    }
  }
}

// The cell tangents sum the computed corners, those whose frames have the default's bits too.
// The plane is tilted, so that the cell normal n has x and y components: then the fallback
// (Duff et al.'s basis of n) differs from +x made perpendicular to n, which the computed corners
// give. On a plane perpendicular to the normals both would be (1,0,0).
TEST(PolyDataTangentFramesMikkTSpace, CellTangentsIncludeComputedCornersWithTheDefaultBits)
{
  vtkSmartPointer<vtkPolyData> input = DefaultBitsGrid().Build();
  ASSERT_TRUE(ComputedWithTheDefaultBits(ComputeExpected(input).Kernel, 16));
  const glm::dvec3 n = glm::normalize(glm::dvec3(-0.5, -0.25, 1.0));
  const glm::dvec3 x(1.0, 0.0, 0.0);
  const glm::dvec3 expected = glm::normalize(x - glm::dot(x, n) * n);
  // The fallback is 3.2 degrees (0.057) away: far outside the bound below.
  ASSERT_GT(glm::length(vtkNormalMapping::FallbackTangent(n) - expected), 0.05);

  const FilterRun run =
    RunFilter(input, [](vtkPolyDataTangentFrames* f) { f->ComputeCellTangentsOn(); });
  ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
  EXPECT_EQ(run.DefaultCorners, 0);
  vtkDataArray* cellTangents = run.Output->GetCellData()->GetTangents();
  ASSERT_NE(cellTangents, nullptr);
  ASSERT_EQ(cellTangents->GetNumberOfTuples(), 4);
  for (vtkIdType c = 0; c < 4; ++c)
  {
    double actual[3];
    cellTangents->GetTuple(c, actual);
    for (int k = 0; k < 3; ++k)
    {
      // Float output of a double result: rounded once (6e-8).
      EXPECT_NEAR(actual[k], expected[k], 1e-6) << "cell " << c << ", component " << k;
    }
  }
}

namespace
{
/// Adds a unit quad at x = 5 ... 6 whose corners share one texture coordinate (zero UV area: the
/// kernel leaves its 4 corners at the default) and returns its first point.
vtkIdType AddFlatQuad(TestMesh& m)
{
  const vtkIdType flat = m.AddPoint({ 5, 0, 0 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  m.AddPoint({ 6, 0, 0 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  m.AddPoint({ 6, 1, 0 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  m.AddPoint({ 5, 1, 0 }, { 0, 0, 1 }, { 0.5f, 0.5f });
  m.Polys.push_back({ flat, flat + 1, flat + 2, flat + 3 });
  return flat;
}

/// Adds the point array "TANGENT" (4 components, w the sign) with frame(p) at point p.
void AddSuppliedTangents(vtkPolyData* input,
  const std::function<std::array<double, 4>(vtkIdType)>& frame)
{
  vtkNew<vtkFloatArray> supplied;
  supplied->SetName("TANGENT");
  supplied->SetNumberOfComponents(4);
  supplied->SetNumberOfTuples(input->GetNumberOfPoints());
  for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
  {
    supplied->SetTuple(p, frame(p).data());
  }
  input->GetPointData()->AddArray(supplied);
}
}

// With supplied tangents kept (KEEP, KEEP_VALID), the fallback count leaves out the face corners
// of the kept points, as the weighted methods leave out kept points. A point whose frame is
// computed counts by what its corners are, not by their bits: here computed corners with the
// default's bits (not counted) beside a piece of zero texture-coordinate area, whose corners the
// kernel leaves at the default (counted where their point is not kept).
TEST(PolyDataTangentFramesMikkTSpace, FallbacksLeaveOutKeptPointsWhateverTheFrameBits)
{
  TestMesh m = DefaultBitsGrid();
  const vtkIdType centre = 4; // of the grid: one corner in each of its 4 quads
  const vtkIdType flat = AddFlatQuad(m);
  vtkSmartPointer<vtkPolyData> input = m.Build();
  // Valid supplied frames (unit, perpendicular to +z, the texture's sign -1), but for a NaN at
  // the grid's centre and at one corner of the flat quad: only those two are computed.
  AddSuppliedTangents(input,
    [&](vtkIdType p)
    {
      const bool computed = p == centre || p == flat;
      return std::array<double, 4>{ computed ? std::nan("") : 0.0, 1.0, 0.0, -1.0 };
    });

  const ExpectedFrames e = ComputeExpected(input);
  ASSERT_EQ(e.Kernel.Corners.size(), 20u);
  ASSERT_TRUE(ComputedWithTheDefaultBits(e.Kernel, 16)); // the grid's
  ASSERT_EQ(e.Kernel.NumberOfDefaultCorners, 4);         // the flat quad's

  EXPECT_EQ(RunFilter(input).DefaultCorners, 4);
  for (int mode : { vtkPolyDataTangentFrames::KEEP, vtkPolyDataTangentFrames::KEEP_VALID })
  {
    SCOPED_TRACE(mode == vtkPolyDataTangentFrames::KEEP ? "KEEP" : "KEEP_VALID");
    const FilterRun run = RunFilter(input,
      [&](vtkPolyDataTangentFrames* f)
      {
        f->SetSuppliedTangents(mode);
        f->SetSuppliedTangentsArrayName("TANGENT");
      });
    ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
    // The flat quad's corner at its computed point; none of the grid's centre.
    EXPECT_EQ(run.DefaultCorners, 1);
    EXPECT_TRUE(BitEqual(PointFrame(run.Output, centre), mikk::DefaultCornerFrame));
    EXPECT_TRUE(BitEqual(PointFrame(run.Output, flat), mikk::DefaultCornerFrame));
    EXPECT_TRUE(BitEqual(PointFrame(run.Output, flat + 1), mikk::CornerFrame{ { 0, 1, 0 }, -1 }));
  }
}

TEST(PolyDataTangentFramesMikkTSpace, FallbacksLeaveOutPolygonsOfFewerThanThreePoints)
{
  // A triangle with a frame, polygons of 2 and 1 points (which pass through and give no frame:
  // the kernel leaves their corners at its default) and a quad of zero UV area (4 fallback
  // corners): only the quad's corners are fallbacks, also where every point keeps a supplied
  // frame but one of the quad's.
  TestMesh m;
  const vtkIdType a = m.AddPoint({ 0, 0, 0 }, { 0, 0, 1 }, { 0, 0 });
  m.AddPoint({ 1, 0, 0 }, { 0, 0, 1 }, { 1, 0 });
  m.AddPoint({ 0, 1, 0 }, { 0, 0, 1 }, { 0, 1 });
  m.Polys.push_back({ a, a + 1, a + 2 });
  m.Polys.push_back({ a + 1, a + 2 });
  m.Polys.push_back({ a });
  const vtkIdType flat = AddFlatQuad(m);
  vtkSmartPointer<vtkPolyData> input = m.Build();
  AddSuppliedTangents(input,
    [&](vtkIdType p) {
      return std::array<double, 4>{ p == flat ? std::nan("") : 1.0, 0.0, 0.0, 1.0 };
    });

  EXPECT_EQ(RunFilter(input).DefaultCorners, 4);
  const FilterRun keep = RunFilter(input,
    [](vtkPolyDataTangentFrames* f)
    {
      f->SetSuppliedTangents(vtkPolyDataTangentFrames::KEEP);
      f->SetSuppliedTangentsArrayName("TANGENT");
    });
  EXPECT_EQ(keep.DefaultCorners, 1);
}

TEST(PolyDataTangentFramesMikkTSpace, FrameContractWhereTheReferenceBreaksIt)
{
  TestMesh m;
  // 1. Normals along the texture direction dP/du = +x: every corner's projected tangent is
  // zero, and so is the reference's (and the kernel's) result.
  m.AddPoint({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 0 });
  m.AddPoint({ 1, 0, 0 }, { 1, 0, 0 }, { 1, 0 });
  m.AddPoint({ 0, 1, 0 }, { 1, 0, 0 }, { 0, 1 });
  m.Polys.push_back({ 0, 1, 2 });
  // 2. Zero UV area, normals tilted towards +x: the kernel leaves the default (1,0,0), sign -1.
  const float c = 0.6f, z = 0.8f;
  m.AddPoint({ 2, 0, 0 }, { c, 0, z }, { 0.5f, 0.5f });
  m.AddPoint({ 3, 0, 0 }, { c, 0, z }, { 0.5f, 0.5f });
  m.AddPoint({ 2, 1, 0 }, { c, 0, z }, { 0.5f, 0.5f });
  m.Polys.push_back({ 3, 4, 5 });
  // 3. A good triangle whose normals have length 2 (the kernel assumes unit normals, so its
  // projection of dP/du = +x is far from perpendicular to them).
  m.AddPoint({ 4, 0, 0 }, { 2 * c, 0, 2 * z }, { 0, 0 });
  m.AddPoint({ 5, 0, 0 }, { 2 * c, 0, 2 * z }, { 1, 0 });
  m.AddPoint({ 4, 1, 0 }, { 2 * c, 0, 2 * z }, { 0, 1 });
  m.Polys.push_back({ 6, 7, 8 });
  // 4. A point no polygon uses, normal +x.
  m.AddPoint({ 9, 9, 9 }, { 1, 0, 0 }, { 0, 0 });
  vtkSmartPointer<vtkPolyData> input = m.Build();

  // The kernel keeps the reference's behaviour (bit compatibility is tested elsewhere).
  const ExpectedFrames e = ComputeExpected(input);
  for (int k = 0; k < 3; ++k)
  {
    const mikk::CornerFrame& f = e.Kernel.Corners[static_cast<size_t>(k)];
    EXPECT_LT(std::abs(f.Tangent[0]) + std::abs(f.Tangent[1]) + std::abs(f.Tangent[2]), 1e-19f)
      << "corner " << k << ": the kernel was expected to cancel";
    EXPECT_TRUE(IsDefault(e.Kernel.Corners[static_cast<size_t>(3 + k)])) << "corner " << 3 + k;
    const mikk::CornerFrame& g = e.Kernel.Corners[static_cast<size_t>(6 + k)];
    EXPECT_GT(std::abs(c * g.Tangent[0] + z * g.Tangent[2]), 0.5) << "corner " << 6 + k;
  }
  // Triangle 1's corners cancelled; the default corners and triangle 3's unit tangents did not.
  EXPECT_EQ(e.Kernel.NumberOfCancelledCorners, 3);
  EXPECT_EQ(e.Kernel.NumberOfDefaultCorners, 3);

  for (bool splitting : { true, false })
  {
    SCOPED_TRACE(splitting ? "splitting" : "no splitting");
    const FilterRun run = RunFilter(input,
      [&](vtkPolyDataTangentFrames* f)
      {
        f->SetSplitting(splitting);
        f->ComputeBitangentsOn();
      });
    ASSERT_TRUE(run.Errors.empty()) << Join(run.Errors);
    vtkPolyData* out = run.Output;
    // The 3 cancelled and the 3 default corners; the unused point is not a corner.
    EXPECT_EQ(run.DefaultCorners, 6);
    ASSERT_EQ(out->GetNumberOfPoints(), 10); // one frame per point here: nothing to split
    vtkDataArray* t = out->GetPointData()->GetTangents();
    vtkDataArray* n = out->GetPointData()->GetNormals();
    vtkDataArray* b = out->GetPointData()->GetArray("Bitangents");
    for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
    {
      glm::dvec3 tv, nv, bv;
      t->GetTuple(p, &tv[0]);
      n->GetTuple(p, &nv[0]);
      b->GetTuple(p, &bv[0]);
      nv = glm::normalize(nv);
      // Float output: a unit vector rounded to float is unit and perpendicular within ~2e-7.
      EXPECT_NEAR(glm::length(tv), 1.0, 1e-6) << "point " << p;
      EXPECT_NEAR(glm::dot(tv, nv), 0.0, 1e-6) << "point " << p;
      EXPECT_NEAR(glm::length(bv), 1.0, 1e-6) << "point " << p; // sign * cross(N, T)
      // The documented fallback frame where the kernel's breaks the contract.
      const mikk::CornerFrame expected =
        ContractFrame(p < 9 ? e.Kernel.Corners[static_cast<size_t>(p)] : mikk::DefaultCornerFrame,
          FloatNormal(input, p).data());
      EXPECT_TRUE(BitEqual(PointFrame(out, p), expected)) << "point " << p;
    }
    // Cancelled corners: (1,0,0) is parallel to N = +x, so Duff et al.'s fixed basis of +x
    // (0, 0, -1); the kernel's sign is kept. The unused point (normal +x) gets the same tangent.
    for (vtkIdType p : { 0, 1, 2, 9 })
    {
      const mikk::CornerFrame f = PointFrame(out, p);
      EXPECT_EQ(f.Tangent[0], 0.0f);
      EXPECT_EQ(f.Tangent[1], 0.0f);
      EXPECT_EQ(f.Tangent[2], -1.0f);
    }
    EXPECT_EQ(PointFrame(out, 9).Sign, -1.0f);
    // Default corners: (1,0,0) minus its part along N = (0.6, 0, 0.8): (0.8, 0, -0.6), sign -1.
    // Length-2 normals: the kernel's tangent made perpendicular to the same plane is dP/du = +x
    // projected onto it, the same (0.8, 0, -0.6), with the kernel's sign +1. Bound: the float
    // inputs 0.6f, 0.8f and one rounding of the double result to float, a few 1e-8; 1e-6.
    for (vtkIdType p : { 3, 4, 5, 6, 7, 8 })
    {
      const mikk::CornerFrame f = PointFrame(out, p);
      EXPECT_NEAR(f.Tangent[0], 0.8, 1e-6) << "point " << p;
      EXPECT_EQ(f.Tangent[1], 0.0f) << "point " << p;
      EXPECT_NEAR(f.Tangent[2], -0.6, 1e-6) << "point " << p;
      EXPECT_EQ(f.Sign, p < 6 ? -1.0f : 1.0f) << "point " << p;
    }
  }
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, ProgressAndAbort)
{
  vtkSmartPointer<vtkPolyData> input = BigMixedTorus(64, 32).Build();
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetMethodToMikkTSpace();
  filter->SetInputData(input);
  NormalMappingTesting::ProgressRecorder recorder(filter);
  filter->Update();
  recorder.ExpectRisesToOne();
  EXPECT_GT(filter->GetOutput()->GetNumberOfPoints(), 0);

  vtkNew<vtkPolyDataTangentFrames> aborting;
  aborting->SetMethodToMikkTSpace();
  aborting->SetInputData(input);
  NormalMappingTesting::AbortAfter abort(aborting, 0.2);
  aborting->Update();
  EXPECT_EQ(aborting->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(aborting->GetOutput()->GetNumberOfCells(), 0);
}

//------------------------------------------------------------------------------
/// The filter output (MikkTSpace, bitangents and cell tangents on) for 1, 2 and 8 threads is
/// bit for bit the same, and some points are split.
static void ExpectSameForAnyThreadCount(vtkPolyData* input)
{
  struct Snapshot
  {
    std::vector<double> Points, Tangents, Signs, Bitangents, CellTangents;
    std::vector<vtkIdType> Polys, Strips;
    vtkIdType Conflicts = 0, Splits = 0;
  };
  // TBB cannot exceed the hardware concurrency: 8 threads means all cores.
  int maxThreads = 1;
  NormalMappingTesting::WithThreads(
    64, [&]() { maxThreads = vtkSMPTools::GetEstimatedNumberOfThreads(); });
  const auto snapshot = [&](int threads)
  {
    Snapshot s;
    NormalMappingTesting::WithThreads(threads,
      [&]()
      {
        EXPECT_EQ(vtkSMPTools::GetEstimatedNumberOfThreads(), std::min(threads, maxThreads));
        const FilterRun run = RunFilter(input,
          [](vtkPolyDataTangentFrames* f)
          {
            f->ComputeBitangentsOn();
            f->ComputeCellTangentsOn();
          });
        vtkPolyData* out = run.Output;
        s.Points = Values<double>(out->GetPoints()->GetData());
        s.Tangents = Values<double>(out->GetPointData()->GetArray("Tangents"));
        s.Signs = Values<double>(out->GetPointData()->GetArray("TangentSigns"));
        s.Bitangents = Values<double>(out->GetPointData()->GetArray("Bitangents"));
        s.CellTangents = Values<double>(out->GetCellData()->GetTangents());
        s.Polys = Values<vtkIdType>(out->GetPolys()->GetConnectivityArray());
        s.Strips = Values<vtkIdType>(out->GetStrips()->GetConnectivityArray());
        s.Conflicts = run.Conflicts;
        s.Splits = run.SplitPoints;
      });
    return s;
  };
  const Snapshot one = snapshot(1);
  EXPECT_GT(one.Splits, 0);
  for (int threads : { 2, 8 })
  {
    const Snapshot other = snapshot(threads);
    // SameBits also tells -0 from +0, which == does not.
    EXPECT_EQ(one.Points, other.Points) << threads << " threads";
    EXPECT_TRUE(SameBits(one.Tangents, other.Tangents)) << threads << " threads";
    EXPECT_EQ(one.Signs, other.Signs) << threads << " threads";
    EXPECT_TRUE(SameBits(one.Bitangents, other.Bitangents)) << threads << " threads";
    EXPECT_EQ(one.CellTangents, other.CellTangents) << threads << " threads";
    EXPECT_EQ(one.Polys, other.Polys) << threads << " threads";
    EXPECT_EQ(one.Strips, other.Strips) << threads << " threads";
    EXPECT_EQ(one.Conflicts, other.Conflicts);
    EXPECT_EQ(one.Splits, other.Splits);
  }
}

//------------------------------------------------------------------------------
TEST(PolyDataTangentFramesMikkTSpace, BitIdenticalForAnyThreadCount)
{
  // With and without strips: on one thread, polygon-only input takes a shorter path when
  // assigning frames to points (see Assign).
  for (const bool strips : { true, false })
  {
    SCOPED_TRACE(strips ? "with strips" : "polygons only");
    ExpectSameForAnyThreadCount(BigMixedTorus(256, 160, strips).Build());
  }
}
