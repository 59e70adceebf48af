// SPDX-License-Identifier: BSD-3-Clause
// The normalmap command-line tool: one function per subcommand, each in its own file
// (<Name>Command.cxx), listed in the table in NormalMapTool.cxx.
#ifndef NormalMapTool_h
#define NormalMapTool_h

#include <string>
#include <vector>

namespace NormalMapTool
{
/// A subcommand: `argv[0]` is its name; returns the process exit code.
using CommandFunction = int (*)(int argc, char* argv[]);

struct Command
{
  const char* Name;
  const char* Summary;
  CommandFunction Run;
};

/// Exit codes shared by the subcommands.
enum ExitCode
{
  Success = 0,
  Failure = 1,    // the input could not be read or processed, or the output written
  Usage = 2,      // the command line is wrong
  Unreadable = 2, // check: the input cannot be read (Failure means its tangents are wrong)
};

/// Prints "normalmap <command>: error: <message>" as one line on stderr and returns `code`.
int Fail(const char* command, const std::string& message, int code = Failure);

/// Whether `path` names a mesh format the tool reads (.vtp .vtk .ply .obj .stl .gltf .glb).
bool IsMeshFile(const std::string& path);

/**
 * The command-line checks shared by commands that read one mesh and write one output: exactly
 * one positional argument (stored in `input`), an output given (`outputHint` names it in the
 * message) and a readable mesh format. Returns an empty string or the usage error.
 */
std::string CheckInputAndOutput(const std::vector<std::string>& positional,
  const std::string& output,
  const char* outputHint,
  std::string& input);

int TangentsCommand(int argc, char* argv[]);
int CheckCommand(int argc, char* argv[]);
int RenderCommand(int argc, char* argv[]);
int DemoCommand(int argc, char* argv[]);
}

#endif
