// SPDX-License-Identifier: BSD-3-Clause
// Tests of NormalMapGLTF (glTF in and out with TANGENT.w) and NormalMapTangents (the sign
// convention), on the hand-written quad in Data/ and on the Khronos glTF samples
// NormalTangentMirrorTest and NormalTangentTest in ../shared/data/gltf (mesh and textures by
// Ed Mackey, (c) 2017-2018 Analytical Graphics, Inc., CC-BY 4.0,
// https://creativecommons.org/licenses/by/4.0/); those tests skip when the folder is absent.
#include "NormalMapFiles.h"
#include "NormalMapGLTF.h"
#include "NormalMapTangents.h"
#include "NormalMappingTestData.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMath.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using NormalMapGLTF::Document;
using NormalMapGLTF::PrimitiveId;

namespace
{
const std::string DataDir = NORMALMAP_TEST_DATA;
const PrimitiveId First{ 0, 0 };

// A unit tangent from the filter or the file, stored in float: |t| - 1 is within a few float
// ulps (2^-24 relative rounding per component, ~1e-7). 1e-6 allows ~8 ulps.
constexpr double kUnitTol = 1e-6;

// Exact frames of the quad (planar map, T = +-x): the filter's double arithmetic stored in
// float, so a few float ulps of a unit vector.
constexpr double kQuadTol = 1e-6;

// Regenerated MikkTSpace tangents vs the ones stored in NormalTangentMirrorTest, in degrees.
// The filter is bit-exact with the reference mikktspace.c; the file's tangents were exported
// by Blender's MikkTSpace rewrite, whose polynomial acos (~1e-4 rad absolute error per corner
// weight) tilts an average of directions spread by at most ~90 degrees by less than
// ~0.005 degrees. The same bound as the filter's own test against this file (0.003 measured).
constexpr double kRegenerateMaxAngleDeg = 0.01;

std::string ReadText(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool OneLine(const std::string& error)
{
  return !error.empty() && error.find('\n') == std::string::npos;
}

// A fresh folder for one test's outputs, removed afterwards.
class TempDir
{
public:
  TempDir()
  {
    std::string pattern = (fs::temp_directory_path() / "normalmap-test-XXXXXX").string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    this->Path = mkdtemp(buffer.data()) ? buffer.data() : "";
  }
  ~TempDir()
  {
    std::error_code ec;
    fs::remove_all(this->Path, ec);
  }
  std::string operator/(const std::string& name) const
  {
    return (fs::path(this->Path) / name).string();
  }
  std::string Path;
};

Document ReadOrFail(const std::string& path)
{
  Document doc;
  std::string error;
  EXPECT_TRUE(NormalMapGLTF::ReadDocument(path, doc, error)) << error;
  return doc;
}

vtkSmartPointer<vtkPolyData> ToPolyData(const Document& doc, PrimitiveId id = First)
{
  std::string error;
  vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(doc, id, error);
  EXPECT_TRUE(mesh) << error;
  return mesh;
}

vtkSmartPointer<vtkPolyData> Frames(vtkPolyData* mesh,
  int method,
  bool splitting = true,
  NormalMapTangents::Counts* countsOut = nullptr)
{
  NormalMapTangents::Options options;
  options.Method = method;
  options.Splitting = splitting;
  NormalMapTangents::Counts counts;
  std::vector<std::string> warnings;
  std::string error;
  vtkSmartPointer<vtkPolyData> out =
    NormalMapTangents::Compute(mesh, options, counts, warnings, error);
  EXPECT_TRUE(out) << error;
  if (countsOut)
  {
    *countsOut = counts;
  }
  return out;
}

vtkDataArray* Array(vtkPolyData* mesh, const char* name)
{
  return mesh->GetPointData()->GetArray(name);
}

double FieldValue(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* a = mesh->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, 0) : -999.0;
}

std::string FieldString(vtkPolyData* mesh, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return a && a->GetNumberOfValues() ? a->GetValue(0) : std::string("<missing>");
}

// The TANGENT of a written primitive, checked to be valid glTF: FLOAT VEC4 with min and max,
// unit xyz and w exactly +1 or -1.
std::vector<float> CheckedTangents(const Document& doc, PrimitiveId id = First)
{
  const tinygltf::Model& m = doc.Model;
  const auto& prim = m.meshes.at(id.Mesh).primitives.at(id.Primitive);
  EXPECT_EQ(prim.attributes.count("TANGENT"), 1u);
  EXPECT_EQ(prim.attributes.count("POSITION"), 1u);
  if (!prim.attributes.count("TANGENT") || !prim.attributes.count("POSITION"))
  {
    return {};
  }
  const tinygltf::Accessor& position = m.accessors.at(prim.attributes.at("POSITION"));
  EXPECT_EQ(position.minValues.size(), 3u) << "POSITION needs min (glTF 3.7.2.1)";
  EXPECT_EQ(position.maxValues.size(), 3u) << "POSITION needs max (glTF 3.7.2.1)";
  const tinygltf::Accessor& acc = m.accessors.at(prim.attributes.at("TANGENT"));
  EXPECT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  EXPECT_EQ(acc.type, TINYGLTF_TYPE_VEC4);
  EXPECT_EQ(acc.minValues.size(), 4u);
  EXPECT_EQ(acc.maxValues.size(), 4u);
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc, id);
  std::vector<float> out;
  if (!mesh)
  {
    return out;
  }
  vtkDataArray* t = mesh->GetPointData()->GetTangents();
  vtkDataArray* s = Array(mesh, "TangentSigns");
  EXPECT_TRUE(t && s);
  if (!t || !s)
  {
    return out;
  }
  for (vtkIdType i = 0; i < t->GetNumberOfTuples(); ++i)
  {
    double v[3];
    t->GetTuple(i, v);
    EXPECT_NEAR(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), 1.0, kUnitTol) << "point " << i;
    const double w = s->GetComponent(i, 0);
    EXPECT_TRUE(w == 1.0 || w == -1.0) << "w " << w << " at point " << i;
    out.insert(out.end(), { float(v[0]), float(v[1]), float(v[2]), float(w) });
  }
  return out;
}

//------------------------------------------------------------------------------
TEST(NormalMapGLTF, ReadsTheQuadIntoPolyData)
{
  const Document doc = ReadOrFail(DataDir + "/quad.gltf");
  ASSERT_EQ(NormalMapGLTF::TrianglePrimitives(doc).size(), 1u);
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc);
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->GetNumberOfPoints(), 4);
  EXPECT_EQ(mesh->GetNumberOfPolys(), 2);
  vtkDataArray* uv = mesh->GetPointData()->GetTCoords();
  ASSERT_TRUE(uv);
  EXPECT_STREQ(uv->GetName(), "TEXCOORD_0");
  EXPECT_EQ(uv->GetComponent(0, 1), 1.0) << "UVs stay as stored (v down)";
  EXPECT_TRUE(mesh->GetPointData()->GetNormals());
  EXPECT_TRUE(Array(mesh, NormalMapGLTF::VertexIdArrayName));
  EXPECT_TRUE(NormalMapTangents::IsVDown(mesh));
  EXPECT_EQ(FieldValue(mesh, "GLTFMaterial"), 0.0);
  EXPECT_EQ(FieldValue(mesh, "NormalTextureImage"), 0.0);
  EXPECT_EQ(FieldValue(mesh, "NormalTextureTexCoord"), 0.0);
  EXPECT_EQ(FieldValue(mesh, "NormalTextureScale"), 0.5);
  EXPECT_EQ(FieldString(mesh, "NormalTextureURI"), "quad_normal.png");
  EXPECT_EQ(FieldString(mesh, "NormalTextureFile"),
    (fs::path(DataDir) / "quad_normal.png").lexically_normal().string());
  EXPECT_EQ(NormalMapGLTF::NormalTextureTexCoordName(doc, First), "TEXCOORD_0");
}

// The scene's nodes place each mesh: a parent's translation after its child's translation,
// rotation and scale (glTF 2.0, 5.25), once per node that draws the mesh; a mesh no node
// draws has no placement.
TEST(NormalMapGLTF, NodesPlaceTheirMeshes)
{
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  tinygltf::Node parent;
  parent.children = { 0, 2 };
  parent.translation = { 3.0, 0.0, 0.0 };
  doc.Model.nodes[0].rotation = { 0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5) }; // 90 deg about z
  doc.Model.nodes[0].scale = { 2.0, 1.0, 1.0 };
  tinygltf::Node second;
  second.mesh = 0;
  second.matrix = { -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1 }; // x mirrored, z + 5
  doc.Model.nodes.push_back(parent);
  doc.Model.nodes.push_back(second);
  doc.Model.scenes[0].nodes = { 1 };
  const auto placements = NormalMapGLTF::PlaceMeshes(doc);
  ASSERT_EQ(placements.size(), 1u);
  ASSERT_EQ(placements[0].size(), 2u);
  EXPECT_EQ(placements[0][0].Node, 0);
  EXPECT_EQ(placements[0][1].Node, 2);

  // The quad [0, 1]^2: scaled to [0, 2] x [0, 1], turned to [-1, 0] x [0, 2], moved by 3. The
  // matrices are products of a few exact values and of sqrt(0.5)^2: 1e-12 is rounding.
  vtkSmartPointer<vtkPolyData> quad = ToPolyData(doc);
  ASSERT_TRUE(quad);
  double b[6];
  NormalMapGLTF::Placed(quad, placements[0][0].Matrix)->GetBounds(b);
  const double expected[6] = { 2, 3, 0, 2, 0, 0 };
  for (int k = 0; k < 6; ++k)
  {
    EXPECT_NEAR(b[k], expected[k], 1e-12) << "bound " << k;
  }

  // The mirrored placement with tangents: the normal stays +z, the tangent turns to -x and the
  // sign flips, so that sign * cross(N, T) is the placed bitangent, +y, as before.
  vtkNew<vtkFloatArray> tangents, signs;
  tangents->SetName("Tangents");
  tangents->SetNumberOfComponents(3);
  signs->SetName("TangentSigns");
  for (vtkIdType p = 0; p < quad->GetNumberOfPoints(); ++p)
  {
    tangents->InsertNextTuple3(1.0, 0.0, 0.0);
    signs->InsertNextValue(-1.0); // B = -cross(+z, +x) = -y
  }
  quad->GetPointData()->SetTangents(tangents);
  quad->GetPointData()->AddArray(signs);
  vtkSmartPointer<vtkPolyData> mirrored = NormalMapGLTF::Placed(quad, placements[0][1].Matrix);
  vtkPointData* pd = mirrored->GetPointData();
  double n[3], t[3];
  pd->GetNormals()->GetTuple(0, n);
  pd->GetTangents()->GetTuple(0, t);
  const double sign = pd->GetArray("TangentSigns")->GetComponent(0, 0);
  EXPECT_NEAR(n[2], 1.0, 1e-12);
  EXPECT_NEAR(t[0], -1.0, 1e-12);
  EXPECT_EQ(sign, 1.0);
  double bitangent[3];
  vtkMath::Cross(n, t, bitangent);
  // Before: -1 * cross(+z, +x) = -y; the mirror in x keeps y: still -y.
  EXPECT_NEAR(sign * bitangent[1], -1.0, 1e-12);
  EXPECT_EQ(quad->GetPointData()->GetArray("TangentSigns")->GetComponent(0, 0), -1.0)
    << "the input is not modified";

  // A node scaled to 0 (hidden): its points collapse, its normals stay finite.
  std::array<double, 16> hidden{};
  hidden[15] = 1.0;
  vtkSmartPointer<vtkPolyData> flat = NormalMapGLTF::Placed(quad, hidden);
  flat->GetPointData()->GetNormals()->GetTuple(0, n);
  EXPECT_TRUE(std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]));
  flat->GetBounds(b);
  EXPECT_EQ(b[1] - b[0] + b[3] - b[2] + b[5] - b[4], 0.0);

  doc.Model.scenes[0].nodes.clear();
  EXPECT_TRUE(NormalMapGLTF::PlaceMeshes(doc)[0].empty()) << "a scene without nodes draws none";
}

// A hierarchy as deep as the file is long is placed without recursion (a recursive walk needs a
// stack frame per level), and a cycle, which a valid file does not have, ends.
TEST(NormalMapGLTF, DeepAndCyclicNodeHierarchies)
{
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  const int depth = 200000;
  for (int k = 0; k < depth; ++k)
  {
    tinygltf::Node link;
    link.children = { static_cast<int>(doc.Model.nodes.size()) - 1 };
    link.translation = { 1.0, 0.0, 0.0 };
    doc.Model.nodes.push_back(link);
  }
  doc.Model.scenes[0].nodes = { static_cast<int>(doc.Model.nodes.size()) - 1 };
  auto placements = NormalMapGLTF::PlaceMeshes(doc);
  ASSERT_EQ(placements[0].size(), 1u);
  EXPECT_EQ(placements[0][0].Matrix[3], static_cast<double>(depth)); // integers: exact

  doc.Model.nodes[0].children = { static_cast<int>(doc.Model.nodes.size()) - 1 }; // a cycle
  placements = NormalMapGLTF::PlaceMeshes(doc);
  EXPECT_EQ(placements[0].size(), 1u);
}

// KHR_texture_transform's texCoord overrides the normal texture's own: tangents must be
// computed on the set the texture is sampled with.
TEST(NormalMapGLTF, TextureTransformNamesTheTexCoordSet)
{
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  tinygltf::Value::Object transform;
  transform["texCoord"] = tinygltf::Value(1);
  doc.Model.materials[0].normalTexture.extensions["KHR_texture_transform"] =
    tinygltf::Value(transform);
  EXPECT_EQ(NormalMapGLTF::NormalTextureTexCoordName(doc, First), "TEXCOORD_1");
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc);
  ASSERT_TRUE(mesh);
  EXPECT_EQ(FieldValue(mesh, "NormalTextureTexCoord"), 1.0);
}

// TangentSigns means the same for every method and both UV conventions: bitangent =
// sign * cross(N, T) points to the top of the image, i.e. glTF's TANGENT.w.
TEST(NormalMapGLTF, SignFollowsGltfForEveryMethodAndUVConvention)
{
  const Document doc = ReadOrFail(DataDir + "/quad.gltf");
  std::string error;
  vtkSmartPointer<vtkPolyData> vUp = NormalMapFiles::ReadVTKMesh(DataDir + "/quad.obj", error);
  ASSERT_TRUE(vUp) << error;
  for (int method = vtkPolyDataTangentFrames::UNWEIGHTED;
       method <= vtkPolyDataTangentFrames::MIKKTSPACE;
       ++method)
  {
    for (bool mirrored : { false, true })
    {
      for (bool gltf : { true, false })
      {
        vtkSmartPointer<vtkPolyData> mesh = gltf ? ToPolyData(doc) : vUp;
        auto copy = vtkSmartPointer<vtkPolyData>::New();
        copy->DeepCopy(mesh);
        if (mirrored) // u -> 1 - u: T = -x, and the bitangent stays +y: w = -1
        {
          vtkDataArray* uv = copy->GetPointData()->GetTCoords();
          for (vtkIdType i = 0; i < uv->GetNumberOfTuples(); ++i)
          {
            uv->SetComponent(i, 0, 1.0 - uv->GetComponent(i, 0));
          }
        }
        vtkSmartPointer<vtkPolyData> out = Frames(copy, method);
        ASSERT_TRUE(out);
        vtkDataArray* t = out->GetPointData()->GetTangents();
        vtkDataArray* s = Array(out, "TangentSigns");
        const double expected = mirrored ? -1.0 : 1.0;
        for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
        {
          EXPECT_EQ(s->GetComponent(i, 0), expected)
            << vtkPolyDataTangentFrames::GetMethodName(method) << (gltf ? " glTF" : " OBJ");
          EXPECT_NEAR(t->GetComponent(i, 0), expected, kQuadTol);
        }
      }
    }
  }
}

TEST(NormalMapGLTF, WritesValidGltfAndGlbKeepingMaterialAndImages)
{
  TempDir tmp;
  for (const char* name : { "out.gltf", "sub/out.glb" })
  {
    Document doc = ReadOrFail(DataDir + "/quad.gltf");
    vtkSmartPointer<vtkPolyData> out =
      Frames(ToPolyData(doc), vtkPolyDataTangentFrames::MIKKTSPACE);
    std::string error;
    ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, First, out, error)) << error;
    fs::create_directories(fs::path(tmp / name).parent_path());
    ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / name, error)) << error;

    const Document back = ReadOrFail(tmp / name);
    const std::vector<float> tangents = CheckedTangents(back);
    ASSERT_EQ(tangents.size(), 16u);
    for (size_t i = 0; i < 4; ++i)
    {
      EXPECT_NEAR(tangents[4 * i], 1.0, kQuadTol);
      EXPECT_EQ(tangents[4 * i + 3], 1.0f);
    }
    const tinygltf::Model& m = back.Model;
    EXPECT_EQ(m.accessors.size(), 5u); // indices, POSITION, NORMAL, TEXCOORD_0 and TANGENT
    EXPECT_EQ(m.buffers.size(), 1u);
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].normalTexture.index, 0);
    EXPECT_EQ(m.materials[0].normalTexture.scale, 0.5);
    ASSERT_EQ(m.images.size(), 1u);
    // The image URI is rewritten for the output's folder and still names the same file.
    EXPECT_EQ((fs::path(tmp / name).parent_path() / m.images[0].uri).lexically_normal(),
      (fs::absolute(DataDir) / "quad_normal.png").lexically_normal())
      << m.images[0].uri;
    EXPECT_EQ(m.nodes.size(), 1u);
    EXPECT_EQ(m.scenes.size(), 1u);
  }
  // Nothing but the outputs: no temporary folders left.
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(tmp.Path))
  {
    files += entry.is_regular_file() ? 1 : 0;
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  EXPECT_EQ(files, 3); // out.gltf, out.bin, sub/out.glb
}

// Tangents written to glTF are unit and finite whatever the frames hold: a zero tangent becomes
// (1, 0, 0), MikkTSpace's default, and a tangent off unit length is normalized.
TEST(NormalMapGLTF, WrittenTangentsAreUnit)
{
  TempDir tmp;
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  vtkSmartPointer<vtkPolyData> out = Frames(ToPolyData(doc), vtkPolyDataTangentFrames::MIKKTSPACE);
  ASSERT_TRUE(out);
  vtkDataArray* tangents = out->GetPointData()->GetTangents();
  tangents->SetTuple3(0, 0.0, 0.0, 0.0);
  tangents->SetTuple3(1, 0.0, 3.0, 4.0);
  std::string error;
  ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, First, out, error)) << error;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "out.gltf", error)) << error;
  const std::vector<float> written = CheckedTangents(ReadOrFail(tmp / "out.gltf"));
  ASSERT_EQ(written.size(), 16u);
  EXPECT_EQ(written[0], 1.0f);
  EXPECT_EQ(written[1], 0.0f);
  EXPECT_EQ(written[2], 0.0f);
  // (0, 3, 4) / 5, rounded to float.
  EXPECT_NEAR(written[5], 0.6, kUnitTol);
  EXPECT_NEAR(written[6], 0.8, kUnitTol);
}

// Attributes stored as normalized integers (KHR_mesh_quantization's encodings) are read as the
// glTF specification dequantizes them: c / 127 and c / 32767 for signed bytes and shorts,
// clamped to -1 (so -128 and -32768 read as -1), c / 255 and c / 65535 for unsigned ones.
TEST(NormalMapGLTF, ReadsNormalizedIntegerAttributes)
{
  std::string bytes;
  const auto put = [&bytes](const auto& value)
  { bytes.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  for (const float p : { 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f })
  {
    put(p); // POSITION, offset 0, 36 bytes
  }
  for (const int8_t n : { 0, 0, 127, 0, -128, 0, 0, 0, 0, 127, 0, 0 })
  {
    put(n); // NORMAL, byte3 with a stride of 4, offset 36, 12 bytes
  }
  for (const uint16_t uv : { 0, 0, 65535, 0, 0, 65535 })
  {
    put(uv); // TEXCOORD_0, unsigned short2, offset 48, 12 bytes
  }
  for (const int16_t t : { 32767, 0, 0, 32767, 0, -32768, 0, -32768, 0, 0, 32767, 32767 })
  {
    put(t); // TANGENT, short4, offset 60, 24 bytes
  }
  ASSERT_EQ(bytes.size(), 84u);
  const std::string json = R"({
  "asset": { "version": "2.0" },
  "buffers": [ { "uri": "q.bin", "byteLength": 84 } ],
  "bufferViews": [
    { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
    { "buffer": 0, "byteOffset": 36, "byteLength": 12, "byteStride": 4 },
    { "buffer": 0, "byteOffset": 48, "byteLength": 12 },
    { "buffer": 0, "byteOffset": 60, "byteLength": 24 } ],
  "accessors": [
    { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
      "min": [ 0, 0, 0 ], "max": [ 1, 1, 0 ] },
    { "bufferView": 1, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3" },
    { "bufferView": 2, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2" },
    { "bufferView": 3, "componentType": 5122, "normalized": true, "count": 3, "type": "VEC4" } ],
  "meshes": [ { "primitives": [ { "attributes":
    { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3 } } ] } ],
  "nodes": [ { "mesh": 0 } ],
  "scenes": [ { "nodes": [ 0 ] } ]
})";
  TempDir tmp;
  std::ofstream(tmp / "q.bin", std::ios::binary) << bytes;
  std::ofstream(tmp / "q.gltf") << json;
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(ReadOrFail(tmp / "q.gltf"));
  ASSERT_TRUE(mesh);
  const auto tuple = [](vtkDataArray* a, vtkIdType i)
  {
    std::vector<double> v(static_cast<size_t>(a->GetNumberOfComponents()));
    a->GetTuple(i, v.data());
    return v;
  };
  vtkPointData* pd = mesh->GetPointData();
  EXPECT_EQ(tuple(pd->GetNormals(), 0), (std::vector<double>{ 0, 0, 1 }));
  EXPECT_EQ(tuple(pd->GetNormals(), 1), (std::vector<double>{ -1, 0, 0 }));
  EXPECT_EQ(tuple(pd->GetTCoords(), 1), (std::vector<double>{ 1, 0 }));
  EXPECT_EQ(tuple(pd->GetTCoords(), 2), (std::vector<double>{ 0, 1 }));
  EXPECT_EQ(tuple(pd->GetTangents(), 0), (std::vector<double>{ 1, 0, 0 }));
  EXPECT_EQ(tuple(pd->GetTangents(), 1), (std::vector<double>{ 0, -1, 0 }));
  vtkDataArray* signs = Array(mesh, "TangentSigns");
  ASSERT_NE(signs, nullptr);
  EXPECT_EQ(signs->GetComponent(0, 0), 1.0);
  EXPECT_EQ(signs->GetComponent(1, 0), -1.0);
}

// A mirror seam shared by two triangles fans: MikkTSpace splits its points, and every
// attribute, including a normalized UNSIGNED_BYTE COLOR_0 that needs a padded stride, follows
// its source vertex.
TEST(NormalMapGLTF, SplitPointsRewriteEveryAttribute)
{
  // Two quads side by side, x in [0, 2]; u mirrored about x = 1 (seam points 1 and 4).
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> uv, normals, tangents;
  uv->SetName("TCoords");
  uv->SetNumberOfComponents(2);
  normals->SetNumberOfComponents(3);
  tangents->SetName("Tangents");
  tangents->SetNumberOfComponents(3);
  for (int row = 0; row < 2; ++row)
  {
    for (int col = 0; col < 3; ++col)
    {
      points->InsertNextPoint(col, row, 0);
      uv->InsertNextTuple2(col == 1 ? 1.0 : 0.0, row);
      normals->InsertNextTuple3(0, 0, 1);
      tangents->InsertNextTuple3(1, 0, 0);
    }
  }
  mesh->SetPoints(points);
  mesh->GetPointData()->SetTCoords(uv);
  mesh->GetPointData()->SetNormals(normals);
  mesh->GetPointData()->AddArray(tangents);
  vtkNew<vtkCellArray> polys;
  for (vtkIdType quad = 0; quad < 2; ++quad)
  {
    const vtkIdType a = quad, b = quad + 1, c = quad + 4, d = quad + 3;
    const vtkIdType t1[3] = { a, b, c }, t2[3] = { a, c, d };
    polys->InsertNextCell(3, t1);
    polys->InsertNextCell(3, t2);
  }
  mesh->SetPolys(polys);
  Document doc;
  std::string error;
  ASSERT_TRUE(NormalMapGLTF::DocumentFromPolyData(mesh, "", doc, error)) << error;
  // COLOR_0 = (10 * vertex, 0, 0, 255), normalized UNSIGNED_BYTE VEC4 (4 bytes, no padding).
  {
    tinygltf::Model& m = doc.Model;
    tinygltf::Buffer colors;
    for (unsigned char v = 0; v < 6; ++v)
    {
      colors.data.insert(colors.data.end(), { static_cast<unsigned char>(10 * v), 0, 0, 255 });
    }
    m.buffers.push_back(colors);
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(m.buffers.size()) - 1;
    view.byteLength = colors.data.size();
    m.bufferViews.push_back(view);
    tinygltf::Accessor acc;
    acc.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
    acc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    acc.normalized = true;
    acc.type = TINYGLTF_TYPE_VEC4;
    acc.count = 6;
    m.accessors.push_back(acc);
    m.meshes[0].primitives[0].attributes["COLOR_0"] = static_cast<int>(m.accessors.size()) - 1;
  }
  TempDir tmp;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "seam.glb", error)) << error;

  Document seam = ReadOrFail(tmp / "seam.glb");
  const size_t accessorsBefore = seam.Model.accessors.size();
  NormalMapTangents::Counts counts;
  vtkSmartPointer<vtkPolyData> out =
    Frames(ToPolyData(seam), vtkPolyDataTangentFrames::MIKKTSPACE, true, &counts);
  ASSERT_TRUE(out);
  EXPECT_EQ(counts.SplitPoints, 2);
  ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(seam, First, out, error)) << error;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(seam, tmp / "split.gltf", error)) << error;

  const Document back = ReadOrFail(tmp / "split.gltf");
  EXPECT_EQ(back.Model.accessors.size(), accessorsBefore) << "the replaced accessors are removed";
  const auto& prim = back.Model.meshes[0].primitives[0];
  EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
  const tinygltf::Accessor& color = back.Model.accessors.at(prim.attributes.at("COLOR_0"));
  EXPECT_EQ(color.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE);
  EXPECT_TRUE(color.normalized);
  EXPECT_EQ(color.count, 8u);
  const std::vector<float> t = CheckedTangents(back);
  vtkSmartPointer<vtkPolyData> written = ToPolyData(back);
  ASSERT_TRUE(written);
  ASSERT_EQ(written->GetNumberOfPoints(), 8);
  const tinygltf::BufferView& view = back.Model.bufferViews.at(color.bufferView);
  const unsigned char* bytes = back.Model.buffers.at(view.buffer).data.data() + view.byteOffset;
  const size_t stride = view.byteStride ? view.byteStride : 4;
  for (vtkIdType i = 0; i < 8; ++i)
  {
    double p[3];
    written->GetPoint(i, p);
    const int source = static_cast<int>(p[0] + 3 * p[1]); // the vertex this point copies
    EXPECT_EQ(bytes[i * stride], 10 * source) << "point " << i;
    // Left half (x < 1, or a seam copy used by the left quad) has u increasing with x: T = +x.
    EXPECT_EQ(t[4 * i + 3], t[4 * i] > 0 ? 1.0f : -1.0f) << "point " << i;
  }
}

TEST(NormalMapGLTF, HandlesSeveralMeshesAndPrimitives)
{
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  // Mesh 1: the quad without UVs, and the quad as lines (not triangles: left alone).
  tinygltf::Mesh extra = doc.Model.meshes[0];
  extra.primitives.push_back(extra.primitives[0]);
  extra.primitives[0].attributes.erase("TEXCOORD_0");
  extra.primitives[1].mode = TINYGLTF_MODE_LINE;
  doc.Model.meshes.push_back(extra);
  const auto triangles = NormalMapGLTF::TrianglePrimitives(doc);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_EQ(triangles[1].Mesh, 1);

  // The quad with UVs is computed; the one without is refused and stays as it was.
  std::string error;
  for (PrimitiveId id : triangles)
  {
    vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc, id);
    ASSERT_TRUE(mesh);
    NormalMapTangents::Options options;
    NormalMapTangents::Counts counts;
    std::vector<std::string> warnings;
    vtkSmartPointer<vtkPolyData> out =
      NormalMapTangents::Compute(mesh, options, counts, warnings, error);
    if (id.Mesh == 1)
    {
      EXPECT_FALSE(out);
      EXPECT_TRUE(OneLine(error)) << error;
      continue;
    }
    ASSERT_TRUE(out) << error;
    ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, id, out, error)) << error;
  }
  TempDir tmp;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "two.glb", error)) << error;
  const Document back = ReadOrFail(tmp / "two.glb");
  ASSERT_EQ(back.Model.meshes.size(), 2u);
  EXPECT_EQ(CheckedTangents(back).size(), 16u);
  const auto& untouched = back.Model.meshes[1].primitives;
  ASSERT_EQ(untouched.size(), 2u);
  EXPECT_EQ(untouched[0].attributes.count("TANGENT"), 0u);
  EXPECT_EQ(untouched[1].mode, TINYGLTF_MODE_LINE);
  EXPECT_TRUE(ToPolyData(back, { 1, 0 })); // still readable: its accessors were kept
}

// v-down texture coordinates turned up: every set, in its own type, on this mesh only.
TEST(NormalMapTangents, FlipToVUpTurnsEverySetOfThisMeshOnly)
{
  vtkSmartPointer<vtkPolyData> quad = ToPolyData(ReadOrFail(DataDir + "/quad.gltf"));
  ASSERT_TRUE(quad);
  ASSERT_TRUE(NormalMapTangents::IsVDown(quad));
  vtkNew<vtkDoubleArray> second;
  second->SetName("TEXCOORD_1");
  second->SetNumberOfComponents(2);
  for (vtkIdType p = 0; p < quad->GetNumberOfPoints(); ++p)
  {
    second->InsertNextTuple2(0.5, 0.25 * static_cast<double>(p));
  }
  quad->GetPointData()->AddArray(second);
  vtkNew<vtkPolyData> flipped;
  flipped->ShallowCopy(quad);
  NormalMapTangents::FlipToVUp(flipped);

  EXPECT_FALSE(NormalMapTangents::IsVDown(flipped));
  EXPECT_TRUE(NormalMapTangents::IsVDown(quad)); // the mesh it shared arrays with keeps its own
  for (const char* name : { "TEXCOORD_0", "TEXCOORD_1" })
  {
    vtkDataArray* before = quad->GetPointData()->GetArray(name);
    vtkDataArray* after = flipped->GetPointData()->GetArray(name);
    ASSERT_TRUE(before && after) << name;
    EXPECT_EQ(after->GetDataType(), before->GetDataType()) << name;
    for (vtkIdType p = 0; p < quad->GetNumberOfPoints(); ++p)
    {
      EXPECT_EQ(after->GetComponent(p, 0), before->GetComponent(p, 0)) << name;
      // 1 - v is exact for these v (multiples of 1/4).
      EXPECT_EQ(after->GetComponent(p, 1), 1.0 - before->GetComponent(p, 1)) << name;
    }
  }
  EXPECT_EQ(flipped->GetPointData()->GetTCoords(), flipped->GetPointData()->GetArray("TEXCOORD_0"));
}

//------------------------------------------------------------------------------
// .vtm files: the polydata blocks with polygons, in order, named, their texture files resolved.
TEST(NormalMapFiles, MultiblockFilesGiveTheirPolyDataBlocks)
{
  vtkSmartPointer<vtkPolyData> quad = ToPolyData(ReadOrFail(DataDir + "/quad.gltf"));
  ASSERT_TRUE(quad);
  // The quad's material refers to quad_normal.png beside the glTF; as `tangents` writes it, the
  // block refers to it relative to the .vtm's folder.
  vtkNew<vtkPolyData> named;
  named->ShallowCopy(quad);
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(quad->GetFieldData());
  vtkNew<vtkStringArray> file;
  file->SetName("NormalTextureFile");
  file->InsertNextValue("textures/map.png");
  fields->AddArray(file);
  vtkNew<vtkDoubleArray> scale; // not a strength: the reader says so and takes 1
  scale->SetName("NormalTextureScale");
  scale->InsertNextValue(std::nan(""));
  fields->AddArray(scale);
  named->SetFieldData(fields);
  vtkNew<vtkPolyData> noPolygons;
  noPolygons->SetPoints(quad->GetPoints());
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 1);

  // A UV set number out of int's range, as a file may hold: no UV set named, and no overflow.
  vtkNew<vtkPolyData> farSet;
  farSet->ShallowCopy(quad);
  vtkNew<vtkFieldData> farFields;
  farFields->ShallowCopy(quad->GetFieldData());
  vtkNew<vtkDoubleArray> farNumber;
  farNumber->SetName("NormalTextureTexCoord");
  farNumber->InsertNextValue(1e30);
  farFields->AddArray(farNumber);
  farSet->SetFieldData(farFields);

  vtkNew<vtkMultiBlockDataSet> inner;
  inner->SetBlock(0, image);
  inner->SetBlock(1, farSet); // unnamed: its index among the leaves
  vtkNew<vtkMultiBlockDataSet> root;
  root->SetBlock(0, named);
  root->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "first quad");
  root->SetBlock(1, noPolygons);
  root->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "points only");
  root->SetBlock(2, inner);

  TempDir tmp;
  std::string error;
  ASSERT_TRUE(NormalMapFiles::WriteVTM(root, tmp / "scene.vtm", error)) << error;
  EXPECT_TRUE(fs::is_directory(NormalMapFiles::BlockFolder(tmp / "scene.vtm")));
  std::vector<NormalMapFiles::Block> blocks;
  std::vector<std::string> warnings;
  ASSERT_TRUE(NormalMapFiles::ReadVTMBlocks(tmp / "scene.vtm", blocks, warnings, error)) << error;
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].Name, "first quad");
  EXPECT_EQ(blocks[1].Name, "block 3");
  for (const auto& block : blocks)
  {
    EXPECT_EQ(block.Mesh->GetNumberOfPolys(), 2);
  }
  EXPECT_EQ(blocks[0].TCoordsName, "TEXCOORD_0"); // the material's normalTexture.texCoord
  EXPECT_EQ(blocks[1].TCoordsName, "");
  auto* resolved = vtkStringArray::SafeDownCast(
    blocks[0].Mesh->GetFieldData()->GetAbstractArray("NormalTextureFile"));
  ASSERT_TRUE(resolved);
  EXPECT_EQ(fs::path(std::string(resolved->GetValue(0))), fs::path(tmp / "textures/map.png"));
  EXPECT_EQ(blocks[0].NormalTextureScale, 1.0);
  EXPECT_EQ(blocks[1].NormalTextureScale, 0.5); // the glTF material's scale
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(
    warnings[0].find("first quad: NormalTextureScale is not finite; using 1"), std::string::npos)
    << warnings[0];
  EXPECT_NE(warnings[1].find("points only has no polygons; skipped"), std::string::npos)
    << warnings[1];
  EXPECT_NE(warnings[2].find("block 2 is not polydata; skipped"), std::string::npos) << warnings[2];

  // Nothing to draw: an error of one line.
  vtkNew<vtkMultiBlockDataSet> none;
  none->SetBlock(0, image);
  ASSERT_TRUE(NormalMapFiles::WriteVTM(none, tmp / "none.vtm", error)) << error;
  blocks.clear();
  EXPECT_FALSE(NormalMapFiles::ReadVTMBlocks(tmp / "none.vtm", blocks, warnings, error));
  EXPECT_TRUE(OneLine(error)) << error;
  EXPECT_NE(error.find("has no polydata block with polygons"), std::string::npos) << error;
  EXPECT_FALSE(NormalMapFiles::ReadVTMBlocks(tmp / "missing.vtm", blocks, warnings, error));
  EXPECT_NE(error.find("no such file"), std::string::npos) << error;
}

//------------------------------------------------------------------------------
// Corrupt files: an error of one line, never a crash.
TEST(NormalMapGLTF, CorruptFilesGiveOneLineErrors)
{
  const std::string text = ReadText(DataDir + "/quad.gltf");
  ASSERT_FALSE(text.empty());
  struct Case
  {
    const char* Name;
    std::string From, To;
  };
  const Case cases[] = {
    { "empty", text, "" },
    { "garbage", text, "this is { not [ JSON" },
    { "truncated", text.substr(text.size() / 2), "" },
    { "no version", "\"version\": \"2.0\"", "\"versio\": \"2.0\"" },
    { "accessor index", "\"POSITION\": 1", "\"POSITION\": 42" },
    { "negative accessor", "\"NORMAL\": 2", "\"NORMAL\": -3" },
    { "buffer view index", "{ \"bufferView\": 3,", "{ \"bufferView\": 17," },
    { "buffer view range",
      "\"byteOffset\": 108, \"byteLength\": 32",
      "\"byteOffset\": 4000, \"byteLength\": 32" },
    { "huge count",
      "\"count\": 4, \"type\": \"VEC2\"",
      "\"count\": 4000000000, \"type\": \"VEC2\"" },
    { "count too large", "\"count\": 4, \"type\": \"VEC2\"", "\"count\": 5, \"type\": \"VEC2\"" },
    { "indices out of range",
      "\"componentType\": 5123, \"count\": 6",
      "\"componentType\": 5125, \"count\": 3" },
    { "not triangles", "\"indices\": 0,", "\"indices\": 0, \"mode\": 4, \"x\": 0," },
    { "stride",
      "\"byteOffset\": 60, \"byteLength\": 48,",
      "\"byteOffset\": 60, \"byteLength\": 48, \"byteStride\": 200," },
    { "wrong type", "\"count\": 4, \"type\": \"VEC3\" }", "\"count\": 4, \"type\": \"MAT4\" }" },
    { "bad base64", "base64,AAAB", "base64,@@@@" },
  };
  int failures = 0;
  for (const Case& c : cases)
  {
    std::string broken = text;
    const size_t at = broken.find(c.From);
    ASSERT_NE(at, std::string::npos) << c.Name;
    broken.replace(at, c.From.size(), c.To);
    Document doc;
    std::string error;
    bool ok = NormalMapGLTF::ReadDocumentFromMemory(
      reinterpret_cast<const unsigned char*>(broken.data()), broken.size(), DataDir, doc, error);
    for (PrimitiveId id : NormalMapGLTF::TrianglePrimitives(doc))
    {
      ok = ok && NormalMapGLTF::PrimitiveToPolyData(doc, id, error) != nullptr;
    }
    if (std::string(c.Name) == "not triangles")
    {
      EXPECT_TRUE(ok) << "an unknown key is no error: " << error;
      continue;
    }
    EXPECT_FALSE(ok) << c.Name;
    EXPECT_TRUE(OneLine(error)) << c.Name << ": '" << error << "'";
    std::printf("[ corrupt  ] %-22s %s\n", c.Name, error.c_str());
    failures += ok ? 0 : 1;
  }
  EXPECT_EQ(failures, static_cast<int>(std::size(cases)) - 1);
}

// An accessor without a buffer view stands for zeros (glTF 3.6.2.3). Within the size of the
// file's buffers it reads as zeros; beyond, it is an error of one line, found before any memory
// is asked for: the quad's 140 bytes of buffer cannot stand for 200 million texture coordinates
// (1.6 GB, which the accessor size limit alone allows).
TEST(NormalMapGLTF, ZeroAccessorsStayWithinTheFilesBuffers)
{
  const std::string text = ReadText(DataDir + "/quad.gltf");
  const std::string uvs = "{ \"bufferView\": 3, \"componentType\": 5126, \"count\": 4,";
  ASSERT_NE(text.find(uvs), std::string::npos);
  const auto read = [&](const std::string& count, std::string& error)
  {
    std::string changed = text;
    changed.replace(
      changed.find(uvs), uvs.size(), "{ \"componentType\": 5126, \"count\": " + count + ",");
    Document doc;
    vtkSmartPointer<vtkPolyData> mesh;
    if (NormalMapGLTF::ReadDocumentFromMemory(
          reinterpret_cast<const unsigned char*>(changed.data()),
          changed.size(),
          DataDir,
          doc,
          error))
    {
      mesh =
        NormalMapGLTF::PrimitiveToPolyData(doc, NormalMapGLTF::TrianglePrimitives(doc)[0], error);
    }
    return mesh;
  };
  std::string error;
  const vtkSmartPointer<vtkPolyData> zeros = read("4", error);
  ASSERT_TRUE(zeros) << error;
  vtkDataArray* tcoords = zeros->GetPointData()->GetTCoords();
  ASSERT_TRUE(tcoords);
  ASSERT_EQ(tcoords->GetNumberOfTuples(), 4);
  for (vtkIdType i = 0; i < 4; ++i)
  {
    EXPECT_EQ(tcoords->GetComponent(i, 0), 0.0);
    EXPECT_EQ(tcoords->GetComponent(i, 1), 0.0);
  }
  for (const char* count : { "141", "200000000" })
  {
    error.clear();
    EXPECT_FALSE(read(count, error)) << count;
    EXPECT_TRUE(OneLine(error)) << error;
    EXPECT_NE(error.find("has no buffer view and more elements (" + std::string(count) +
                ") than the file's buffers have bytes (140)"),
      std::string::npos)
      << error;
  }
}

// Every prefix of a .glb, and random byte changes of the .gltf: read, convert and write back
// without crashing (errors are fine). A cheap stand-in for the fuzzer.
TEST(NormalMapGLTF, SurvivesTruncatedAndMutatedInput)
{
  TempDir tmp;
  std::string error;
  Document doc = ReadOrFail(DataDir + "/quad.gltf");
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "quad.glb", error)) << error;
  const std::string glb = ReadText(tmp / "quad.glb");
  const std::string gltf = ReadText(DataDir + "/quad.gltf");
  std::mt19937 random(12345);
  std::vector<std::string> inputs;
  for (size_t n = 0; n < glb.size(); ++n)
  {
    inputs.push_back(glb.substr(0, n));
  }
  for (int k = 0; k < 300; ++k)
  {
    std::string mutated = random() % 2 ? gltf : glb;
    const size_t changes = 1 + random() % 4;
    for (size_t c = 0; c < changes; ++c)
    {
      const char bytes[] = "0123456789-{}[]\",: e";
      mutated[random() % mutated.size()] = bytes[random() % (sizeof(bytes) - 1)];
    }
    inputs.push_back(mutated);
  }
  int read = 0, computed = 0, written = 0;
  for (const std::string& input : inputs)
  {
    Document d;
    if (!NormalMapGLTF::ReadDocumentFromMemory(
          reinterpret_cast<const unsigned char*>(input.data()), input.size(), DataDir, d, error))
    {
      EXPECT_TRUE(OneLine(error)) << error;
      continue;
    }
    ++read;
    for (PrimitiveId id : NormalMapGLTF::TrianglePrimitives(d))
    {
      vtkSmartPointer<vtkPolyData> mesh = NormalMapGLTF::PrimitiveToPolyData(d, id, error);
      if (mesh && NormalMapTangents::FindTCoords(mesh, ""))
      {
        NormalMapTangents::Options options;
        NormalMapTangents::Counts counts;
        std::vector<std::string> warnings;
        vtkSmartPointer<vtkPolyData> out =
          NormalMapTangents::Compute(mesh, options, counts, warnings, error);
        if (out)
        {
          ++computed;
          NormalMapGLTF::UpdatePrimitive(d, id, out, error);
        }
      }
    }
    written += NormalMapGLTF::WriteDocument(d, tmp / "mutated.glb", error) ? 1 : 0;
  }
  std::printf("[ mutated  ] %zu inputs, %d read as glTF, %d primitives given tangents, %d "
              "written back\n",
    inputs.size(),
    read,
    computed,
    written);
  // Most mutations break the JSON; the ones that do not must go through every step, or the
  // test only proves that the reader rejects input.
  EXPECT_GT(read, 0);
  EXPECT_GT(computed, 0);
  EXPECT_GT(written, 0);
}

//------------------------------------------------------------------------------
// The Khronos sample NormalTangentMirrorTest (CC-BY 4.0, see the top of this file).
std::string MirrorTestPath(const std::string& shared)
{
  return shared + "/gltf/NormalTangentMirrorTest/NormalTangentMirrorTest.gltf";
}

// Reading keeps TANGENT exactly, and writing the primitive back without computing keeps it
// bit for bit in .gltf and .glb, with everything else in the file.
TEST(NormalMapGLTFShared, MirrorTestRoundTripKeepsStoredTangents)
{
  REQUIRE_SHARED_DATA(shared);
  const std::string path = MirrorTestPath(shared);
  NormalMappingTestData::GltfPrimitive stored; // an independent reader of the same file
  std::string error;
  ASSERT_TRUE(NormalMappingTestData::LoadGltfPrimitive(path, stored, error)) << error;
  ASSERT_FALSE(stored.Tangents.empty());

  Document doc = ReadOrFail(path);
  const tinygltf::Model original = doc.Model;
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc);
  ASSERT_TRUE(mesh);
  ASSERT_EQ(static_cast<size_t>(mesh->GetNumberOfPoints()) * 4, stored.Tangents.size());
  TempDir tmp;
  ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, First, mesh, error)) << error;
  Document copy = doc;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "mirror.gltf", error)) << error;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(copy, tmp / "mirror.glb", error)) << error;

  NormalMappingTestData::GltfPrimitive independent;
  ASSERT_TRUE(NormalMappingTestData::LoadGltfPrimitive(tmp / "mirror.gltf", independent, error))
    << error;
  EXPECT_EQ(independent.Tangents, stored.Tangents);
  EXPECT_EQ(independent.Positions, stored.Positions);
  EXPECT_EQ(independent.Normals, stored.Normals);
  EXPECT_EQ(independent.TexCoords, stored.TexCoords);
  EXPECT_EQ(independent.Indices, stored.Indices);
  for (const char* name : { "mirror.gltf", "mirror.glb" })
  {
    const Document back = ReadOrFail(tmp / name);
    const std::vector<float> t = CheckedTangents(back);
    ASSERT_EQ(t.size(), stored.Tangents.size()) << name;
    size_t differences = 0;
    for (size_t i = 0; i < t.size(); ++i)
    {
      differences += static_cast<double>(t[i]) == stored.Tangents[i] ? 0 : 1;
    }
    EXPECT_EQ(differences, 0u) << name << ": stored tangents must pass through bit for bit";
    const tinygltf::Model& m = back.Model;
    EXPECT_EQ(m.accessors.size(), original.accessors.size()) << name;
    EXPECT_EQ(m.materials.size(), original.materials.size());
    EXPECT_EQ(m.textures.size(), original.textures.size());
    EXPECT_EQ(m.samplers.size(), original.samplers.size());
    EXPECT_EQ(m.nodes.size(), original.nodes.size());
    EXPECT_EQ(m.asset.copyright, original.asset.copyright) << "the CC-BY attribution is kept";
    ASSERT_EQ(m.images.size(), original.images.size());
    for (const tinygltf::Image& image : m.images)
    {
      EXPECT_TRUE(fs::exists(fs::path(tmp.Path) / image.uri)) << image.uri;
    }
    EXPECT_EQ(m.materials[0].normalTexture.index, original.materials[0].normalTexture.index);
  }
}

// MikkTSpace (glTF signs) regenerates the stored tangents; the weighted methods agree on
// every sign.
TEST(NormalMapGLTFShared, MirrorTestMikkTSpaceReproducesStoredTangents)
{
  REQUIRE_SHARED_DATA(shared);
  const std::string path = MirrorTestPath(shared);
  NormalMappingTestData::GltfPrimitive stored;
  std::string error;
  ASSERT_TRUE(NormalMappingTestData::LoadGltfPrimitive(path, stored, error)) << error;
  TempDir tmp;
  for (int method = vtkPolyDataTangentFrames::UNWEIGHTED;
       method <= vtkPolyDataTangentFrames::MIKKTSPACE;
       ++method)
  {
    Document doc = ReadOrFail(path);
    NormalMapTangents::Counts counts;
    vtkSmartPointer<vtkPolyData> out = Frames(ToPolyData(doc), method, true, &counts);
    ASSERT_TRUE(out);
    ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, First, out, error)) << error;
    ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "regenerated.glb", error)) << error;
    const Document back = ReadOrFail(tmp / "regenerated.glb");
    const std::vector<float> t = CheckedTangents(back);
    vtkSmartPointer<vtkPolyData> written = ToPolyData(back);
    ASSERT_TRUE(written);
    // The written vertices map to the stored ones through the filter's GLTFVertexId.
    vtkDataArray* source = Array(out, NormalMapGLTF::VertexIdArrayName);
    ASSERT_EQ(source->GetNumberOfTuples() * 4, static_cast<vtkIdType>(t.size()));
    NormalMappingTestData::Stats st;
    for (vtkIdType i = 0; i < source->GetNumberOfTuples(); ++i)
    {
      const size_t s = static_cast<size_t>(source->GetComponent(i, 0));
      const float a[3] = { float(stored.Tangents[4 * s]),
        float(stored.Tangents[4 * s + 1]),
        float(stored.Tangents[4 * s + 2]) };
      st.Angles.push_back(NormalMappingTestData::AngleDeg(a, &t[4 * static_cast<size_t>(i)]));
      st.SignMismatches += t[4 * static_cast<size_t>(i) + 3] == stored.Tangents[4 * s + 3] ? 0 : 1;
    }
    std::printf("[ regen    ] %-13s points %lld -> %lld, split %lld: angle to stored mean %.3g"
                " p99 %.3g max %.3g deg, sign mismatches %lld\n",
      vtkPolyDataTangentFrames::GetMethodName(method),
      static_cast<long long>(counts.InputPoints),
      static_cast<long long>(counts.OutputPoints),
      static_cast<long long>(counts.SplitPoints),
      st.Mean(),
      st.Quantile(0.99),
      st.Max(),
      st.SignMismatches);
    EXPECT_EQ(st.SignMismatches, 0) << vtkPolyDataTangentFrames::GetMethodName(method);
    if (method == vtkPolyDataTangentFrames::MIKKTSPACE)
    {
      EXPECT_EQ(counts.SplitPoints, 0) << "the file's vertices already carry one frame each";
      EXPECT_LE(st.Max(), kRegenerateMaxAngleDeg);
    }
  }
}

// NormalTangentTest has no TANGENT: one is added, valid, with MikkTSpace's frames.
TEST(NormalMapGLTFShared, TangentTestGetsTangents)
{
  REQUIRE_SHARED_DATA(shared);
  const std::string path = shared + "/gltf/NormalTangentTest/NormalTangentTest.gltf";
  Document doc = ReadOrFail(path);
  vtkSmartPointer<vtkPolyData> mesh = ToPolyData(doc);
  ASSERT_TRUE(mesh);
  EXPECT_FALSE(mesh->GetPointData()->GetTangents());
  vtkSmartPointer<vtkPolyData> out = Frames(mesh, vtkPolyDataTangentFrames::MIKKTSPACE);
  std::string error;
  ASSERT_TRUE(NormalMapGLTF::UpdatePrimitive(doc, First, out, error)) << error;
  TempDir tmp;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "tangent.gltf", error)) << error;
  const Document back = ReadOrFail(tmp / "tangent.gltf");
  EXPECT_EQ(CheckedTangents(back).size(), static_cast<size_t>(out->GetNumberOfPoints()) * 4);
}
}

// An image in a data: URI that says application/octet-stream, its type in the image's mimeType
// (tinygltf keeps no mimeType for an image with a URI): the written file gives the image the
// type its bytes have, JPEG, not the PNG a missing type used to become.
TEST(NormalMapGLTF, DataURIImagesKeepTheTypeOfTheirBytes)
{
  TempDir tmp;
  std::string gltf = ReadText(DataDir + "/embedded/quad_jpeg.gltf");
  const std::string jpegURI = "\"uri\": \"data:image/jpeg;";
  const size_t at = gltf.find(jpegURI);
  ASSERT_NE(at, std::string::npos);
  gltf.replace(
    at, jpegURI.size(), "\"mimeType\": \"image/jpeg\", \"uri\": \"data:application/octet-stream;");
  {
    std::ofstream(tmp / "octet.gltf") << gltf;
  }
  Document doc = ReadOrFail(tmp / "octet.gltf");
  std::string error;
  ASSERT_TRUE(NormalMapGLTF::WriteDocument(doc, tmp / "out.glb", error)) << error;
  const Document written = ReadOrFail(tmp / "out.glb");
  ASSERT_EQ(written.Model.images.size(), 1u);
  EXPECT_EQ(written.Model.images[0].mimeType, "image/jpeg");
}
