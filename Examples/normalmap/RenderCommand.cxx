// SPDX-License-Identifier: BSD-3-Clause
// normalmap render: draws a mesh offscreen with vtkNormalMapPolyDataMapper and writes a PNG
// (see UsageText below).
#include "NormalMapFiles.h"
#include "NormalMapGLTF.h"
#include "NormalMapImages.h"
#include "NormalMapPatterns.h"
#include "NormalMapRender.h"
#include "NormalMapTangents.h"
#include "NormalMapTool.h"

#include <vtkAppendPolyData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkNormalMapPolyDataMapper.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkStringArray.h>
#include <vtkTexture.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
constexpr const char* Name = "render";

const char* UsageText =
  R"(usage: normalmap render IN -o OUT.png [options]

Draws IN offscreen with vtkNormalMapPolyDataMapper and writes the picture as PNG.

  IN   .vtp, .vtk, .ply, .obj, .gltf or .glb with texture coordinates (glTF: every triangle
       primitive, with the first normal texture found)

options:
  -o, --output OUT.png      the picture (written whole or not at all)
  --normal-map PNG          the normal map (PNG or JPEG); default: the glTF material's normal
                            texture (a file, or PNG or JPEG embedded in the glTF), else a
                            built-in procedural map (bricks with rivets)
  --encoding E              opengl (default; +Y green) | directx (-Y green) | rg (two
                            channels) | object (object-space normals; needs --normal-map)
  --strength S              normal map strength (default 1, or the glTF normalTexture.scale)
  --frame F                 tangents: the file's tangents, else computed (MikkTSpace);
                            derivatives: per-pixel frames from screen-space derivatives;
                            default: the file's tangents if it has them, else derivatives
  --lighting L              phong (default) | pbr
  --size WxH                picture size in pixels, 16..8192 each (default 800x600)
  --camera A,E,Z            azimuth and elevation in degrees, zoom factor (default 0,0,1),
                            applied after fitting the camera to the mesh
  -h, --help                this text

Rendering needs an OpenGL context: with Debian's VTK an X display, also offscreen (run under
Xvfb on a machine without one). Without one the command fails with one error line.
)";

struct Arguments
{
  std::string Input;
  std::string Output;
  std::string NormalMap;
  int Encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
  std::string EncodingName = "opengl";
  double Strength = 1.0;
  bool StrengthGiven = false;
  std::string Frame; // empty: automatic
  bool PBR = false;
  int Width = 800;
  int Height = 600;
  double Camera[3] = { 0.0, 0.0, 1.0 };
  bool Help = false;
};

bool ParseNumber(const std::string& text, double& value)
{
  std::istringstream in(text);
  in >> value;
  return !in.fail() && in.eof() && std::isfinite(value);
}

bool ParseCamera(const std::string& text, double camera[3])
{
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, ','))
  {
    parts.push_back(part);
  }
  if (parts.size() != 3)
  {
    return false;
  }
  for (int i = 0; i < 3; ++i)
  {
    if (!ParseNumber(parts[i], camera[i]))
    {
      return false;
    }
  }
  return camera[2] > 0.0;
}

std::string Parse(int argc, char* argv[], Arguments& args)
{
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help")
    {
      args.Help = true;
      continue;
    }
    if (arg.size() > 1 && arg[0] == '-')
    {
      const bool known = arg == "-o" || arg == "--output" || arg == "--normal-map" ||
        arg == "--encoding" || arg == "--strength" || arg == "--frame" || arg == "--lighting" ||
        arg == "--size" || arg == "--camera";
      if (!known)
      {
        return "unknown option '" + arg + "'";
      }
      if (i + 1 >= argc)
      {
        return arg + " needs a value";
      }
      const std::string value = argv[++i];
      if (arg == "-o" || arg == "--output")
      {
        args.Output = value;
      }
      else if (arg == "--normal-map")
      {
        args.NormalMap = value;
      }
      else if (arg == "--encoding")
      {
        args.EncodingName = value;
        if (value == "opengl")
          args.Encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_OPENGL;
        else if (value == "directx")
          args.Encoding = vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX;
        else if (value == "rg")
          args.Encoding = vtkNormalMapPolyDataMapper::TWO_CHANNEL_OPENGL;
        else if (value == "object")
          args.Encoding = vtkNormalMapPolyDataMapper::OBJECT_SPACE;
        else
          return "unknown encoding '" + value + "' (opengl, directx, rg, object)";
      }
      else if (arg == "--strength")
      {
        if (!ParseNumber(value, args.Strength) || args.Strength < 0.0)
        {
          return "--strength needs a number >= 0, not '" + value + "'";
        }
        args.StrengthGiven = true;
      }
      else if (arg == "--frame")
      {
        if (value != "tangents" && value != "derivatives")
        {
          return "unknown frame '" + value + "' (tangents, derivatives)";
        }
        args.Frame = value;
      }
      else if (arg == "--lighting")
      {
        if (value != "phong" && value != "pbr")
        {
          return "unknown lighting '" + value + "' (phong, pbr)";
        }
        args.PBR = value == "pbr";
      }
      else if (arg == "--size")
      {
        if (!NormalMapRender::ParseSize(value, args.Width, args.Height))
        {
          return "bad --size '" + value + "' (WxH, each 16..8192, e.g. 800x600)";
        }
      }
      else if (!ParseCamera(value, args.Camera))
      {
        return "bad --camera '" + value + "' (azimuth,elevation,zoom with zoom > 0)";
      }
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
    NormalMapTool::CheckInputAndOutput(positional, args.Output, "OUT.png", args.Input);
  if (!error.empty())
  {
    return error;
  }
  if (NormalMapFiles::Extension(args.Output) != ".png")
  {
    return "'" + args.Output + "': the output must be a .png file";
  }
  const std::string in = NormalMapFiles::Extension(args.Input);
  if (args.Encoding == vtkNormalMapPolyDataMapper::OBJECT_SPACE && args.NormalMap.empty() &&
    in != ".gltf" && in != ".glb")
  {
    return "--encoding object needs --normal-map (the built-in map is tangent-space)";
  }
  return std::string();
}

std::string FieldString(vtkPolyData* mesh, const char* name)
{
  auto* array = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}

double FieldNumber(vtkPolyData* mesh, const char* name, double fallback)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? array->GetComponent(0, 0) : fallback;
}

// glTF stores v pointing down; the mapper and vtkPNGReader's images have v up. Flipping v
// keeps the tangents and their signs, which point the bitangent to the top of the image.
void FlipToVUp(vtkPolyData* mesh)
{
  vtkDataArray* uv = mesh->GetPointData()->GetTCoords();
  vtkNew<vtkFloatArray> flipped;
  flipped->SetName(uv->GetName());
  flipped->SetNumberOfComponents(2);
  flipped->SetNumberOfTuples(uv->GetNumberOfTuples());
  for (vtkIdType i = 0; i < uv->GetNumberOfTuples(); ++i)
  {
    flipped->SetTypedTuple(i,
      std::array<float, 2>{ static_cast<float>(uv->GetComponent(i, 0)),
        static_cast<float>(1.0 - uv->GetComponent(i, 1)) }
        .data());
  }
  mesh->GetPointData()->SetTCoords(flipped);
  mesh->GetFieldData()->RemoveArray(NormalMapTangents::VDownArrayName);
}

struct Input
{
  vtkSmartPointer<vtkPolyData> Mesh;
  std::string NormalTextureFile; // from the glTF material
  double NormalTextureScale = 1.0;
  vtkSmartPointer<vtkImageData> EmbeddedTexture; // the glTF material's, decoded from the file
  std::string EmbeddedTextureText;               // what it is, for the report
  std::vector<std::string> Warnings;
};

// The normal texture image embedded in the glTF file (a data: URI or a buffer view), decoded;
// when it cannot be, a warning and the built-in map.
void DecodeEmbeddedTexture(const NormalMapGLTF::Document& doc, int image, Input& input)
{
  std::vector<unsigned char> bytes;
  std::string mimeType, error;
  if (NormalMapGLTF::EmbeddedImage(doc, image, bytes, mimeType, error))
  {
    input.EmbeddedTexture = NormalMapImages::Decode(bytes.data(), bytes.size(), error);
    if (!input.EmbeddedTexture && NormalMapImages::Format(bytes.data(), bytes.size()).empty() &&
      !mimeType.empty())
    {
      error += " (its mimeType says " + mimeType + ")";
    }
  }
  if (!input.EmbeddedTexture)
  {
    input.Warnings.push_back(
      "cannot use the file's normal texture: " + error + "; using the built-in map");
    return;
  }
  int dims[3];
  input.EmbeddedTexture->GetDimensions(dims);
  input.EmbeddedTextureText = "embedded image " + std::to_string(image) + " (" +
    NormalMapImages::Format(bytes.data(), bytes.size()) + ", " + std::to_string(dims[0]) + "x" +
    std::to_string(dims[1]) + ")";
}

bool ReadGLTF(const std::string& path, Input& input, std::string& error)
{
  NormalMapGLTF::Document doc;
  if (!NormalMapGLTF::ReadDocument(path, doc, error))
  {
    return false;
  }
  vtkNew<vtkAppendPolyData> append;
  int kept = 0;
  int embeddedImage = -1;
  for (const auto& id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (!mesh)
    {
      error = "'" + path + "': " + error;
      return false;
    }
    const std::string uv = NormalMapGLTF::NormalTextureTexCoordName(doc, id);
    vtkDataArray* tcoords = NormalMapTangents::FindTCoords(mesh, uv);
    if (!tcoords)
    {
      input.Warnings.push_back("mesh " + std::to_string(id.Mesh) + " primitive " +
        std::to_string(id.Primitive) + " has no " + uv + "; not drawn");
      continue;
    }
    mesh->GetPointData()->SetTCoords(tcoords);
    FlipToVUp(mesh);
    if (input.NormalTextureFile.empty() && FieldNumber(mesh, "NormalTextureImage", -1) >= 0)
    {
      input.NormalTextureFile = FieldString(mesh, "NormalTextureFile");
      input.NormalTextureScale = FieldNumber(mesh, "NormalTextureScale", 1.0);
      if (input.NormalTextureFile.empty())
      {
        embeddedImage = static_cast<int>(FieldNumber(mesh, "NormalTextureImage", -1));
      }
    }
    append->AddInputData(mesh);
    ++kept;
  }
  if (kept == 0)
  {
    error = "'" + path + "' has no triangle primitive with texture coordinates";
    return false;
  }
  if (embeddedImage >= 0)
  {
    DecodeEmbeddedTexture(doc, embeddedImage, input);
  }
  append->Update();
  input.Mesh = append->GetOutput();
  return true;
}

bool ReadInput(const std::string& path, Input& input, std::string& error)
{
  const std::string ext = NormalMapFiles::Extension(path);
  if (ext == ".gltf" || ext == ".glb")
  {
    return ReadGLTF(path, input, error);
  }
  input.Mesh = NormalMapFiles::ReadVTKMesh(path, error);
  if (!input.Mesh)
  {
    return false;
  }
  if (!NormalMapTangents::FindTCoords(input.Mesh, std::string()))
  {
    error = "'" + path + "' has no texture coordinates, which a normal map needs" +
      (ext == ".stl" ? " (STL files cannot store them)" : "");
    return false;
  }
  return true;
}
}

int NormalMapTool::RenderCommand(int argc, char* argv[])
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
    return Fail(Name, usageError + " (see normalmap render --help)", Usage);
  }
  std::string error;
  NormalMapFiles::OutputTransaction output;
  if (!output.Begin(args.Output, error))
  {
    return Fail(Name, error);
  }

  Input input;
  if (!ReadInput(args.Input, input, error))
  {
    return Fail(Name, error);
  }
  vtkSmartPointer<vtkPolyData> mesh = input.Mesh;
  if (!mesh->GetPointData()->GetNormals())
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(mesh);
    normals->SplittingOff();
    normals->Update();
    mesh = normals->GetOutput();
  }

  // The frame.
  std::string frameText;
  int frameSource = vtkNormalMapPolyDataMapper::AUTOMATIC;
  const bool hasTangents = mesh->GetPointData()->GetTangents() != nullptr;
  if (args.Frame == "derivatives")
  {
    frameSource = vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES;
    frameText = "screen-space derivatives";
  }
  else if (args.Frame == "tangents")
  {
    frameSource = vtkNormalMapPolyDataMapper::POINT_TANGENTS;
    frameText = "point tangents from the file";
    if (!hasTangents)
    {
      NormalMapTangents::Options options; // MikkTSpace: what normal maps are baked against
      NormalMapTangents::Counts counts;
      mesh = NormalMapTangents::Compute(mesh, options, counts, input.Warnings, error);
      if (!mesh)
      {
        return Fail(Name, "'" + args.Input + "': " + error);
      }
      frameText = "point tangents computed (MikkTSpace, " + std::to_string(counts.SplitPoints) +
        " points split)";
    }
  }
  else
  {
    frameText = hasTangents ? "automatic: the file's point tangents"
                            : "automatic: screen-space derivatives (no tangents in the file)";
  }

  // The normal map.
  std::string mapText;
  vtkSmartPointer<vtkImageData> image;
  const std::string mapFile = args.NormalMap.empty() ? input.NormalTextureFile : args.NormalMap;
  if (!mapFile.empty())
  {
    image = NormalMapRender::ReadImage(mapFile, error);
    if (!image)
    {
      return Fail(Name, error);
    }
    int dims[3];
    image->GetDimensions(dims);
    mapText = mapFile + " (" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + ")";
  }
  else if (input.EmbeddedTexture)
  {
    image = input.EmbeddedTexture;
    mapText = input.EmbeddedTextureText;
  }
  else if (args.Encoding == vtkNormalMapPolyDataMapper::OBJECT_SPACE)
  {
    return Fail(Name,
      "'" + args.Input + "' has no normal texture file, and --encoding object needs --normal-map",
      Usage);
  }
  else
  {
    const auto encoding = args.Encoding == vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX
      ? NormalMapPatterns::Encoding::DirectX
      : (args.Encoding == vtkNormalMapPolyDataMapper::TWO_CHANNEL_OPENGL
            ? NormalMapPatterns::Encoding::TwoChannel
            : NormalMapPatterns::Encoding::OpenGL);
    image = NormalMapPatterns::MakeBrickNormalMap(NormalMapPatterns::Bricks(), 512, encoding);
    mapText = "built-in bricks with rivets (512x512, procedural)";
  }
  vtkSmartPointer<vtkTexture> texture = NormalMapRender::MakeTexture(image);

  NormalMapRender::Scene scene;
  scene.Mesh = mesh;
  scene.NormalMap = texture;
  scene.Strength =
    args.StrengthGiven ? args.Strength : (args.NormalMap.empty() ? input.NormalTextureScale : 1.0);
  scene.Encoding = args.Encoding;
  scene.FrameSource = frameSource;
  scene.PBR = args.PBR;
  scene.Width = args.Width;
  scene.Height = args.Height;
  scene.Azimuth = args.Camera[0];
  scene.Elevation = args.Camera[1];
  scene.Zoom = args.Camera[2];
  NormalMapRender::Rendered rendered;
  if (!NormalMapRender::Render(scene, rendered, error))
  {
    return Fail(Name, error);
  }
  if (!NormalMapRender::WritePNG(rendered.Image, output, error) || !output.Commit(error))
  {
    return Fail(Name, error);
  }

  for (const std::string& w : input.Warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
  for (const std::string& w : rendered.Warnings)
  {
    std::cerr << "normalmap " << Name << ": warning: " << w << "\n";
  }
  std::cout << std::fixed << std::setprecision(1) << "normalmap render: " << args.Input << " -> "
            << args.Output << "\n"
            << "  mesh          " << mesh->GetNumberOfPoints() << " points, "
            << mesh->GetNumberOfPolys() << " polygons\n"
            << "  normal map    " << mapText << ", " << args.EncodingName << ", strength "
            << scene.Strength << "\n"
            << "  frame         " << frameText << "; the mapper applied: " << rendered.AppliedFrame
            << "\n"
            << "  lighting      " << (args.PBR ? "PBR" : "Phong") << "\n"
            << "  picture       " << args.Width << "x" << args.Height << "\n"
            << "  render        " << rendered.FirstFrameMs << " ms first frame, "
            << rendered.NextFrameMs << " ms the next\n"
            << "  rendering     " << rendered.Window << "; OpenGL renderer " << rendered.Renderer
            << "\n";
  return Success;
}
