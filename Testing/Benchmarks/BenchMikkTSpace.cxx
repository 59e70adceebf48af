// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the MikkTSpace kernel (vtkMikkTSpaceKernel.h) in triangles per second on three
// meshes made by others, and of vtkPolyDataTangentFrames with Method MIKKTSPACE on the torus
// (BM_MikkTSpaceFilter):
//  - Sphere: vtkTexturedSphereSource, 1024 x 512 (theta x phi resolution);
//  - Torus: vtkParametricTorus through vtkParametricFunctionSource, 1024 x 512 with texture
//    coordinates, through vtkTriangleFilter;
//  - FlightHelmet: the largest model of shared/data/gltf-external, all its primitives in one
//    mesh, texture coordinates as stored (skipped when the shared data is absent).
// Each runs with 1 and 2 threads (vtkSMPTools).
//
// The "x_ref" counter is the throughput divided by the reference mikktspace.c's single-thread
// throughput on the same mesh (thread CPU time), measured side by side on the machine described
// in docs/mikktspace.md (the reference itself is not part of this repository).

#include "MikkTSpaceKernelMesh.h"
#include "NormalMappingReferenceData.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkGLTFDocumentLoader.h>
#include <vtkNew.h>
#include <vtkParametricFunctionSource.h>
#include <vtkParametricTorus.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkTexturedSphereSource.h>
#include <vtkTriangleFilter.h>

#include <benchmark/benchmark.h>

#include <string>

namespace
{
namespace mikk = vtkNormalMapping::mikk;

struct BenchMesh : NormalMappingTesting::KernelMesh
{
  vtkSmartPointer<vtkPolyData> PolyData; // the source's output (all primitives appended)
  long long NumberOfTriangles = 0;
  double ReferenceTrianglesPerSecond = 0; // mikktspace.c on this mesh (docs/mikktspace.md)
};

// Appends the polygons of pd (with point normals and texture coordinates) to m, as floats.
void Append(BenchMesh& m, vtkPolyData* pd, vtkDataArray* normals, vtkDataArray* tcoords)
{
  const long long base = static_cast<long long>(m.P.size() / 3);
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3], n[3];
    pd->GetPoint(i, p);
    normals->GetTuple(i, n);
    m.AddPoint({ float(p[0]), float(p[1]), float(p[2]) },
      { float(n[0]), float(n[1]), float(n[2]) },
      { float(tcoords->GetComponent(i, 0)), float(tcoords->GetComponent(i, 1)) });
  }
  vtkIdType npts;
  const vtkIdType* ids;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    for (vtkIdType k = 0; k < npts; ++k)
    {
      m.Conn.push_back(base + ids[k]);
    }
    m.Offsets.push_back(static_cast<long long>(m.Conn.size()));
    m.NumberOfTriangles += npts - 2;
  }
}

BenchMesh FromPolyData(vtkPolyData* pd, double referenceTrianglesPerSecond)
{
  BenchMesh m;
  m.PolyData = pd;
  m.ReferenceTrianglesPerSecond = referenceTrianglesPerSecond;
  Append(m, pd, pd->GetPointData()->GetNormals(), pd->GetPointData()->GetTCoords());
  return m;
}

BenchMesh Sphere()
{
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(1024);
  sphere->SetPhiResolution(512);
  sphere->Update();
  return FromPolyData(sphere->GetOutput(), 0.36e6);
}

BenchMesh Torus()
{
  vtkNew<vtkParametricTorus> torus;
  vtkNew<vtkParametricFunctionSource> source;
  source->SetParametricFunction(torus);
  source->SetUResolution(1024);
  source->SetVResolution(512);
  source->GenerateTextureCoordinatesOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(source->GetOutputPort());
  triangles->Update();
  return FromPolyData(triangles->GetOutput(), 0.74e6);
}

// Every primitive of FlightHelmet.gltf appended; empty when the shared data is absent. The
// geometry comes from vtkGLTFDocumentLoader: the copy in the shared data has no texture images,
// on which vtkGLTFReader fails (the loader reports them and builds the geometry anyway).
BenchMesh Helmet()
{
  BenchMesh m;
  m.ReferenceTrianglesPerSecond = 0.80e6;
  const std::string dir = NormalMappingTestData::FindSharedData(nullptr);
  if (dir.empty())
  {
    return m;
  }
  vtkNew<vtkGLTFDocumentLoader> loader;
  const bool warnings = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  const bool read =
    loader->LoadModelMetaDataFromFile(dir + "/gltf-external/FlightHelmet/FlightHelmet.gltf");
  if (read)
  {
    loader->LoadModelData({});
    loader->BuildModelVTKGeometry();
  }
  vtkObject::SetGlobalWarningDisplay(warnings);
  if (!read)
  {
    return m;
  }
  for (const auto& mesh : loader->GetInternalModel()->Meshes)
  {
    for (const auto& primitive : mesh.Primitives)
    {
      vtkPolyData* pd = primitive.Geometry;
      vtkPointData* attributes = pd ? pd->GetPointData() : nullptr;
      if (attributes && attributes->GetArray("NORMAL") && attributes->GetArray("TEXCOORD_0"))
      {
        Append(m, pd, attributes->GetArray("NORMAL"), attributes->GetArray("TEXCOORD_0"));
      }
    }
  }
  return m;
}

const BenchMesh& Mesh(int which)
{
  static const BenchMesh sphere = Sphere();
  static const BenchMesh torus = Torus();
  static const BenchMesh helmet = Helmet();
  return which == 0 ? sphere : (which == 1 ? torus : helmet);
}

void BM_MikkTSpace(benchmark::State& state, int which)
{
  const BenchMesh& m = Mesh(which);
  if (m.NumberOfTriangles == 0)
  {
    state.SkipWithError("shared test data not found");
    return;
  }
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

// The torus through vtkPolyDataTangentFrames (Method MIKKTSPACE): kernel plus input conversion,
// per-point assignment/splitting and output arrays.
void BM_MikkTSpaceFilter(benchmark::State& state, int which)
{
  const BenchMesh& m = Mesh(which);
  const int threads = static_cast<int>(state.range(0));
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetMethodToMikkTSpace();
  filter->SetInputData(m.PolyData);
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

BENCHMARK_CAPTURE(BM_MikkTSpace, Sphere, 0)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MikkTSpace, Torus, 1)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_MikkTSpace, FlightHelmet, 2)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_MikkTSpaceFilter, Torus, 1)
  ->Arg(1)
  ->Arg(2)
  ->ArgName("threads")
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

#ifndef BENCH_MIKKTSPACE_NO_MAIN
BENCHMARK_MAIN();
#endif
