// SPDX-License-Identifier: BSD-3-Clause
// normalmap check: says whether a mesh's supplied tangents are right, and names the defect.
#include "NormalMapCheck.h"
#include "NormalMapFiles.h"
#include "NormalMapTool.h"

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr const char* Name = "check";

const char* UsageText =
  R"(usage: normalmap check FILE [options]

Checks the tangents a mesh carries (glTF TANGENT, or a VTK file's tangents array) and prints,
per primitive: the vertices whose tangent is non-finite, not unit, not perpendicular to the
normal, whose w is not +1 or -1, whose w disagrees with the winding of the UVs (those shade
inside out); identical vertices with different tangents; the angle to MikkTSpace computed on the
same mesh (median, p99, max) and the sign agreement; and a one-line verdict naming the defect.

  FILE   .gltf or .glb (every triangle primitive, with the UVs of its normal texture), or
         .vtp / .vtk with point Normals, texture coordinates and tangents (4 components, or 3
         plus the point array TangentSigns), or .vtm (every polydata block, as a .vtp)

options:
  --json             one JSON object on stdout instead of the text report
  --tangents NAME    the point array of tangents (VTK files; default: the active tangents,
                     else 'Tangents')
  --gltf-sign        the UVs of a VTK file have v pointing down, as glTF's do: w is expected to
                     be glTF's (automatic for glTF and for files marked TCoordsVDown)
  -h, --help         this text

exit code: 0 every primitive is fine (or has no tangents), 1 some primitive's tangents are
wrong, 2 the file cannot be read or the command line is wrong.
)";
}

int NormalMapTool::CheckCommand(int argc, char* argv[])
{
  bool json = false;
  bool vDown = false;
  std::string tangentsName;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      std::cout << UsageText;
      return Success;
    }
    if (arg == "--json")
    {
      json = true;
    }
    else if (arg == "--gltf-sign")
    {
      vDown = true;
    }
    else if (arg == "--tangents" && i + 1 < argc)
    {
      tangentsName = argv[++i];
    }
    else if (arg.size() > 1 && arg[0] == '-')
    {
      return Fail(Name, "unknown option '" + arg + "' (see normalmap check --help)", Usage);
    }
    else
    {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 1)
  {
    return Fail(Name,
      std::string(positional.empty() ? "no input file" : "more than one input file") +
        " (see normalmap check --help)",
      Usage);
  }
  const std::string& path = positional.front();
  if (!IsMeshFile(path))
  {
    return Fail(Name,
      "'" + path + "': unknown input format (.vtp .vtm .vtk .ply .obj .stl .gltf .glb)",
      Usage);
  }
  std::vector<NormalMapCheck::Report> reports;
  std::vector<std::string> warnings;
  std::string error;
  {
    NormalMapFiles::VTKMessageCapture messages; // the reports say what matters
    if (!NormalMapCheck::CheckFile(path, tangentsName, vDown, reports, error, &warnings))
    {
      return Fail(Name, error, Unreadable);
    }
  }
  for (const std::string& w : warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
  if (json)
  {
    NormalMapCheck::PrintJson(std::cout, path, reports);
  }
  else
  {
    NormalMapCheck::PrintText(std::cout, path, reports);
  }
  const bool ok = std::all_of(
    reports.begin(), reports.end(), [](const NormalMapCheck::Report& r) { return r.Ok; });
  return ok ? Success : Failure;
}
