// Throughput of vtkPolyDataTangentFrames against VTK's vtkPolyDataTangents, in one process on
// the same meshes. Each method runs with 1 and 2 threads; VTK's filter with 1 thread is the
// reference every ratio is taken against.
//
//   BenchTangentFrames [--markdown FILE] [google benchmark flags]
#include "NormalMappingThreads.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkPolyData.h"
#include "vtkPolyDataTangents.h"
#include "vtkSMPTools.h"
#include "vtkVersionMacros.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> Torus(int64_t triangles)
{
  static std::map<int64_t, vtkSmartPointer<vtkPolyData>> cache;
  auto& mesh = cache[triangles];
  if (!mesh)
  {
    vtkNormalMapping::TorusOptions options;
    options.V = static_cast<int>(std::sqrt(triangles / 4.0));
    options.U = static_cast<int>(triangles / (2 * options.V));
    mesh = vtkNormalMapping::MakeTorus(options);
  }
  return mesh;
}

template<typename Filter, typename Configure>
void RunFilter(benchmark::State& state, Configure configure)
{
  auto mesh = Torus(state.range(0));
  NormalMappingTesting::WithThreads(static_cast<int>(state.range(1)),
    [&]()
    {
      vtkNew<Filter> filter;
      filter->SetInputData(mesh);
      configure(filter.Get());
      for (auto _ : state)
      {
        filter->Modified();
        filter->Update();
        benchmark::DoNotOptimize(filter->GetOutput());
      }
    });
  state.SetItemsProcessed(state.iterations() * mesh->GetNumberOfPolys());
}

void VTKPolyDataTangents(benchmark::State& state)
{
  RunFilter<vtkPolyDataTangents>(state, [](vtkPolyDataTangents*) {});
}

template<int Method>
void TangentFrames(benchmark::State& state)
{
  RunFilter<vtkPolyDataTangentFrames>(
    state, [](vtkPolyDataTangentFrames* f) { f->SetMethod(Method); });
}

void Sizes(benchmark::internal::Benchmark* b, bool twoThreads)
{
  for (int64_t n : { 1 << 14, 1 << 20 })
  {
    b->Args({ n, 1 });
    if (twoThreads)
    {
      b->Args({ n, 2 });
    }
  }
  b->ArgNames({ "triangles", "threads" })->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(VTKPolyDataTangents)->Apply([](auto* b) { Sizes(b, false); });
BENCHMARK_TEMPLATE(TangentFrames, vtkPolyDataTangentFrames::UNWEIGHTED)
  ->Name("TangentFrames/Unweighted")
  ->Apply([](auto* b) { Sizes(b, true); });
BENCHMARK_TEMPLATE(TangentFrames, vtkPolyDataTangentFrames::AREA_WEIGHTED)
  ->Name("TangentFrames/AreaWeighted")
  ->Apply([](auto* b) { Sizes(b, true); });
BENCHMARK_TEMPLATE(TangentFrames, vtkPolyDataTangentFrames::ANGLE_WEIGHTED)
  ->Name("TangentFrames/AngleWeighted")
  ->Apply([](auto* b) { Sizes(b, true); });
BENCHMARK_TEMPLATE(TangentFrames, vtkPolyDataTangentFrames::MIKKTSPACE)
  ->Name("TangentFrames/MikkTSpace")
  ->Apply([](auto* b) { Sizes(b, true); });

/// Keeps every run so that ratios to the reference can be printed at the end.
class Collector : public benchmark::ConsoleReporter
{
public:
  struct Result
  {
    std::string Name;
    double ItemsPerSecond;
  };
  std::vector<Result> Results;

  void ReportRuns(const std::vector<Run>& runs) override
  {
    for (const Run& run : runs)
    {
      const auto it = run.counters.find("items_per_second");
      if (it != run.counters.end() && run.run_type == Run::RT_Iteration)
      {
        this->Results.push_back({ run.benchmark_name(), it->second.value });
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

/// CPU model, core count and load, so that a reader can judge the figures.
std::string MachineDescription()
{
  std::string model = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
  {
    if (line.rfind("model name", 0) == 0)
    {
      model = line.substr(line.find(':') + 2);
      break;
    }
  }
  std::string load = "unknown";
  std::ifstream loadavg("/proc/loadavg");
  std::getline(loadavg, load);
  std::ostringstream os;
  os << model << ", " << std::thread::hardware_concurrency() << " hardware threads, "
     << "load average at the end of the run: " << load.substr(0, load.find(' ', 10));
  return os.str();
}

std::string Field(const std::string& name, const std::string& key)
{
  const size_t at = name.find(key + ":");
  if (at == std::string::npos)
  {
    return "";
  }
  const size_t begin = at + key.size() + 1;
  return name.substr(begin, name.find('/', begin) - begin);
}
}

int main(int argc, char** argv)
{
  std::string markdown;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--markdown") == 0 && i + 1 < argc)
    {
      markdown = argv[++i];
    }
    else
    {
      args.push_back(argv[i]);
    }
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);

  // Ratios against VTK's filter on the same mesh, one thread.
  std::map<std::string, double> reference;
  for (const auto& r : collector.Results)
  {
    if (r.Name.rfind("VTKPolyDataTangents", 0) == 0)
    {
      reference[Field(r.Name, "triangles")] = r.ItemsPerSecond;
    }
  }
  std::ostringstream table;
  table << "| filter | triangles | threads | M triangles/s | ratio to vtkPolyDataTangents |\n"
        << "|---|---:|---:|---:|---:|\n";
  for (const auto& r : collector.Results)
  {
    const std::string triangles = Field(r.Name, "triangles");
    const double ref = reference.count(triangles) ? reference[triangles] : 0.0;
    table << "| " << r.Name.substr(0, r.Name.find('/', r.Name.find('/') + 1)) << " | " << triangles
          << " | " << Field(r.Name, "threads") << " | " << r.ItemsPerSecond / 1e6 << " | "
          << (ref > 0 ? r.ItemsPerSecond / ref : 0.0) << " |\n";
  }
  std::cout << "\n" << table.str();
  if (!markdown.empty())
  {
    std::ofstream out(markdown);
    out << "# vtkPolyDataTangentFrames throughput\n\n"
        << "Written by `BenchTangentFrames --markdown` (`bash scripts/bootstrap.sh bench`); do not "
           "edit by hand.\n\n"
        << "Machine: " << MachineDescription() << "\n\n"
        << "Meshes: generated tori (float points, normals and texture coordinates). Each ratio "
           "is against vtkPolyDataTangents (VTK "
        << VTK_VERSION << ", one thread) on the same mesh in the same run.\n\n"
        << table.str();
  }
  benchmark::Shutdown();
  return 0;
}
