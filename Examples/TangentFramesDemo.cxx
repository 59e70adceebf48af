// SPDX-License-Identifier: BSD-3-Clause
// The built-in demo: tangent frames for a generated torus with mirrored UV halves, with what
// the filter produced, how long it took and how far it is from the true tangents.
//
//   TangentFramesDemo [--triangles N] [--method unweighted|area|angle] [--threads N]
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTimerLog.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  long long triangles = 1 << 20;
  int method = vtkPolyDataTangentFrames::ANGLE_WEIGHTED;
  int threads = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--triangles" && hasValue)
    {
      triangles = std::atoll(argv[++i]);
    }
    else if (arg == "--threads" && hasValue)
    {
      threads = std::atoi(argv[++i]);
    }
    else if (arg == "--method" && hasValue)
    {
      const std::string m = argv[++i];
      method = m == "unweighted" ? vtkPolyDataTangentFrames::UNWEIGHTED
        : m == "area"            ? vtkPolyDataTangentFrames::AREA_WEIGHTED
        : m == "angle"           ? vtkPolyDataTangentFrames::ANGLE_WEIGHTED
                                 : -1;
      if (method < 0)
      {
        std::cerr << "error: unknown method '" << m << "' (unweighted, area, angle)\n";
        return 2;
      }
    }
    else
    {
      std::cerr << "usage: " << argv[0]
                << " [--triangles N] [--method unweighted|area|angle] [--threads N]\n";
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  if (triangles < 32)
  {
    std::cerr << "error: --triangles must be at least 32\n";
    return 2;
  }
  vtkSMPTools::Initialize(threads);

  // A torus twice as long around the ring as around the tube, mirrored in u.
  vtkNormalMapping::TorusOptions options;
  options.V = std::max(4, static_cast<int>(std::lround(std::sqrt(triangles / 4.0))));
  options.U = std::max(4, static_cast<int>(triangles / (2 * options.V)));
  options.MirrorU = true;
  vtkSmartPointer<vtkPolyData> mesh = vtkNormalMapping::MakeTorus(options);

  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(mesh);
  filter->SetMethod(method);
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  filter->Update();
  timer->StopTimer();
  vtkPolyData* out = filter->GetOutput();

  // Angle to the true tangent sign * (-sin phi, cos phi, 0) on points off the mirror seams.
  vtkDataArray* t = out->GetPointData()->GetTangents();
  vtkDataArray* s = out->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  std::vector<double> errors;
  vtkIdType wrongSigns = 0;
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    double x[3], tv[3];
    out->GetPoint(p, x);
    t->GetTuple(p, tv);
    const double phi = std::atan2(x[1], x[0]);
    const double frac = std::fmod(phi / (2.0 * std::acos(-1.0)) + 1.0, 1.0);
    const double seam = std::min({ frac, std::abs(frac - 0.5), 1.0 - frac });
    if (seam < 1e-6)
    {
      continue; // on a mirror seam: each copy carries one side's frame
    }
    const double sign = frac < 0.5 ? 1.0 : -1.0;
    wrongSigns += (s->GetComponent(p, 0) == sign) ? 0 : 1;
    const double dot = sign * (-std::sin(phi) * tv[0] + std::cos(phi) * tv[1]);
    errors.push_back(std::acos(std::max(-1.0, std::min(1.0, dot))) * 180.0 / std::acos(-1.0));
  }
  std::sort(errors.begin(), errors.end());
  double mean = 0.0;
  for (double e : errors)
  {
    mean += e;
  }
  mean /= std::max<size_t>(errors.size(), 1);

  std::cout << "vtkPolyDataTangentFrames demo: mirrored-UV torus\n"
            << "  method                 " << vtkPolyDataTangentFrames::GetMethodName(method)
            << "\n"
            << "  threads                " << vtkSMPTools::GetEstimatedNumberOfThreads() << " ("
            << vtkSMPTools::GetBackend() << ")\n"
            << "  input                  " << mesh->GetNumberOfPoints() << " points, "
            << mesh->GetNumberOfPolys() << " triangles\n"
            << "  output                 " << out->GetNumberOfPoints() << " points\n"
            << "  points split           " << filter->GetNumberOfSplitPoints()
            << " (mirror seams)\n"
            << "  degenerate triangles   " << filter->GetNumberOfDegenerateTriangles() << "\n"
            << "  fallback points        " << filter->GetNumberOfFallbackPoints() << "\n"
            << "  time                   " << timer->GetElapsedTime() * 1000.0 << " ms ("
            << mesh->GetNumberOfPolys() / timer->GetElapsedTime() / 1e6 << " M triangles/s)\n"
            << "  wrong signs            " << wrongSigns << " of " << errors.size() << "\n"
            << "  angle to true tangent  mean " << mean << " deg, max "
            << (errors.empty() ? 0.0 : errors.back()) << " deg\n";
  return wrongSigns == 0 ? 0 : 1;
}
