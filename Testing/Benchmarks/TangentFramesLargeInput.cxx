// SPDX-License-Identifier: BSD-3-Clause
// Large input: vtkPolyDataTangentFrames on a generated 20-million-triangle torus (mirrored UVs,
// so seam points are split and the cells re-pointed). For each method it reports the time and
// the peak memory of the run against a bound stated from the output size, then aborts a run
// from a progress observer and checks that the output is valid and empty. Not a ctest test (it
// needs ~5 GB and a minute); run it by hand:
//   build/bin/TangentFramesLargeInput [triangles in millions, default 20]
// Exit status 1 when a bound or the abort check fails.
#include "BenchMemory.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace BenchMemory;

int main(int argc, char* argv[])
{
  const double millions = argc > 1 ? std::atof(argv[1]) : 20.0;
  AllocateLargeBlocksWithMmap(); // so that the second method's peak is not hidden by the first's
                                 // freed, still resident heap
  vtkNormalMapping::TorusOptions options;
  // 2 U V triangles with U = 1.6 V.
  options.V = static_cast<int>(std::lround(std::sqrt(millions * 1e6 / 3.2)));
  options.U = static_cast<int>(std::lround(millions * 1e6 / (2.0 * options.V)));
  options.MirrorU = true;
  auto input = vtkNormalMapping::MakeTorus(options);
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numTriangles = input->GetNumberOfPolys();
  std::printf("input: %lld triangles, %lld points (float), %.0f MiB; process RSS %.0f MiB\n",
    static_cast<long long>(numTriangles),
    static_cast<long long>(numPoints),
    input->GetActualMemorySize() / 1024.0,
    StatusBytes("VmRSS:") / MiB);

  int failures = 0;
  for (int method :
    { vtkPolyDataTangentFrames::ANGLE_WEIGHTED, vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetInputData(input);
    filter->SetMethod(method);
    const double before = StatusBytes("VmRSS:");
    const bool phasePeak = ResetPeak();
    const auto start = std::chrono::steady_clock::now();
    filter->Update();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double peak = phasePeak ? StatusBytes("VmHWM:") : MaxRssBytes();
    vtkPolyData* output = filter->GetOutput();
    const double outputBytes = NewOutputBytes(input, output);
    // The bound: what the README promises the run needs besides its input, that is the
    // output's new arrays plus the working memory (64 bytes per point of accumulators for the
    // weighted methods; about 150 bytes per triangle for MikkTSpace), with 10% and 64 MiB of
    // slack for allocator rounding and thread stacks.
    const bool mikk = method == vtkPolyDataTangentFrames::MIKKTSPACE;
    const double working = mikk ? 150.0 * numTriangles : 64.0 * numPoints;
    const double bound = 1.1 * (outputBytes + working) + 64 * MiB;
    const double used = peak - before;
    const bool ok = used <= bound && output->GetNumberOfPoints() > numPoints;
    failures += ok ? 0 : 1;
    std::printf("%-13s %6.2f s  %5.1f M tri/s  split points %lld  peak above input %5.0f MiB "
                "(output's new arrays %5.0f MiB + working %5.0f MiB; bound %5.0f MiB) %s\n",
      vtkPolyDataTangentFrames::GetMethodName(method),
      seconds,
      numTriangles / seconds / 1e6,
      static_cast<long long>(filter->GetNumberOfSplitPoints()),
      used / MiB,
      outputBytes / MiB,
      working / MiB,
      bound / MiB,
      ok ? "ok" : "OVER THE BOUND");

    // Abort from a progress observer at the first report past 30%: a valid, empty output.
    vtkNew<vtkCallbackCommand> abortAt30;
    abortAt30->SetCallback(
      [](vtkObject* caller, unsigned long, void*, void* progress)
      {
        if (*static_cast<double*>(progress) >= 0.3)
        {
          static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
        }
      });
    filter->AddObserver(vtkCommand::ProgressEvent, abortAt30);
    filter->Modified();
    const auto abortStart = std::chrono::steady_clock::now();
    filter->Update();
    const double abortSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - abortStart).count();
    output = filter->GetOutput();
    const bool empty = output->GetNumberOfPoints() == 0 && output->GetNumberOfCells() == 0 &&
      output->GetPointData()->GetNumberOfArrays() == 0 &&
      output->GetCellData()->GetNumberOfArrays() == 0;
    failures += empty ? 0 : 1;
    std::printf("%-13s aborted at 30%%: returned after %.2f s, output %lld points, %lld cells, "
                "%d point arrays: %s\n",
      vtkPolyDataTangentFrames::GetMethodName(method),
      abortSeconds,
      static_cast<long long>(output->GetNumberOfPoints()),
      static_cast<long long>(output->GetNumberOfCells()),
      output->GetPointData()->GetNumberOfArrays(),
      empty ? "valid and empty" : "NOT EMPTY");
  }
  std::printf("process peak (getrusage maxrss): %.0f MiB\n", MaxRssBytes() / MiB);
  return failures == 0 ? 0 : 1;
}
