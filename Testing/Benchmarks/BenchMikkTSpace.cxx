// SPDX-License-Identifier: BSD-3-Clause
// The MikkTSpace kernel (vtkMikkTSpaceKernel.h) and vtkPolyDataTangentFrames with Method
// MIKKTSPACE against the original mikktspace.c, in one process, on the meshes of the paired runs
// (Bench::PairingMeshes): vtkTexturedSphereSource 1024 x 512, vtkParametricTorus 1024 x 512
// through vtkTriangleFilter, and the largest glTF model of shared/data/gltf-external.
//
//   BenchMikkTSpace [--out DIR] [--smoke] [--rounds N]
//   BenchMikkTSpace --throughput [google benchmark flags]
//
// Paired runs (the default): the original's genTangSpaceDefault, the kernel (ComputeMikkTSpace,
// one thread) and the filter (one thread) run in turn on the same input, N rounds (11; --smoke: 1,
// on 64 x 32 meshes) after one warm-up run each, the first of a round rotating
// (Bench::RunRounds). Per mesh: the median and quartiles of the original's time / ours, the ratio
// of the fastest runs, and the face corners whose kernel frame differs from the original's.
// Then the original and the kernel on 100,000 small random meshes (1,000 with --smoke), face
// corner by face corner (RandomMeshes). Last, the paired runs again with glibc keeping freed
// memory, which shows what the page faults cost (ComparePairedKeepingMemory).
// Printed, and written to DIR/mikktspace.md (a section of docs/benchmarks.md) with --out;
// scripts/bench.sh runs it. The original is compiled in only when the CMake variable
// NORMALMAPPING_MIKKTSPACE_REFERENCE_DIR names its source (it is not part of this repository);
// otherwise the program and the section say that the comparison was not run and how to run it.
//
// --throughput: the kernel's and the filter's throughput alone, with 1 and 2 threads (Google
// Benchmark), on the same meshes; it does not need the original.
#include "BenchPaired.h"
#include "MikkTSpaceKernelMesh.h"
#include "NormalMappingThreads.h"
#include "vtkMikkTSpaceKernel.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <benchmark/benchmark.h>

#ifdef NORMALMAPPING_MIKKTSPACE_REFERENCE
#include "mikktspace.h"
#endif
#if defined(__GLIBC__)
#include <malloc.h> // mallopt
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace mikk = vtkNormalMapping::mikk;

/// The polygons of pd with its point normals and texture coordinates, as floats, in the kernel's
/// input layout.
NormalMappingTesting::KernelMesh ToKernelMesh(vtkPolyData* pd)
{
  NormalMappingTesting::KernelMesh m;
  vtkDataArray* normals = pd->GetPointData()->GetNormals();
  vtkDataArray* tcoords = pd->GetPointData()->GetTCoords();
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
    m.Conn.insert(m.Conn.end(), ids, ids + npts);
    m.Offsets.push_back(static_cast<long long>(m.Conn.size()));
  }
  return m;
}

/// Wall-clock seconds that f() takes.
template<typename F>
double Seconds(F&& f)
{
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The section's heading, which the smoke test looks for.
const char* const Heading = "## MikkTSpace against the original `mikktspace.c`";

#ifdef NORMALMAPPING_MIKKTSPACE_REFERENCE
/// The original's genTangSpaceDefault on a kernel input: its frames land in Corners, one per face
/// corner in the kernel's layout, so that the two compare corner by corner.
class Reference
{
public:
  explicit Reference(const mikk::MeshInput& in)
    : In(in)
    , Corners(static_cast<size_t>(in.FaceOffsets[in.NumberOfFaces]), mikk::DefaultCornerFrame)
  {
  }

  bool Run()
  {
    SMikkTSpaceInterface callbacks{};
    callbacks.m_getNumFaces = [](const SMikkTSpaceContext* c)
    { return static_cast<int>(Of(c).In.NumberOfFaces); };
    callbacks.m_getNumVerticesOfFace = [](const SMikkTSpaceContext* c, int face)
    { return static_cast<int>(Of(c).In.FaceOffsets[face + 1] - Of(c).In.FaceOffsets[face]); };
    callbacks.m_getPosition = [](const SMikkTSpaceContext* c, float out[], int face, int vert)
    { Of(c).Copy(Of(c).In.Positions, 3, out, face, vert); };
    callbacks.m_getNormal = [](const SMikkTSpaceContext* c, float out[], int face, int vert)
    { Of(c).Copy(Of(c).In.Normals, 3, out, face, vert); };
    callbacks.m_getTexCoord = [](const SMikkTSpaceContext* c, float out[], int face, int vert)
    { Of(c).Copy(Of(c).In.TCoords, 2, out, face, vert); };
    callbacks.m_setTSpaceBasic =
      [](const SMikkTSpaceContext* c, const float t[], float sign, int face, int vert)
    {
      Reference& self = *static_cast<Reference*>(c->m_pUserData);
      self.Corners[static_cast<size_t>(self.In.FaceOffsets[face] + vert)] = { { t[0], t[1], t[2] },
        sign };
    };
    SMikkTSpaceContext context{ &callbacks, this };
    return genTangSpaceDefault(&context) != 0;
  }

  const mikk::MeshInput& In;
  std::vector<mikk::CornerFrame> Corners;

private:
  static const Reference& Of(const SMikkTSpaceContext* c)
  {
    return *static_cast<const Reference*>(c->m_pUserData);
  }
  void Copy(const float* values, int size, float out[], int face, int vert) const
  {
    const long long point = this->In.FaceConnectivity[this->In.FaceOffsets[face] + vert];
    std::memcpy(out, values + size * point, sizeof(float) * static_cast<size_t>(size));
  }
};

/// One mesh's paired runs and corner comparison.
struct Comparison
{
  std::string Name;
  long long Triangles = 0;
  Bench::Paired Kernel; // the original's time / the kernel's
  Bench::Paired Filter; // the original's time / the filter's
  long long Corners = 0;
  long long DifferingBits = 0;   // corners whose frame differs in any bit
  long long DifferingValues = 0; // of those, corners whose frame differs in value (-0 == +0)
  bool Ok = false;
};

Comparison Compare(const Bench::PairingMesh& mesh, int rounds)
{
  Comparison result;
  result.Name = mesh.Name;
  const NormalMappingTesting::KernelMesh kernelMesh = ToKernelMesh(mesh.Mesh);
  const mikk::MeshInput in = kernelMesh.Input();
  Reference reference(in);
  mikk::Result kernel;
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetMethodToMikkTSpace();
  filter->SetInputData(mesh.Mesh);
  bool referenceOk = true;
  Bench::Rounds seconds;
  // One thread for the whole measurement: the kernel and the filter run with the scope's thread
  // count, so that neither time includes entering a thread scope (VTK's TBB backend makes a task
  // arena for each).
  NormalMappingTesting::WithThreads(1,
    [&]()
    {
      seconds = Bench::RunRounds(
        { [&]() { return Seconds([&]() { referenceOk = reference.Run() && referenceOk; }); },
          [&]()
          {
            mikk::Result r;
            const double s = Seconds([&]() { r = mikk::ComputeMikkTSpace(in); });
            kernel = std::move(r);
            return s;
          },
          [&]() { return Bench::TimedUpdate(filter); } },
        rounds);
    });
  result.Kernel = Bench::PairedRatios(seconds, 0, 1);
  result.Filter = Bench::PairedRatios(seconds, 0, 2);
  for (long long f = 0; f < in.NumberOfFaces; ++f)
  {
    result.Triangles += in.FaceOffsets[f + 1] - in.FaceOffsets[f] - 2;
  }
  result.Corners = static_cast<long long>(reference.Corners.size());
  for (size_t i = 0; i < reference.Corners.size() && i < kernel.Corners.size(); ++i)
  {
    const mikk::CornerFrame& a = reference.Corners[i];
    const mikk::CornerFrame& b = kernel.Corners[i];
    if (std::memcmp(&a, &b, sizeof(a)) != 0)
    {
      ++result.DifferingBits;
      const bool equal = a.Tangent[0] == b.Tangent[0] && a.Tangent[1] == b.Tangent[1] &&
        a.Tangent[2] == b.Tangent[2] && a.Sign == b.Sign;
      result.DifferingValues += equal ? 0 : 1;
    }
  }
  result.Ok = referenceOk && kernel.Corners.size() == reference.Corners.size() &&
    filter->GetOutput()->GetPointData()->GetTangents() != nullptr;
  return result;
}

/**
 * Small random meshes, for the corner by corner comparison: 4 to 12 points on a small integer
 * grid (mostly flat, some lifted by one), normals of a few directions, texture coordinates on a
 * half-integer grid, and 1 to 12 triangles or quads on random points (a point may repeat within a
 * face); one mesh in eight crowds 48 to 80 faces onto 4 to 6 points. So they hold what large meshes
 * rarely do: folds, mirrored and zero UV areas, non-manifold and repeated edges, degenerate
 * triangles and quads. Each ends with an isolated triangle on points of its own: the original
 * leaves the edges of the largest welded index unsorted (docs/mikktspace.md), and that triangle's
 * edges are then the only ones there.
 */
class RandomMeshes
{
public:
  NormalMappingTesting::KernelMesh Next()
  {
    NormalMappingTesting::KernelMesh m;
    // One mesh in eight crowds many faces onto few points, so that some vertex has a fan of
    // more than 32 corners: the kernel pairs the edges of such fans through a sorted index
    // instead of a scan.
    const bool crowded = this->Uniform(0, 7) == 0;
    const int numPoints = crowded ? this->Uniform(4, 6) : this->Uniform(4, 12);
    for (int p = 0; p < numPoints; ++p)
    {
      const bool lifted = this->Uniform(0, 2) == 0;
      const std::array<float, 3> position = { float(this->Uniform(-2, 2)),
        float(this->Uniform(-2, 2)),
        lifted ? float(this->Uniform(-1, 1)) : 0.0f };
      std::array<float, 3> normal = { this->Uniform(0, 3) == 0 ? float(this->Uniform(-1, 1)) : 0.0f,
        this->Uniform(0, 3) == 0 ? float(this->Uniform(-1, 1)) : 0.0f,
        1.0f };
      const float length =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      for (float& c : normal)
      {
        c /= length;
      }
      m.AddPoint(position,
        normal,
        { 0.5f * float(this->Uniform(-3, 3)), 0.5f * float(this->Uniform(-3, 3)) });
    }
    const int numFaces = crowded ? this->Uniform(48, 80) : this->Uniform(1, 12);
    for (int f = 0; f < numFaces; ++f)
    {
      const int corners = this->Uniform(0, 2) == 0 ? 3 : 4;
      for (int k = 0; k < corners; ++k)
      {
        m.Conn.push_back(this->Uniform(0, numPoints - 1));
      }
      m.Offsets.push_back(static_cast<long long>(m.Conn.size()));
    }
    const long long a = m.AddPoint({ 10, 0, 0 }, { 0, 0, 1 }, { 10, 0 });
    const long long b = m.AddPoint({ 11, 0, 0 }, { 0, 0, 1 }, { 11, 0 });
    const long long c = m.AddPoint({ 10, 1, 0 }, { 0, 0, 1 }, { 10, 1 });
    m.AddFace({ a, b, c });
    return m;
  }

private:
  /// An integer in [lo, hi], the same sequence with every standard library.
  int Uniform(int lo, int hi)
  {
    return lo + static_cast<int>(this->Engine() % static_cast<unsigned>(hi - lo + 1));
  }
  std::mt19937 Engine{ 1 };
};

/// The original and the kernel (with the calling scope's threads) on `count` random meshes
/// (RandomMeshes), corner by corner; the section's paragraph in `md`. False when the original
/// failed on one.
bool CompareRandomMeshes(long long count, std::ostringstream& md)
{
  RandomMeshes meshes;
  long long corners = 0, differing = 0, meshesDiffering = 0;
  bool ok = true;
  for (long long i = 0; i < count; ++i)
  {
    const NormalMappingTesting::KernelMesh mesh = meshes.Next();
    const mikk::MeshInput in = mesh.Input();
    Reference reference(in);
    ok = reference.Run() && ok;
    const mikk::Result kernel = mikk::ComputeMikkTSpace(in);
    long long here = 0;
    for (size_t c = 0; c < reference.Corners.size(); ++c)
    {
      here +=
        std::memcmp(&reference.Corners[c], &kernel.Corners[c], sizeof(mikk::CornerFrame)) ? 1 : 0;
    }
    corners += static_cast<long long>(reference.Corners.size());
    differing += here;
    meshesDiffering += here > 0 ? 1 : 0;
  }
  std::cout << "random small meshes: " << count << " meshes, " << corners << " face corners, "
            << differing << " differing from mikktspace.c in " << meshesDiffering << " meshes"
            << (ok ? "" : " (A RUN FAILED)") << std::endl;
  md
    << "Random small meshes (4 to 12 points on a small grid, 1 to 12 triangles and quads on them, "
       "or one mesh in eight 48 to 80 on 4 to 6 points, so that fans of more than 32 corners "
       "occur; with folds, mirrored and zero UV areas, non-manifold and repeated edges, degenerate "
       "faces; see `RandomMeshes` in `Testing/Benchmarks/BenchMikkTSpace.cxx`): "
    << Bench::Count(count) << " meshes, " << Bench::Count(corners) << " face corners, of which "
    << Bench::Count(differing) << " differ from the original's in any bit (in "
    << Bench::Count(meshesDiffering) << " meshes).\n";
  return ok;
}

/// Compare() on every mesh of the paired runs, each printed; `note` says why a mesh is missing.
std::vector<Comparison> CompareMeshes(bool smoke, int rounds, std::string& note)
{
  std::vector<Comparison> comparisons;
  for (const Bench::PairingMesh& mesh : Bench::PairingMeshes(smoke, note))
  {
    comparisons.push_back(Compare(mesh, rounds));
    const Comparison& c = comparisons.back();
    std::cout << c.Name << " (" << c.Triangles << " triangles): mikktspace.c "
              << Bench::Format(c.Kernel.MedianMilliseconds(0)) << " ms, kernel "
              << Bench::Format(c.Kernel.MedianMilliseconds(1)) << " ms, x mikktspace.c "
              << c.Kernel.Cells() << "; filter " << Bench::Format(c.Filter.MedianMilliseconds(1))
              << " ms, x mikktspace.c " << c.Filter.Cells() << "; corners differing from "
              << "mikktspace.c: " << c.DifferingBits << " in bits, " << c.DifferingValues
              << " in value, of " << c.Corners << "; page faults per run: mikktspace.c "
              << c.Kernel.MedianFaults(0) << ", kernel " << c.Kernel.MedianFaults(1) << ", filter "
              << c.Filter.MedianFaults(1) << (c.Ok ? "" : " (A RUN FAILED)") << std::endl;
  }
  if (!note.empty())
  {
    std::cout << note << std::endl;
  }
  return comparisons;
}

/// The comparisons' table of times, ratios and differing corners, then their page faults; false
/// when a run failed.
bool WriteComparisons(const std::vector<Comparison>& comparisons, std::ostringstream& md)
{
  md << "| mesh | triangles | `mikktspace.c` | kernel | kernel x `mikktspace.c`: median "
        "[quartiles] | fastest runs | filter | filter x `mikktspace.c`: median [quartiles] | "
        "fastest runs | differing corners: bits / value / all |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  bool ok = true;
  for (const Comparison& c : comparisons)
  {
    md << "| " << c.Name << " | " << Bench::Count(c.Triangles) << " | "
       << Bench::Format(c.Kernel.MedianMilliseconds(0)) << " ms | "
       << Bench::Format(c.Kernel.MedianMilliseconds(1)) << " ms | " << c.Kernel.Cells() << " | "
       << Bench::Format(c.Filter.MedianMilliseconds(1)) << " ms | " << c.Filter.Cells() << " | "
       << Bench::Count(c.DifferingBits) << " / " << Bench::Count(c.DifferingValues) << " / "
       << Bench::Count(c.Corners) << " |\n";
    ok = ok && c.Ok;
  }
  md << "\n"
     << Bench::PageFaultText << "\n\n"
     << "| mesh | `mikktspace.c` | kernel | filter |\n"
     << "|---|---:|---:|---:|\n";
  for (const Comparison& c : comparisons)
  {
    md << "| " << c.Name << " | " << Bench::FaultCount(c.Kernel.MedianFaults(0)) << " | "
       << Bench::FaultCount(c.Kernel.MedianFaults(1)) << " | "
       << Bench::FaultCount(c.Filter.MedianFaults(1)) << " |\n";
  }
  return ok;
}

/// The paired runs on every mesh; the section's text in `md`. False when a run failed.
bool ComparePaired(bool smoke, int rounds, std::ostringstream& md)
{
  std::string note;
  const std::vector<Comparison> comparisons = CompareMeshes(smoke, rounds, note);
  md << "The original `genTangSpaceDefault` (https://github.com/mmikk/MikkTSpace, compiled as C: "
    // The compiler, build type and flags, as CMake gave them.
    NORMALMAPPING_MIKKTSPACE_REFERENCE_BUILD
        "), our kernel (`vtkNormalMapping::mikk::ComputeMikkTSpace`, one thread) and "
        "`vtkPolyDataTangentFrames` with `SetMethodToMikkTSpace()` (one thread: the kernel, "
        "plus reading the polydata, writing and splitting points) on the meshes of the paired "
        "runs above, the same input for all three (points, normals and texture coordinates as "
        "floats). The three run in turn, "
     << rounds << " round" << (rounds > 1 ? "s" : "")
     << " after one warm-up run each, the first of a round rotating (wall-clock time, the "
        "original's output and ours reused). Times: medians. Each ratio: the median over the "
        "rounds of `mikktspace.c`'s time / ours (above 1: faster than the original), with the "
        "first and third quartiles, and the ratio of the fastest runs. Differing corners: face "
        "corners whose kernel frame (tangent and sign) differs from the original's in any bit, "
        "then in value (where -0 equals +0), of all face corners.\n\n";
  const bool ok = WriteComparisons(comparisons, md);
  if (!note.empty())
  {
    md << "\n" << note << "\n";
  }
  return ok;
}

/**
 * The paired runs again with glibc keeping the memory the process frees (no mmap of large
 * blocks, no trimming of the heap), so that no run faults in pages an earlier one gave back:
 * how much of the times above the page faults are. Changes the allocator for the rest of the
 * process, so it runs last. Without glibc: a note.
 */
bool ComparePairedKeepingMemory(bool smoke, int rounds, std::ostringstream& md)
{
  md << "### The same with glibc keeping freed memory\n\n";
#if defined(__GLIBC__)
  if (mallopt(M_MMAP_MAX, 0) == 0 || mallopt(M_TRIM_THRESHOLD, INT_MAX) == 0)
  {
    md << "Not run: glibc refused the settings.\n";
    return true;
  }
  std::string note;
  const std::vector<Comparison> comparisons = CompareMeshes(smoke, rounds, note);
  md << "The paired runs above, repeated in the same process after `mallopt(M_MMAP_MAX, 0)` "
        "and `mallopt(M_TRIM_THRESHOLD, INT_MAX)`: glibc then serves every block from its heap "
        "and never gives freed memory back to the system, so that a run reuses the pages an "
        "earlier one touched instead of faulting in new ones. The difference from the times "
        "above is what the page faults cost. A program gets the same from the environment "
        "(`GLIBC_TUNABLES=glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=<bytes>`), at the "
        "cost of keeping its largest footprint.\n\n";
  return WriteComparisons(comparisons, md);
#else
  (void)smoke;
  (void)rounds;
  md << "Not run: the C library is not glibc.\n";
  return true;
#endif
}
#endif

/// The paired runs against the original when it is compiled in; otherwise a note that says why
/// they were not run and how to run them. Prints the results, and writes the section to
/// out/mikktspace.md when `out` is not empty.
int RunPaired(const std::string& out, bool smoke, int rounds)
{
  std::ostringstream md;
  md << Heading << "\n\n";
  bool ok = true;
#ifdef NORMALMAPPING_MIKKTSPACE_REFERENCE
  ok = ComparePaired(smoke, rounds, md);
  md << "\n";
  NormalMappingTesting::WithThreads(
    1, [&]() { ok = CompareRandomMeshes(smoke ? 1000 : 100000, md) && ok; });
  md << "\n";
  ok = ComparePairedKeepingMemory(smoke, rounds, md) && ok;
#else
  (void)smoke;
  (void)rounds;
  const std::string why =
    "Not run: the comparison needs the original's source, which is not part of this "
    "repository: `git clone https://github.com/mmikk/MikkTSpace`, then give its folder to CMake "
    "(`-DNORMALMAPPING_MIKKTSPACE_REFERENCE_DIR=<folder>`, or "
    "`MIKKTSPACE_REFERENCE_DIR=<folder> bash scripts/bootstrap.sh bench`).";
  std::cout << why << std::endl;
  md << why << "\n";
#endif
  md << "\n";
  if (!out.empty() && !Bench::WriteText(out + "/mikktspace.md", md.str()))
  {
    return 1;
  }
  if (!ok)
  {
    std::cerr << "a run failed: see above" << std::endl;
  }
  return ok ? 0 : 1;
}

/// The kernel's and the filter's throughput (Google Benchmark), 1 and 2 threads.
int RunThroughput(int argc, char** argv)
{
  std::string note;
  const std::vector<Bench::PairingMesh> meshes = Bench::PairingMeshes(false, note);
  std::vector<NormalMappingTesting::KernelMesh> kernelMeshes;
  for (const Bench::PairingMesh& mesh : meshes)
  {
    kernelMeshes.push_back(ToKernelMesh(mesh.Mesh));
  }
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    const vtkIdType triangles = meshes[i].Mesh->GetNumberOfPolys();
    benchmark::RegisterBenchmark(("MikkTSpaceKernel/" + meshes[i].Name).c_str(),
      [&, i, triangles](benchmark::State& state)
      {
        const mikk::MeshInput in = kernelMeshes[i].Input();
        long long degenerate = 0;
        NormalMappingTesting::WithThreads(static_cast<int>(state.range(0)),
          [&]()
          {
            for (auto _ : state)
            {
              mikk::Result r = mikk::ComputeMikkTSpace(in);
              degenerate = r.NumberOfDegenerateTriangles;
              benchmark::DoNotOptimize(r.Corners.data());
            }
          });
        state.SetItemsProcessed(state.iterations() * triangles);
        state.counters["degenerate"] = static_cast<double>(degenerate);
      })
      ->Arg(1)
      ->Arg(2)
      ->ArgName("threads")
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("MikkTSpaceFilter/" + meshes[i].Name).c_str(),
      [&, i, triangles](benchmark::State& state)
      {
        vtkNew<vtkPolyDataTangentFrames> filter;
        filter->SetMethodToMikkTSpace();
        filter->SetInputData(meshes[i].Mesh);
        NormalMappingTesting::WithThreads(static_cast<int>(state.range(0)),
          [&]()
          {
            for (auto _ : state)
            {
              filter->Modified();
              filter->Update();
              benchmark::DoNotOptimize(filter->GetOutput()->GetPointData()->GetTangents());
            }
          });
        state.SetItemsProcessed(state.iterations() * triangles);
        state.counters["split"] = static_cast<double>(filter->GetNumberOfSplitPoints());
      })
      ->Arg(1)
      ->Arg(2)
      ->ArgName("threads")
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (!note.empty())
  {
    std::cout << note << std::endl;
  }
  return 0;
}
}

int main(int argc, char** argv)
{
  std::string out;
  bool smoke = false;
  int rounds = 11;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--throughput")
    {
      argv[i] = argv[0];
      return RunThroughput(argc - i, argv + i);
    }
    if (arg == "--out" && i + 1 < argc)
    {
      out = argv[++i];
    }
    else if (arg == "--smoke")
    {
      smoke = true;
      rounds = 1;
    }
    else if (arg == "--rounds" && i + 1 < argc)
    {
      rounds = std::max(1, std::atoi(argv[++i]));
    }
    else
    {
      std::cerr << "usage: " << argv[0] << " [--out DIR] [--smoke] [--rounds N]\n       " << argv[0]
                << " --throughput [google benchmark flags]" << std::endl;
      return 2;
    }
  }
  return RunPaired(out, smoke, rounds);
}
