// SPDX-License-Identifier: BSD-3-Clause
// normalmap: tangent frames for normal mapping from the command line.
//
//   normalmap <command> [options]    (normalmap --help, normalmap <command> --help)
#include "NormalMapTool.h"

#include "NormalMapFiles.h"

#include <cstring>
#include <exception>
#include <iostream>
#include <new>

namespace
{
// One row per subcommand.
const NormalMapTool::Command Commands[] = {
  { "tangents",
    "compute tangent frames of a mesh and write .vtp, .gltf or .glb",
    &NormalMapTool::TangentsCommand },
  { "check",
    "say whether a mesh's tangents are right, and name the defect",
    &NormalMapTool::CheckCommand },
  { "render",
    "draw a mesh with its normal map offscreen and write a PNG",
    &NormalMapTool::RenderCommand },
  { "demo",
    "render the built-in scene (mirrored UVs, procedural map) and print measurements",
    &NormalMapTool::DemoCommand },
};

void PrintUsage(std::ostream& os)
{
  os << "usage: normalmap <command> [options]\n\ncommands:\n";
  for (const auto& command : Commands)
  {
    os << "  " << command.Name << std::string(12 - std::strlen(command.Name), ' ')
       << command.Summary << "\n";
  }
  os << "\n'normalmap <command> --help' describes a command.\n";
}
}

int NormalMapTool::Fail(const char* command, const std::string& message, int code)
{
  std::cerr << "normalmap" << (command ? " " : "") << (command ? command : "")
            << ": error: " << message << std::endl;
  return code;
}

bool NormalMapTool::IsMeshFile(const std::string& path)
{
  const std::string ext = NormalMapFiles::Extension(path);
  for (const char* known : { ".vtp", ".vtm", ".vtk", ".ply", ".obj", ".stl", ".gltf", ".glb" })
  {
    if (ext == known)
    {
      return true;
    }
  }
  return false;
}

std::string NormalMapTool::CheckInputAndOutput(const std::vector<std::string>& positional,
  const std::string& output,
  const char* outputHint,
  std::string& input)
{
  if (positional.size() != 1)
  {
    return positional.empty() ? "no input file" : "more than one input file";
  }
  input = positional.front();
  if (output.empty())
  {
    return std::string("no output file (-o ") + outputHint + ")";
  }
  if (!IsMeshFile(input))
  {
    return "'" + input + "': unknown input format (.vtp .vtm .vtk .ply .obj .stl .gltf .glb)";
  }
  return std::string();
}

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    PrintUsage(std::cerr);
    return NormalMapTool::Usage;
  }
  const std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help")
  {
    PrintUsage(std::cout);
    return NormalMapTool::Success;
  }
  for (const auto& command : Commands)
  {
    if (name == command.Name)
    {
      try
      {
        return command.Run(argc - 1, argv + 1);
      }
      catch (const std::bad_alloc&)
      {
        return NormalMapTool::Fail(command.Name, "out of memory");
      }
      catch (const std::exception& e)
      {
        return NormalMapTool::Fail(command.Name, e.what());
      }
    }
  }
  return NormalMapTool::Fail(
    nullptr, "unknown command '" + name + "' (see normalmap --help)", NormalMapTool::Usage);
}
