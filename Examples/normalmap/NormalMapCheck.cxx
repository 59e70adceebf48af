// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapCheck.h"

#include "NormalMapFiles.h"
#include "NormalMapGLTF.h"
#include "NormalMapTangents.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <ostream>
#include <sstream>

namespace NormalMapCheck
{
namespace
{
constexpr double DegreesPerRadian = 57.29577951308232;

/// Unit direction of a supplied tangent, or false when it is not finite or zero.
bool SuppliedDirection(const vtkNormalMapping::SuppliedFrameArrays& supplied,
  vtkIdType id,
  std::array<double, 3>& direction,
  double& sign)
{
  vtkNormalMapping::SuppliedFrame(supplied, id, direction.data(), sign);
  const double length = std::sqrt(
    direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  if (!std::isfinite(length) || !(length > 0.0) || !std::isfinite(sign))
  {
    return false;
  }
  for (double& c : direction)
  {
    c /= length;
  }
  return true;
}

/// Angle in degrees between unit vectors, accurate near 0 (atan2 of |a x b| and a.b).
double AngleDegrees(const std::array<double, 3>& a, const double b[3])
{
  const double cross[3] = {
    a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
  };
  const double sine = std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  return std::atan2(sine, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) * DegreesPerRadian;
}

/// Value at fraction q of sorted values (nearest rank).
double Quantile(const std::vector<double>& sorted, double q)
{
  if (sorted.empty())
  {
    return 0.0;
  }
  const size_t rank = static_cast<size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size() - 1, rank > 0 ? rank - 1 : 0)];
}

/// Whether two supplied frames differ (DifferingAngleDegrees, or in sign).
bool FramesDiffer(const vtkNormalMapping::SuppliedFrameArrays& supplied, vtkIdType a, vtkIdType b)
{
  std::array<double, 3> ta, tb;
  double sa, sb;
  const bool fa = SuppliedDirection(supplied, a, ta, sa);
  const bool fb = SuppliedDirection(supplied, b, tb, sb);
  if (!fa || !fb)
  {
    return fa != fb;
  }
  return (sa > 0.0) != (sb > 0.0) || AngleDegrees(ta, tb.data()) > DifferingAngleDegrees;
}

/// Groups of vertices with bit-identical position, normal and texture coordinates whose
/// supplied frames differ.
vtkIdType CountInconsistentDuplicates(vtkPolyData* mesh,
  vtkDataArray* normals,
  vtkDataArray* uvs,
  const vtkNormalMapping::SuppliedFrameArrays& supplied)
{
  using Key = std::array<double, 8>;
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<Key> keys(static_cast<size_t>(n));
  for (vtkIdType p = 0; p < n; ++p)
  {
    Key& k = keys[p];
    mesh->GetPoint(p, k.data());
    normals->GetTuple(p, k.data() + 3);
    k[6] = uvs->GetComponent(p, 0);
    k[7] = uvs->GetNumberOfComponents() > 1 ? uvs->GetComponent(p, 1) : 0.0;
  }
  std::vector<vtkIdType> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&](vtkIdType a, vtkIdType b) { return keys[a] < keys[b]; });
  vtkIdType groups = 0;
  for (size_t begin = 0; begin < order.size();)
  {
    size_t end = begin + 1;
    bool differ = false;
    for (; end < order.size() && keys[order[end]] == keys[order[begin]]; ++end)
    {
      differ = differ || FramesDiffer(supplied, order[begin], order[end]);
    }
    groups += differ ? 1 : 0;
    begin = end;
  }
  return groups;
}

/// MikkTSpace on the mesh, without splitting, so that point i is input point i.
MikkTSpaceComparison CompareWithMikkTSpace(vtkPolyData* mesh,
  const std::string& tcoordsName,
  const vtkNormalMapping::SuppliedFrameArrays& supplied,
  const std::vector<unsigned char>& defects,
  bool vDown)
{
  MikkTSpaceComparison result;
  NormalMapTangents::Options options;
  options.Method = vtkPolyDataTangentFrames::MIKKTSPACE;
  options.Splitting = false;
  options.TCoordsName = tcoordsName;
  options.VDown = vDown;
  NormalMapTangents::Counts counts;
  std::vector<std::string> warnings;
  std::string error;
  vtkSmartPointer<vtkPolyData> mikk =
    NormalMapTangents::Compute(mesh, options, counts, warnings, error);
  vtkDataArray* tangents =
    mikk ? mikk->GetPointData()->GetArray(vtkPolyDataTangentFrames::TangentsArrayName()) : nullptr;
  vtkDataArray* signs =
    mikk ? mikk->GetPointData()->GetArray(vtkPolyDataTangentFrames::SignsArrayName()) : nullptr;
  if (!tangents || !signs || tangents->GetNumberOfTuples() != mesh->GetNumberOfPoints())
  {
    return result;
  }
  std::vector<double> angles;
  angles.reserve(static_cast<size_t>(mesh->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    std::array<double, 3> t;
    double sign;
    if (!SuppliedDirection(supplied, p, t, sign))
    {
      continue;
    }
    double m[3];
    tangents->GetTuple(p, m);
    const double angle = AngleDegrees(t, m);
    const bool signAgrees = (sign > 0.0) == (signs->GetComponent(p, 0) > 0.0);
    angles.push_back(angle);
    result.SignsAgree += signAgrees ? 1 : 0;
    const unsigned char againstWinding =
      vtkNormalMapping::DefectSignAgainstWinding | vtkNormalMapping::DefectMixedWinding;
    result.SignsWrong += !signAgrees && (defects[p] & againstWinding) ? 1 : 0;
    result.Differing += !signAgrees || angle > DifferingAngleDegrees ? 1 : 0;
  }
  std::sort(angles.begin(), angles.end());
  result.Compared = static_cast<vtkIdType>(angles.size());
  result.MedianDegrees = Quantile(angles, 0.5);
  result.P99Degrees = Quantile(angles, 0.99);
  result.MaxDegrees = angles.empty() ? 0.0 : angles.back();
  return result;
}

std::string Percent(vtkIdType count, vtkIdType total)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << (total > 0 ? 100.0 * count / total : 0.0) << "%";
  return os.str();
}

std::string Number(double value, int precision)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << value;
  return os.str();
}

/// The defects of a report, each named with its extent; empty when there is none.
std::vector<std::string> Defects(const Report& r)
{
  const vtkNormalMapping::FrameCheckCounts& c = r.Counts;
  const vtkIdType n = r.Vertices;
  std::vector<std::string> defects;
  if (!r.HasNormals)
  {
    defects.push_back("tangents without normals (glTF viewers ignore them)");
    return defects;
  }
  if (c.NonFinite > 0)
  {
    defects.push_back("NaN or infinite tangents on " + Percent(c.NonFinite, n) + " of vertices");
  }
  if (c.SignNotUnit > 0)
  {
    defects.push_back("w is not +1 or -1 on " + Percent(c.SignNotUnit, n) + " of vertices");
  }
  const vtkIdType wrong = r.MikkTSpace.SignsWrong;
  if (2 * wrong > r.MikkTSpace.Compared)
  {
    defects.push_back("signs look computed on flipped v: w is opposite to the UV winding and "
                      "to MikkTSpace on " +
      Percent(wrong, n) + " of vertices");
  }
  else if (wrong > 0 && (c.PositiveSigns == c.Points - c.NonFinite || c.PositiveSigns == 0))
  {
    defects.push_back("w is " + std::string(c.PositiveSigns ? "+1" : "-1") +
      " everywhere: mirrored UV islands shade inside out (" + Percent(wrong, n) + " of vertices)");
  }
  else if (wrong > 0)
  {
    defects.push_back("w against the UV winding and MikkTSpace on " + Percent(wrong, n) +
      " of vertices (they shade inside out)");
  }
  if (c.NotPerpendicular > 0)
  {
    defects.push_back("tangents not orthogonalized to the normal on " +
      Percent(c.NotPerpendicular, n) + " of vertices (|T.N| up to " +
      Number(c.MaxCosineToNormal, 3) + ")");
  }
  if (c.NotUnit > 0)
  {
    defects.push_back("tangents not normalized on " + Percent(c.NotUnit, n) +
      " of vertices (|T| off 1 by up to " + Number(c.MaxLengthError, 3) + ")");
  }
  return defects;
}

/// The verdict line and whether it is OK.
void Judge(Report& r)
{
  if (!r.HasTangents)
  {
    r.Ok = true;
    r.Verdict = "OK: no tangents (viewers compute MikkTSpace)";
    return;
  }
  const std::vector<std::string> defects = Defects(r);
  r.Ok = defects.empty();
  if (!r.Ok)
  {
    r.Verdict = defects.front();
    for (size_t i = 1; i < defects.size(); ++i)
    {
      r.Verdict += "; " + defects[i];
    }
    return;
  }
  const MikkTSpaceComparison& m = r.MikkTSpace;
  if (m.Compared > 0 && m.Differing == 0)
  {
    r.Verdict = "OK: matches MikkTSpace";
  }
  else if (m.Compared > 0 && m.Differing <= MikkTSpaceLikeFraction * m.Compared)
  {
    r.Verdict = "OK: MikkTSpace-like (" + std::to_string(m.Differing) +
      " vertices differ by over " + Number(DifferingAngleDegrees, 0) + " degree or in sign)";
  }
  else
  {
    r.Verdict = "OK: valid, not MikkTSpace (" + Percent(m.Differing, m.Compared) +
      " of vertices differ, median " + Number(m.MedianDegrees, 2) + " degrees)";
  }
}

std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (const char ch : text)
  {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\')
    {
      out += '\\';
      out += ch;
    }
    else if (c < 0x20)
    {
      char buffer[8];
      std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
      out += buffer;
    }
    else
    {
      out += ch;
    }
  }
  return out + "\"";
}
} // namespace

Report CheckMesh(vtkPolyData* mesh,
  const std::string& name,
  const std::string& tcoordsName,
  const std::string& tangentsName,
  bool vDown)
{
  Report r;
  r.Name = name;
  r.Vertices = mesh->GetNumberOfPoints();
  r.VDown = vDown || NormalMapTangents::IsVDown(mesh);
  std::string problem;
  const vtkNormalMapping::SuppliedFrameArrays supplied =
    vtkNormalMapping::FindSuppliedFrames(mesh, tangentsName, problem);
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkDataArray* uvs = NormalMapTangents::FindTCoords(mesh, tcoordsName);
  r.HasTangents = supplied.IsUsable();
  r.HasNormals =
    normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() >= r.Vertices;
  r.HasTCoords = uvs != nullptr;
  if (r.HasTangents && r.HasNormals)
  {
    const vtkNormalMapping::FrameCheck check =
      vtkNormalMapping::CheckSuppliedFrames(mesh, normals, uvs, supplied, r.VDown);
    r.Counts = check.Counts;
    if (uvs)
    {
      r.InconsistentDuplicates = CountInconsistentDuplicates(mesh, normals, uvs, supplied);
      r.MikkTSpace = CompareWithMikkTSpace(mesh, tcoordsName, supplied, check.Defects, r.VDown);
    }
  }
  Judge(r);
  return r;
}

bool CheckFile(const std::string& path,
  const std::string& tangentsName,
  bool vDown,
  std::vector<Report>& reports,
  std::string& error,
  std::vector<std::string>* warnings)
{
  const std::string ext = NormalMapFiles::Extension(path);
  if (ext == ".vtm")
  {
    std::vector<NormalMapFiles::Block> blocks;
    std::vector<std::string> skipped;
    const bool read = NormalMapFiles::ReadVTMBlocks(path, blocks, skipped, error);
    if (warnings)
    {
      warnings->insert(warnings->end(), skipped.begin(), skipped.end());
    }
    if (!read)
    {
      return false;
    }
    for (const NormalMapFiles::Block& block : blocks)
    {
      reports.push_back(CheckMesh(block.Mesh, block.Name, block.TCoordsName, tangentsName, vDown));
    }
    return true;
  }
  if (ext != ".gltf" && ext != ".glb")
  {
    vtkSmartPointer<vtkPolyData> mesh = NormalMapFiles::ReadVTKMesh(path, error);
    if (!mesh)
    {
      return false;
    }
    reports.push_back(CheckMesh(mesh, "mesh", std::string(), tangentsName, vDown));
    return true;
  }
  NormalMapGLTF::Document doc;
  if (!NormalMapGLTF::ReadDocument(path, doc, error))
  {
    return false;
  }
  for (const NormalMapGLTF::PrimitiveId& id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (!mesh)
    {
      error = "'" + path + "': " + error;
      return false;
    }
    const std::string name = NormalMapGLTF::PrimitiveName(id);
    reports.push_back(
      CheckMesh(mesh, name, NormalMapGLTF::NormalTextureTexCoordName(doc, id), tangentsName, true));
  }
  if (reports.empty())
  {
    error = "'" + path + "' has no triangle primitive";
    return false;
  }
  return true;
}

void PrintText(std::ostream& os, const std::string& path, const std::vector<Report>& reports)
{
  const vtkNormalMapping::FrameCheckTolerances tol;
  os << "normalmap check: " << path << "\n"
     << "  tolerances: | |T| - 1 | <= " << tol.Unit << ", |T.N| / |T| <= " << tol.Perpendicular
     << ", | |w| - 1 | <= " << tol.Sign << "; a vertex differs from MikkTSpace by over "
     << DifferingAngleDegrees << " degree or in sign\n";
  for (const Report& r : reports)
  {
    const vtkNormalMapping::FrameCheckCounts& c = r.Counts;
    const vtkIdType n = r.Vertices;
    const auto line = [&](const char* label, vtkIdType count)
    { return std::string(label) + std::to_string(count) + " (" + Percent(count, n) + ")"; };
    os << r.Name << ": " << n << " vertices, " << (r.HasTangents ? "tangents" : "no tangents")
       << (r.HasNormals ? ", normals" : ", no normals")
       << (r.HasTCoords ? (r.VDown ? ", UVs (v down)" : ", UVs (v up)") : ", no UVs") << "\n";
    if (r.HasTangents && r.HasNormals)
    {
      os << "  " << line("non-finite          ", c.NonFinite) << "\n"
         << "  " << line("not unit            ", c.NotUnit) << ", max | |T| - 1 | "
         << Number(c.MaxLengthError, 4) << "\n"
         << "  " << line("not perpendicular   ", c.NotPerpendicular) << ", max |T.N| "
         << Number(c.MaxCosineToNormal, 4) << "\n"
         << "  " << line("w not +-1           ", c.SignNotUnit) << "\n";
      if (r.HasTCoords)
      {
        const MikkTSpaceComparison& m = r.MikkTSpace;
        os << "  " << line("w agrees with UVs   ", c.SignAgreesWithWinding) << "; against "
           << c.SignAgainstWinding << ", mixed windings " << c.MixedWinding << ", no UV area "
           << c.NoWinding << "\n"
           << "  identical vertices with different tangents: " << r.InconsistentDuplicates
           << " groups\n"
           << "  vs MikkTSpace       angle median " << Number(m.MedianDegrees, 3) << ", p99 "
           << Number(m.P99Degrees, 3) << ", max " << Number(m.MaxDegrees, 2)
           << " degrees; sign agrees " << Percent(m.SignsAgree, m.Compared) << "; " << m.Differing
           << " vertices differ\n"
           << "  " << line("w against UVs and MikkTSpace ", m.SignsWrong)
           << " (shade inside out)\n";
      }
    }
    os << "  verdict: " << r.Verdict << "\n";
  }
}

void PrintJson(std::ostream& os, const std::string& path, const std::vector<Report>& reports)
{
  const vtkNormalMapping::FrameCheckTolerances tol;
  const bool ok = std::all_of(reports.begin(), reports.end(), [](const Report& r) { return r.Ok; });
  os << std::setprecision(9) << "{\"file\": " << JsonString(path)
     << ", \"ok\": " << (ok ? "true" : "false") << ",\n \"tolerances\": {\"unit\": " << tol.Unit
     << ", \"perpendicular\": " << tol.Perpendicular << ", \"sign\": " << tol.Sign
     << ", \"differing_degrees\": " << DifferingAngleDegrees << "},\n \"primitives\": [";
  for (size_t i = 0; i < reports.size(); ++i)
  {
    const Report& r = reports[i];
    const vtkNormalMapping::FrameCheckCounts& c = r.Counts;
    const MikkTSpaceComparison& m = r.MikkTSpace;
    os << (i ? ",\n  " : "\n  ") << "{\"name\": " << JsonString(r.Name)
       << ", \"vertices\": " << r.Vertices << ", \"tangents\": " << std::boolalpha << r.HasTangents
       << ", \"normals\": " << r.HasNormals << ", \"tcoords\": " << r.HasTCoords
       << ", \"v_down\": " << r.VDown << ", \"non_finite\": " << c.NonFinite
       << ", \"not_unit\": " << c.NotUnit << ", \"not_perpendicular\": " << c.NotPerpendicular
       << ", \"w_not_unit\": " << c.SignNotUnit
       << ", \"sign_against_winding\": " << c.SignAgainstWinding
       << ", \"mixed_winding\": " << c.MixedWinding
       << ", \"sign_agrees_with_winding\": " << c.SignAgreesWithWinding
       << ", \"no_winding\": " << c.NoWinding << ", \"max_length_error\": " << c.MaxLengthError
       << ", \"max_cos_to_normal\": " << c.MaxCosineToNormal
       << ", \"inconsistent_duplicates\": " << r.InconsistentDuplicates
       << ", \"mikktspace\": {\"compared\": " << m.Compared
       << ", \"median_degrees\": " << m.MedianDegrees << ", \"p99_degrees\": " << m.P99Degrees
       << ", \"max_degrees\": " << m.MaxDegrees << ", \"signs_agree\": " << m.SignsAgree
       << ", \"differing\": " << m.Differing << ", \"signs_wrong\": " << m.SignsWrong
       << "}, \"ok\": " << r.Ok << ", \"verdict\": " << JsonString(r.Verdict) << "}"
       << std::noboolalpha;
  }
  os << "\n ]}\n";
}
}
