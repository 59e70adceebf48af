// SPDX-License-Identifier: BSD-3-Clause
// normalmap tangents: reads a mesh, computes its tangent frames with vtkPolyDataTangentFrames
// and writes them (see Usage below).
#include "NormalMapFiles.h"
#include "NormalMapGLTF.h"
#include "NormalMapTangents.h"
#include "NormalMapTool.h"

#include <vtkAppendPolyData.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
constexpr const char* Name = "tangents";

const char* UsageText =
  R"(usage: normalmap tangents IN -o OUT [options]

Computes tangent frames (unit tangents and handedness signs) for normal mapping.

  IN   .vtp, .vtm (each polydata block), .vtk, .ply, .obj, .stl (has no UVs: always an
       error), .gltf or .glb
  OUT  .vtp (point arrays Tangents and TangentSigns), .vtm (the same, a block per glTF
       primitive where the scene's nodes place it), or .gltf / .glb (TANGENT, vec4)

options:
  -o, --output OUT   the output file (written whole or not at all)
  --method M         unweighted | area | angle | mikktspace (default: mikktspace, the
                     tangents glTF viewers and bakers use)
  --split            duplicate points whose corners need different frames (default)
  --no-split         keep the point count; conflicting points take one frame
  --uv NAME          the point array of texture coordinates (default: the active ones; for
                     glTF, TEXCOORD_<n> of the material's normal texture, else TEXCOORD_0)
  --gltf-sign        the UVs have v pointing down, as glTF's do (automatic for glTF input):
                     signs then follow glTF's TANGENT.w
  --keep-valid       keep the tangents the input has where they pass the checks of
                     'normalmap check' and compute only the others (default: compute all)
  -h, --help         this text

glTF input: every triangle primitive with the texture coordinates is computed on its own and
written back into the file, which otherwise stays as it was (materials, textures, nodes, other
primitives). Written to .vtp, several primitives are appended into one mesh, in their meshes'
coordinates; written to .vtm, each is a block of its own, once per node that draws it.
)";

struct Arguments
{
  std::string Input;
  std::string Output;
  NormalMapTangents::Options Tangents;
  bool Help = false;
};

bool ParseMethod(const std::string& text, int& method)
{
  struct Entry
  {
    const char* Name;
    int Method;
  };
  const Entry entries[] = { { "unweighted", vtkPolyDataTangentFrames::UNWEIGHTED },
    { "area", vtkPolyDataTangentFrames::AREA_WEIGHTED },
    { "angle", vtkPolyDataTangentFrames::ANGLE_WEIGHTED },
    { "mikktspace", vtkPolyDataTangentFrames::MIKKTSPACE } };
  for (const Entry& e : entries)
  {
    if (text == e.Name)
    {
      method = e.Method;
      return true;
    }
  }
  return false;
}

// Returns an empty string on success, else the usage error.
std::string Parse(int argc, char* argv[], Arguments& args)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "-h" || arg == "--help")
    {
      args.Help = true;
    }
    else if (arg == "-o" || arg == "--output" || arg == "--method" || arg == "--uv")
    {
      if (!hasValue)
      {
        return arg + " needs a value";
      }
      const std::string value = argv[++i];
      if (arg == "--method")
      {
        if (!ParseMethod(value, args.Tangents.Method))
        {
          return "unknown method '" + value + "' (unweighted, area, angle, mikktspace)";
        }
      }
      else if (arg == "--uv")
      {
        args.Tangents.TCoordsName = value;
      }
      else
      {
        args.Output = value;
      }
    }
    else if (arg == "--split" || arg == "--no-split")
    {
      args.Tangents.Splitting = arg == "--split";
    }
    else if (arg == "--gltf-sign")
    {
      args.Tangents.VDown = true;
    }
    else if (arg == "--keep-valid")
    {
      args.Tangents.SuppliedTangents = vtkPolyDataTangentFrames::KEEP_VALID;
    }
    else if (arg.size() > 1 && arg[0] == '-')
    {
      return "unknown option '" + arg + "'";
    }
    else
    {
      positional.push_back(arg);
    }
  }
  if (args.Help)
  {
    return std::string();
  }
  const std::string error =
    NormalMapTool::CheckInputAndOutput(positional, args.Output, "OUT", args.Input);
  if (!error.empty())
  {
    return error;
  }
  const std::string out = NormalMapFiles::Extension(args.Output);
  if (out != ".vtp" && out != ".vtm" && out != ".gltf" && out != ".glb")
  {
    return "'" + args.Output + "': unknown output format (.vtp .vtm .gltf .glb)";
  }
  return std::string();
}

// Progress on stderr once the work has taken half a second: one updating line on a terminal,
// a line every 10% otherwise.
class ProgressPrinter
{
public:
  void Start(int part, int parts)
  {
    this->Part = part;
    this->Parts = parts;
    this->LastTenth = -1;
  }
  void Report(double fraction)
  {
    const double elapsed = std::chrono::duration<double>(Clock::now() - this->Begin).count();
    const int tenth = static_cast<int>(fraction * 10.0);
    if (elapsed < 0.5 || (!this->Terminal && tenth == this->LastTenth))
    {
      return;
    }
    this->LastTenth = tenth;
    std::fprintf(stderr, "%scomputing tangents", this->Terminal ? "\r" : "");
    if (this->Parts > 1)
    {
      std::fprintf(stderr, " (primitive %d of %d)", this->Part + 1, this->Parts);
    }
    std::fprintf(stderr, ": %3.0f%%%s", 100.0 * fraction, this->Terminal ? "" : "\n");
    this->Shown = true;
  }
  void Finish()
  {
    if (this->Shown && this->Terminal)
    {
      std::fprintf(stderr, "\n");
    }
    this->Shown = false;
  }

private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point Begin = Clock::now();
  bool Terminal = isatty(fileno(stderr)) != 0;
  bool Shown = false;
  int Part = 0;
  int Parts = 1;
  int LastTenth = -1;
};

double Milliseconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
    .count();
}

/**
 * `mesh` as a VTK file in `folder` stores it: `uv` as the active texture coordinates, v up when
 * `vUp` (glTF's v-down coordinates turned to VTK's, so that ParaView and VTK's texture readers
 * agree with them), and the field data's NormalTextureFile (resolved against the current folder)
 * relative to `folder`, so that the file and its textures can move together.
 */
vtkSmartPointer<vtkPolyData> ForFile(vtkPolyData* mesh,
  const std::string& uv,
  bool vUp,
  const std::filesystem::path& folder)
{
  namespace fs = std::filesystem;
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  if (vtkDataArray* tcoords = NormalMapTangents::FindTCoords(mesh, uv))
  {
    copy->GetPointData()->SetTCoords(tcoords);
  }
  if (vUp && NormalMapTangents::IsVDown(copy))
  {
    NormalMapTangents::FlipToVUp(copy);
  }
  const std::string file = NormalMapFiles::FieldString(copy, "NormalTextureFile");
  if (!file.empty())
  {
    std::error_code ec;
    const fs::path texture = fs::absolute(file, ec).lexically_normal();
    const fs::path base = fs::absolute(folder, ec).lexically_normal();
    NormalMapFiles::SetFieldString(
      copy, "NormalTextureFile", texture.lexically_relative(base).generic_string());
  }
  return copy;
}

/**
 * The framed meshes as blocks named `names`, each glTF primitive (`primitives`, empty for other
 * input) where the default scene places it (NormalMapGLTF::PlaceMesh, as `render` does).
 */
vtkSmartPointer<vtkMultiBlockDataSet> SceneBlocks(const NormalMapGLTF::Document& doc,
  const std::vector<NormalMapGLTF::PrimitiveId>& primitives,
  const std::vector<vtkSmartPointer<vtkPolyData>>& framed,
  const std::vector<std::string>& names)
{
  auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  const auto placements = NormalMapGLTF::PlaceMeshes(doc);
  for (size_t i = 0; i < framed.size(); ++i)
  {
    const int mesh = primitives.empty() ? -1 : primitives[i].Mesh;
    for (const auto& placed : NormalMapGLTF::PlaceMesh(placements, mesh, framed[i], names[i]))
    {
      const unsigned int index = blocks->GetNumberOfBlocks();
      blocks->SetBlock(index, placed.Mesh);
      blocks->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), placed.Name.c_str());
    }
  }
  return blocks;
}

void PrintWarnings(const std::vector<std::string>& warnings)
{
  for (const std::string& w : warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
}
}

int NormalMapTool::TangentsCommand(int argc, char* argv[])
{
  Arguments args;
  const std::string usageError = Parse(argc, argv, args);
  if (args.Help)
  {
    std::cout << UsageText;
    return Success;
  }
  if (!usageError.empty())
  {
    return Fail(Name, usageError + " (see normalmap tangents --help)", NormalMapTool::Usage);
  }
  const auto start = std::chrono::steady_clock::now();
  std::string error;

  // The output first: an unwritable folder fails before any work is done.
  NormalMapFiles::OutputTransaction output;
  if (!output.Begin(args.Output, error))
  {
    return Fail(Name, error);
  }

  // Read: one mesh, or one mesh per glTF triangle primitive.
  const std::string inExt = NormalMapFiles::Extension(args.Input);
  const std::string outExt = NormalMapFiles::Extension(args.Output);
  const bool gltfIn = inExt == ".gltf" || inExt == ".glb";
  NormalMapGLTF::Document doc;
  std::vector<NormalMapGLTF::PrimitiveId> primitives;
  std::vector<vtkSmartPointer<vtkPolyData>> meshes;
  std::vector<std::string> uvNames;
  std::vector<std::string> names; // of the meshes, for .vtm blocks
  std::vector<std::string> warnings;
  if (gltfIn)
  {
    if (!NormalMapGLTF::ReadDocument(args.Input, doc, error))
    {
      return Fail(Name, error);
    }
    for (const auto& id : NormalMapGLTF::TrianglePrimitives(doc))
    {
      vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
      if (!mesh)
      {
        return Fail(Name, "'" + args.Input + "': " + error);
      }
      const std::string uv = args.Tangents.TCoordsName.empty()
        ? NormalMapGLTF::NormalTextureTexCoordName(doc, id)
        : args.Tangents.TCoordsName;
      const std::string name = NormalMapGLTF::PrimitiveName(id);
      if (mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
      {
        // A strip or fan of fewer than 3 vertices: nothing to give frames to.
        warnings.push_back(name + " has no triangle; left unchanged");
        continue;
      }
      if (!NormalMapTangents::FindTCoords(mesh, uv))
      {
        warnings.push_back(name + " has no " + uv + "; left unchanged");
        continue;
      }
      if (!doc.Model.meshes[id.Mesh].primitives[id.Primitive].attributes.count("NORMAL"))
      {
        // glTF viewers draw a primitive without NORMAL flat and ignore its TANGENT: the
        // output needs the normals the tangents are computed with.
        warnings.push_back(name +
          " has no NORMAL: writing the smooth normals its tangents are computed with (without "
          "NORMAL, glTF viewers draw it flat and ignore TANGENT)");
      }
      primitives.push_back(id);
      meshes.push_back(mesh);
      uvNames.push_back(uv);
      names.push_back(name);
    }
    if (meshes.empty())
    {
      return Fail(Name,
        "'" + args.Input + "' has no triangle primitive with texture coordinates" +
          (args.Tangents.TCoordsName.empty() ? "" : " '" + args.Tangents.TCoordsName + "'"));
    }
  }
  else if (inExt == ".vtm")
  {
    std::vector<NormalMapFiles::Block> blocks;
    if (!NormalMapFiles::ReadVTMBlocks(args.Input, blocks, warnings, error))
    {
      return Fail(Name, error);
    }
    for (const NormalMapFiles::Block& block : blocks)
    {
      const std::string uv =
        args.Tangents.TCoordsName.empty() ? block.TCoordsName : args.Tangents.TCoordsName;
      if (!NormalMapTangents::FindTCoords(block.Mesh, uv))
      {
        warnings.push_back(block.Name + " has no texture coordinates" +
          (uv.empty() ? std::string() : " '" + uv + "'") + "; left out");
        continue;
      }
      meshes.push_back(block.Mesh);
      uvNames.push_back(uv);
      names.push_back(block.Name);
    }
    if (meshes.empty())
    {
      return Fail(Name, "'" + args.Input + "' has no block with texture coordinates");
    }
    if (meshes.size() > 1 && outExt != ".vtm" && outExt != ".vtp")
    {
      return Fail(Name,
        "'" + args.Input + "' has " + std::to_string(meshes.size()) +
          " blocks with texture coordinates, and glTF output takes one mesh: write .vtm or .vtp");
    }
  }
  else
  {
    vtkSmartPointer<vtkPolyData> mesh = NormalMapFiles::ReadVTKMesh(args.Input, error);
    if (!mesh)
    {
      return Fail(Name, error);
    }
    if (!NormalMapTangents::FindTCoords(mesh, args.Tangents.TCoordsName))
    {
      if (inExt == ".stl")
      {
        return Fail(Name,
          "'" + args.Input +
            "': STL files have no texture coordinates, which tangent frames need (use .obj, "
            ".ply, .vtp, .vtk or glTF)");
      }
      return Fail(Name,
        "'" + args.Input + "' has no texture coordinates" +
          (args.Tangents.TCoordsName.empty() ? std::string()
                                             : " named '" + args.Tangents.TCoordsName + "'"));
    }
    meshes.push_back(mesh);
    uvNames.push_back(args.Tangents.TCoordsName);
    names.push_back("mesh");
  }
  const double readMs = Milliseconds(start);

  // Compute.
  const auto computeStart = std::chrono::steady_clock::now();
  NormalMapTangents::Counts total;
  ProgressPrinter progress;
  std::vector<vtkSmartPointer<vtkPolyData>> framed;
  for (size_t i = 0; i < meshes.size(); ++i)
  {
    NormalMapTangents::Options options = args.Tangents;
    options.TCoordsName = uvNames[i];
    NormalMapTangents::Counts counts;
    progress.Start(static_cast<int>(i), static_cast<int>(meshes.size()));
    vtkSmartPointer<vtkPolyData> result = NormalMapTangents::Compute(
      meshes[i], options, counts, warnings, error, [&progress](double f) { progress.Report(f); });
    progress.Finish();
    if (!result)
    {
      return Fail(Name, "'" + args.Input + "': " + error);
    }
    total.Add(counts);
    framed.push_back(result);
  }
  const double computeMs = Milliseconds(computeStart);

  // Write.
  const auto writeStart = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkMultiBlockDataSet> blocks;
  if (outExt == ".vtp" || outExt == ".vtm")
  {
    const std::filesystem::path folder = std::filesystem::path(args.Output).parent_path();
    for (size_t i = 0; i < framed.size(); ++i)
    {
      framed[i] = ForFile(framed[i], uvNames[i], gltfIn, folder);
    }
  }
  if (outExt == ".vtp")
  {
    vtkSmartPointer<vtkPolyData> result = framed.front();
    if (framed.size() > 1)
    {
      vtkNew<vtkAppendPolyData> append;
      for (const auto& mesh : framed)
      {
        append->AddInputData(mesh);
      }
      append->Update();
      result = append->GetOutput();
    }
    if (!NormalMapFiles::WriteVTP(result, output.MainPath(), error))
    {
      return Fail(Name, error);
    }
  }
  else if (outExt == ".vtm")
  {
    blocks = SceneBlocks(doc, primitives, framed, names);
    if (!NormalMapFiles::WriteVTM(blocks, output.MainPath(), error))
    {
      return Fail(Name, error);
    }
  }
  else
  {
    bool ok = true;
    if (gltfIn)
    {
      for (size_t i = 0; i < framed.size() && ok; ++i)
      {
        ok = NormalMapGLTF::UpdatePrimitive(doc, primitives[i], framed[i], error);
      }
      if (!ok)
      {
        return Fail(Name, "'" + args.Input + "': " + error); // an input defect, as when read
      }
    }
    else
    {
      ok = NormalMapGLTF::DocumentFromPolyData(framed.front(), uvNames.front(), doc, error);
    }
    if (!ok || !NormalMapGLTF::WriteDocument(doc, output, error))
    {
      return Fail(Name, error);
    }
  }
  if (!output.Commit(error))
  {
    return Fail(Name, error);
  }
  const double writeMs = Milliseconds(writeStart);

  PrintWarnings(warnings);
  const bool vDown = args.Tangents.VDown || gltfIn || NormalMapTangents::IsVDown(meshes.front());
  std::cout << std::fixed << std::setprecision(1) << "normalmap tangents: " << args.Input << " -> "
            << args.Output << "\n"
            << "  method                "
            << vtkPolyDataTangentFrames::GetMethodName(args.Tangents.Method)
            << (vDown ? " (UVs v-down, glTF signs)" : " (UVs v-up)") << "\n";
  if (gltfIn)
  {
    std::cout << "  primitives            " << meshes.size() << " computed\n";
  }
  if (blocks)
  {
    std::cout << "  blocks                " << blocks->GetNumberOfBlocks()
              << (gltfIn ? " (placed by the scene's nodes)" : "") << "\n";
  }
  std::cout << "  points                " << total.InputPoints << " in, " << total.OutputPoints
            << " out\n"
            << "  triangles             " << total.Triangles << "\n"
            << "  points split          " << total.SplitPoints
            << (args.Tangents.Splitting ? "" : " (splitting off)") << "\n"
            << "  degenerate triangles  " << total.DegenerateTriangles << "\n"
            << "  fallback points       " << total.FallbackPoints << "\n";
  if (args.Tangents.SuppliedTangents == vtkPolyDataTangentFrames::KEEP_VALID)
  {
    std::cout << "  tangents replaced     " << total.ReplacedTangents << " of " << total.InputPoints
              << " (the others kept)\n";
  }
  std::cout << "  time                  " << Milliseconds(start) << " ms (read " << readMs
            << ", tangents " << computeMs << ", write " << writeMs << ")\n";
  return Success;
}
