// SPDX-License-Identifier: BSD-3-Clause
// Accuracy of the tangent filters (vtkPolyDataTangentFrames with every method, and VTK's
// vtkPolyDataTangents):
// - the angle between each output point's tangent and the analytic dP/du on a sphere, a torus
//   and a wavy sheared height field, at three resolutions, with the convergence order;
// - the angle to the MikkTSpace reference tangents of ../shared/data/mikktspace (every corner),
//   and the handedness signs; this table is replaced by a note when the data is absent.
//
//   BenchTangentAccuracy [--out DIR] [--smoke]
//
// Writes DIR/accuracy.md (its section of docs/benchmarks.md) and DIR/accuracy.tsv (for
// BenchChart). --smoke: coarser resolutions (for the ctest smoke test). scripts/bench.sh runs it.
//
// On the analytic surfaces every tangent is first projected onto the plane of its point normal:
// a no-op for ours up to rounding, and for VTK's filter (which does not orthogonalize) what its
// mapper does in the shader; against the MikkTSpace references only VTK's is projected. A tangent
// that is zero or not finite counts as 180 degrees and is counted on its own. The expected
// directions are exact (analytic dP/du lies in the tangent plane) or the reference's own.
#include "BenchCommon.h"
#include "NormalMappingGrid.h"
#include "NormalMappingReferenceData.h"
#include "vtkNormalMappingMeshes.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTexturedSphereSource.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Vec = std::array<double, 3>;
const double Pi = 3.14159265358979323846;

double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// v without its component along the unit vector n.
Vec Project(Vec v, const Vec& n)
{
  const double d = Dot(v, n);
  for (int k = 0; k < 3; ++k)
  {
    v[k] -= d * n[k];
  }
  return v;
}

Vec Tuple(vtkDataArray* array, vtkIdType i)
{
  Vec v;
  array->GetTuple(i, v.data());
  return v;
}

/**
 * Angle in degrees between a computed tangent, projected onto the plane of the unit normal n,
 * and the expected direction; 180 when the computed tangent is zero or not finite. A tangent
 * along n (nothing left after the projection) is compared as it is.
 */
double TangentError(const Vec& computed,
  const Vec& expected,
  const Vec& n,
  bool& invalid,
  bool project = true)
{
  const double raw = std::sqrt(Dot(computed, computed));
  invalid = !(raw > 0.0) || !std::isfinite(raw);
  if (invalid)
  {
    return 180.0;
  }
  Vec t = project ? Project(computed, n) : computed;
  if (!(std::sqrt(Dot(t, t)) > 1e-6 * raw))
  {
    t = computed;
  }
  return NormalMappingTestData::AngleDeg(t.data(), expected.data());
}

struct Errors
{
  NormalMappingTestData::Stats Angles;
  NormalMappingTestData::Stats Interior; // the points away from seams and boundaries
  long long Invalid = 0;
};

//------------------------------------------------------------------------------
// Analytic surfaces: the mesh at a resolution, and dP/du from a point's texture coordinates.
struct Surface
{
  std::string Name;
  std::string Description;
  std::function<vtkSmartPointer<vtkPolyData>(int n)> Mesh; // 4 n^2 triangles
  std::function<Vec(double u, double v)> DPDu; // zero where dP/du is undefined (sphere poles)
  /// Not on a u seam or the boundary, where a point sees triangles on one side only.
  std::function<bool(double u, double v)> Interior;
};

// The wavy sheared height field over s in [0, 2], t in [0, 1] with (u, v) = (s, t):
// P = (s + a sin(2 pi t), t, h(s, t)), h = b sin(2 pi s) sin(2 pi t).
const double WavyShear = 0.15, WavyHeight = 0.15;

Vec WavyPoint(double s, double t)
{
  return { s + WavyShear * std::sin(2 * Pi * t),
    t,
    WavyHeight * std::sin(2 * Pi * s) * std::sin(2 * Pi * t) };
}

Vec WavyDPDs(double s, double t)
{
  return { 1.0, 0.0, WavyHeight * 2 * Pi * std::cos(2 * Pi * s) * std::sin(2 * Pi * t) };
}

Vec WavyDPDt(double s, double t)
{
  return { WavyShear * 2 * Pi * std::cos(2 * Pi * t),
    1.0,
    WavyHeight * 2 * Pi * std::sin(2 * Pi * s) * std::cos(2 * Pi * t) };
}

/// The wavy surface as a (2n x n)-quad grid in double with its analytic unit normals.
vtkSmartPointer<vtkPolyData> WavyMesh(int n)
{
  // MakeGrid's parameters are in [0, 1]^2; s spans [0, 2].
  return NormalMappingTesting::MakeGrid(
    2 * n,
    n,
    [](double a, double t) { return WavyPoint(2 * a, t); },
    [](double a, double t)
    {
      const Vec du = WavyDPDs(2 * a, t), dv = WavyDPDt(2 * a, t);
      Vec normal{
        du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]
      };
      const double length = std::sqrt(Dot(normal, normal));
      for (double& c : normal)
      {
        c /= length;
      }
      return normal;
    },
    [](double a, double t) {
      return std::array<double, 2>{ 2 * a, t };
    });
}

std::vector<Surface> Surfaces()
{
  // Around the z axis, u = azimuth / (2 pi): dP/du points along (-sin, cos, 0) of the azimuth.
  const auto aroundZ = [](double u, double) {
    return Vec{ -std::sin(2 * Pi * u), std::cos(2 * Pi * u), 0.0 };
  };
  // The texture coordinates are float or double; the seam columns have u = 0 and 1 exactly.
  const auto awayFromUSeam = [](double u, double) { return u > 1e-6 && u < 1 - 1e-6; };
  return {
    { "sphere",
      "`vtkTexturedSphereSource`, 2n x n quads split in two, double points (float normals and "
      "texture coordinates, as VTK makes them); the pole points (where dP/du is undefined) are "
      "left out, their rings are not",
      [](int n)
      {
        vtkNew<vtkTexturedSphereSource> sphere;
        sphere->SetThetaResolution(2 * n);
        sphere->SetPhiResolution(n);
        sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
        sphere->Update();
        return vtkSmartPointer<vtkPolyData>(sphere->GetOutput());
      },
      [aroundZ](double u, double v)
      {
        // VTK's v runs from 1 at the north pole to 0 at the south pole.
        return std::sin(Pi * v) < 1e-9 ? Vec{ 0, 0, 0 } : aroundZ(u, v);
      },
      awayFromUSeam },
    { "torus",
      "`vtkNormalMapping::MakeTorus` (ring radius 1, tube 0.35), 2n x n quads, double",
      [](int n)
      {
        vtkNormalMapping::TorusOptions options;
        options.U = 2 * n;
        options.V = n;
        options.DoublePrecision = true;
        return vtkNormalMapping::MakeTorus(options);
      },
      aroundZ,
      awayFromUSeam },
    { "wavy",
      "P = (s + 0.15 sin 2 pi t, t, 0.15 sin 2 pi s sin 2 pi t), (u, v) = (s, t), s in [0, 2], "
      "t in [0, 1]: a height field with a sheared (non-orthogonal) parametrization, 2n x n "
      "quads, double, analytic normals",
      WavyMesh,
      [](double u, double v) { return WavyDPDs(u, v); },
      [](double u, double v) { return u > 1e-6 && u < 2 - 1e-6 && v > 1e-6 && v < 1 - 1e-6; } },
  };
}

/// Errors of a filter's output against the analytic dP/du, over every output point where it
/// is defined (the copies of split points included).
Errors AgainstAnalytic(vtkPolyData* out, const Surface& surface)
{
  Errors errors;
  vtkDataArray* tangents = out->GetPointData()->GetTangents();
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  vtkDataArray* tcoords = out->GetPointData()->GetTCoords();
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p)
  {
    const double u = tcoords->GetComponent(p, 0), v = tcoords->GetComponent(p, 1);
    const Vec expected = surface.DPDu(u, v);
    if (Dot(expected, expected) == 0.0)
    {
      continue;
    }
    bool invalid = false;
    const double angle = TangentError(Tuple(tangents, p), expected, Tuple(normals, p), invalid);
    errors.Angles.Angles.push_back(angle);
    if (surface.Interior(u, v))
    {
      errors.Interior.Angles.push_back(angle);
    }
    errors.Invalid += invalid ? 1 : 0;
  }
  return errors;
}

vtkSmartPointer<vtkPolyData> Run(const Bench::TangentFilter& filter, vtkPolyData* mesh)
{
  auto algorithm = Bench::MakeTangentFilter(filter);
  algorithm->SetInputData(mesh);
  algorithm->Update();
  return algorithm->GetOutput();
}

std::string StatsCell(const NormalMappingTestData::Stats& s)
{
  return Bench::Format(s.Mean(), 2) + " / " + Bench::Format(s.Quantile(0.99), 2) + " / " +
    Bench::Format(s.Max(), 2);
}

/// The convergence order between two resolutions n and 2n: log2(e(n) / e(2n)); "rounding" when
/// both errors are below 1e-4 degrees, float rounding's level (a float unit vector is good to
/// ~3e-6 degrees; MikkTSpace computes in float and accumulates a few of those).
std::string Order(double coarse, double fine)
{
  if (coarse < 1e-4 && fine < 1e-4)
  {
    return "rounding";
  }
  if (!(coarse > 0.0) || !(fine > 0.0))
  {
    return "-";
  }
  return Bench::Format(std::log2(coarse / fine), 2);
}

//------------------------------------------------------------------------------
// The MikkTSpace reference meshes.
struct ReferenceErrors
{
  Errors Angles;
  long long Corners = 0, SignMismatches = 0;
  bool HasSigns = false;
};

/// Triangles whose winding (right-hand rule) points away from the sum of their corner normals.
long long WoundAgainstNormals(vtkPolyData* mesh)
{
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> ids;
  long long count = 0;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    if (ids->GetNumberOfIds() != 3 || !normals)
    {
      continue;
    }
    Vec p[3], n{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids->GetId(k), p[k].data());
      const Vec corner = Tuple(normals, ids->GetId(k));
      for (int j = 0; j < 3; ++j)
      {
        n[j] += corner[j];
      }
    }
    const Vec a{ p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const Vec b{ p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const Vec g{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    count += Dot(g, n) < 0 ? 1 : 0;
  }
  return count;
}

/// Angle between each corner's output tangent and the file's CornerTangents, over the corners
/// whose reference is not MikkTSpace's default frame ((1, 0, 0), w = -1) and is not zero (one
/// corner of noisy.vtp).
ReferenceErrors AgainstReference(vtkPolyData* input, vtkPolyData* out)
{
  ReferenceErrors r;
  vtkDataArray* reference = input->GetFieldData()->GetArray("CornerTangents");
  vtkDataArray* tangents = out->GetPointData()->GetTangents();
  vtkDataArray* signs = out->GetPointData()->GetArray("TangentSigns");
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  r.HasSigns = signs != nullptr;
  vtkCellArray* polys = out->GetPolys();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->GetCellAtId(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double ref[4];
      reference->GetTuple(3 * c + k, ref);
      const bool isDefault = ref[0] == 1.0 && ref[1] == 0.0 && ref[2] == 0.0 && ref[3] == -1.0;
      if (isDefault || !(Dot({ ref[0], ref[1], ref[2] }, { ref[0], ref[1], ref[2] }) > 0.0))
      {
        continue;
      }
      const vtkIdType p = ids->GetId(k);
      bool invalid = false;
      // Only VTK's filter (the one without signs) is projected, as its mapper does: MikkTSpace's
      // own tangents are not exactly perpendicular to these stored normals (not unit in float),
      // so projecting ours would move them away from the reference (by up to 6.5e-4 degrees).
      r.Angles.Angles.Angles.push_back(TangentError(
        Tuple(tangents, p), { ref[0], ref[1], ref[2] }, Tuple(normals, p), invalid, !r.HasSigns));
      r.Angles.Invalid += invalid ? 1 : 0;
      r.SignMismatches += signs && (signs->GetComponent(p, 0) < 0) != (ref[3] < 0) ? 1 : 0;
      ++r.Corners;
    }
  }
  return r;
}
}

int main(int argc, char* argv[])
{
  std::string out = ".";
  std::vector<int> resolutions{ 32, 64, 128 };
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc)
    {
      out = argv[++i];
    }
    else if (arg == "--smoke")
    {
      resolutions = { 8, 16, 32 };
    }
    else
    {
      std::cerr << "usage: BenchTangentAccuracy [--out DIR] [--smoke]" << std::endl;
      return 2;
    }
  }
  const std::vector<Bench::TangentFilter> filters = Bench::TangentFilters();
  std::ostringstream md, tsv;
  tsv << "filter\tsurface\tn\ttriangles\tmean\tp99\tmax\n";

  md << "## Filter: accuracy\n\n"
     << "### Against the analytic tangent\n\n"
     << "The angle, in degrees, between each output point's tangent, projected onto the plane "
        "of the point normal (a no-op for our outputs; for `vtkPolyDataTangents`, which does not "
        "orthogonalize, it is what VTK's mapper does in its shader), and the analytic dP/du at "
        "the point's texture coordinates. Every output point where dP/du is defined counts, the "
        "copies of split points included. Each cell: mean / 99th percentile / maximum over all "
        "points, and in parentheses the mean over the **interior** points (those not on a u "
        "seam or the boundary). n x 2n quads give 4 n^2 triangles. The order is log2(error at n "
        "/ error at 2n) for the two finest resolutions: 2 means the error falls 4x per halving "
        "of the cells; \"rounding\" when both errors are below 1e-4 degrees, the level of float "
        "rounding (MikkTSpace computes in float; the sphere's normals are float).\n\n"
     << "Where they come from: a point on a u seam or a boundary sees triangles on one side "
        "only, and its tangent is a one-sided chord (the maximum, about half the angular step "
        "of a cell, falling at first order). On the sphere and the torus the interior points of "
        "these symmetric grids are exact for the methods whose weights are symmetric there, so "
        "the mean over all points is the seams' share (first order error on a shrinking share "
        "of points: second order overall); the p99 drops to the interior's error once the seam "
        "points are less than 1% of all. The wavy surface has no symmetry: its interior error is "
        "the methods' own discretization error.\n\n";
  for (const Surface& surface : Surfaces())
  {
    md << "**" << surface.Name << "**: " << surface.Description << ".\n\n| filter";
    for (int n : resolutions)
    {
      md << " | n = " << n << " (" << Bench::Count(4LL * n * n) << " triangles)";
    }
    md << " | order: mean / max / interior mean | zero or non-finite tangents |\n|---";
    for (size_t i = 0; i < resolutions.size() + 2; ++i)
    {
      md << "|---:";
    }
    md << "|\n";
    for (const Bench::TangentFilter& filter : filters)
    {
      md << "| " << filter.Name;
      std::vector<Errors> errors;
      for (int n : resolutions)
      {
        auto mesh = surface.Mesh(n);
        errors.push_back(AgainstAnalytic(Run(filter, mesh), surface));
        const auto& s = errors.back().Angles;
        md << " | " << StatsCell(s) << " (" << Bench::Format(errors.back().Interior.Mean(), 2)
           << ")";
        tsv << filter.Name << "\t" << surface.Name << "\t" << n << "\t" << mesh->GetNumberOfPolys()
            << "\t" << s.Mean() << "\t" << s.Quantile(0.99) << "\t" << s.Max() << "\n";
      }
      const Errors& coarse = errors[errors.size() - 2];
      const Errors& fine = errors.back();
      long long invalid = 0;
      for (const Errors& e : errors)
      {
        invalid += e.Invalid;
      }
      md << " | " << Order(coarse.Angles.Mean(), fine.Angles.Mean()) << " / "
         << Order(coarse.Angles.Max(), fine.Angles.Max()) << " / "
         << Order(coarse.Interior.Mean(), fine.Interior.Mean()) << " | " << invalid << " |\n";
    }
    md << "\n";
  }

  md << "### Against the MikkTSpace reference tangents\n\n";
  std::string lookedFor;
  const std::string shared = NormalMappingTestData::FindSharedData(&lookedFor);
  const std::string folder = shared + "/mikktspace";
  std::vector<std::string> files;
  if (!shared.empty() && std::filesystem::is_directory(folder))
  {
    for (const auto& entry : std::filesystem::directory_iterator(folder))
    {
      if (entry.path().extension() == ".vtp")
      {
        files.push_back(entry.path().string());
      }
    }
    std::sort(files.begin(), files.end());
  }
  if (files.empty())
  {
    md << "Skipped: the reference meshes (`shared/data/mikktspace/*.vtp`, beside the project "
          "root) were not found; looked for "
       << (shared.empty() ? lookedFor : folder) << ".\n\n";
  }
  else
  {
    md << "The meshes of `shared/data/mikktspace` (tangents computed by the original "
          "`mikktspace.c`, one per triangle corner, float input). Each corner's output tangent "
          "(that of the output point the corner uses, after splitting) against the reference, "
          "over the corners whose reference is not MikkTSpace's default frame and not zero; "
          "only `vtkPolyDataTangents`' tangents are projected as above (ours are compared as they "
          "are). Angles in degrees: mean / 99th percentile / maximum. Sign "
          "mismatches: the "
          "output's `TangentSigns` against the reference's w (`vtkPolyDataTangents` has no "
          "signs). MikkTSpace takes the sign from the winding of each triangle's texture "
          "coordinates; our weighted methods judge it against the point normal (see the "
          "README), so the two disagree mostly at the corners of triangles wound against their "
          "normals (counted after the mesh's name).\n\n"
       << "| mesh | corners | filter | mean / p99 / max | sign mismatches | zero or non-finite "
          "tangents |\n|---|---:|---|---:|---:|---:|\n";
    std::vector<ReferenceErrors> totals(filters.size());
    for (const std::string& file : files)
    {
      vtkNew<vtkXMLPolyDataReader> reader;
      reader->SetFileName(file.c_str());
      reader->Update();
      vtkPolyData* mesh = reader->GetOutput();
      std::string name = std::filesystem::path(file).stem().string();
      if (const long long against = WoundAgainstNormals(mesh))
      {
        name += " (" + Bench::Count(against) + " of " + Bench::Count(mesh->GetNumberOfPolys()) +
          " triangles wound against their normals)";
      }
      if (!mesh->GetFieldData()->GetArray("CornerTangents"))
      {
        md << "| " << name << " | - | (no CornerTangents: not a reference mesh) | - | - | - |\n";
        continue;
      }
      for (size_t f = 0; f < filters.size(); ++f)
      {
        const ReferenceErrors r = AgainstReference(mesh, Run(filters[f], mesh));
        md << "| " << name << " | " << Bench::Count(r.Corners) << " | " << filters[f].Name << " | "
           << StatsCell(r.Angles.Angles) << " | "
           << (r.HasSigns ? std::to_string(r.SignMismatches) : std::string("-")) << " | "
           << r.Angles.Invalid << " |\n";
        auto& all = totals[f];
        all.Angles.Angles.Angles.insert(all.Angles.Angles.Angles.end(),
          r.Angles.Angles.Angles.begin(),
          r.Angles.Angles.Angles.end());
        all.Angles.Invalid += r.Angles.Invalid;
        all.Corners += r.Corners;
        all.SignMismatches += r.SignMismatches;
        all.HasSigns = r.HasSigns;
      }
    }
    md << "\nAll " << files.size() << " meshes together:\n\n"
       << "| filter | corners | mean / p99 / max | sign mismatches | zero or non-finite tangents "
          "|\n|---|---:|---:|---:|---:|\n";
    for (size_t f = 0; f < filters.size(); ++f)
    {
      const auto& all = totals[f];
      md << "| " << filters[f].Name << " | " << Bench::Count(all.Corners) << " | "
         << StatsCell(all.Angles.Angles) << " | "
         << (all.HasSigns ? std::to_string(all.SignMismatches) : std::string("-")) << " | "
         << all.Angles.Invalid << " |\n";
      tsv << filters[f].Name << "\tmikktspace-reference\t0\t" << all.Corners << "\t"
          << all.Angles.Angles.Mean() << "\t" << all.Angles.Angles.Quantile(0.99) << "\t"
          << all.Angles.Angles.Max() << "\n";
    }
    md << "\n";
  }
  const bool written = Bench::WriteText(out + "/accuracy.md", md.str()) &&
    Bench::WriteText(out + "/accuracy.tsv", tsv.str());
  return written ? 0 : 1;
}
