// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the MikkTSpace kernel (vtkMikkTSpaceKernel.h) in triangles per second, and of
// vtkPolyDataTangentFrames with Method MIKKTSPACE on the 1M torus (BM_MikkTSpaceFilter).
//
// Meshes: tori of 65,536 and 1,048,576 triangles (quads split in two, u and v seams) and a
// 65,536-triangle latitude-longitude sphere whose 512 pole triangles are degenerate (two
// coincident corners). Each runs with 1 and 2 threads (vtkSMPTools).
//
// The "x_ref" counter is the throughput divided by the reference mikktspace.c's documented
// single-core figure on this kind of machine, 0.91 million triangles/s (0.85-0.97 M/s, see
// shared/docs/MIKKTSPACE.md; 0.56 M/s on the degenerate-pole sphere). Measured side-by-side
// ratios are in docs/mikktspace.md.

#include "MikkTSpaceKernelMesh.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkTypeInt64Array.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
namespace mikk = vtkNormalMapping::mikk;

struct BenchMesh : NormalMappingTesting::KernelMesh
{
  long long NumberOfTriangles = 0;
  double ReferenceTrianglesPerSecond = 0.91e6; // documented reference figure

  void Triangle(long long a, long long b, long long c)
  {
    this->AddFace({ a, b, c });
    ++NumberOfTriangles;
  }
};

// (nu+1) x (nv+1) grid of points (duplicated seam columns/rows), 2*nu*nv triangles.
template<typename PointFunction>
BenchMesh Grid(int nu, int nv, PointFunction point)
{
  BenchMesh m;
  for (int j = 0; j <= nv; ++j)
  {
    for (int i = 0; i <= nu; ++i)
    {
      float p[3], n[3];
      const float u = float(i) / float(nu), v = float(j) / float(nv);
      point(u, v, p, n);
      m.P.insert(m.P.end(), { p[0], p[1], p[2] });
      m.N.insert(m.N.end(), { n[0], n[1], n[2] });
      m.U.insert(m.U.end(), { u, v });
    }
  }
  const long long row = nu + 1;
  for (long long j = 0; j < nv; ++j)
  {
    for (long long i = 0; i < nu; ++i)
    {
      const long long p00 = j * row + i, p10 = p00 + 1, p01 = p00 + row, p11 = p01 + 1;
      m.Triangle(p00, p10, p11);
      m.Triangle(p00, p11, p01);
    }
  }
  return m;
}

const float kTwoPi = 6.28318531f;

BenchMesh Torus(int nu, int nv)
{
  return Grid(nu,
    nv,
    [](float u, float v, float* p, float* n)
    {
      const float a = kTwoPi * u, b = kTwoPi * v;
      const float ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
      p[0] = (2.0f + 0.7f * cb) * ca;
      p[1] = (2.0f + 0.7f * cb) * sa;
      p[2] = 0.7f * sb;
      n[0] = cb * ca;
      n[1] = cb * sa;
      n[2] = sb;
    });
}

// Latitude-longitude sphere: the pole rows are nu coincident points with different u, so
// each pole quad has one degenerate triangle (2 * nu in total).
BenchMesh Sphere(int nu, int nv)
{
  BenchMesh m = Grid(nu,
    nv,
    [](float u, float v, float* p, float* n)
    {
      const float a = kTwoPi * u, b = 3.14159265f * v;
      const float st = (v == 0.0f || v == 1.0f) ? 0.0f : std::sin(b);
      const float ct = v == 0.0f ? 1.0f : (v == 1.0f ? -1.0f : std::cos(b));
      n[0] = st * std::cos(a);
      n[1] = st * std::sin(a);
      n[2] = ct;
      p[0] = n[0];
      p[1] = n[1];
      p[2] = n[2];
    });
  m.ReferenceTrianglesPerSecond = 0.56e6; // documented reference figure for this mesh
  return m;
}

const BenchMesh& Mesh(int which)
{
  static const BenchMesh torus64k = Torus(256, 128);   // 65,536 triangles
  static const BenchMesh torus1m = Torus(1024, 512);   // 1,048,576 triangles
  static const BenchMesh sphere64k = Sphere(256, 128); // 65,536 triangles, 512 degenerate
  return which == 0 ? torus64k : (which == 1 ? torus1m : sphere64k);
}

void BM_MikkTSpace(benchmark::State& state, int which)
{
  const BenchMesh& m = Mesh(which);
  const int threads = static_cast<int>(state.range(0));
  const mikk::MeshInput in = m.Input();
  long long degenerate = 0;
  for (auto _ : state)
  {
    mikk::Result r = mikk::ComputeMikkTSpace(in, threads);
    degenerate = r.NumberOfDegenerateTriangles;
    benchmark::DoNotOptimize(r.Corners.data());
  }
  state.SetItemsProcessed(state.iterations() * m.NumberOfTriangles);
  state.counters["degenerate"] = static_cast<double>(degenerate);
  state.counters["x_ref"] =
    benchmark::Counter(static_cast<double>(m.NumberOfTriangles) / m.ReferenceTrianglesPerSecond,
      benchmark::Counter::kIsIterationInvariantRate);
}
// The same meshes through vtkPolyDataTangentFrames (Method MIKKTSPACE): kernel plus input
// conversion to float, per-point assignment/splitting and output arrays.
vtkSmartPointer<vtkPolyData> ToPolyData(const BenchMesh& m)
{
  const auto floats = [](const std::vector<float>& v, int comps, const char* name)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(static_cast<vtkIdType>(v.size()) / comps);
    std::copy(v.begin(), v.end(), a->GetPointer(0));
    return vtkSmartPointer<vtkFloatArray>(a.Get());
  };
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetData(floats(m.P, 3, "Points"));
  pd->SetPoints(points);
  pd->GetPointData()->SetNormals(floats(m.N, 3, "Normals"));
  pd->GetPointData()->SetTCoords(floats(m.U, 2, "TCoords"));
  vtkNew<vtkTypeInt64Array> offsets, conn;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(m.Offsets.size()));
  std::copy(m.Offsets.begin(), m.Offsets.end(), offsets->GetPointer(0));
  conn->SetNumberOfValues(static_cast<vtkIdType>(m.Conn.size()));
  std::copy(m.Conn.begin(), m.Conn.end(), conn->GetPointer(0));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, conn);
  pd->SetPolys(polys);
  return pd;
}

void BM_MikkTSpaceFilter(benchmark::State& state, int which)
{
  const BenchMesh& m = Mesh(which);
  const int threads = static_cast<int>(state.range(0));
  vtkSmartPointer<vtkPolyData> input = ToPolyData(m);
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetMethodToMikkTSpace();
  filter->SetInputData(input);
  // VTK 9.1's TBB backend ignores a LocalScope whose count equals the previous scope's: enter
  // one with another count first (as ComputeMikkTSpace does).
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads == 1 ? 2 : 1 },
    [&]()
    {
      vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
        [&]()
        {
          for (auto _ : state)
          {
            filter->Modified();
            filter->Update();
            benchmark::DoNotOptimize(filter->GetOutput()->GetPointData()->GetTangents());
          }
        });
    });
  state.SetItemsProcessed(state.iterations() * m.NumberOfTriangles);
  state.counters["split"] = static_cast<double>(filter->GetNumberOfSplitPoints());
  state.counters["x_ref"] =
    benchmark::Counter(static_cast<double>(m.NumberOfTriangles) / m.ReferenceTrianglesPerSecond,
      benchmark::Counter::kIsIterationInvariantRate);
}
} // namespace

BENCHMARK_CAPTURE(BM_MikkTSpace, Torus64K, 0)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MikkTSpace, Torus1M, 1)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MikkTSpace, Sphere64KDegeneratePoles, 2)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_MikkTSpaceFilter, Torus1M, 1)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

#ifndef BENCH_MIKKTSPACE_NO_MAIN
BENCHMARK_MAIN();
#endif
