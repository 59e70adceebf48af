// SPDX-License-Identifier: BSD-3-Clause
// Helpers shared by the MikkTSpace tests: locating ../shared/data, angle statistics and a
// minimal glTF (JSON + .bin accessor) reader.
//
// Locating the shared data and angle statistics: NormalMappingReferenceData.h.
#ifndef NormalMappingTestData_h
#define NormalMappingTestData_h

#include "NormalMappingReferenceData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace NormalMappingTestData
{
#define REQUIRE_SHARED_DATA(dirVar)                                                                \
  std::string lookedFor;                                                                           \
  const std::string dirVar = NormalMappingTestData::FindSharedData(&lookedFor);                    \
  if (dirVar.empty())                                                                              \
  {                                                                                                \
    GTEST_SKIP() << "shared test data not found; looked for " << lookedFor;                        \
  }

//------------------------------------------------------------------------------
// Minimal JSON reader (objects, arrays, strings, numbers, literals), enough for a .gltf file.
struct Json
{
  enum Kind
  {
    Null,
    Bool,
    Number,
    String,
    Array,
    Object
  } K = Null;
  double Num = 0;
  std::string Str;
  std::vector<Json> Items;
  std::vector<std::pair<std::string, Json>> Members;

  const Json* Get(const std::string& key) const
  {
    for (const auto& m : Members)
    {
      if (m.first == key)
      {
        return &m.second;
      }
    }
    return nullptr;
  }
  long long Int(const std::string& key, long long fallback) const
  {
    const Json* j = Get(key);
    return j && j->K == Number ? static_cast<long long>(j->Num) : fallback;
  }
};

class JsonParser
{
public:
  explicit JsonParser(const std::string& text)
    : T(text)
  {
  }
  bool Parse(Json& out) { return Value(out) && (Skip(), I == T.size()); }

private:
  const std::string& T;
  size_t I = 0;
  void Skip()
  {
    while (I < T.size() && std::isspace(static_cast<unsigned char>(T[I])))
    {
      ++I;
    }
  }
  bool Literal(const char* word)
  {
    const size_t n = std::strlen(word);
    if (T.compare(I, n, word) != 0)
    {
      return false;
    }
    I += n;
    return true;
  }
  bool StringValue(std::string& out)
  {
    if (T[I] != '"')
    {
      return false;
    }
    for (++I; I < T.size() && T[I] != '"'; ++I)
    {
      if (T[I] == '\\' && I + 1 < T.size())
      {
        ++I;
        out += T[I] == 'n' ? '\n' : T[I]; // \uXXXX is not needed for glTF keys used here
      }
      else
      {
        out += T[I];
      }
    }
    return I++ < T.size();
  }
  bool Value(Json& out)
  {
    Skip();
    if (I >= T.size())
    {
      return false;
    }
    const char c = T[I];
    if (c == '{')
    {
      out.K = Json::Object;
      ++I;
      Skip();
      if (T[I] == '}')
      {
        ++I;
        return true;
      }
      for (;;)
      {
        Skip();
        std::string key;
        if (!StringValue(key))
        {
          return false;
        }
        Skip();
        if (T[I++] != ':')
        {
          return false;
        }
        out.Members.emplace_back(key, Json());
        if (!Value(out.Members.back().second))
        {
          return false;
        }
        Skip();
        if (T[I] == ',')
        {
          ++I;
          continue;
        }
        return T[I++] == '}';
      }
    }
    if (c == '[')
    {
      out.K = Json::Array;
      ++I;
      Skip();
      if (T[I] == ']')
      {
        ++I;
        return true;
      }
      for (;;)
      {
        out.Items.emplace_back();
        if (!Value(out.Items.back()))
        {
          return false;
        }
        Skip();
        if (T[I] == ',')
        {
          ++I;
          continue;
        }
        return T[I++] == ']';
      }
    }
    if (c == '"')
    {
      out.K = Json::String;
      return StringValue(out.Str);
    }
    if (Literal("true") || Literal("false"))
    {
      out.K = Json::Bool;
      return true;
    }
    if (Literal("null"))
    {
      return true;
    }
    char* end = nullptr;
    out.Num = std::strtod(T.c_str() + I, &end);
    if (end == T.c_str() + I)
    {
      return false;
    }
    out.K = Json::Number;
    I = static_cast<size_t>(end - T.c_str());
    return true;
  }
};

inline std::string ReadFile(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Reads accessor `index` of a glTF document as floats (FLOAT) or integers (UNSIGNED_*).
inline bool ReadAccessor(const Json& doc,
  const std::string& bin,
  long long index,
  int wantComponents,
  std::vector<double>& out)
{
  const Json* accessors = doc.Get("accessors");
  const Json* views = doc.Get("bufferViews");
  if (!accessors || !views || index < 0 || index >= static_cast<long long>(accessors->Items.size()))
  {
    return false;
  }
  const Json& acc = accessors->Items[static_cast<size_t>(index)];
  const Json* type = acc.Get("type");
  const std::map<std::string, int> comps = {
    { "SCALAR", 1 }, { "VEC2", 2 }, { "VEC3", 3 }, { "VEC4", 4 }
  };
  if (!type || !comps.count(type->Str) || comps.at(type->Str) != wantComponents)
  {
    return false;
  }
  const long long viewIndex = acc.Int("bufferView", -1);
  if (viewIndex < 0 || viewIndex >= static_cast<long long>(views->Items.size()))
  {
    return false;
  }
  const Json& view = views->Items[static_cast<size_t>(viewIndex)];
  const long long componentType = acc.Int("componentType", 0);
  const int size = componentType == 5126 || componentType == 5125 ? 4
    : componentType == 5123                                       ? 2
    : componentType == 5121                                       ? 1
                                                                  : 0;
  if (size == 0)
  {
    return false;
  }
  const long long count = acc.Int("count", 0);
  const long long stride = view.Int("byteStride", size * wantComponents);
  const long long base = view.Int("byteOffset", 0) + acc.Int("byteOffset", 0);
  if (base < 0 ||
    base + (count - 1) * stride + size * wantComponents > static_cast<long long>(bin.size()))
  {
    return false;
  }
  out.resize(static_cast<size_t>(count * wantComponents));
  for (long long i = 0; i < count; ++i)
  {
    for (int k = 0; k < wantComponents; ++k)
    {
      const char* p = bin.data() + base + i * stride + k * size;
      double v = 0;
      if (componentType == 5126)
      {
        float f;
        std::memcpy(&f, p, 4);
        v = f;
      }
      else if (componentType == 5125)
      {
        uint32_t u;
        std::memcpy(&u, p, 4);
        v = u;
      }
      else if (componentType == 5123)
      {
        uint16_t u;
        std::memcpy(&u, p, 2);
        v = u;
      }
      else
      {
        v = static_cast<unsigned char>(*p);
      }
      out[static_cast<size_t>(i * wantComponents + k)] = v;
    }
  }
  return true;
}

/// The first primitive of the first mesh of a .gltf file (attributes as doubles, one entry per
/// component; Indices empty when the primitive is not indexed).
struct GltfPrimitive
{
  std::vector<double> Positions, Normals, TexCoords, Tangents, Indices;
};

inline bool LoadGltfPrimitive(const std::string& path, GltfPrimitive& out, std::string& error)
{
  const std::string text = ReadFile(path);
  if (text.empty())
  {
    error = "cannot read " + path;
    return false;
  }
  Json doc;
  if (!JsonParser(text).Parse(doc))
  {
    error = "cannot parse the JSON of " + path;
    return false;
  }
  const Json* buffers = doc.Get("buffers");
  if (!buffers || buffers->Items.empty() || !buffers->Items[0].Get("uri"))
  {
    error = "no buffer in " + path;
    return false;
  }
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? std::string(".") : path.substr(0, slash);
  const std::string bin = ReadFile(dir + "/" + buffers->Items[0].Get("uri")->Str);
  const Json* meshes = doc.Get("meshes");
  const Json* prims =
    meshes && !meshes->Items.empty() ? meshes->Items[0].Get("primitives") : nullptr;
  const Json* attrs = prims && !prims->Items.empty() ? prims->Items[0].Get("attributes") : nullptr;
  if (!attrs)
  {
    error = "no mesh primitive in " + path;
    return false;
  }
  const Json& prim = prims->Items[0];
  if (!ReadAccessor(doc, bin, attrs->Int("POSITION", -1), 3, out.Positions) ||
    !ReadAccessor(doc, bin, attrs->Int("NORMAL", -1), 3, out.Normals) ||
    !ReadAccessor(doc, bin, attrs->Int("TEXCOORD_0", -1), 2, out.TexCoords))
  {
    error = "cannot read POSITION, NORMAL or TEXCOORD_0 of " + path;
    return false;
  }
  if (attrs->Get("TANGENT") && !ReadAccessor(doc, bin, attrs->Int("TANGENT", -1), 4, out.Tangents))
  {
    error = "cannot read TANGENT of " + path;
    return false;
  }
  if (prim.Get("indices") && !ReadAccessor(doc, bin, prim.Int("indices", -1), 1, out.Indices))
  {
    error = "cannot read the indices of " + path;
    return false;
  }
  return true;
}

} // namespace NormalMappingTestData

#endif
