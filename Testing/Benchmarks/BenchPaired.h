// SPDX-License-Identifier: BSD-3-Clause
// What the paired measurements of BenchTangentFrames and BenchMikkTSpace share: the meshes that
// are not ours (VTK's sources and the largest glTF model of the shared data), and timed runs of
// several subjects in rounds, with the ratios of their times within each round.
#ifndef BenchPaired_h
#define BenchPaired_h

#include "BenchCommon.h"
#include "NormalMapGLTF.h"
#include "NormalMappingReferenceData.h"

#include "vtkAppendPolyData.h"
#include "vtkNew.h"
#include "vtkParametricFunctionSource.h"
#include "vtkParametricTorus.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"
#include "vtkTexturedSphereSource.h"
#include "vtkTriangleFilter.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace Bench
{
/// Ratios of two subjects' times, each from one round of runs made back to back (RunRounds).
struct Paired
{
  std::string Name;
  int Threads = 1;
  std::vector<double> Ratios;     // the first subject's time / the second's, one per round
  double FastestRatio = 0.0;      // the first's fastest run / the second's fastest run
  std::vector<double> Seconds[2]; // the first's and the second's times, one per round
  std::vector<double> Faults[2];  // the first's and the second's page faults, one per round
  double Quantile(double q) const { return Bench::Quantile(this->Ratios, q); }
  /// The median number of page faults of one run of subject `which` (0: first, 1: second).
  double MedianFaults(int which) const { return Bench::Quantile(this->Faults[which], 0.5); }
  /// The median time of subject `which` (0: first, 1: second), in milliseconds.
  double MedianMilliseconds(int which) const
  {
    return 1000.0 * Bench::Quantile(this->Seconds[which], 0.5);
  }
  /// A table cell: "median [first quartile, third quartile]".
  std::string MedianCell() const
  {
    return Bench::Format(this->Quantile(0.5), 3) + " [" + Bench::Format(this->Quantile(0.25), 3) +
      ", " + Bench::Format(this->Quantile(0.75), 3) + "]";
  }
  /// The two cells of a table row: MedianCell, then "| fastest runs".
  std::string Cells() const
  {
    return this->MedianCell() + " | " + Bench::Format(this->FastestRatio, 3);
  }
};

/// Re-executes the filter (Modified, Update) and returns the wall-clock seconds it took.
inline double TimedUpdate(vtkPolyDataAlgorithm* f)
{
  f->Modified();
  const auto t0 = std::chrono::steady_clock::now();
  f->Update();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The page faults this process has taken so far that needed no disk read: each is the first
/// touch of a page of memory the process got from the system (zeroed by the kernel).
inline double MinorPageFaults()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_minflt);
}

/// A median page fault count as a table cell.
inline std::string FaultCount(double faults)
{
  return Count(static_cast<long long>(std::llround(faults)));
}

/// What the page fault tables of the paired runs show.
constexpr const char* PageFaultText =
  "Page faults per run (medians over the same runs): each is the first touch of a 4 KiB page "
  "that the process got from the system, which the kernel zeroes. Memory a run frees goes "
  "back to glibc, which returns large blocks, and the top of its heap beyond a threshold, to "
  "the system; a run that allocates them again faults them in again. The counts depend on "
  "what the process allocated and freed before, and each fault's time (zeroing and mapping the "
  "page) is part of the times above.";

/// What RunRounds measures: per subject, one entry per round.
struct Rounds
{
  std::vector<std::vector<double>> Seconds;
  std::vector<std::vector<double>> Faults; // MinorPageFaults during the run
};

/**
 * `rounds` rounds of the timed runs `runs` (each returns its seconds), run back to back, after one
 * warm-up run each; the subject that goes first rotates from round to round (with two: the
 * order alternates). Returns each subject's times and page faults, one per round. The runs of a
 * round are close in time, so a change of the machine's speed (other virtual machines,
 * frequency) mostly hits all of them: a ratio within a round is steadier than the ratio of
 * medians over repetitions that are seconds apart.
 */
inline Rounds RunRounds(const std::vector<std::function<double()>>& runs, int rounds)
{
  for (const auto& run : runs)
  {
    run();
  }
  Rounds result;
  result.Seconds.resize(runs.size());
  result.Faults.resize(runs.size());
  for (int i = 0; i < rounds; ++i)
  {
    for (size_t j = 0; j < runs.size(); ++j)
    {
      const size_t which = (static_cast<size_t>(i) + j) % runs.size();
      const double faults = MinorPageFaults();
      result.Seconds[which].push_back(runs[which]());
      result.Faults[which].push_back(MinorPageFaults() - faults);
    }
  }
  return result;
}

/// Subject a's time / subject b's in each round of `rounds` (RunRounds' result), and the
/// ratio of their fastest runs.
inline Paired PairedRatios(const Rounds& rounds, size_t a, size_t b)
{
  const std::vector<std::vector<double>>& seconds = rounds.Seconds;
  Paired result;
  result.Seconds[0] = seconds[a];
  result.Seconds[1] = seconds[b];
  result.Faults[0] = rounds.Faults[a];
  result.Faults[1] = rounds.Faults[b];
  for (size_t i = 0; i < seconds[a].size(); ++i)
  {
    result.Ratios.push_back(seconds[a][i] / seconds[b][i]);
  }
  result.FastestRatio = *std::min_element(seconds[a].begin(), seconds[a].end()) /
    *std::min_element(seconds[b].begin(), seconds[b].end());
  return result;
}

/// A mesh of the paired runs.
struct PairingMesh
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
};

/// Every triangle primitive of a glTF file as one polydata (points, normals, TEXCOORD_0 as the
/// active texture coordinates, as stored); null when the file cannot be read or has no
/// triangles.
inline vtkSmartPointer<vtkPolyData> ReadGLTF(const std::string& path)
{
  NormalMapGLTF::Document doc;
  std::string error;
  if (!NormalMapGLTF::ReadDocument(path, doc, error))
  {
    return nullptr;
  }
  vtkNew<vtkAppendPolyData> append;
  for (const NormalMapGLTF::PrimitiveId id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    vtkSmartPointer<vtkPolyData> primitive = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (primitive && primitive->GetPointData()->GetNormals() &&
      primitive->GetPointData()->GetTCoords())
    {
      append->AddInputData(primitive);
    }
  }
  if (append->GetNumberOfInputConnections(0) == 0)
  {
    return nullptr;
  }
  append->Update();
  return append->GetOutput();
}

/**
 * The meshes of the paired runs: VTK's textured sphere and parametric torus at 1024 x 512 (64 x 32
 * for the smoke run), and the glTF model of `shared/gltf-external` with the most triangles. `note`
 * says why the glTF model is missing, when it is.
 */
inline std::vector<PairingMesh> PairingMeshes(bool smoke, std::string& note)
{
  const int u = smoke ? 64 : 1024;
  const int v = smoke ? 32 : 512;
  const std::string resolution = std::to_string(u) + " x " + std::to_string(v);
  std::vector<PairingMesh> meshes;
  vtkNew<vtkTexturedSphereSource> sphere;
  sphere->SetThetaResolution(u);
  sphere->SetPhiResolution(v);
  sphere->Update();
  meshes.push_back({ "vtkTexturedSphereSource " + resolution, sphere->GetOutput() });

  vtkNew<vtkParametricTorus> torus;
  vtkNew<vtkParametricFunctionSource> torusSource;
  torusSource->SetParametricFunction(torus);
  torusSource->SetUResolution(u);
  torusSource->SetVResolution(v);
  torusSource->GenerateTextureCoordinatesOn();
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(torusSource->GetOutputPort());
  triangles->Update();
  meshes.push_back(
    { "vtkParametricTorus " + resolution + ", triangulated", triangles->GetOutput() });

  std::string lookedFor;
  const std::string shared = NormalMappingTestData::FindSharedData(&lookedFor);
  const std::filesystem::path folder = std::filesystem::path(shared) / "gltf-external";
  std::error_code ec;
  if (shared.empty() || !std::filesystem::is_directory(folder, ec))
  {
    note = "Skipped: the glTF models (`shared/data/gltf-external`, beside the project) were not "
           "found; looked for " +
      (shared.empty() ? lookedFor : folder.string()) + ".";
    return meshes;
  }
  PairingMesh largest;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder, ec))
  {
    if (entry.path().extension() != ".gltf")
    {
      continue;
    }
    vtkSmartPointer<vtkPolyData> mesh = ReadGLTF(entry.path().string());
    if (mesh && (!largest.Mesh || mesh->GetNumberOfPolys() > largest.Mesh->GetNumberOfPolys()))
    {
      largest = { "glTF " + entry.path().stem().string(), mesh };
    }
  }
  if (!largest.Mesh)
  {
    note =
      "Skipped: no glTF model with normals and texture coordinates in " + folder.string() + ".";
    return meshes;
  }
  meshes.push_back(largest);
  return meshes;
}
}

#endif
