// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target for the normalmap tool's glTF path: arbitrary bytes are read as a .gltf
// (JSON) or .glb (binary, by its "glTF" magic) with NormalMapGLTF, and when they read, every
// triangle primitive goes through the tool's `tangents` path (NormalMapTangents::Compute, the
// filter with MikkTSpace and with its default method, glTF signs), is written back into the
// document, the document written to a file (.gltf + .bin, or .glb) and read back. Any broken
// invariant aborts, so libFuzzer reports it with the input:
// - no crash, leak or undefined behaviour (AddressSanitizer + UBSan, scripts/sanitize.sh; the
//   sanitizer build compiles tinygltf itself from its header, so its accesses are checked too);
// - a failure is one clean error line: not empty, no line break;
// - a primitive that reads and has the normal texture's UV set gets tangents (the filter
//   reports no error on what the reader built);
// - what the tool writes reads back; each updated primitive's TANGENT is unit (1e-6), its w
//   exactly +1 or -1, one per vertex of the filter's output, perpendicular to a usable NORMAL;
// - `render`'s placement by the scene's nodes ends (also on deep or cyclic hierarchies), places
//   each node at most once, and its placed copies keep the primitive's points and cells.
//
// The seed corpus (Testing/Fuzz/gltf-corpus, written by make_gltf_corpus.py) holds small valid
// and nearly valid files; gltf.dict is a dictionary of glTF's keys and values for -dict=.
//
// Harness limits (not findings): the first read resolves external URIs against a folder that
// does not exist, and external image URIs are replaced by a missing file name before writing, so
// that no file outside the harness's own temporary folder is read; inputs declaring an accessor
// of more than kMaxElements elements are skipped, so that each run stays short.
#include "NormalMapGLTF.h"
#include "NormalMapTangents.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkDataArray.h>
#include <vtkLogger.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

constexpr size_t kMaxElements = 1 << 12;
/// Where the first read resolves external URIs: nothing there, so nothing is read.
const char* const kNoFolder = "/nonexistent-normalmap-fuzz";

std::string WorkDir;

/// How far the inputs got, printed at exit when NORMALMAP_FUZZ_STATS is set (to see how much
/// of a corpus reaches the tangents and the writer).
struct Stats
{
  long Inputs = 0, Read = 0, Computed = 0, Written = 0;
} Reached;

[[noreturn]] void Fail(const std::string& what)
{
  std::fprintf(stderr, "FuzzNormalMapGLTF invariant violated: %s\n", what.c_str());
  std::abort();
}

void Require(bool ok, const std::string& what)
{
  if (!ok)
  {
    Fail(what);
  }
}

/// The tool prints `error` as its one error line.
void RequireCleanError(const std::string& error, const std::string& context)
{
  Require(!error.empty(), context + ": failed without an error message");
  Require(error.find_first_of("\r\n") == std::string::npos,
    context + ": error message on more than one line: " + error);
}

/// Inputs the harness does not run (see the top): accessors declaring more than kMaxElements.
bool WithinLimits(const NormalMapGLTF::Document& doc)
{
  for (const tinygltf::Accessor& accessor : doc.Model.accessors)
  {
    if (accessor.count > kMaxElements)
    {
      return false;
    }
  }
  return true;
}

/// No file outside WorkDir may be read back: external image URIs point at a missing file.
void NeutralizeImageURIs(NormalMapGLTF::Document& doc)
{
  for (tinygltf::Image& image : doc.Model.images)
  {
    if (!image.uri.empty() && image.uri.compare(0, 5, "data:") != 0)
    {
      image.uri = "missing-image.png";
    }
  }
}

double Dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The frames of one updated primitive as read back from the written file.
void CheckWrittenTangents(vtkPolyData* mesh,
  vtkIdType expectedPoints,
  int method,
  const std::string& context)
{
  vtkPointData* pd = mesh->GetPointData();
  vtkDataArray* t = pd->GetArray(vtkPolyDataTangentFrames::TangentsArrayName());
  vtkDataArray* w = pd->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  vtkDataArray* n = pd->GetNormals();
  Require(t && w, context + ": the written primitive has no TANGENT");
  Require(mesh->GetNumberOfPoints() == expectedPoints && t->GetNumberOfTuples() == expectedPoints,
    context + ": TANGENT count differs from the computed points");
  // The float TANGENT.xyz is written unit to 4 float ulps (TangentVec4) and read back exactly:
  // |T| - 1 <= ~5e-7; 1e-6 bounds it. Perpendicular to the normal within the filter's own
  // contract (1e-6 for the weighted methods' Gram-Schmidt; 1e-4 for MikkTSpace, which keeps
  // the reference's tangents that far off), plus the float rounding of T (~2e-7).
  const double perpendicular = method == vtkPolyDataTangentFrames::MIKKTSPACE ? 1e-4 : 1e-6;
  for (vtkIdType p = 0; p < expectedPoints; ++p)
  {
    double tv[3];
    t->GetTuple(p, tv);
    const std::string at = context + " vertex " + std::to_string(p);
    const double length = std::sqrt(Dot3(tv, tv));
    Require(std::isfinite(length) && std::abs(length - 1.0) <= 1e-6, at + ": TANGENT not unit");
    const double sign = w->GetComponent(p, 0);
    Require(sign == 1.0 || sign == -1.0, at + ": TANGENT.w not +1 or -1");
    if (n)
    {
      double nv[3];
      n->GetTuple(p, nv);
      const double nl = std::sqrt(Dot3(nv, nv));
      if (std::isfinite(nl) && nl > 1e-30)
      {
        Require(std::abs(Dot3(tv, nv)) / nl <= perpendicular + 1e-6,
          at + ": TANGENT not perpendicular to NORMAL");
      }
    }
  }
}

/// The `tangents` command on one document, as TangentsCommand.cxx runs it, with `method`.
void RunTangents(NormalMapGLTF::Document doc, int method, bool splitting, bool binary)
{
  const std::string context = std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
    (splitting ? ", splitting, " : ", no splitting, ") + (binary ? ".glb" : ".gltf");
  std::string error;
  std::vector<NormalMapGLTF::PrimitiveId> updated;
  std::vector<vtkIdType> points;
  for (const NormalMapGLTF::PrimitiveId& id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    const std::string where =
      context + ", mesh " + std::to_string(id.Mesh) + " primitive " + std::to_string(id.Primitive);
    vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (!mesh)
    {
      RequireCleanError(error, where + " (reading)");
      return; // the tool stops at the first corrupt primitive
    }
    if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
    {
      continue; // no triangle: left unchanged, as the tool does (with a warning)
    }
    NormalMapTangents::Options options;
    options.Method = method;
    options.Splitting = splitting;
    options.TCoordsName = NormalMapGLTF::NormalTextureTexCoordName(doc, id);
    if (!NormalMapTangents::FindTCoords(mesh, options.TCoordsName))
    {
      continue; // left unchanged, as the tool does (with a warning)
    }
    NormalMapTangents::Counts counts;
    std::vector<std::string> warnings;
    vtkSmartPointer<vtkPolyData> framed =
      NormalMapTangents::Compute(mesh, options, counts, warnings, error);
    Require(framed != nullptr, where + ": no tangents for a primitive that read: " + error);
    if (!NormalMapGLTF::UpdatePrimitive(doc, id, framed, error))
    {
      RequireCleanError(error, where + " (updating)");
      return;
    }
    updated.push_back(id);
    points.push_back(framed->GetNumberOfPoints());
    ++Reached.Computed;
  }
  if (updated.empty())
  {
    return; // the tool fails: no triangle primitive with texture coordinates
  }
  NeutralizeImageURIs(doc);
  const std::string path = WorkDir + (binary ? "/out.glb" : "/out.gltf");
  if (!NormalMapGLTF::WriteDocument(doc, path, error))
  {
    RequireCleanError(error, context + " (writing)");
    return;
  }
  ++Reached.Written;
  NormalMapGLTF::Document back;
  Require(NormalMapGLTF::ReadDocument(path, back, error),
    context + ": the written file does not read back: " + error);
  for (size_t i = 0; i < updated.size(); ++i)
  {
    const std::string where = context + ", written mesh " + std::to_string(updated[i].Mesh) +
      " primitive " + std::to_string(updated[i].Primitive);
    vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(back, updated[i], error);
    Require(mesh != nullptr, where + ": does not read back: " + error);
    CheckWrittenTangents(mesh, points[i], method, where);
  }
  std::error_code ignored;
  for (const char* name : { "/out.glb", "/out.gltf", "/out.bin" })
  {
    fs::remove(WorkDir + name, ignored);
  }
}
/// What `render` does with the scene's nodes: every placement of every triangle primitive
/// (a copy with as many points, normals and tangents), and each node placed at most once.
void RunPlacements(const NormalMapGLTF::Document& doc)
{
  const auto placements = NormalMapGLTF::PlaceMeshes(doc);
  Require(placements.size() == doc.Model.meshes.size(), "placements: one list per mesh");
  size_t total = 0;
  for (const auto& mesh : placements)
  {
    total += mesh.size();
  }
  Require(total <= doc.Model.nodes.size(), "placements: a node placed more than once");
  std::string error;
  for (const NormalMapGLTF::PrimitiveId& id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (!mesh)
    {
      return;
    }
    for (const auto& placed : NormalMapGLTF::PlaceMesh(placements, id.Mesh, mesh, "fuzz"))
    {
      Require(placed.Mesh->GetNumberOfPoints() == mesh->GetNumberOfPoints() &&
          placed.Mesh->GetNumberOfCells() == mesh->GetNumberOfCells(),
        "placements: the placed copy has other points or cells");
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // The filter's messages are captured by NormalMapTangents; everything else stays quiet.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  std::string pattern = (fs::temp_directory_path() / "normalmap-fuzz-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
  {
    Fail("cannot make a temporary folder");
  }
  WorkDir = pattern;
  std::atexit(
    []()
    {
      std::error_code ignored;
      fs::remove_all(WorkDir, ignored);
      if (std::getenv("NORMALMAP_FUZZ_STATS"))
      {
        std::printf("inputs %ld, read %ld, primitives given tangents %ld (3 runs each), "
                    "documents written and read back %ld\n",
          Reached.Inputs,
          Reached.Read,
          Reached.Computed,
          Reached.Written);
      }
    });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  NormalMapGLTF::Document doc;
  std::string error;
  ++Reached.Inputs;
  if (!NormalMapGLTF::ReadDocumentFromMemory(data, size, kNoFolder, doc, error))
  {
    RequireCleanError(error, "reading");
    return 0;
  }
  ++Reached.Read;
  if (!WithinLimits(doc))
  {
    return 0;
  }
  // The tool's default (MikkTSpace, splitting), the filter's default method, and MikkTSpace
  // without splitting; .glb and .gltf outputs alternate with the input's kind.
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  RunTangents(doc, vtkPolyDataTangentFrames::MIKKTSPACE, true, glb);
  RunTangents(doc, vtkPolyDataTangentFrames::ANGLE_WEIGHTED, true, !glb);
  RunTangents(doc, vtkPolyDataTangentFrames::MIKKTSPACE, false, !glb);
  RunPlacements(doc);
  return 0;
}
