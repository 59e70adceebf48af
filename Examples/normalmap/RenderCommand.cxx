// SPDX-License-Identifier: BSD-3-Clause
// normalmap render: draws a mesh offscreen with vtkNormalMapPolyDataMapper, or a glTF file's
// primitives with vtkNormalMapCompositePolyDataMapper, and writes a PNG (see UsageText below).
#include "NormalMapFiles.h"
#include "NormalMapGLTF.h"
#include "NormalMapImages.h"
#include "NormalMapPatterns.h"
#include "NormalMapRender.h"
#include "NormalMapTangents.h"
#include "NormalMapTool.h"

#include <vtkBoundingBox.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkNormalMapPolyDataMapper.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTexture.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr const char* Name = "render";

const char* UsageText =
  R"(usage: normalmap render IN -o OUT.png [options]

Draws IN offscreen and writes the picture as PNG.

  IN   .vtp, .vtk, .ply, .obj (vtkNormalMapPolyDataMapper), .gltf or .glb with texture
       coordinates: every triangle primitive with its material's normal texture, as blocks of
       vtkNormalMapCompositePolyDataMapper (one per normal texture; primitives whose material
       has none are drawn without a map, unless no material has one); .vtm: every polydata
       block so, with the normal texture file its field data names (as 'tangents' writes it)

options:
  -o, --output OUT.png      the picture (written whole or not at all)
  --normal-map PNG          the normal map (PNG or JPEG) for every primitive; default: each
                            glTF material's normal texture (a file, or PNG or JPEG embedded in
                            the glTF), else a built-in procedural map (bricks with rivets)
  --encoding E              opengl (default; +Y green) | directx (-Y green) | rg (two
                            channels) | object (object-space normals; needs --normal-map)
  --strength S              normal map strength (default 1, or each glTF normalTexture.scale)
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

double FieldNumber(vtkPolyData* mesh, const char* name, double fallback)
{
  vtkDataArray* array = mesh->GetFieldData()->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? array->GetComponent(0, 0) : fallback;
}

/// One mesh of the input: a glTF triangle primitive, or the whole file.
struct Primitive
{
  vtkSmartPointer<vtkPolyData> Mesh;
  std::string Name;                // "mesh 0 primitive 1" (glTF), empty for other files
  int GLTFMesh = -1;               // glTF: the mesh it belongs to
  bool HasNormalTexture = false;   // its glTF material has a normal texture:
  std::string NormalTextureFile;   // as a file (resolved), or
  int EmbeddedImage = -1;          // embedded in the glTF file
  double NormalTextureScale = 1.0; // glTF normalTexture.scale
};

struct Input
{
  std::vector<Primitive> Primitives;
  bool GLTF = false;
  bool Blocks = false;              // drawn as blocks of the composite mapper (glTF, .vtm)
  NormalMapGLTF::Document Document; // glTF: the embedded images
  std::vector<std::string> Warnings;
};

// The normal texture image embedded in the glTF file (a data: URI or a buffer view), decoded
// and described; nullptr with `error` when it cannot be.
vtkSmartPointer<vtkImageData> DecodeEmbeddedTexture(const NormalMapGLTF::Document& doc,
  int image,
  std::string& text,
  std::string& error)
{
  std::vector<unsigned char> bytes;
  std::string mimeType;
  vtkSmartPointer<vtkImageData> decoded;
  if (NormalMapGLTF::EmbeddedImage(doc, image, bytes, mimeType, error))
  {
    decoded = NormalMapImages::Decode(bytes.data(), bytes.size(), error);
    if (!decoded && NormalMapImages::Format(bytes.data(), bytes.size()).empty() &&
      !mimeType.empty())
    {
      error += " (its mimeType says " + mimeType + ")";
    }
  }
  if (decoded)
  {
    int dims[3];
    decoded->GetDimensions(dims);
    text = "embedded image " + std::to_string(image) + " (" +
      NormalMapImages::Format(bytes.data(), bytes.size()) + ", " + std::to_string(dims[0]) + "x" +
      std::to_string(dims[1]) + ")";
  }
  return decoded;
}

bool ReadGLTF(const std::string& path, Input& input, std::string& error)
{
  NormalMapGLTF::Document& doc = input.Document;
  if (!NormalMapGLTF::ReadDocument(path, doc, error))
  {
    return false;
  }
  input.GLTF = true;
  input.Blocks = true;
  for (const auto& id : NormalMapGLTF::TrianglePrimitives(doc))
  {
    Primitive primitive;
    primitive.Mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
    if (!primitive.Mesh)
    {
      error = "'" + path + "': " + error;
      return false;
    }
    primitive.Name = NormalMapGLTF::PrimitiveName(id);
    primitive.GLTFMesh = id.Mesh;
    vtkPolyData* mesh = primitive.Mesh;
    const std::string uv = NormalMapGLTF::NormalTextureTexCoordName(doc, id);
    vtkDataArray* tcoords = NormalMapTangents::FindTCoords(mesh, uv);
    if (!tcoords)
    {
      input.Warnings.push_back(primitive.Name + " has no " + uv + "; not drawn");
      continue;
    }
    mesh->GetPointData()->SetTCoords(tcoords);
    // glTF's v points down; the mapper and the images read from files have v up.
    NormalMapTangents::FlipToVUp(mesh);
    if (FieldNumber(mesh, "NormalTextureImage", -1) >= 0)
    {
      // A normal texture comes from the primitive's material.
      const int material = doc.Model.meshes[id.Mesh].primitives[id.Primitive].material;
      const auto& info = doc.Model.materials[static_cast<size_t>(material)].normalTexture;
      const auto transform = info.extensions.find("KHR_texture_transform");
      if (transform != info.extensions.end() &&
        (transform->second.Has("offset") || transform->second.Has("rotation") ||
          transform->second.Has("scale")))
      {
        input.Warnings.push_back(primitive.Name +
          ": the normal texture's KHR_texture_transform offset, rotation and scale are not "
          "applied");
      }
      primitive.HasNormalTexture = true;
      primitive.NormalTextureFile = NormalMapFiles::FieldString(mesh, "NormalTextureFile");
      primitive.NormalTextureScale = FieldNumber(mesh, "NormalTextureScale", 1.0);
      if (primitive.NormalTextureFile.empty())
      {
        primitive.EmbeddedImage = static_cast<int>(FieldNumber(mesh, "NormalTextureImage", -1));
      }
    }
    input.Primitives.push_back(primitive);
  }
  if (input.Primitives.empty())
  {
    error = "'" + path + "' has no triangle primitive with texture coordinates";
    return false;
  }
  return true;
}

/**
 * The polydata blocks of a VTK multiblock file, each drawn as a glTF primitive is: with the
 * texture coordinates and normal texture file its field data names (as `tangents` writes them
 * from glTF), v flipped where they are v-down.
 */
bool ReadBlocks(const std::string& path, Input& input, std::string& error)
{
  std::vector<NormalMapFiles::Block> blocks;
  if (!NormalMapFiles::ReadVTMBlocks(path, blocks, input.Warnings, error))
  {
    return false;
  }
  input.Blocks = true;
  for (const NormalMapFiles::Block& block : blocks)
  {
    Primitive primitive;
    primitive.Mesh = block.Mesh;
    primitive.Name = block.Name;
    vtkPolyData* mesh = primitive.Mesh;
    vtkDataArray* tcoords = NormalMapTangents::FindTCoords(mesh, block.TCoordsName);
    if (!tcoords)
    {
      input.Warnings.push_back(block.Name + " has no texture coordinates; not drawn");
      continue;
    }
    mesh->GetPointData()->SetTCoords(tcoords);
    if (NormalMapTangents::IsVDown(mesh))
    {
      NormalMapTangents::FlipToVUp(mesh);
    }
    const std::string file = NormalMapFiles::FieldString(mesh, "NormalTextureFile");
    if (!file.empty())
    {
      primitive.HasNormalTexture = true;
      primitive.NormalTextureFile = file;
      primitive.NormalTextureScale = block.NormalTextureScale;
    }
    else if (FieldNumber(mesh, "NormalTextureImage", -1) >= 0)
    {
      input.Warnings.push_back(block.Name +
        ": its normal texture was embedded in the glTF file, which this file does not hold");
    }
    input.Primitives.push_back(primitive);
  }
  if (input.Primitives.empty())
  {
    error = "'" + path + "' has no block with texture coordinates";
    return false;
  }
  return true;
}

bool ReadInput(const std::string& path, Input& input, std::string& error)
{
  const std::string ext = NormalMapFiles::Extension(path);
  if (ext == ".gltf" || ext == ".glb")
  {
    return ReadGLTF(path, input, error);
  }
  if (ext == ".vtm")
  {
    return ReadBlocks(path, input, error);
  }
  Primitive whole;
  whole.Mesh = NormalMapFiles::ReadVTKMesh(path, error);
  if (!whole.Mesh)
  {
    return false;
  }
  input.Primitives.push_back(whole);
  vtkDataArray* tcoords = NormalMapTangents::FindTCoords(whole.Mesh, std::string());
  if (!tcoords)
  {
    error = "'" + path + "' has no texture coordinates, which a normal map needs" +
      (ext == ".stl" ? " (STL files cannot store them)" : "");
    return false;
  }
  // A mesh whose v points down says so (TCoordsVDown field data).
  if (NormalMapTangents::IsVDown(whole.Mesh))
  {
    whole.Mesh->GetPointData()->SetTCoords(tcoords);
    NormalMapTangents::FlipToVUp(whole.Mesh);
  }
  return true;
}
}

/// Normals where a primitive has none, and point tangents (MikkTSpace) where --frame tangents
/// asks for them and the file has none; `text` says what the frame is, for the report.
bool PrepareFrames(const Arguments& args,
  Input& input,
  int& frameSource,
  std::string& text,
  std::string& error)
{
  const size_t total = input.Primitives.size();
  size_t withTangents = 0, computed = 0;
  NormalMapTangents::Counts counts;
  for (Primitive& primitive : input.Primitives)
  {
    if (!primitive.Mesh->GetPointData()->GetNormals())
    {
      vtkNew<vtkPolyDataNormals> normals;
      normals->SetInputData(primitive.Mesh);
      normals->SplittingOff();
      normals->Update();
      primitive.Mesh = normals->GetOutput();
    }
    if (primitive.Mesh->GetPointData()->GetTangents())
    {
      ++withTangents;
    }
    else if (args.Frame == "tangents")
    {
      NormalMapTangents::Options options; // MikkTSpace: what normal maps are baked against
      NormalMapTangents::Counts one;
      primitive.Mesh =
        NormalMapTangents::Compute(primitive.Mesh, options, one, input.Warnings, error);
      if (!primitive.Mesh)
      {
        error = "'" + args.Input + "': " + error;
        return false;
      }
      counts.Add(one);
      ++computed;
    }
  }
  // "k of n primitives" where some primitives differ from the others.
  const auto some = [total](size_t k)
  {
    return total > 1 ? " (" + std::to_string(k) + " of " + std::to_string(total) + " primitives)"
                     : std::string();
  };
  if (args.Frame == "derivatives")
  {
    frameSource = vtkNormalMapPolyDataMapper::SCREEN_DERIVATIVES;
    text = "screen-space derivatives";
  }
  else if (args.Frame == "tangents")
  {
    frameSource = vtkNormalMapPolyDataMapper::POINT_TANGENTS;
    text = computed == 0 ? "point tangents from the file"
                         : "point tangents computed" + (withTangents ? some(computed) : "") +
        " (MikkTSpace, " + std::to_string(counts.SplitPoints) + " points split)";
  }
  else if (withTangents == total)
  {
    text = "automatic: the file's point tangents";
  }
  else if (withTangents == 0)
  {
    text = "automatic: screen-space derivatives (no tangents in the file)";
  }
  else
  {
    text = "automatic: the file's point tangents" + some(withTangents) +
      ", else screen-space derivatives";
  }
  return true;
}

/// The normal map a primitive is drawn with.
struct MapChoice
{
  vtkSmartPointer<vtkImageData> Image; // none: drawn without a map
  std::string Text;                    // what it is, for the report
  double Strength = 1.0;
};

/// The built-in map, in the encoding asked for.
MapChoice BuiltInMap(const Arguments& args)
{
  const auto encoding = args.Encoding == vtkNormalMapPolyDataMapper::TANGENT_SPACE_DIRECTX
    ? NormalMapPatterns::Encoding::DirectX
    : (args.Encoding == vtkNormalMapPolyDataMapper::TWO_CHANNEL_OPENGL
          ? NormalMapPatterns::Encoding::TwoChannel
          : NormalMapPatterns::Encoding::OpenGL);
  MapChoice choice;
  choice.Image = NormalMapPatterns::MakeBrickNormalMap(NormalMapPatterns::Bricks(), 512, encoding);
  choice.Text = "built-in bricks with rivets (512x512, procedural)";
  return choice;
}

/**
 * Each primitive's normal map: --normal-map for all; else its glTF material's normal texture
 * (a file, or an image embedded in the file; one that cannot be decoded gives a warning and
 * the built-in map); a primitive whose material has none is drawn without a map, unless no
 * primitive has one, when all get the built-in map. Images are read once each.
 */
bool ChooseMaps(const Arguments& args,
  Input& input,
  std::vector<MapChoice>& choices,
  std::string& error)
{
  std::map<std::string, MapChoice> known; // by file path or "#<embedded image>"
  bool anyTexture = false;
  for (const Primitive& primitive : input.Primitives)
  {
    anyTexture = anyTexture || primitive.HasNormalTexture;
  }
  for (const Primitive& primitive : input.Primitives)
  {
    const std::string file = args.NormalMap.empty() ? primitive.NormalTextureFile : args.NormalMap;
    const std::string key = !file.empty()
      ? file
      : (primitive.EmbeddedImage >= 0 ? "#" + std::to_string(primitive.EmbeddedImage) : "");
    auto found = known.find(key);
    if (found == known.end() && !key.empty())
    {
      MapChoice choice;
      if (!file.empty())
      {
        choice.Image = NormalMapRender::ReadImage(file, error);
        if (choice.Image)
        {
          int dims[3];
          choice.Image->GetDimensions(dims);
          choice.Text = file + " (" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + ")";
        }
      }
      else
      {
        choice.Image =
          DecodeEmbeddedTexture(input.Document, primitive.EmbeddedImage, choice.Text, error);
      }
      if (!choice.Image && !args.NormalMap.empty())
      {
        return false; // the map asked for on the command line must be readable
      }
      if (!choice.Image && args.Encoding == vtkNormalMapPolyDataMapper::OBJECT_SPACE)
      {
        // The built-in map is tangent-space: drawn as object-space normals it would be wrong.
        error = "cannot use the file's normal texture: " + error +
          "; --encoding object needs --normal-map (the built-in map is tangent-space)";
        return false;
      }
      if (!choice.Image)
      {
        // A material's texture that cannot be used (a missing file, a corrupt image): the
        // picture is still drawn, with the built-in map.
        input.Warnings.push_back(
          "cannot use the file's normal texture: " + error + "; using the built-in map");
        choice = BuiltInMap(args);
      }
      found = known.emplace(key, choice).first;
    }
    MapChoice choice;
    if (found != known.end())
    {
      choice = found->second;
    }
    else if (anyTexture)
    {
      choice.Text = "none (the material has no normal texture)";
    }
    else if (args.Encoding == vtkNormalMapPolyDataMapper::OBJECT_SPACE)
    {
      error =
        "'" + args.Input + "' has no normal texture file, and --encoding object needs --normal-map";
      return false;
    }
    else
    {
      choice = BuiltInMap(args);
    }
    choice.Strength = args.StrengthGiven
      ? args.Strength
      : (args.NormalMap.empty() ? primitive.NormalTextureScale : 1.0);
    choices.push_back(choice);
  }
  return true;
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
  std::string frameText;
  int frameSource = vtkNormalMapPolyDataMapper::AUTOMATIC;
  if (!PrepareFrames(args, input, frameSource, frameText, error))
  {
    return Fail(Name, error);
  }
  std::vector<MapChoice> choices;
  if (!ChooseMaps(args, input, choices, error))
  {
    return Fail(
      Name, error, error.find("--encoding object") != std::string::npos ? Usage : Failure);
  }

  NormalMapRender::Scene scene;
  // A glTF file's primitives: one composite actor per normal map, each primitive a block.
  std::vector<vtkSmartPointer<vtkTexture>> textures;
  std::vector<vtkSmartPointer<vtkMultiBlockDataSet>> blocks;
  std::vector<std::string> mapTexts;
  std::map<std::pair<vtkImageData*, double>, size_t> parts; // by image and strength
  // Each glTF primitive where the scene's nodes place it (once per node that draws its mesh),
  // or as it is stored when no node of the scene draws it.
  const auto placements = input.GLTF ? NormalMapGLTF::PlaceMeshes(input.Document)
                                     : std::vector<std::vector<NormalMapGLTF::MeshPlacement>>();
  size_t placedBlocks = 0;
  vtkBoundingBox bounds;
  for (size_t i = 0; i < input.Primitives.size(); ++i)
  {
    const MapChoice& choice = choices[i];
    const auto key = std::make_pair(choice.Image.Get(), choice.Strength);
    auto part = parts.find(key);
    if (part == parts.end())
    {
      part = parts.emplace(key, scene.Parts.size()).first;
      textures.push_back(choice.Image ? NormalMapRender::MakeTexture(choice.Image) : nullptr);
      blocks.push_back(vtkSmartPointer<vtkMultiBlockDataSet>::New());
      NormalMapRender::Part added;
      added.Blocks = blocks.back();
      added.NormalMap = textures.back();
      added.Strength = choice.Strength;
      scene.Parts.push_back(added);
      std::ostringstream text;
      text << std::fixed << std::setprecision(1) << choice.Text;
      if (choice.Image)
      {
        text << ", " << args.EncodingName << ", strength " << choice.Strength;
      }
      mapTexts.push_back(text.str());
    }
    NormalMapRender::Part& target = scene.Parts[part->second];
    const Primitive& primitive = input.Primitives[i];
    for (const auto& placed :
      NormalMapGLTF::PlaceMesh(placements, primitive.GLTFMesh, primitive.Mesh, primitive.Name))
    {
      target.Blocks->SetBlock(target.Blocks->GetNumberOfBlocks(), placed.Mesh);
      target.BlockNames.push_back(placed.Name);
      bounds.AddBounds(placed.Mesh->GetBounds());
      placedBlocks += placed.ByNode ? 1 : 0;
    }
  }
  if (!input.Blocks)
  {
    // Other files are one mesh, drawn with vtkNormalMapPolyDataMapper.
    scene.Mesh = input.Primitives[0].Mesh;
    scene.NormalMap = scene.Parts[0].NormalMap;
    scene.Strength = scene.Parts[0].Strength;
    scene.Parts.clear();
  }
  vtkIdType points = 0, polygons = 0;
  for (const Primitive& primitive : input.Primitives)
  {
    points += primitive.Mesh->GetNumberOfPoints();
    polygons += primitive.Mesh->GetNumberOfPolys();
  }
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
            << "  mesh          " << points << " points, " << polygons << " polygons"
            << (input.Primitives.size() > 1
                   ? " in " + std::to_string(input.Primitives.size()) + " primitives"
                   : std::string())
            << "\n";
  for (size_t p = 0; p < mapTexts.size(); ++p)
  {
    std::cout << "  normal map    " << mapTexts[p];
    if (input.Primitives.size() > 1)
    {
      std::cout << " for";
      for (size_t b = 0; b < scene.Parts[p].BlockNames.size(); ++b)
      {
        std::cout << (b ? ", " : " ") << scene.Parts[p].BlockNames[b];
      }
    }
    std::cout << "\n";
  }
  if (input.Blocks)
  {
    std::cout << "  scene         "
              << (input.GLTF ? std::to_string(placedBlocks) + " primitive(s) placed by their nodes"
                             : std::to_string(input.Primitives.size()) + " block(s)")
              << "; bounds (" << bounds.GetMinPoint()[0] << ", " << bounds.GetMinPoint()[1] << ", "
              << bounds.GetMinPoint()[2] << ") to (" << bounds.GetMaxPoint()[0] << ", "
              << bounds.GetMaxPoint()[1] << ", " << bounds.GetMaxPoint()[2] << ")\n";
  }
  std::cout << "  frame         " << frameText << "; the mapper applied: " << rendered.AppliedFrame
            << "\n"
            << "  lighting      " << (args.PBR ? "PBR" : "Phong") << "\n"
            << "  picture       " << args.Width << "x" << args.Height << "\n"
            << "  render        " << rendered.FirstFrameMs << " ms first frame, "
            << rendered.NextFrameMs << " ms the next\n"
            << "  rendering     " << rendered.Window << "; OpenGL renderer " << rendered.Renderer
            << "\n";
  return Success;
}
