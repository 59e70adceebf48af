// SPDX-License-Identifier: BSD-3-Clause
// Locating ../shared/data, and angle statistics for comparing with it, without GoogleTest: used
// by the tests (through NormalMappingTestData.h) and by the benchmarks.
//
// Shared data location: $NORMALMAPPING_SHARED_DATA if set, else the first ancestor of this
// source file, of the executable or of the working directory that contains shared/data.
#ifndef NormalMappingReferenceData_h
#define NormalMappingReferenceData_h

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#if defined(__linux__)
#include <unistd.h>
#endif

namespace NormalMappingTestData
{
//------------------------------------------------------------------------------
// Locating the shared data
inline bool IsDir(const std::string& path)
{
  std::ifstream probe(path + "/README.md");
  return probe.good();
}

inline std::string Parent(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos || slash == 0)
  {
    return std::string();
  }
  return path.substr(0, slash);
}

inline std::string FindSharedData(std::string* lookedFor)
{
  if (const char* env = std::getenv("NORMALMAPPING_SHARED_DATA"))
  {
    if (lookedFor)
    {
      *lookedFor = std::string(env) + " ($NORMALMAPPING_SHARED_DATA)";
    }
    return IsDir(env) ? std::string(env) : std::string();
  }
  std::vector<std::string> starts;
  std::string file = __FILE__;
  std::replace(file.begin(), file.end(), '\\', '/');
  starts.push_back(Parent(file));
#if defined(__linux__)
  char exe[4096];
  const ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
  if (n > 0)
  {
    exe[n] = 0;
    starts.push_back(Parent(exe));
  }
  char cwd[4096];
  if (getcwd(cwd, sizeof(cwd)))
  {
    starts.push_back(cwd);
  }
#endif
  for (std::string dir : starts)
  {
    while (!dir.empty())
    {
      const std::string candidate = dir + "/shared/data";
      if (IsDir(candidate))
      {
        return candidate;
      }
      dir = Parent(dir);
    }
  }
  if (lookedFor)
  {
    *lookedFor = "$NORMALMAPPING_SHARED_DATA (unset) or shared/data in an ancestor of " +
      starts.front() + (starts.size() > 1 ? " / " + starts[1] : std::string());
  }
  return std::string();
}

// Angle between two 3-vectors in degrees, evaluated in double with atan2 (accurate near 0).
template<typename Real>
inline double AngleDeg(const Real* a, const Real* b)
{
  const double ax = a[0], ay = a[1], az = a[2], bx = b[0], by = b[1], bz = b[2];
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  const double s = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double c = ax * bx + ay * by + az * bz;
  return std::atan2(s, c) * 180.0 / 3.14159265358979323846;
}

struct Stats
{
  std::vector<double> Angles;
  long long SignMismatches = 0;
  long long DefaultMismatches = 0;
  long long ReferenceDefaults = 0;

  double Mean() const
  {
    double s = 0;
    for (double a : Angles)
    {
      s += a;
    }
    return Angles.empty() ? 0.0 : s / static_cast<double>(Angles.size());
  }
  double Quantile(double q) const
  {
    if (Angles.empty())
    {
      return 0.0;
    }
    std::vector<double> v = Angles;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
  }
  double Max() const
  {
    return Angles.empty() ? 0.0 : *std::max_element(Angles.begin(), Angles.end());
  }
  long long Exact() const
  {
    return static_cast<long long>(std::count(Angles.begin(), Angles.end(), 0.0));
  }
};

} // namespace NormalMappingTestData

#endif
