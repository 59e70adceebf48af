// SPDX-License-Identifier: BSD-3-Clause
// Filter throughput and peak memory, in one process on the same meshes: vtkPolyDataTangentFrames
// with every method, VTK's vtkPolyDataTangents, and a floor (a pass that reads the filters'
// inputs and writes vtkPolyDataTangentFrames' outputs once, with no tangent math: what memory
// bandwidth allows); float and double input, 1 and 2 threads, generated tori (plain u and v
// seams) of 10 thousand to 4 million triangles. Every throughput is also given as a ratio to
// VTK's filter and to the floor, run with the same input, precision and thread count.
//
//   BenchTangentFrames [--out DIR] [--smoke] [--sizes N,N,...] [--repetitions N]
//                      [--paired-only PAIRS] [--build-variant] [google benchmark flags]
//   BenchTangentFrames --first-update MESH vtk|default THREADS [--smoke]
//
// Writes DIR/filter.md (the markdown section of docs/benchmarks.md) and DIR/filter.tsv (one
// tab-separated line per configuration, read by BenchChart). --smoke: one 10,000-triangle size, one
// short repetition (for the ctest smoke test). --paired-only PAIRS: only the paired runs, with
// PAIRS pairs each, printed to the console (a quick check while changing the filter).
// --build-variant: only the default method paired with VTK's filter, one thread, as one row of
// DIR/variants.md (written with its section header when it does not exist yet), which describes
// this program's build: its compiler and whether the module's loops are multiversioned.
// scripts/bench.sh runs it, also from builds of other kinds. --first-update: one Update of a new
// filter on pairing mesh MESH (0, 1, 2) in this process, its seconds and page faults printed
// (MeasureFirstUpdates starts this program again in this mode for each run).
//
// Timing: Google Benchmark, wall-clock time, repetitions randomly interleaved across all
// configurations (so a burst of load from other processes does not hit one configuration's
// repetitions only); the median of the repetitions is reported, and its spread.
// Paired runs (MeasurePaired): the default method (AngleWeighted) and VTK's filter updated
// alternately on three meshes that are not ours: vtkTexturedSphereSource and vtkParametricTorus
// (through vtkParametricFunctionSource and vtkTriangleFilter) at 1024 x 512, and the largest glTF
// model of ../shared/data/gltf-external (skipped with a note when the data is absent); 1 and 2
// threads, the median and quartiles of the per-pair ratios; on the same meshes, one thread, the
// default method with Splitting against without; and every method against VTK's filter on the
// million-triangle torus, one thread. Scaling (MeasureScaling): each filter
// alone, updated alternately with one and with two threads, on the million-triangle torus; VTK's
// filter and the default method also on every other size. First updates (MeasureFirstUpdates):
// the default method and VTK's filter each updated once in a new process, alternately.
// Peak memory: see BenchMemory.h; one Update per configuration, after the timing.
#include "BenchCommon.h"
#include "BenchMemory.h"
#include "BenchPaired.h"
#include "NormalMappingShuffle.h"
#include "NormalMappingThreads.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkNormalMappingPrivate.h" // MultiversionedLoops

#include "vtkAOSDataArrayTemplate.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkVersionMacros.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Bench::Paired;
using Bench::PairingMesh;
using Bench::PairingMeshes;
using Bench::TimedUpdate;

/**
 * The floor: one pass over the points that reads their coordinates, normals and texture
 * coordinates and writes `Tangents` (3 components) and `TangentSigns` in the points' precision
 * (what vtkPolyDataTangentFrames writes by default), and one pass that reads every triangle's
 * point ids; both on vtkSMPTools threads, in memory order. No tangent is computed: this is the
 * memory traffic every tangent filter needs at least, plus allocating its outputs.
 */
class FloorPass : public vtkPolyDataAlgorithm
{
public:
  static FloorPass* New() { VTK_STANDARD_NEW_BODY(FloorPass); }
  vtkTypeMacro(FloorPass, vtkPolyDataAlgorithm);
  long long Checksum = 0; // the sum of the point ids read, so that the reads are not removed

protected:
  int RequestData(vtkInformation*,
    vtkInformationVector** inputs,
    vtkInformationVector* outputs) override
  {
    vtkPolyData* input = vtkPolyData::GetData(inputs[0]);
    vtkPolyData* output = vtkPolyData::GetData(outputs);
    output->CopyStructure(input);
    output->GetPointData()->PassData(input->GetPointData());
    if (!input->GetPoints())
    {
      return 1;
    }
    const bool ok = input->GetPoints()->GetDataType() == VTK_DOUBLE
      ? this->Pass<double>(input, output)
      : this->Pass<float>(input, output);
    if (!ok)
    {
      vtkErrorMacro("the floor pass needs points, normals and texture coordinates of one type");
    }
    return ok ? 1 : 0;
  }

private:
  template<typename T>
  bool Pass(vtkPolyData* input, vtkPolyData* output)
  {
    using Array = vtkAOSDataArrayTemplate<T>;
    auto* points = Array::FastDownCast(input->GetPoints()->GetData());
    auto* normals = Array::FastDownCast(input->GetPointData()->GetNormals());
    auto* tcoords = Array::FastDownCast(input->GetPointData()->GetTCoords());
    if (!points || !normals || !tcoords || tcoords->GetNumberOfComponents() != 2)
    {
      return false;
    }
    const vtkIdType numPoints = input->GetNumberOfPoints();
    vtkNew<Array> tangents, signs;
    tangents->SetName("Tangents");
    tangents->SetNumberOfComponents(3);
    tangents->SetNumberOfTuples(numPoints);
    signs->SetName("TangentSigns");
    signs->SetNumberOfTuples(numPoints);
    const T* p = points->GetPointer(0);
    const T* n = normals->GetPointer(0);
    const T* uv = tcoords->GetPointer(0);
    T* t = tangents->GetPointer(0);
    T* s = signs->GetPointer(0);
    vtkSMPTools::For(0,
      numPoints,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          for (int k = 0; k < 3; ++k)
          {
            t[3 * i + k] = n[3 * i + k] + p[3 * i + k] * uv[2 * i];
          }
          s[i] = uv[2 * i + 1] < 0 ? T(-1) : T(1);
        }
      });
    vtkCellArray* polys = input->GetPolys();
    this->Checksum = polys->IsStorage64Bit()
      ? SumIds(polys->GetConnectivityArray64()->GetPointer(0), polys->GetNumberOfConnectivityIds())
      : SumIds(polys->GetConnectivityArray32()->GetPointer(0), polys->GetNumberOfConnectivityIds());
    output->GetPointData()->SetTangents(tangents);
    output->GetPointData()->AddArray(signs);
    return true;
  }

  template<typename Id>
  static long long SumIds(const Id* ids, vtkIdType count)
  {
    vtkSMPThreadLocal<long long> sums(0);
    vtkSMPTools::For(0,
      count,
      [&](vtkIdType begin, vtkIdType end)
      {
        long long& sum = sums.Local();
        for (vtkIdType i = begin; i < end; ++i)
        {
          sum += ids[i];
        }
      });
    long long total = 0;
    for (long long s : sums)
    {
      total += s;
    }
    return total;
  }
};

/// What is timed: one of the tangent filters, or the floor.
struct Subject
{
  std::string Name;
  int Method = Bench::TangentFilter::VTKFilter;
  bool Floor = false;
};

std::vector<Subject> Subjects()
{
  std::vector<Subject> subjects;
  for (const Bench::TangentFilter& f : Bench::TangentFilters())
  {
    subjects.push_back({ f.Name, f.Method, false });
  }
  subjects.push_back({ "floor", Bench::TangentFilter::VTKFilter, true });
  return subjects;
}

vtkSmartPointer<vtkPolyDataAlgorithm> MakeSubject(const Subject& subject)
{
  if (subject.Floor)
  {
    return vtkSmartPointer<FloorPass>::New();
  }
  return Bench::MakeTangentFilter({ subject.Name, subject.Method });
}

struct Config
{
  Subject What;
  bool Double = false;
  int Threads = 1;
  long long Size = 0; // requested triangles; the torus has 4 V^2 of them, the nearest
  std::string Key() const
  {
    return What.Name + "/" + (Double ? "double" : "float") + "/threads:" + std::to_string(Threads) +
      "/triangles:" + std::to_string(Size);
  }
};

/// A torus of U = 2 V columns and V rows of quads: 4 V^2 triangles, the nearest to `size`.
vtkPolyData* Torus(long long size, bool doublePrecision)
{
  static std::map<std::pair<long long, bool>, vtkSmartPointer<vtkPolyData>> cache;
  auto& mesh = cache[{ size, doublePrecision }];
  if (!mesh)
  {
    vtkNormalMapping::TorusOptions options;
    options.V = std::max(3, static_cast<int>(std::lround(std::sqrt(size / 4.0))));
    options.U = 2 * options.V;
    options.DoublePrecision = doublePrecision;
    mesh = vtkNormalMapping::MakeTorus(options);
  }
  return mesh;
}

struct Measured
{
  std::vector<double> Rates; // triangles per second, one per repetition
  double PeakBytes = -1.0;   // peak resident memory above the input, -1: not measured
  double OutputBytes = 0.0;  // the output's arrays that the input does not share
  long long Triangles = 0;
  double Median() const
  {
    if (this->Rates.empty())
    {
      return 0.0;
    }
    std::vector<double> r = this->Rates;
    std::sort(r.begin(), r.end());
    const size_t m = r.size() / 2;
    return r.size() % 2 ? r[m] : 0.5 * (r[m - 1] + r[m]);
  }
  /// (max - min) / median of the repetitions.
  double Spread() const
  {
    if (this->Rates.size() < 2)
    {
      return 0.0;
    }
    const auto range = std::minmax_element(this->Rates.begin(), this->Rates.end());
    return (*range.second - *range.first) / this->Median();
  }
};

/// Keeps the rate of every repetition of every configuration, and prints as usual.
class Collector : public benchmark::ConsoleReporter
{
public:
  std::map<std::string, Measured>* Results = nullptr;
  void ReportRuns(const std::vector<Run>& runs) override
  {
    for (const Run& run : runs)
    {
      const auto it = run.counters.find("items_per_second");
      if (run.run_type == Run::RT_Iteration && !run.error_occurred && it != run.counters.end())
      {
        (*this->Results)[run.run_name.function_name].Rates.push_back(it->second.value);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

/// One Update of the configuration with the resident-set peak reset before it.
void MeasurePeak(const Config& config, Measured& result, bool& peakAvailable)
{
  vtkPolyData* mesh = Torus(config.Size, config.Double);
  NormalMappingTesting::WithThreads(config.Threads,
    [&]()
    {
      auto filter = MakeSubject(config.What);
      filter->SetInputData(mesh);
      BenchMemory::ReleaseFreedMemory();
      const double before = BenchMemory::StatusBytes("VmRSS:");
      peakAvailable = peakAvailable && BenchMemory::ResetPeak();
      filter->Update();
      if (peakAvailable)
      {
        result.PeakBytes = BenchMemory::StatusBytes("VmHWM:") - before;
      }
      result.OutputBytes = BenchMemory::NewOutputBytes(mesh, filter->GetOutput());
    });
  BenchMemory::ReleaseFreedMemory();
}

std::vector<long long> ParseSizes(const std::string& text)
{
  std::vector<long long> sizes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
  {
    sizes.push_back(std::atoll(item.c_str()));
  }
  return sizes;
}

/// "13.2 (0.36 / 0.051)": M triangles/s, ratio to VTK's filter, ratio to the floor.
std::string RateCell(double rate, double vtk, double floor)
{
  return Bench::Format(rate / 1e6) + " (" + Bench::Format(vtk > 0 ? rate / vtk : 0.0, 2) + " / " +
    Bench::Format(floor > 0 ? rate / floor : 0.0, 2) + ")";
}

/// The rows of a table with one row per mesh size and subject and one cell per precision and
/// thread count: cell(configuration).
template<typename Cell>
std::string ConfigurationRows(const std::vector<long long>& sizes,
  std::map<std::string, Measured>& results,
  Cell cell)
{
  std::ostringstream rows;
  for (long long size : sizes)
  {
    for (const Subject& s : Subjects())
    {
      rows << "| " << Bench::Count(results[Config{ s, false, 1, size }.Key()].Triangles) << " | "
           << s.Name;
      for (bool doublePrecision : { false, true })
      {
        for (int threads : { 1, 2 })
        {
          rows << " | " << cell(Config{ s, doublePrecision, threads, size });
        }
      }
      rows << " |\n";
    }
  }
  return rows.str();
}

/// `pairs` pairs of Updates of `reference` (VTK's filter unless given) and `filter` on the same
/// mesh in this process, with `threads` threads (Bench::RunRounds): the reference's time / the
/// filter's.
Paired MeasurePaired(const Bench::TangentFilter& filter,
  vtkPolyData* mesh,
  int threads,
  int pairs,
  const Bench::TangentFilter& reference = { "vtkPolyDataTangents",
    Bench::TangentFilter::VTKFilter })
{
  Paired result;
  NormalMappingTesting::WithThreads(threads,
    [&]()
    {
      vtkSmartPointer<vtkPolyDataAlgorithm> run[2] = { Bench::MakeTangentFilter(reference),
        Bench::MakeTangentFilter(filter) };
      for (auto& f : run)
      {
        f->SetInputData(mesh);
      }
      result = Bench::PairedRatios(
        Bench::RunRounds(
          { [&]() { return TimedUpdate(run[0]); }, [&]() { return TimedUpdate(run[1]); } }, pairs),
        0,
        1);
    });
  result.Name = filter.Name;
  result.Threads = threads;
  return result;
}

/// `pairs` pairs of Updates of one `filter` on the same mesh, one with one thread and one with
/// two (Bench::RunRounds): the one-thread time / the two-thread time, the speed-up of the second
/// thread. The thread count is set outside the timed Update, and an untimed Update with that
/// count comes first: an application sets it once, and the first Update after a change pays for
/// it (VTK's TBB backend makes a new task arena, which the worker threads join), a cost that
/// would dominate the Update of a small mesh.
Paired MeasureScaling(const Bench::TangentFilter& filter, vtkPolyData* mesh, int pairs)
{
  auto f = Bench::MakeTangentFilter(filter);
  f->SetInputData(mesh);
  const auto with = [&](int threads)
  {
    double seconds = 0.0;
    NormalMappingTesting::WithThreads(threads,
      [&]()
      {
        TimedUpdate(f);
        seconds = TimedUpdate(f);
      });
    return seconds;
  };
  Paired result = Bench::PairedRatios(
    Bench::RunRounds({ [&]() { return with(1); }, [&]() { return with(2); } }, pairs), 0, 1);
  result.Name = filter.Name;
  result.Threads = 2;
  return result;
}

/// The default method (AngleWeighted), which the paired runs compare with VTK's filter.
Bench::TangentFilter DefaultMethod()
{
  return { vtkPolyDataTangentFrames::GetMethodName(vtkPolyDataTangentFrames::ANGLE_WEIGHTED),
    vtkPolyDataTangentFrames::ANGLE_WEIGHTED };
}

/**
 * The --first-update mode: the first Update on pairing mesh `index` in this process, of a new
 * filter (VTK's with `vtk`, else the default method) with `threads` threads; prints its seconds
 * and page faults. The thread pool has started and the same filter has updated a small torus
 * before, which loads its code: the time is that of the mesh's own memory coming fresh from the
 * system.
 */
int PrintFirstUpdate(int index, bool vtk, int threads, bool smoke)
{
  std::string note;
  const std::vector<PairingMesh> meshes = PairingMeshes(smoke, note);
  if (index < 0 || index >= static_cast<int>(meshes.size()))
  {
    std::cerr << "--first-update: there is no pairing mesh " << index << std::endl;
    return 1;
  }
  NormalMappingTesting::WithThreads(threads,
    [&]()
    {
      const Bench::TangentFilter which = vtk
        ? Bench::TangentFilter{ "vtkPolyDataTangents", Bench::TangentFilter::VTKFilter }
        : DefaultMethod();
      {
        auto warmUp = Bench::MakeTangentFilter(which);
        warmUp->SetInputData(Torus(10000, false));
        warmUp->Update();
      }
      auto filter = Bench::MakeTangentFilter(which);
      filter->SetInputData(meshes[index].Mesh);
      const double faults = Bench::MinorPageFaults();
      const double seconds = TimedUpdate(filter);
      std::cout << seconds << " " << Bench::MinorPageFaults() - faults << std::endl;
    });
  return 0;
}

/**
 * `runs` pairs of first updates (PrintFirstUpdate) of VTK's filter and the default method on
 * pairing mesh `index`, each in a new process of `program` (this one), the order within a pair
 * alternating: VTK's time / the method's, in `result`. False when a run fails.
 */
bool MeasureFirstUpdates(const std::string& program,
  int index,
  int threads,
  int runs,
  bool smoke,
  Paired& result)
{
  Bench::Rounds rounds;
  rounds.Seconds.resize(2);
  rounds.Faults.resize(2);
  for (int i = 0; i < runs; ++i)
  {
    for (int j = 0; j < 2; ++j)
    {
      const int which = (i + j) % 2; // 0: VTK's filter
      const std::string command = "'" + program + "' --first-update " + std::to_string(index) +
        (which == 0 ? " vtk " : " default ") + std::to_string(threads) + (smoke ? " --smoke" : "");
      FILE* pipe = popen(command.c_str(), "r");
      double seconds = 0.0;
      double faults = 0.0;
      const bool read = pipe && std::fscanf(pipe, "%lf %lf", &seconds, &faults) == 2;
      if (!pipe || pclose(pipe) != 0 || !read)
      {
        std::cerr << "failed: " << command << std::endl;
        return false;
      }
      rounds.Seconds[which].push_back(seconds);
      rounds.Faults[which].push_back(faults);
    }
  }
  result = Bench::PairedRatios(rounds, 0, 1);
  result.Threads = threads;
  return true;
}

/// The paired runs alone, `pairs` pairs per mesh and thread count, printed to the console.
int PrintPairedRuns(int pairs)
{
  const Bench::TangentFilter angleWeighted = DefaultMethod();
  std::string note;
  const std::vector<PairingMesh> meshes = PairingMeshes(false, note);
  for (const PairingMesh& m : meshes)
  {
    for (int threads : { 1, 2 })
    {
      const Paired p = MeasurePaired(angleWeighted, m.Mesh, threads, pairs);
      std::cout << m.Name << " (" << m.Mesh->GetNumberOfPolys() << " triangles), " << threads
                << " thread" << (threads > 1 ? "s" : "") << ": x VTK " << p.Cells() << " (median "
                << Bench::Format(p.MedianMilliseconds(0), 3) << " ms VTK's, "
                << Bench::Format(p.MedianMilliseconds(1), 3)
                << " ms ours); page faults per update: VTK " << p.MedianFaults(0) << ", ours "
                << p.MedianFaults(1) << std::endl;
    }
    const Paired scaling = MeasureScaling(angleWeighted, m.Mesh, pairs);
    std::cout << m.Name << ", two threads against one: " << scaling.Cells() << " (median "
              << Bench::Format(scaling.MedianMilliseconds(0), 3) << " ms with one, "
              << Bench::Format(scaling.MedianMilliseconds(1), 3) << " ms with two)" << std::endl;
  }
  const Paired shuffled = MeasureScaling(
    angleWeighted, NormalMappingTesting::ShuffledPoints(meshes.front().Mesh, 7), pairs);
  std::cout << "the sphere with shuffled point ids, two threads against one: " << shuffled.Cells()
            << std::endl;
  if (!note.empty())
  {
    std::cout << note << std::endl;
  }
  return 0;
}

/// The compiler of this program and CMake's build type: scripts/bench.sh builds the module it
/// links the same way.
std::string BuildName()
{
#if defined(__clang__)
  std::string compiler =
    "Clang " + std::to_string(__clang_major__) + "." + std::to_string(__clang_minor__);
#elif defined(__GNUC__)
  std::string compiler = "GCC " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__);
#elif defined(_MSC_VER)
  std::string compiler = "MSVC " + std::to_string(_MSC_VER);
#else
  std::string compiler = "an unknown compiler";
#endif
  const std::string type = NORMALMAPPING_BUILD_TYPE;
  return compiler + ", " + (type.empty() ? "no CMake build type" : type);
}

/**
 * FNV-1a, 64 bits, of the bytes of the default method's output frames (point tangents, then
 * signs) on each mesh in turn: equal across builds when every build gives the same bits.
 */
std::string OutputBitsHash(const std::vector<PairingMesh>& meshes)
{
  std::uint64_t hash = 14695981039346656037ull;
  for (const PairingMesh& m : meshes)
  {
    vtkNew<vtkPolyDataTangentFrames> frames;
    frames->SetInputData(m.Mesh);
    frames->Update();
    for (const char* name :
      { vtkPolyDataTangentFrames::TangentsArrayName(), vtkPolyDataTangentFrames::SignsArrayName() })
    {
      vtkDataArray* array = frames->GetOutput()->GetPointData()->GetArray(name);
      const auto* bytes = static_cast<const unsigned char*>(array->GetVoidPointer(0));
      const size_t count = static_cast<size_t>(array->GetDataSize()) * array->GetDataTypeSize();
      for (size_t i = 0; i < count; ++i)
      {
        hash = (hash ^ bytes[i]) * 1099511628211ull;
      }
    }
  }
  std::ostringstream text;
  text << std::hex << std::setw(16) << std::setfill('0') << hash;
  return text.str();
}

/**
 * --build-variant: the default method paired with VTK's filter, one thread, on the paired runs'
 * meshes, as a row of `out`/variants.md, with OutputBitsHash; the section's header first when
 * the file is new.
 */
int WriteBuildVariant(const std::string& out, bool smoke)
{
  const Bench::TangentFilter angleWeighted = DefaultMethod();
  std::string note;
  const std::vector<PairingMesh> meshes = PairingMeshes(smoke, note);
  const int pairs = smoke ? 3 : 40;
  const std::string path = out + "/variants.md";
  const bool header = !std::filesystem::exists(path);
  std::ofstream md(path, std::ios::app);
  if (!md)
  {
    std::cerr << "cannot write " << path << "\n";
    return 1;
  }
  if (header)
  {
    md << "\n### Builds: AngleWeighted (the default) against VTK's filter, one thread\n\n"
       << "The one-thread paired runs above (" << pairs
       << " pairs, the same meshes), each row from another build of the module and of this "
          "program, run as its own process: the project's build, one with Clang, and one "
          "configured with `-DNORMALMAPPING_MULTIVERSIONING=OFF`, whose block loops are compiled "
          "once, for the compiler's default target (on x86-64: SSE2), as compilers without "
          "function multiversioning (MSVC, Apple Clang) and other CPUs compile them. VTK's "
          "filter is the same library in every row. Each cell: the median over the pairs of "
          "`vtkPolyDataTangents`' time / AngleWeighted's [first and third quartiles], then the "
          "two medians: each process times both filters, so a row whose VTK time differs from the "
          "other rows' shows that the process, not the build, changed the ratio. Output "
          "bits: FNV-1a (64 bits) of the bytes of AngleWeighted's point tangents and signs on "
          "the meshes in turn, the same in every row when every build gives the same output, bit "
          "for bit.\n\n"
       << "| build | loops |";
    for (const PairingMesh& m : meshes)
    {
      md << " " << m.Name << " |";
    }
    md << " output bits |\n|---|---|";
    for (size_t i = 0; i < meshes.size(); ++i)
    {
      md << "---:|";
    }
    md << "---|\n";
  }
  md << "| " << BuildName() << " | "
     << (vtkNormalMapping::detail::MultiversionedLoops() ? "multiversioned: AVX-512, AVX2, default"
                                                         : "default target only")
     << " |";
  for (const PairingMesh& m : meshes)
  {
    const Paired p = MeasurePaired(angleWeighted, m.Mesh, 1, pairs);
    const std::string times = "VTK " + Bench::Format(p.MedianMilliseconds(0), 3) + " ms, ours " +
      Bench::Format(p.MedianMilliseconds(1), 3) + " ms";
    md << " " << p.MedianCell() << " (" << times << ") |";
    std::cout << m.Name << ": x VTK " << p.Cells() << " (" << times << ")" << std::endl;
  }
  md << " `" << OutputBitsHash(meshes) << "` |\n";
  return md ? 0 : 1;
}

std::string MemoryCell(const Measured& m)
{
  if (m.PeakBytes < 0)
  {
    return "not measured";
  }
  return Bench::Format(m.PeakBytes / BenchMemory::MiB) + " MiB (" +
    Bench::Format(m.PeakBytes / static_cast<double>(m.Triangles), 2) + " B/tri)";
}
}

int main(int argc, char** argv)
{
  std::string out = ".";
  bool smoke = false;
  std::vector<long long> sizes{ 10000, 100000, 1000000, 4000000 };
  int repetitions = 5;
  int pairedOnly = 0;
  bool buildVariant = false;
  std::vector<char*> args{ argv[0] };
  std::string interleave = "--benchmark_enable_random_interleaving=true";
  args.push_back(&interleave[0]);
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc)
    {
      out = argv[++i];
    }
    else if (arg == "--smoke")
    {
      smoke = true;
      sizes = { 10000 };
      repetitions = 1;
    }
    else if (arg == "--sizes" && i + 1 < argc)
    {
      sizes = ParseSizes(argv[++i]);
    }
    else if (arg == "--repetitions" && i + 1 < argc)
    {
      repetitions = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--paired-only" && i + 1 < argc)
    {
      pairedOnly = std::max(1, std::atoi(argv[++i]));
    }
    else if (arg == "--build-variant")
    {
      buildVariant = true;
    }
    else if (arg == "--first-update" && i + 3 < argc)
    {
      const bool smokeMeshes = i + 4 < argc && std::string(argv[i + 4]) == "--smoke";
      return PrintFirstUpdate(std::atoi(argv[i + 1]),
        std::string(argv[i + 2]) == "vtk",
        std::max(1, std::atoi(argv[i + 3])),
        smokeMeshes);
    }
    else
    {
      args.push_back(argv[i]);
    }
  }
  if (pairedOnly > 0)
  {
    return PrintPairedRuns(pairedOnly);
  }
  if (buildVariant)
  {
    return WriteBuildVariant(out, smoke);
  }
  std::vector<Config> configs;
  for (long long size : sizes)
  {
    for (bool doublePrecision : { false, true })
    {
      for (int threads : { 1, 2 })
      {
        for (const Subject& subject : Subjects())
        {
          configs.push_back({ subject, doublePrecision, threads, size });
        }
      }
    }
  }

  const auto start = std::chrono::steady_clock::now();
  std::map<std::string, Measured> results;
  for (const Config& c : configs)
  {
    results[c.Key()].Triangles = Torus(c.Size, c.Double)->GetNumberOfPolys();
  }
  const double meshSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "meshes generated in " << meshSeconds << " s" << std::endl;

  for (const Config& c : configs)
  {
    benchmark::RegisterBenchmark(c.Key().c_str(),
      [c](benchmark::State& state)
      {
        vtkPolyData* mesh = Torus(c.Size, c.Double);
        NormalMappingTesting::WithThreads(c.Threads,
          [&]()
          {
            auto filter = MakeSubject(c.What);
            filter->SetInputData(mesh);
            for (auto _ : state)
            {
              filter->Modified();
              filter->Update();
              benchmark::DoNotOptimize(filter->GetOutputDataObject(0));
            }
          });
        state.SetItemsProcessed(state.iterations() * mesh->GetNumberOfPolys());
      })
      ->Repetitions(repetitions)
      ->MinTime(smoke ? 0.01 : 0.1)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  Collector collector;
  collector.Results = &results;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();

  long long summarySize = sizes.front();
  for (long long size : sizes)
  {
    if (std::abs(std::log(size / 1e6)) < std::abs(std::log(summarySize / 1e6)))
    {
      summarySize = size;
    }
  }
  const int pairs = smoke ? 3 : 40;
  // Paired runs: the default method against VTK's filter on meshes that are not ours.
  const Bench::TangentFilter angleWeighted = DefaultMethod();
  std::string pairingNote;
  const std::vector<PairingMesh> pairingMeshes = PairingMeshes(smoke, pairingNote);
  std::vector<std::vector<Paired>> paired; // per mesh: 1 thread, 2 threads
  // And per mesh, one thread: the default method without splitting against with it, and the
  // points it splits.
  Bench::TangentFilter withoutSplitting = angleWeighted;
  withoutSplitting.Name += " without splitting";
  withoutSplitting.Splitting = false;
  std::vector<Paired> splittingCost;
  std::vector<vtkIdType> splitPoints;
  const auto pairedStart = std::chrono::steady_clock::now();
  for (const PairingMesh& m : pairingMeshes)
  {
    paired.push_back({ MeasurePaired(angleWeighted, m.Mesh, 1, pairs),
      MeasurePaired(angleWeighted, m.Mesh, 2, pairs) });
    splittingCost.push_back(MeasurePaired(withoutSplitting, m.Mesh, 1, pairs, angleWeighted));
    vtkNew<vtkPolyDataTangentFrames> frames;
    frames->SetInputData(m.Mesh);
    frames->Update();
    splitPoints.push_back(frames->GetNumberOfSplitPoints());
  }
  std::cout << "paired runs in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - pairedStart).count()
            << " s" << std::endl;
  // First updates, each in a new process: per mesh, one thread and two.
  const int firstRuns = smoke ? 2 : 10;
  std::vector<std::vector<Paired>> firstUpdates(pairingMeshes.size());
  const auto firstStart = std::chrono::steady_clock::now();
  for (size_t i = 0; i < pairingMeshes.size(); ++i)
  {
    for (int threads : { 1, 2 })
    {
      Paired p;
      if (!MeasureFirstUpdates(argv[0], static_cast<int>(i), threads, firstRuns, smoke, p))
      {
        return 1;
      }
      firstUpdates[i].push_back(p);
    }
  }
  std::cout << "first updates in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - firstStart).count()
            << " s" << std::endl;
  // Every method against VTK's filter on the summary torus, one thread: the ratios of the
  // summary table come from separate repetitions, which the machine's load moves more.
  std::vector<Paired> methods;
  for (const Bench::TangentFilter& f : Bench::TangentFilters())
  {
    if (!f.IsVTK())
    {
      methods.push_back(MeasurePaired(f, Torus(summarySize, false), 1, pairs));
    }
  }
  // Two threads against one, each filter alone.
  std::vector<Paired> scaling;
  const auto scalingStart = std::chrono::steady_clock::now();
  for (const Bench::TangentFilter& f : Bench::TangentFilters())
  {
    scaling.push_back(MeasureScaling(f, Torus(summarySize, false), pairs));
  }
  // The same for the default method and VTK's filter at every mesh size, with more pairs for the
  // smaller meshes (whose Updates take a fraction of a millisecond) so that every size's pairs
  // take some time: at least 40 pairs, up to 400.
  struct SizeScaling
  {
    long long Size;
    int Pairs;
    std::vector<Paired> Filters; // VTK's, then AngleWeighted
  };
  std::vector<SizeScaling> scalingBySize;
  for (long long size : sizes)
  {
    SizeScaling row{ size,
      smoke ? pairs : static_cast<int>(std::clamp<long long>(40 * (1000000 / size), 40, 400)),
      {} };
    for (const Bench::TangentFilter& f : Bench::TangentFilters())
    {
      if (f.IsVTK() || f.Method == vtkPolyDataTangentFrames::ANGLE_WEIGHTED)
      {
        row.Filters.push_back(MeasureScaling(f, Torus(size, false), row.Pairs));
      }
    }
    scalingBySize.push_back(row);
  }
  // The same on the sphere of the paired runs with its point ids in order and shuffled.
  std::vector<std::vector<Paired>> scalingByOrder; // in order, shuffled: VTK's, then AngleWeighted
  for (bool shuffled : { false, true })
  {
    vtkSmartPointer<vtkPolyData> sphere = pairingMeshes.front().Mesh;
    if (shuffled)
    {
      sphere = NormalMappingTesting::ShuffledPoints(sphere, 7);
    }
    scalingByOrder.emplace_back();
    for (const Bench::TangentFilter& f : Bench::TangentFilters())
    {
      if (f.IsVTK() || f.Method == vtkPolyDataTangentFrames::ANGLE_WEIGHTED)
      {
        scalingByOrder.back().push_back(MeasureScaling(f, sphere, pairs));
      }
    }
  }
  std::cout
    << "two threads against one in "
    << std::chrono::duration<double>(std::chrono::steady_clock::now() - scalingStart).count()
    << " s" << std::endl;

  // Peak memory, after the timing (whose allocations keep glibc's usual behaviour, as in an
  // application): large blocks from mmap from now on; each subject runs once on the smallest
  // mesh first (one-time allocations), then each configuration once with the peak reset.
  BenchMemory::AllocateLargeBlocksWithMmap();
  const auto memoryStart = std::chrono::steady_clock::now();
  for (const Subject& subject : Subjects())
  {
    auto filter = MakeSubject(subject);
    filter->SetInputData(Torus(sizes.front(), false));
    NormalMappingTesting::WithThreads(2, [&]() { filter->Update(); });
  }
  bool peakAvailable = true;
  for (const Config& c : configs)
  {
    MeasurePeak(c, results[c.Key()], peakAvailable);
  }
  std::cout << "peak memory measured in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - memoryStart).count()
            << " s" << (peakAvailable ? "" : " (VmHWM cannot be reset here: not measured)")
            << std::endl;

  // The tables.
  const auto find = [&](Config c, const std::string& name) -> const Measured&
  {
    for (const Subject& s : Subjects())
    {
      if (s.Name == name)
      {
        c.What = s;
      }
    }
    return results[c.Key()];
  };
  std::ostringstream md, tsv;
  tsv << "filter\tprecision\tthreads\ttriangles\tmtri_per_s\tspread\tpeak_bytes\toutput_bytes\n";
  for (const Config& c : configs)
  {
    const Measured& m = results[c.Key()];
    tsv << c.What.Name << "\t" << (c.Double ? "double" : "float") << "\t" << c.Threads << "\t"
        << m.Triangles << "\t" << m.Median() / 1e6 << "\t" << m.Spread() << "\t" << m.PeakBytes
        << "\t" << m.OutputBytes << "\n";
  }

  // The summary: the size nearest to one million, float input.
  md << "## Filter: throughput and peak memory\n\n"
     << "Generated tori (`vtkNormalMapping::MakeTorus`: points, normals and texture coordinates "
        "in the stated precision, u and v seams, no mirroring), "
     << repetitions << " repetition" << (repetitions > 1 ? "s" : "")
     << " of each configuration, randomly interleaved (Google Benchmark, wall-clock time, at "
        "least "
     << (smoke ? "0.01" : "0.1")
     << " s per repetition); the median is reported. `vtkPolyDataTangents` is VTK " << VTK_VERSION
     << "'s filter (float output, no handedness, no orthogonalization); the **floor** reads the "
        "same inputs and writes `vtkPolyDataTangentFrames`' outputs (`Tangents`, `TangentSigns` "
        "in the input's precision) once, with no tangent math: what memory bandwidth allows. "
        "Ratios compare runs with the same mesh, precision and thread count in this process.\n\n";
  md << "### Summary: " << Bench::Count(find({ {}, false, 1, summarySize }, "floor").Triangles)
     << " triangles, float input\n\n"
     << "| filter | 1 thread: M tri/s | x VTK | x floor | 2 threads: M tri/s | x VTK | x floor "
        "| peak memory, 1 thread | of which output arrays |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Subject& s : Subjects())
  {
    md << "| " << s.Name;
    for (int threads : { 1, 2 })
    {
      const Config c{ s, false, threads, summarySize };
      const double rate = results[c.Key()].Median();
      const double vtk = find(c, "vtkPolyDataTangents").Median();
      const double floor = find(c, "floor").Median();
      md << " | " << Bench::Format(rate / 1e6) << " | " << Bench::Format(rate / vtk, 2) << " | "
         << Bench::Format(rate / floor, 2);
    }
    const Measured& m = results[Config{ s, false, 1, summarySize }.Key()];
    md << " | " << MemoryCell(m) << " | " << Bench::Format(m.OutputBytes / BenchMemory::MiB)
       << " MiB |\n";
  }

  md << "\n### Paired runs: every method against VTK's filter, "
     << Bench::Count(find({ {}, false, 1, summarySize }, "floor").Triangles)
     << " triangles, float input, one thread\n\n"
     << "The torus of the summary; each method and VTK's filter updated alternately as in the "
        "paired runs below, "
     << pairs
     << " pairs. Each cell: the median over the pairs of `vtkPolyDataTangents`' time / the "
        "method's (above 1: faster than VTK's), with the first and third quartiles, and the "
        "ratio of the two filters' fastest runs; then the median times of the two, which show "
        "when one of them ran slower than in the other tables. These ratios, not the "
        "summary's, are the ones to quote: a pair's two runs see the same machine.\n\n"
     << "| filter | x VTK: median [quartiles] | fastest runs | VTK's filter: median | the "
        "method: median |\n"
     << "|---|---:|---:|---:|---:|\n";
  for (const Paired& p : methods)
  {
    md << "| " << p.Name << " | " << p.Cells() << " | " << Bench::Format(p.MedianMilliseconds(0), 3)
       << " ms | " << Bench::Format(p.MedianMilliseconds(1), 3) << " ms |\n";
  }

  md << "\n### Paired runs: AngleWeighted (the default) against VTK's filter\n\n"
     << "Meshes that are not ours: VTK's sources (their points, normals and texture coordinates, "
        "float) and the largest glTF model of `shared/data/gltf-external` (read with the "
        "normalmap tool's reader, its triangle primitives appended). The two filters updated "
        "alternately, "
     << pairs
     << " pairs after one warm-up Update each, the order within a pair alternating (wall-clock "
        "time, the same two filter objects throughout). A pair's two runs are milliseconds "
        "apart, so a change in the machine's speed mostly hits both. Each cell: the median over "
        "the pairs of `vtkPolyDataTangents`' time / AngleWeighted's (above 1: faster than "
        "VTK's), with the first and third quartiles, and the ratio of the two filters' fastest "
        "runs.\n\n"
     << "| mesh | triangles | 1 thread: median [quartiles] | fastest runs | 2 threads: median "
        "[quartiles] | fastest runs |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < pairingMeshes.size(); ++i)
  {
    md << "| " << pairingMeshes[i].Name << " | "
       << Bench::Count(pairingMeshes[i].Mesh->GetNumberOfPolys()) << " | " << paired[i][0].Cells()
       << " | " << paired[i][1].Cells() << " |\n";
  }
  md << "\n"
     << Bench::PageFaultText
     << " With two threads, memory that a worker thread frees goes back to that thread's own "
        "heap, which glibc trims on its own terms.\n\n"
     << "| mesh | 1 thread: vtkPolyDataTangents | AngleWeighted | 2 threads: vtkPolyDataTangents "
        "| AngleWeighted |\n"
     << "|---|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < pairingMeshes.size(); ++i)
  {
    md << "| " << pairingMeshes[i].Name;
    for (const Paired& p : paired[i])
    {
      md << " | " << Bench::FaultCount(p.MedianFaults(0)) << " | "
         << Bench::FaultCount(p.MedianFaults(1));
    }
    md << " |\n";
  }
  if (!pairingNote.empty())
  {
    md << "\n" << pairingNote << "\n";
  }

  md << "\n### What splitting costs: AngleWeighted with Splitting on and off\n\n"
     << "The meshes above, one thread: AngleWeighted with its default Splitting on and with it "
        "off updated alternately as in the paired runs, "
     << pairs
     << " pairs. Splitting gives each point on a mirror seam a copy, so that both sides keep "
        "their frames: the output then copies every point array and the re-pointed cells' "
        "connectivity. Each cell: the median over the pairs of the time with splitting / the "
        "time without (1 where no point is split), with the first and third quartiles, and the "
        "ratio of the fastest runs; then the two median times.\n\n"
     << "| mesh | split points | with / without: median [quartiles] | fastest runs | with: "
        "median | without: median |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < pairingMeshes.size(); ++i)
  {
    const Paired& p = splittingCost[i];
    md << "| " << pairingMeshes[i].Name << " | " << Bench::Count(splitPoints[i]) << " | "
       << p.Cells() << " | " << Bench::Format(p.MedianMilliseconds(0), 3) << " ms | "
       << Bench::Format(p.MedianMilliseconds(1), 3) << " ms |\n";
  }

  md << "\n### First update in a new process: AngleWeighted (the default) against VTK's filter\n\n"
     << "Each run is a new process that builds the meshes above and updates a new filter on a "
        "10,000-triangle torus (which starts the thread pool and loads the filter's code), then "
        "times the first Update of another new filter on the mesh: the memory that Update "
        "allocates comes fresh from the system and is faulted in, as in a script that runs a "
        "pipeline once. VTK's filter and AngleWeighted in turn, "
     << firstRuns
     << " runs each, the order within a pair alternating. Each cell: the median over the pairs "
        "of `vtkPolyDataTangents`' time / AngleWeighted's (above 1: faster than VTK's), with the "
        "first and third quartiles; then each filter's median time and page faults.\n\n"
     << "| mesh | threads | x VTK: median [quartiles] | VTK's filter: median, page faults | "
        "AngleWeighted: median, page faults |\n"
     << "|---|---:|---:|---:|---:|\n";
  for (size_t i = 0; i < pairingMeshes.size(); ++i)
  {
    for (const Paired& p : firstUpdates[i])
    {
      md << "| " << pairingMeshes[i].Name << " | " << p.Threads << " | " << p.MedianCell() << " | "
         << Bench::Format(p.MedianMilliseconds(0), 3) << " ms, "
         << Bench::FaultCount(p.MedianFaults(0)) << " | "
         << Bench::Format(p.MedianMilliseconds(1), 3) << " ms, "
         << Bench::FaultCount(p.MedianFaults(1)) << " |\n";
    }
  }

  md << "\n### Two threads against one: paired runs, "
     << Bench::Count(find({ {}, false, 1, summarySize }, "floor").Triangles)
     << " triangles, float input\n\n"
     << "Each filter alone, updated alternately with one thread and with two (the thread count "
        "set before an untimed Update that precedes each timed one, so that the time does not "
        "include the change of thread count), "
     << pairs
     << " pairs after one warm-up Update each, the order within a pair alternating, the same "
        "filter object throughout (wall-clock time). Each cell: the median over the pairs of the "
        "one-thread time / the two-thread time (the speed-up of the second thread; 2 is perfect "
        "scaling, below 1 slower), with the first and third quartiles, and the ratio of the "
        "fastest runs.\n\n"
     << "| filter | two threads against one: median [quartiles] | fastest runs |\n"
     << "|---|---:|---:|\n";
  for (const Paired& p : scaling)
  {
    md << "| " << p.Name << " | " << p.Cells() << " |\n";
  }

  md << "\n### Two threads against one, by mesh size: float input\n\n"
     << "As above for VTK's filter and AngleWeighted (the default) on each torus, with more pairs "
        "for the smaller ones (40 times a million over the triangle count, between 40 and 400), so "
        "that the short Updates of a small mesh still add up to a measurable time.\n\n"
     << "| triangles | pairs";
  for (const Paired& p : scalingBySize.front().Filters)
  {
    md << " | " << p.Name << ": median [quartiles] | fastest runs";
  }
  md << " |\n|---:|---:";
  for (size_t i = 0; i < scalingBySize.front().Filters.size(); ++i)
  {
    md << "|---:|---:";
  }
  md << "|\n";
  for (const SizeScaling& row : scalingBySize)
  {
    md << "| " << Bench::Count(find({ {}, false, 1, row.Size }, "floor").Triangles) << " | "
       << row.Pairs;
    for (const Paired& p : row.Filters)
    {
      md << " | " << p.Cells();
    }
    md << " |\n";
  }

  md << "\n### Two threads against one: point ids in order and in random order\n\n"
     << "As above for VTK's filter and AngleWeighted (the default), " << pairs << " pairs, on the "
     << pairingMeshes.front().Name
     << " of the paired runs: as VTK makes it, and with its point ids shuffled (the same points, "
        "point data and triangles in the same order, the points numbered at random). "
        "AngleWeighted sums the points in ranges of point ids, each on one thread, which "
        "computes the triangles that reach its range: with point ids in random order, that is "
        "nearly every triangle for every range, and it uses one range per thread.\n\n"
     << "| point ids";
  for (const Paired& p : scalingByOrder.front())
  {
    md << " | " << p.Name << ": median [quartiles] | fastest runs";
  }
  md << " |\n|---";
  for (size_t i = 0; i < scalingByOrder.front().size(); ++i)
  {
    md << "|---:|---:";
  }
  md << "|\n";
  for (size_t row = 0; row < scalingByOrder.size(); ++row)
  {
    md << (row == 0 ? "| in order" : "| shuffled");
    for (const Paired& p : scalingByOrder[row])
    {
      md << " | " << p.Cells();
    }
    md << " |\n";
  }

  md << "\n### Throughput, every configuration\n\n"
     << "Each cell: million triangles per second (ratio to `vtkPolyDataTangents` / ratio to the "
        "floor, same precision and threads).\n\n"
     << "| triangles | filter | float, 1 thread | float, 2 threads | double, 1 thread | double, "
        "2 threads |\n"
     << "|---:|---|---:|---:|---:|---:|\n";
  double worstSpread = 0.0;
  std::string worstKey;
  std::vector<double> spreads;
  md << ConfigurationRows(sizes,
    results,
    [&](const Config& c)
    {
      const Measured& m = results[c.Key()];
      spreads.push_back(m.Spread());
      if (m.Spread() > worstSpread)
      {
        worstSpread = m.Spread();
        worstKey = c.Key();
      }
      return RateCell(
        m.Median(), find(c, "vtkPolyDataTangents").Median(), find(c, "floor").Median());
    });
  if (repetitions > 1)
  {
    std::sort(spreads.begin(), spreads.end());
    md << "\nSpread of the repetitions ((max - min) / median): median "
       << Bench::Format(100.0 * spreads[spreads.size() / 2], 2) << "%, largest "
       << Bench::Format(100.0 * worstSpread, 2) << "% (`" << worstKey << "`).\n";
  }

  md << "\n### Peak memory, every configuration\n\n"
     << "Each cell: the peak of the process's resident memory during one `Update()` above its "
        "resident memory just before (VmHWM reset through `/proc/self/clear_refs`; freed heap "
        "returned to the system first, blocks of 128 KiB and more always from mmap), and that "
        "per triangle. It counts the output's new arrays (tangents, signs, the copies of split "
        "points and the re-pointed cells) and the filter's working memory; not the input, which "
        "is resident before.\n\n"
     << "| triangles | filter | float, 1 thread | float, 2 threads | double, 1 thread | double, "
        "2 threads |\n"
     << "|---:|---|---:|---:|---:|---:|\n";
  md << ConfigurationRows(
    sizes, results, [&](const Config& c) { return MemoryCell(results[c.Key()]); });
  md << "\n";
  const bool written = Bench::WriteText(out + "/filter.md", md.str()) &&
    Bench::WriteText(out + "/filter.tsv", tsv.str()) &&
    Bench::WriteText(out + "/filter.env", std::string("VTK ") + VTK_VERSION + "\n");
  return written ? 0 : 1;
}
