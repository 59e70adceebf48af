// SPDX-License-Identifier: BSD-3-Clause
// What the benchmark programs of scripts/bench.sh share: the tangent filters they compare, number
// formatting for the markdown tables, and the files they write (a markdown fragment and a CSV
// table per program, in the output folder that bench.sh assembles into docs/benchmarks.md).
#ifndef BenchCommon_h
#define BenchCommon_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkPolyDataTangents.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace Bench
{
/// A tangent filter under comparison: VTK's vtkPolyDataTangents or one method of ours.
struct TangentFilter
{
  std::string Name;
  int Method;            // a vtkPolyDataTangentFrames::Methods value, or VTKFilter
  bool Splitting = true; // ours: vtkPolyDataTangentFrames::Splitting
  static constexpr int VTKFilter = -1;
  bool IsVTK() const { return this->Method == VTKFilter; }
};

inline std::vector<TangentFilter> TangentFilters()
{
  std::vector<TangentFilter> filters{ { "vtkPolyDataTangents", TangentFilter::VTKFilter } };
  for (int method : { vtkPolyDataTangentFrames::UNWEIGHTED,
         vtkPolyDataTangentFrames::AREA_WEIGHTED,
         vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
         vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    filters.push_back({ vtkPolyDataTangentFrames::GetMethodName(method), method });
  }
  return filters;
}

/// The filter with its default settings (ours: output precision of the input), and its Splitting.
inline vtkSmartPointer<vtkPolyDataAlgorithm> MakeTangentFilter(const TangentFilter& filter)
{
  if (filter.IsVTK())
  {
    return vtkSmartPointer<vtkPolyDataTangents>::New();
  }
  auto ours = vtkSmartPointer<vtkPolyDataTangentFrames>::New();
  ours->SetMethod(filter.Method);
  ours->SetSplitting(filter.Splitting);
  return ours;
}

/// The q-quantile of `values` (0.5: the median), interpolated between the two nearest.
inline double Quantile(std::vector<double> values, double q)
{
  std::sort(values.begin(), values.end());
  const double x = q * static_cast<double>(values.size() - 1);
  const size_t i = static_cast<size_t>(x);
  return i + 1 < values.size()
    ? values[i] + (x - static_cast<double>(i)) * (values[i + 1] - values[i])
    : values.back();
}

/// A number with `digits` significant digits, without an exponent between 1e-4 and 1e6.
inline std::string Format(double value, int digits = 3)
{
  if (!std::isfinite(value))
  {
    return value != value ? "NaN" : (value > 0 ? "inf" : "-inf");
  }
  if (value == 0.0)
  {
    return "0";
  }
  const double magnitude = std::abs(value);
  char text[64];
  if (magnitude >= 1e-4 && magnitude < 1e6)
  {
    const int decimals =
      std::max(0, digits - 1 - static_cast<int>(std::floor(std::log10(magnitude))));
    std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  }
  else
  {
    std::snprintf(text, sizeof(text), "%.*e", digits - 1, value);
  }
  return text;
}

/// An integer with thousands separators (1,048,576).
inline std::string Count(long long value)
{
  std::string digits = std::to_string(value < 0 ? -value : value);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
  {
    digits.insert(static_cast<size_t>(i), ",");
  }
  return (value < 0 ? "-" : "") + digits;
}

/// Writes text to a file; false (with a message on stderr) when it cannot.
inline bool WriteText(const std::string& path, const std::string& text)
{
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out)
  {
    std::cerr << "cannot write " << path << std::endl;
    return false;
  }
  return true;
}
}

#endif
