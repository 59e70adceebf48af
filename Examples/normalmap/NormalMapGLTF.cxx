// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapGLTF.h"

#include "NormalMapFiles.h"
#include "NormalMapTangents.h"
#include "vtkPolyDataTangentFrames.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkReverseSense.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <set>

namespace fs = std::filesystem;

namespace NormalMapGLTF
{
namespace
{
// Largest accessor we materialize (elements * element size): far beyond real meshes, and it
// keeps a corrupt count on an accessor without a buffer view from allocating without bound.
constexpr uint64_t kMaxAccessorBytes = uint64_t(1) << 31;

std::string Where(const char* what, int index)
{
  return std::string(what) + " " + std::to_string(index);
}

// a + b <= limit, without overflow.
bool FitsSum(uint64_t a, uint64_t b, uint64_t limit)
{
  return a <= limit && b <= limit - a;
}

std::string PercentDecode(const std::string& uri)
{
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i)
  {
    if (uri[i] == '%' && i + 2 < uri.size() &&
      std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
      std::isxdigit(static_cast<unsigned char>(uri[i + 2])))
    {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
    {
      out += uri[i];
    }
  }
  return out;
}

std::string PercentEncodePath(const std::string& path)
{
  std::string out;
  for (char c : path)
  {
    if (c == '%' || c == ' ' || c == '#' || c == '?')
    {
      static const char* hex = "0123456789ABCDEF";
      out += '%';
      out += hex[(static_cast<unsigned char>(c) >> 4) & 15];
      out += hex[static_cast<unsigned char>(c) & 15];
    }
    else
    {
      out += c;
    }
  }
  return out;
}

// A URI that names a file relative to the glTF file (not data:, not scheme://, not absolute).
bool IsRelativeFileURI(const std::string& uri)
{
  return !uri.empty() && uri.compare(0, 5, "data:") != 0 && uri.find("://") == std::string::npos &&
    uri[0] != '/';
}

template<typename T>
double ReadAs(const unsigned char* p)
{
  T v;
  std::memcpy(&v, p, sizeof(T));
  return static_cast<double>(v);
}

// One stored component of type `componentType` (a valid one) at `p`.
double ReadComponent(int componentType, const unsigned char* p)
{
  switch (componentType)
  {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return ReadAs<int8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return ReadAs<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return ReadAs<int16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return ReadAs<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_INT:
      return ReadAs<int32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return ReadAs<uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return ReadAs<float>(p);
    default:
      return ReadAs<double>(p);
  }
}

//------------------------------------------------------------------------------
// Accessors: validated, materialized (sparse substitution applied) as packed elements.
struct AccessorData
{
  std::vector<unsigned char> Bytes;
  size_t Count = 0;
  int ComponentType = 0;
  int Type = 0;
  int Components = 0;
  int ComponentSize = 0;
  bool Normalized = false;

  size_t ElementSize() const { return static_cast<size_t>(this->Components * this->ComponentSize); }

  // The stored value of component k of element i (integers as they are, no normalization).
  double Raw(size_t i, int k) const
  {
    return ReadComponent(this->ComponentType,
      this->Bytes.data() + i * this->ElementSize() + static_cast<size_t>(k * this->ComponentSize));
  }

  // The value the glTF spec gives component k of element i (normalized integers dequantized).
  double Value(size_t i, int k) const
  {
    const double raw = this->Raw(i, k);
    if (!this->Normalized)
    {
      return raw;
    }
    switch (this->ComponentType)
    {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return std::max(raw / 127.0, -1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return raw / 255.0;
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return std::max(raw / 32767.0, -1.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return raw / 65535.0;
      default:
        return raw;
    }
  }
};

// Checks that `count` items of `itemSize` bytes, `stride` apart, starting `offset` bytes into
// buffer view `viewIndex`, lie inside the view and the view inside its buffer. On success
// `first` points at the first item.
bool CheckView(const tinygltf::Model& model,
  int viewIndex,
  uint64_t offset,
  uint64_t count,
  uint64_t itemSize,
  uint64_t stride,
  const unsigned char*& first,
  const std::string& what,
  std::string& error)
{
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size())
  {
    error = what + " refers to buffer view " + std::to_string(viewIndex) + ", which does not exist";
    return false;
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size())
  {
    error = Where("buffer view", viewIndex) + " refers to buffer " + std::to_string(view.buffer) +
      ", which does not exist";
    return false;
  }
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
  if (!FitsSum(view.byteOffset, view.byteLength, buffer.data.size()))
  {
    error = Where("buffer view", viewIndex) + " (bytes " + std::to_string(view.byteOffset) + " + " +
      std::to_string(view.byteLength) + ") is outside buffer " + std::to_string(view.buffer) +
      " (" + std::to_string(buffer.data.size()) + " bytes)";
    return false;
  }
  if (count > 0)
  {
    // offset + (count - 1) * stride + itemSize <= byteLength, without overflow.
    const uint64_t length = view.byteLength;
    const bool fits = FitsSum(offset, itemSize, length) &&
      (stride == 0 || count - 1 <= (length - offset - itemSize) / stride);
    if (!fits)
    {
      error = what + " (" + std::to_string(count) + " items at offset " + std::to_string(offset) +
        ") does not fit in buffer view " + std::to_string(viewIndex) + " (" +
        std::to_string(length) + " bytes)";
      return false;
    }
  }
  first = buffer.data.data() + view.byteOffset + offset;
  return true;
}

/// The bytes of all the file's buffers: an accessor without a buffer view (zeros) may have no
/// more elements than that, so that a small file cannot ask for memory out of proportion to its
/// own size. Real files stay far below: such accessors (sparse morph targets, mostly) have as
/// many elements as the buffer-backed attributes they go with.
uint64_t BufferBytes(const tinygltf::Model& model)
{
  uint64_t bytes = 0;
  for (const tinygltf::Buffer& buffer : model.buffers)
  {
    bytes += buffer.data.size();
  }
  return bytes;
}

bool LoadAccessor(const tinygltf::Model& model, int index, AccessorData& out, std::string& error)
{
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
  {
    error = "accessor " + std::to_string(index) + " does not exist (the file has " +
      std::to_string(model.accessors.size()) + ")";
    return false;
  }
  const tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  const std::string name = Where("accessor", index);
  out = AccessorData();
  out.ComponentType = acc.componentType;
  out.Type = acc.type;
  out.ComponentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType));
  out.Components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
  out.Normalized = acc.normalized;
  out.Count = acc.count;
  if (out.ComponentSize <= 0 || out.Components <= 0)
  {
    error = name + " has an invalid componentType or type";
    return false;
  }
  if (acc.type > TINYGLTF_TYPE_VEC4 && acc.type != TINYGLTF_TYPE_SCALAR)
  {
    error = name + ": matrix accessors are not supported here";
    return false;
  }
  const uint64_t elementSize = out.ElementSize();
  if (acc.count > kMaxAccessorBytes / elementSize)
  {
    error = name + " has an implausible count (" + std::to_string(acc.count) + ")";
    return false;
  }
  if (acc.bufferView < 0 && acc.count > BufferBytes(model))
  {
    error = name + " has no buffer view and more elements (" + std::to_string(acc.count) +
      ") than the file's buffers have bytes (" + std::to_string(BufferBytes(model)) + ")";
    return false;
  }
  out.Bytes.assign(acc.count * elementSize, 0); // no buffer view: zeros (glTF 3.6.2.3)
  if (acc.bufferView >= 0)
  {
    const tinygltf::BufferView* view =
      static_cast<size_t>(acc.bufferView) < model.bufferViews.size()
      ? &model.bufferViews[static_cast<size_t>(acc.bufferView)]
      : nullptr;
    const uint64_t stride = view && view->byteStride ? view->byteStride : elementSize;
    if (stride < elementSize)
    {
      error = name + ": byteStride " + std::to_string(stride) + " is smaller than an element";
      return false;
    }
    const unsigned char* first = nullptr;
    if (!CheckView(model,
          acc.bufferView,
          acc.byteOffset,
          acc.count,
          elementSize,
          stride,
          first,
          name,
          error))
    {
      return false;
    }
    for (size_t i = 0; i < acc.count; ++i)
    {
      std::memcpy(out.Bytes.data() + i * elementSize, first + i * stride, elementSize);
    }
  }
  if (acc.sparse.isSparse)
  {
    const auto& sparse = acc.sparse;
    const int indexSize =
      tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(sparse.indices.componentType));
    if (sparse.count <= 0 || static_cast<size_t>(sparse.count) > acc.count ||
      (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
      sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    {
      error = name + " has an invalid sparse section";
      return false;
    }
    const unsigned char* indices = nullptr;
    const unsigned char* values = nullptr;
    if (!CheckView(model,
          sparse.indices.bufferView,
          sparse.indices.byteOffset,
          sparse.count,
          indexSize,
          indexSize,
          indices,
          name + " sparse indices",
          error) ||
      !CheckView(model,
        sparse.values.bufferView,
        sparse.values.byteOffset,
        sparse.count,
        elementSize,
        elementSize,
        values,
        name + " sparse values",
        error))
    {
      return false;
    }
    for (int s = 0; s < sparse.count; ++s)
    {
      const double target =
        ReadComponent(sparse.indices.componentType, indices + static_cast<size_t>(s) * indexSize);
      if (target >= static_cast<double>(acc.count))
      {
        error = name + " has a sparse index out of range (" +
          std::to_string(static_cast<uint64_t>(target)) + ")";
        return false;
      }
      std::memcpy(out.Bytes.data() + static_cast<size_t>(target) * elementSize,
        values + static_cast<size_t>(s) * elementSize,
        elementSize);
    }
  }
  return true;
}

// The accessor of attribute `name`, checked to have `components` components and `count`
// elements (count 0: any).
bool LoadAttribute(const tinygltf::Model& model,
  const std::map<std::string, int>& attributes,
  const std::string& name,
  int components,
  size_t count,
  AccessorData& out,
  std::string& error)
{
  const auto it = attributes.find(name);
  if (!LoadAccessor(model, it->second, out, error))
  {
    error = name + ": " + error;
    return false;
  }
  if (out.Components != components || (count && out.Count != count))
  {
    error = name + " has " + std::to_string(out.Count) + " elements of " +
      std::to_string(out.Components) + " components; expected " +
      (count ? std::to_string(count) : std::string("any number")) + " of " +
      std::to_string(components);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
const tinygltf::Primitive* FindPrimitive(const tinygltf::Model& model,
  PrimitiveId id,
  std::string& error)
{
  if (id.Mesh < 0 || static_cast<size_t>(id.Mesh) >= model.meshes.size() || id.Primitive < 0 ||
    static_cast<size_t>(id.Primitive) >=
      model.meshes[static_cast<size_t>(id.Mesh)].primitives.size())
  {
    error = PrimitiveName(id) + " does not exist";
    return nullptr;
  }
  return &model.meshes[static_cast<size_t>(id.Mesh)].primitives[static_cast<size_t>(id.Primitive)];
}

// The vertex count (POSITION's) of a primitive.
bool VertexCount(const tinygltf::Model& model,
  const tinygltf::Primitive& prim,
  PrimitiveId id,
  size_t& count,
  std::string& error)
{
  const auto it = prim.attributes.find("POSITION");
  if (it == prim.attributes.end())
  {
    error = PrimitiveName(id) + " has no POSITION";
    return false;
  }
  if (it->second < 0 || static_cast<size_t>(it->second) >= model.accessors.size())
  {
    error = PrimitiveName(id) + ": POSITION refers to accessor " + std::to_string(it->second) +
      ", which does not exist";
    return false;
  }
  count = model.accessors[static_cast<size_t>(it->second)].count;
  return true;
}

// The primitive's triangles as vertex index triples (strips and fans converted, winding kept).
bool PrimitiveTriangles(const tinygltf::Model& model,
  const tinygltf::Primitive& prim,
  PrimitiveId id,
  size_t vertexCount,
  std::vector<uint32_t>& triangles,
  std::string& error)
{
  std::vector<uint32_t> corners;
  if (prim.indices >= 0)
  {
    AccessorData indices;
    if (!LoadAccessor(model, prim.indices, indices, error))
    {
      error = PrimitiveName(id) + " indices: " + error;
      return false;
    }
    if (indices.Components != 1 ||
      (indices.ComponentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indices.ComponentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indices.ComponentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    {
      error = PrimitiveName(id) + ": indices must be unsigned integer scalars";
      return false;
    }
    corners.resize(indices.Count);
    for (size_t i = 0; i < indices.Count; ++i)
    {
      const double v = indices.Raw(i, 0);
      if (v >= static_cast<double>(vertexCount))
      {
        error = PrimitiveName(id) + ": index " + std::to_string(static_cast<uint64_t>(v)) +
          " (at " + std::to_string(i) + ") is out of range (" + std::to_string(vertexCount) +
          " vertices)";
        return false;
      }
      corners[i] = static_cast<uint32_t>(v);
    }
  }
  else
  {
    if (vertexCount > std::numeric_limits<uint32_t>::max())
    {
      error = PrimitiveName(id) + " has too many vertices";
      return false;
    }
    corners.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i)
    {
      corners[i] = static_cast<uint32_t>(i);
    }
  }
  triangles.clear();
  const size_t n = corners.size();
  switch (prim.mode)
  {
    case TINYGLTF_MODE_TRIANGLES:
      if (n % 3 != 0)
      {
        error = PrimitiveName(id) + ": " + std::to_string(n) +
          " corners is not a whole number of triangles";
        return false;
      }
      triangles = std::move(corners);
      break;
    case TINYGLTF_MODE_TRIANGLE_STRIP: // glTF 3.7.2.1: {v_i, v_i+(1+i%2), v_i+(2-i%2)}
      for (size_t i = 0; i + 2 < n; ++i)
      {
        const size_t odd = i % 2;
        triangles.insert(
          triangles.end(), { corners[i], corners[i + 1 + odd], corners[i + 2 - odd] });
      }
      break;
    case TINYGLTF_MODE_TRIANGLE_FAN: // {v_i+1, v_i+2, v_0}
      for (size_t i = 0; i + 2 < n; ++i)
      {
        triangles.insert(triangles.end(), { corners[i + 1], corners[i + 2], corners[0] });
      }
      break;
    default:
      error =
        PrimitiveName(id) + " is not made of triangles (mode " + std::to_string(prim.mode) + ")";
      return false;
  }
  return true;
}

template<typename ArrayT>
vtkSmartPointer<ArrayT> ToArray(const AccessorData& data,
  const char* name,
  int firstComponent,
  int components)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(data.Count));
  for (size_t i = 0; i < data.Count; ++i)
  {
    for (int k = 0; k < components; ++k)
    {
      array->SetTypedComponent(static_cast<vtkIdType>(i),
        k,
        static_cast<typename ArrayT::ValueType>(data.Value(i, firstComponent + k)));
    }
  }
  return array;
}

void AddField(vtkFieldData* fd, const char* name, int value)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void AddField(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void AddField(vtkFieldData* fd, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

/// The texture-coordinate set a normal texture reads: its texCoord, or the one its
/// KHR_texture_transform names instead.
int TexCoordSet(const tinygltf::NormalTextureInfo& info)
{
  const auto transform = info.extensions.find("KHR_texture_transform");
  if (transform != info.extensions.end() && transform->second.Has("texCoord") &&
    transform->second.Get("texCoord").IsInt())
  {
    return std::max(0, transform->second.Get("texCoord").GetNumberAsInt());
  }
  return std::max(0, info.texCoord);
}

void AddMaterialFields(const Document& doc, const tinygltf::Primitive& prim, vtkFieldData* fd)
{
  const tinygltf::Model& model = doc.Model;
  AddField(fd, "GLTFMaterial", prim.material);
  if (prim.material < 0 || static_cast<size_t>(prim.material) >= model.materials.size())
  {
    return;
  }
  const tinygltf::NormalTextureInfo& info =
    model.materials[static_cast<size_t>(prim.material)].normalTexture;
  if (info.index < 0 || static_cast<size_t>(info.index) >= model.textures.size())
  {
    return;
  }
  const int image = model.textures[static_cast<size_t>(info.index)].source;
  std::string uri, file;
  if (image >= 0 && static_cast<size_t>(image) < model.images.size())
  {
    uri = model.images[static_cast<size_t>(image)].uri;
    if (IsRelativeFileURI(uri))
    {
      file = (fs::path(doc.Path).parent_path() / PercentDecode(uri)).lexically_normal().string();
    }
  }
  AddField(fd, "NormalTextureImage", image);
  AddField(fd, "NormalTextureTexCoord", TexCoordSet(info));
  AddField(fd, "NormalTextureScale", info.scale);
  AddField(fd, "NormalTextureURI", uri);
  AddField(fd, "NormalTextureFile", file);
}

//------------------------------------------------------------------------------
// Writing: new accessors go into a staging buffer (packed with the others on writing).
size_t Align4(size_t n)
{
  return (n + 3) & ~size_t(3);
}

int StagingBuffer(tinygltf::Model& model)
{
  if (model.buffers.empty() || model.buffers.back().name != "normalmap-staging")
  {
    tinygltf::Buffer staging;
    staging.name = "normalmap-staging";
    model.buffers.push_back(staging);
  }
  return static_cast<int>(model.buffers.size()) - 1;
}

// Appends a buffer view holding `count` elements of `elementSize` bytes, `stride` apart.
int AppendView(tinygltf::Model& model,
  const unsigned char* elements,
  size_t count,
  size_t elementSize,
  size_t stride,
  int target)
{
  tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(StagingBuffer(model))];
  buffer.data.resize(Align4(buffer.data.size()), 0);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size()) - 1;
  view.byteOffset = buffer.data.size();
  view.byteLength = std::max<size_t>(stride * count, 4); // byteLength >= 1, even for 0 elements
  view.byteStride = stride != elementSize ? stride : 0;
  view.target = target;
  buffer.data.resize(buffer.data.size() + view.byteLength, 0);
  for (size_t i = 0; i < count; ++i)
  {
    std::memcpy(
      buffer.data.data() + view.byteOffset + i * stride, elements + i * elementSize, elementSize);
  }
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

// Appends an accessor over `elements` packed elements. Vertex attributes get a byteStride that
// keeps every element 4-byte aligned (glTF 3.6.2.4).
int AppendAccessor(tinygltf::Model& model,
  const std::vector<unsigned char>& elements,
  size_t count,
  int componentType,
  int type,
  bool normalized,
  int target)
{
  const size_t elementSize = count ? elements.size() / count : 0;
  const size_t stride = target == TINYGLTF_TARGET_ARRAY_BUFFER ? Align4(elementSize) : elementSize;
  tinygltf::Accessor acc;
  acc.bufferView = AppendView(model, elements.data(), count, elementSize, stride, target);
  acc.byteOffset = 0;
  acc.componentType = componentType;
  acc.type = type;
  acc.count = count;
  acc.normalized = normalized;
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

void SetMinMax(tinygltf::Model& model, int index)
{
  AccessorData data;
  std::string unused;
  if (!LoadAccessor(model, index, data, unused) || data.Count == 0)
  {
    return;
  }
  tinygltf::Accessor& acc = model.accessors[static_cast<size_t>(index)];
  acc.minValues.assign(static_cast<size_t>(data.Components), std::numeric_limits<double>::max());
  acc.maxValues.assign(static_cast<size_t>(data.Components), -std::numeric_limits<double>::max());
  for (size_t i = 0; i < data.Count; ++i)
  {
    for (int k = 0; k < data.Components; ++k)
    {
      acc.minValues[static_cast<size_t>(k)] =
        std::min(acc.minValues[static_cast<size_t>(k)], data.Raw(i, k));
      acc.maxValues[static_cast<size_t>(k)] =
        std::max(acc.maxValues[static_cast<size_t>(k)], data.Raw(i, k));
    }
  }
}

int AppendFloats(tinygltf::Model& model,
  const std::vector<float>& values,
  int components,
  bool minMax)
{
  std::vector<unsigned char> bytes(values.size() * sizeof(float));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  const int type = components == 1 ? TINYGLTF_TYPE_SCALAR : components;
  const int index = AppendAccessor(model,
    bytes,
    values.size() / static_cast<size_t>(components),
    TINYGLTF_COMPONENT_TYPE_FLOAT,
    type,
    false,
    TINYGLTF_TARGET_ARRAY_BUFFER);
  if (minMax)
  {
    SetMinMax(model, index);
  }
  return index;
}

int AppendIndices(tinygltf::Model& model, const std::vector<uint32_t>& corners, size_t vertices)
{
  // 65535 is the primitive restart value, which glTF forbids in indices: ushort only below it.
  const bool narrow = vertices <= 65535;
  std::vector<unsigned char> bytes(corners.size() * (narrow ? 2 : 4));
  for (size_t i = 0; i < corners.size(); ++i)
  {
    if (narrow)
    {
      const uint16_t v = static_cast<uint16_t>(corners[i]);
      std::memcpy(bytes.data() + 2 * i, &v, 2);
    }
    else
    {
      std::memcpy(bytes.data() + 4 * i, &corners[i], 4);
    }
  }
  return AppendAccessor(model,
    bytes,
    corners.size(),
    narrow ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
    TINYGLTF_TYPE_SCALAR,
    false,
    TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

// TANGENT as glTF wants it: unit xyz (renormalized only when not unit to float precision, so
// stored tangents pass through bit for bit), w exactly +1 or -1; a zero or non-finite tangent
// becomes (1, 0, 0), MikkTSpace's own default.
bool TangentVec4(vtkPolyData* frames, std::vector<float>& out, std::string& error)
{
  vtkPointData* pd = frames->GetPointData();
  vtkDataArray* t = pd->GetArray(vtkPolyDataTangentFrames::TangentsArrayName());
  vtkDataArray* s = pd->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  const vtkIdType n = frames->GetNumberOfPoints();
  if (!t || t->GetNumberOfComponents() != 3 || t->GetNumberOfTuples() != n ||
    (s && s->GetNumberOfTuples() != n))
  {
    error = std::string("the mesh has no 3-component point array '") +
      vtkPolyDataTangentFrames::TangentsArrayName() + "' (one tuple per point)";
    return false;
  }
  out.resize(static_cast<size_t>(n) * 4);
  for (vtkIdType i = 0; i < n; ++i)
  {
    float v[3] = { static_cast<float>(t->GetComponent(i, 0)),
      static_cast<float>(t->GetComponent(i, 1)),
      static_cast<float>(t->GetComponent(i, 2)) };
    const double length =
      std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
    // 4 float ulps of 1: the rounding a unit vector stored in float can carry.
    if (!std::isfinite(length) || length == 0.0)
    {
      v[0] = 1.0f;
      v[1] = v[2] = 0.0f;
    }
    else if (std::abs(length - 1.0) > 4.0 * std::numeric_limits<float>::epsilon())
    {
      for (float& c : v)
      {
        c = static_cast<float>(c / length);
      }
    }
    const double sign = s ? s->GetComponent(i, 0) : 1.0;
    float* o = &out[4 * static_cast<size_t>(i)];
    o[0] = v[0];
    o[1] = v[1];
    o[2] = v[2];
    o[3] = sign < 0.0 ? -1.0f : 1.0f;
  }
  return true;
}

std::vector<float> FloatTuples(vtkDataArray* array, int components)
{
  std::vector<float> out(static_cast<size_t>(array->GetNumberOfTuples() * components));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int k = 0; k < components; ++k)
    {
      out[static_cast<size_t>(i * components + k)] = static_cast<float>(array->GetComponent(i, k));
    }
  }
  return out;
}

// Unit normals (glTF requires them): zero or non-finite ones become +z.
std::vector<float> UnitNormals(vtkDataArray* normals)
{
  std::vector<float> out = FloatTuples(normals, 3);
  for (size_t i = 0; i + 2 < out.size(); i += 3)
  {
    const double length = std::sqrt(
      double(out[i]) * out[i] + double(out[i + 1]) * out[i + 1] + double(out[i + 2]) * out[i + 2]);
    if (!std::isfinite(length) || length == 0.0)
    {
      out[i] = out[i + 1] = 0.0f;
      out[i + 2] = 1.0f;
    }
    else if (std::abs(length - 1.0) > 4.0 * std::numeric_limits<float>::epsilon())
    {
      for (int k = 0; k < 3; ++k)
      {
        out[i + k] = static_cast<float>(out[i + k] / length);
      }
    }
  }
  return out;
}

// Triangles of polydata: polygons fan-triangulated (as the filter does), strips alternating.
bool PolyDataTriangles(vtkPolyData* mesh, std::vector<uint32_t>& corners, std::string& error)
{
  corners.clear();
  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetPolys()->GetNumberOfCells(); ++c)
  {
    mesh->GetPolys()->GetCellAtId(c, ids);
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
    {
      for (vtkIdType p : { ids->GetId(0), ids->GetId(k), ids->GetId(k + 1) })
      {
        corners.push_back(static_cast<uint32_t>(p));
      }
    }
  }
  for (vtkIdType c = 0; c < mesh->GetStrips()->GetNumberOfCells(); ++c)
  {
    mesh->GetStrips()->GetCellAtId(c, ids);
    for (vtkIdType k = 0; k + 2 < ids->GetNumberOfIds(); ++k)
    {
      const vtkIdType odd = k % 2;
      for (vtkIdType p : { ids->GetId(k + odd), ids->GetId(k + 1 - odd), ids->GetId(k + 2) })
      {
        corners.push_back(static_cast<uint32_t>(p));
      }
    }
  }
  for (uint32_t p : corners)
  {
    if (static_cast<vtkIdType>(p) >= n)
    {
      error = "a cell refers to point " + std::to_string(p) + " of " + std::to_string(n);
      return false;
    }
  }
  if (corners.empty())
  {
    error = "the mesh has no triangles";
    return false;
  }
  return true;
}

// Gathers the elements `ids` of accessor `index` into a new accessor of the same kind.
bool GatherAccessor(tinygltf::Model& model,
  int index,
  const std::vector<size_t>& ids,
  int& result,
  std::string& error)
{
  AccessorData data;
  if (!LoadAccessor(model, index, data, error))
  {
    return false;
  }
  const size_t size = data.ElementSize();
  std::vector<unsigned char> bytes(ids.size() * size);
  for (size_t i = 0; i < ids.size(); ++i)
  {
    if (ids[i] >= data.Count)
    {
      error = Where("accessor", index) + " has fewer elements than the primitive's vertices";
      return false;
    }
    std::memcpy(bytes.data() + i * size, data.Bytes.data() + ids[i] * size, size);
  }
  const tinygltf::Accessor& old = model.accessors[static_cast<size_t>(index)];
  const bool minMax = !old.minValues.empty();
  result = AppendAccessor(model,
    bytes,
    ids.size(),
    data.ComponentType,
    data.Type,
    data.Normalized,
    TINYGLTF_TARGET_ARRAY_BUFFER);
  model.accessors[static_cast<size_t>(result)].name =
    model.accessors[static_cast<size_t>(index)].name;
  if (minMax)
  {
    SetMinMax(model, result);
  }
  return true;
}

//------------------------------------------------------------------------------
// Compaction on writing.
template<typename F>
void ForEachAccessorReference(tinygltf::Model& model, F&& visit)
{
  for (auto& mesh : model.meshes)
  {
    for (auto& prim : mesh.primitives)
    {
      for (auto& attribute : prim.attributes)
      {
        visit(attribute.second);
      }
      visit(prim.indices);
      for (auto& target : prim.targets)
      {
        for (auto& attribute : target)
        {
          visit(attribute.second);
        }
      }
    }
  }
  for (auto& skin : model.skins)
  {
    visit(skin.inverseBindMatrices);
  }
  for (auto& animation : model.animations)
  {
    for (auto& sampler : animation.samplers)
    {
      visit(sampler.input);
      visit(sampler.output);
    }
  }
}

template<typename F>
void ForEachViewReference(tinygltf::Model& model, F&& visit)
{
  for (auto& acc : model.accessors)
  {
    visit(acc.bufferView);
    if (acc.sparse.isSparse)
    {
      visit(acc.sparse.indices.bufferView);
      visit(acc.sparse.values.bufferView);
    }
  }
  for (auto& image : model.images)
  {
    visit(image.bufferView);
  }
}

// Renumbering is safe unless an extension may refer to accessors or buffer views by index.
bool ExtensionsAllowRenumbering(const tinygltf::Model& model)
{
  for (const std::string& ext : model.extensionsUsed)
  {
    const bool known = ext.compare(0, 14, "KHR_materials_") == 0 ||
      ext == "KHR_texture_transform" || ext == "KHR_lights_punctual" ||
      ext == "KHR_mesh_quantization" || ext == "KHR_texture_basisu" || ext == "EXT_texture_webp";
    if (!known)
    {
      return false;
    }
  }
  return true;
}

// Erases the elements whose flag is set and renumbers the references to the rest.
template<typename T, typename ForEachReference>
void EraseAndRenumber(std::vector<T>& items,
  const std::vector<bool>& erase,
  tinygltf::Model& model,
  ForEachReference&& forEachReference)
{
  std::vector<int> newIndex(items.size(), -1);
  std::vector<T> kept;
  for (size_t i = 0; i < items.size(); ++i)
  {
    if (!erase[i])
    {
      newIndex[i] = static_cast<int>(kept.size());
      kept.push_back(std::move(items[i]));
    }
  }
  items = std::move(kept);
  forEachReference(model,
    [&](int& ref)
    {
      if (ref >= 0 && static_cast<size_t>(ref) < newIndex.size())
      {
        ref = newIndex[static_cast<size_t>(ref)];
      }
    });
}

template<typename ForEachReference>
std::vector<int> ReferenceCounts(tinygltf::Model& model, size_t size, ForEachReference&& forEach)
{
  std::vector<int> counts(size, 0);
  forEach(model,
    [&](int& ref)
    {
      if (ref >= 0 && static_cast<size_t>(ref) < size)
      {
        ++counts[static_cast<size_t>(ref)];
      }
    });
  return counts;
}

void RemoveReplacedAccessors(Document& doc)
{
  tinygltf::Model& model = doc.Model;
  const auto forAccessors = [](tinygltf::Model& m, auto&& f) { ForEachAccessorReference(m, f); };
  const auto forViews = [](tinygltf::Model& m, auto&& f) { ForEachViewReference(m, f); };
  if (doc.ReplacedAccessors.empty() || !ExtensionsAllowRenumbering(model))
  {
    return;
  }
  const std::vector<int> used = ReferenceCounts(model, model.accessors.size(), forAccessors);
  std::vector<bool> erase(model.accessors.size(), false);
  bool any = false;
  for (int a : doc.ReplacedAccessors)
  {
    if (a >= 0 && static_cast<size_t>(a) < erase.size() && used[static_cast<size_t>(a)] == 0)
    {
      erase[static_cast<size_t>(a)] = any = true;
    }
  }
  doc.ReplacedAccessors.clear();
  if (!any)
  {
    return;
  }
  const std::vector<int> viewsBefore = ReferenceCounts(model, model.bufferViews.size(), forViews);
  EraseAndRenumber(model.accessors, erase, model, forAccessors);
  const std::vector<int> viewsAfter = ReferenceCounts(model, model.bufferViews.size(), forViews);
  std::vector<bool> eraseViews(model.bufferViews.size(), false);
  for (size_t v = 0; v < eraseViews.size(); ++v)
  {
    eraseViews[v] = viewsBefore[v] > 0 && viewsAfter[v] == 0;
  }
  EraseAndRenumber(model.bufferViews, eraseViews, model, forViews);
}

// The MIME type of an image's bytes from their signature (PNG, JPEG, WebP; glTF's image types),
// or an empty string.
std::string ImageMimeType(const std::vector<unsigned char>& bytes)
{
  const auto startsWith = [&](size_t at, const char* signature, size_t n)
  { return bytes.size() >= at + n && std::memcmp(bytes.data() + at, signature, n) == 0; };
  if (startsWith(0, "\x89PNG", 4))
  {
    return "image/png";
  }
  if (startsWith(0, "\xFF\xD8\xFF", 3))
  {
    return "image/jpeg";
  }
  return startsWith(0, "RIFF", 4) && startsWith(8, "WEBP", 4) ? "image/webp" : "";
}

// Moves data-URI images into buffer views, then packs every buffer view into one buffer.
bool PackBuffers(tinygltf::Model& model, std::string& error)
{
  for (tinygltf::Image& image : model.images)
  {
    if (image.uri.empty() && image.bufferView < 0 && !image.image.empty())
    {
      // The file's data URI may say application/octet-stream, and tinygltf keeps no mimeType
      // of an image with a URI: the bytes tell.
      const std::string type = ImageMimeType(image.image);
      image.mimeType = !type.empty() ? type : image.mimeType.empty() ? "image/png" : image.mimeType;
      image.bufferView =
        AppendView(model, image.image.data(), 1, image.image.size(), image.image.size(), 0);
      model.bufferViews.back().byteLength = image.image.size();
      image.image.clear();
      image.as_is = false;
    }
  }
  tinygltf::Buffer packed;
  if (!model.buffers.empty())
  {
    packed.name =
      model.buffers.front().name == "normalmap-staging" ? "" : model.buffers.front().name;
    packed.extras = model.buffers.front().extras;
  }
  for (size_t v = 0; v < model.bufferViews.size(); ++v)
  {
    tinygltf::BufferView& view = model.bufferViews[v];
    const unsigned char* first = nullptr;
    if (!CheckView(model, static_cast<int>(v), 0, 0, 0, 0, first, "", error))
    {
      return false;
    }
    // Keep the offset modulo 4, so accessors keep their alignment.
    const size_t offset = Align4(packed.data.size()) + view.byteOffset % 4;
    packed.data.resize(offset, 0);
    packed.data.insert(packed.data.end(), first, first + view.byteLength);
    view.buffer = 0;
    view.byteOffset = offset;
  }
  packed.data.resize(Align4(packed.data.size()), 0);
  model.buffers.clear();
  if (!model.bufferViews.empty())
  {
    model.buffers.push_back(std::move(packed));
  }
  return true;
}

// tinygltf 2.7.0 writes a node, scene, texture or material that has none of the properties it
// serializes as `null` instead of `{}`, and then cannot read its own file back ("`textures'
// does not contain an JSON object"); other readers reject it too. Such objects get an empty
// `extras`, which tinygltf writes as `"extras":null` (extras may hold any JSON value), so that
// the object is written as an object. Found by FuzzNormalMapGLTF.
template<typename T>
void KeepAsObject(T& object, bool hasSerializedProperty)
{
  if (!hasSerializedProperty && object.extras.Type() == tinygltf::NULL_TYPE)
  {
    object.extras = tinygltf::Value(tinygltf::Value::Object());
  }
}

void KeepEmptyObjects(tinygltf::Model& model)
{
  for (tinygltf::Node& n : model.nodes)
  {
    KeepAsObject(n,
      n.camera >= 0 || n.skin >= 0 || n.mesh >= 0 || !n.name.empty() || !n.children.empty() ||
        !n.rotation.empty() || !n.scale.empty() || !n.translation.empty() || !n.matrix.empty() ||
        !n.weights.empty() || !n.extensions.empty());
  }
  for (tinygltf::Scene& s : model.scenes)
  {
    KeepAsObject(s, !s.nodes.empty() || !s.name.empty() || !s.extensions.empty());
  }
  for (tinygltf::Texture& t : model.textures)
  {
    KeepAsObject(t, t.sampler >= 0 || t.source >= 0 || !t.name.empty() || !t.extensions.empty());
  }
  for (tinygltf::Material& m : model.materials)
  {
    // Factors equal to their defaults are not written either; only properties that are always
    // written when set count (a material with only factors gets the harmless extras too).
    KeepAsObject(m,
      !m.name.empty() || m.doubleSided || m.alphaMode != "OPAQUE" || m.normalTexture.index >= 0 ||
        m.occlusionTexture.index >= 0 || m.emissiveTexture.index >= 0 ||
        m.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
        m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || !m.extensions.empty());
  }
}

// tinygltf 2.7.0 writes an integer accessor's min and max through static_cast<int>, which is
// undefined outside int's range (UNSIGNED_INT indices above 2^31 - 1 are valid glTF), and
// non-finite bounds as JSON null, which it cannot read back. Such bounds are recomputed from the
// data for float accessors (POSITION requires them) and dropped where they still cannot be
// written (they are optional otherwise). Found by FuzzNormalMapGLTF.
bool WritableBounds(const tinygltf::Accessor& acc)
{
  const bool integer = acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
    acc.componentType != TINYGLTF_COMPONENT_TYPE_DOUBLE;
  for (const std::vector<double>* bounds : { &acc.minValues, &acc.maxValues })
  {
    for (double v : *bounds)
    {
      if (!std::isfinite(v) ||
        (integer && (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())))
      {
        return false;
      }
    }
  }
  return true;
}

void KeepWritableBounds(tinygltf::Model& model)
{
  for (size_t i = 0; i < model.accessors.size(); ++i)
  {
    tinygltf::Accessor& acc = model.accessors[i];
    if (WritableBounds(acc))
    {
      continue;
    }
    acc.minValues.clear();
    acc.maxValues.clear();
    if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
    {
      SetMinMax(model, static_cast<int>(i));
      if (!WritableBounds(acc))
      {
        acc.minValues.clear();
        acc.maxValues.clear();
      }
    }
  }
}

// Image writer for tinygltf: writes no image, only rewrites relative URIs for the output's
// folder.
struct ImageFolders
{
  fs::path Input;
  fs::path Output;
};

bool RewriteImageURI(const std::string*,
  const std::string*,
  const tinygltf::Image* image,
  bool,
  std::string* outURI,
  void* userData)
{
  const auto* folders = static_cast<const ImageFolders*>(userData);
  *outURI = image->uri;
  if (IsRelativeFileURI(image->uri) && folders->Input != folders->Output)
  {
    const std::string decoded = PercentDecode(image->uri);
    const fs::path relative =
      (folders->Input / decoded).lexically_normal().lexically_relative(folders->Output);
    if (!relative.empty())
    {
      *outURI = PercentEncodePath(relative.generic_string());
    }
  }
  return true;
}

// Image loader for tinygltf: no decoding; images stored as data URIs keep their bytes.
bool KeepImageBytes(tinygltf::Image* image,
  const int,
  std::string*,
  std::string*,
  int,
  int,
  const unsigned char* bytes,
  int size,
  void*)
{
  if (image->uri.empty() && image->bufferView < 0 && bytes && size > 0)
  {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
  }
  return true;
}

bool FinishRead(bool ok,
  const std::string& err,
  const std::string& source,
  Document& doc,
  std::string& error)
{
  if (!ok)
  {
    error = "cannot read '" + source +
      "': " + NormalMapFiles::OneLine(err.empty() ? std::string("invalid glTF") : err);
    doc = Document();
    return false;
  }
  return true;
}

fs::path AbsoluteFolder(const std::string& path)
{
  std::error_code ec;
  fs::path folder = fs::path(path).parent_path();
  fs::path absolute = fs::absolute(folder.empty() ? fs::path(".") : folder, ec);
  return (ec ? folder : absolute).lexically_normal();
}
} // namespace

//------------------------------------------------------------------------------
bool ReadDocument(const std::string& path, Document& doc, std::string& error)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    std::error_code ec;
    error = "cannot open '" + path +
      "': " + (fs::exists(path, ec) ? "permission denied" : "no such file");
    return false;
  }
  const std::vector<unsigned char> bytes(
    (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad())
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  std::string folder = fs::path(path).parent_path().string();
  if (!ReadDocumentFromMemory(
        bytes.data(), bytes.size(), folder.empty() ? "." : folder, doc, error))
  {
    const std::string prefix = "cannot read '<memory>': ";
    if (error.compare(0, prefix.size(), prefix) == 0)
    {
      error = "cannot read '" + path + "': " + error.substr(prefix.size());
    }
    return false;
  }
  doc.Path = path;
  return true;
}

bool ReadDocumentFromMemory(const unsigned char* data,
  size_t size,
  const std::string& baseDir,
  Document& doc,
  std::string& error)
{
  doc = Document();
  if (size > std::numeric_limits<unsigned int>::max())
  {
    error = "cannot read '<memory>': larger than 4 GB";
    return false;
  }
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&KeepImageBytes, nullptr);
  std::string err, warn;
  bool ok = false;
  try
  {
    if (size >= 4 && std::memcmp(data, "glTF", 4) == 0)
    {
      ok = loader.LoadBinaryFromMemory(
        &doc.Model, &err, &warn, data, static_cast<unsigned int>(size), baseDir);
    }
    else
    {
      ok = loader.LoadASCIIFromString(&doc.Model,
        &err,
        &warn,
        reinterpret_cast<const char*>(data),
        static_cast<unsigned int>(size),
        baseDir);
    }
  }
  catch (const std::exception& e)
  {
    ok = false;
    err = e.what();
  }
  return FinishRead(ok, err, "<memory>", doc, error);
}

namespace
{
using Matrix4 = std::array<double, 16>; // row-major

/// The node's own transform: its matrix (stored column-major), or translation * rotation *
/// scale (glTF 2.0, 5.25).
Matrix4 LocalMatrix(const tinygltf::Node& node)
{
  Matrix4 m{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  if (node.matrix.size() == 16)
  {
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        m[4 * r + c] = node.matrix[4 * c + r];
      }
    }
    return m;
  }
  const double s[3] = { node.scale.size() == 3 ? node.scale[0] : 1.0,
    node.scale.size() == 3 ? node.scale[1] : 1.0,
    node.scale.size() == 3 ? node.scale[2] : 1.0 };
  // glTF stores the quaternion as (x, y, z, w), vtkMath takes (w, x, y, z) and normalizes it;
  // a zero or non-finite one (invalid glTF) leaves the rotation out.
  double rotation[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  if (node.rotation.size() == 4)
  {
    const double q[4] = { node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2] };
    const double norm2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (std::isfinite(norm2) && norm2 > 0.0)
    {
      vtkMath::QuaternionToMatrix3x3(q, rotation);
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[4 * r + c] = rotation[r][c] * s[c];
    }
    m[4 * r + 3] = node.translation.size() == 3 ? node.translation[r] : 0.0;
  }
  return m;
}

}

std::string PrimitiveName(PrimitiveId id)
{
  return "mesh " + std::to_string(id.Mesh) + " primitive " + std::to_string(id.Primitive);
}

std::vector<std::vector<MeshPlacement>> PlaceMeshes(const Document& doc)
{
  const tinygltf::Model& model = doc.Model;
  std::vector<std::vector<MeshPlacement>> placements(model.meshes.size());
  if (model.scenes.empty())
  {
    return placements;
  }
  const size_t scene =
    model.defaultScene >= 0 && static_cast<size_t>(model.defaultScene) < model.scenes.size()
    ? static_cast<size_t>(model.defaultScene)
    : 0;
  // Depth first, in the order of the nodes' children, without recursion: a hierarchy may be
  // as deep as a file is long. Each node is placed once (a valid file's nodes have one parent
  // and no cycle).
  const Matrix4 identity{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::vector<std::pair<int, Matrix4>> pending;
  const std::vector<int>& roots = model.scenes[scene].nodes;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root)
  {
    pending.emplace_back(*root, identity);
  }
  std::vector<bool> placed(model.nodes.size(), false);
  while (!pending.empty())
  {
    const int node = pending.back().first;
    const Matrix4 parent = pending.back().second;
    pending.pop_back();
    if (node < 0 || static_cast<size_t>(node) >= model.nodes.size() || placed[node])
    {
      continue;
    }
    placed[node] = true;
    const tinygltf::Node& n = model.nodes[static_cast<size_t>(node)];
    const Matrix4 local = LocalMatrix(n);
    Matrix4 world;
    vtkMatrix4x4::Multiply4x4(parent.data(), local.data(), world.data());
    if (n.mesh >= 0 && static_cast<size_t>(n.mesh) < placements.size())
    {
      placements[static_cast<size_t>(n.mesh)].push_back({ node, world });
    }
    for (auto child = n.children.rbegin(); child != n.children.rend(); ++child)
    {
      pending.emplace_back(*child, world);
    }
  }
  return placements;
}

vtkSmartPointer<vtkPolyData> Placed(vtkPolyData* mesh, const std::array<double, 16>& m)
{
  double linear[3][3], normalMatrix[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      linear[r][c] = m[4 * r + c];
    }
  }
  const double determinant = vtkMath::Determinant3x3(linear);
  const bool mirrors = determinant < 0.0;

  auto placed = vtkSmartPointer<vtkPolyData>::New();
  placed->ShallowCopy(mesh);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    mesh->GetPoint(p, x);
    vtkMath::Multiply3x3(linear, x, y);
    points->SetPoint(p, y[0] + m[3], y[1] + m[7], y[2] + m[11]);
  }
  placed->SetPoints(points);
  if (determinant == 0.0)
  {
    // A scale of 0 (glTF's way to hide a node) flattens every triangle: nothing is drawn, and
    // the normals and tangents, which have no transformed direction, stay as they are.
    return placed;
  }
  vtkMath::Invert3x3(linear, normalMatrix);
  vtkMath::Transpose3x3(normalMatrix, normalMatrix);
  const auto transformed = [&](vtkDataArray* vectors, double matrix[3][3])
  {
    auto out = vtk::TakeSmartPointer(vectors->NewInstance());
    out->DeepCopy(vectors);
    for (vtkIdType p = 0; p < vectors->GetNumberOfTuples(); ++p)
    {
      double v[3], w[3];
      vectors->GetTuple(p, v);
      vtkMath::Multiply3x3(matrix, v, w);
      vtkMath::Normalize(w);
      out->SetTuple(p, w);
    }
    return out;
  };
  vtkPointData* pd = placed->GetPointData();
  if (vtkDataArray* normals = mesh->GetPointData()->GetNormals())
  {
    pd->SetNormals(transformed(normals, normalMatrix));
  }
  vtkDataArray* tangents = mesh->GetPointData()->GetArray("Tangents");
  if (tangents && tangents->GetNumberOfComponents() == 3)
  {
    const bool active = mesh->GetPointData()->GetTangents() == tangents;
    auto moved = transformed(tangents, linear);
    pd->RemoveArray("Tangents");
    if (active)
    {
      pd->SetTangents(moved);
    }
    else
    {
      pd->AddArray(moved);
    }
  }
  vtkDataArray* signs = mesh->GetPointData()->GetArray("TangentSigns");
  if (signs && mirrors)
  {
    auto flipped = vtk::TakeSmartPointer(signs->NewInstance());
    flipped->DeepCopy(signs);
    for (vtkIdType p = 0; p < signs->GetNumberOfTuples(); ++p)
    {
      flipped->SetComponent(p, 0, -signs->GetComponent(p, 0));
    }
    pd->RemoveArray("TangentSigns");
    pd->AddArray(flipped);
  }
  if (mirrors)
  {
    // glTF draws the triangles of a mirroring node with their winding reversed (the sign of the
    // determinant decides it). Placed in world coordinates, they keep their front faces, and
    // MikkTSpace (whose sign follows the winding of the texture coordinates) keeps the negated
    // signs, only with their point order reversed.
    vtkNew<vtkReverseSense> reverse;
    reverse->SetInputData(placed);
    reverse->ReverseCellsOn();
    reverse->ReverseNormalsOff();
    reverse->Update();
    placed = reverse->GetOutput();
  }
  return placed;
}

std::vector<PlacedMesh> PlaceMesh(const std::vector<std::vector<MeshPlacement>>& placements,
  int meshIndex,
  vtkPolyData* mesh,
  const std::string& name)
{
  const bool known = meshIndex >= 0 && static_cast<size_t>(meshIndex) < placements.size();
  if (!known || placements[static_cast<size_t>(meshIndex)].empty())
  {
    return { { mesh, name, false } };
  }
  const auto& nodes = placements[static_cast<size_t>(meshIndex)];
  std::vector<PlacedMesh> placed;
  for (const MeshPlacement& node : nodes)
  {
    placed.push_back({ Placed(mesh, node.Matrix),
      name + (nodes.size() > 1 ? ", node " + std::to_string(node.Node) : ""),
      true });
  }
  return placed;
}

std::vector<PrimitiveId> TrianglePrimitives(const Document& doc)
{
  std::vector<PrimitiveId> ids;
  for (size_t m = 0; m < doc.Model.meshes.size(); ++m)
  {
    const auto& prims = doc.Model.meshes[m].primitives;
    for (size_t p = 0; p < prims.size(); ++p)
    {
      const int mode = prims[p].mode;
      if (mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
        mode == TINYGLTF_MODE_TRIANGLE_FAN)
      {
        ids.push_back({ static_cast<int>(m), static_cast<int>(p) });
      }
    }
  }
  return ids;
}

std::string NormalTextureTexCoordName(const Document& doc, PrimitiveId id)
{
  std::string unused;
  const tinygltf::Primitive* prim = FindPrimitive(doc.Model, id, unused);
  int set = 0;
  if (prim && prim->material >= 0 &&
    static_cast<size_t>(prim->material) < doc.Model.materials.size())
  {
    const auto& info = doc.Model.materials[static_cast<size_t>(prim->material)].normalTexture;
    set = info.index >= 0 ? TexCoordSet(info) : 0;
  }
  return "TEXCOORD_" + std::to_string(set);
}

vtkSmartPointer<vtkPolyData> PrimitiveToPolyData(const Document& doc,
  PrimitiveId id,
  std::string& error)
{
  const tinygltf::Model& model = doc.Model;
  const tinygltf::Primitive* prim = FindPrimitive(model, id, error);
  size_t vertexCount = 0;
  if (!prim || !VertexCount(model, *prim, id, vertexCount, error))
  {
    return nullptr;
  }
  std::vector<uint32_t> triangles;
  if (!PrimitiveTriangles(model, *prim, id, vertexCount, triangles, error))
  {
    return nullptr;
  }

  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkPointData* pd = mesh->GetPointData();
  AccessorData data;
  for (const auto& attribute : prim->attributes)
  {
    const std::string& name = attribute.first;
    const bool texcoord = name.compare(0, 9, "TEXCOORD_") == 0;
    if (name != "POSITION" && name != "NORMAL" && name != "TANGENT" && !texcoord)
    {
      continue; // colours, joints, weights, custom: kept in the file, not needed here
    }
    const int components = name == "TANGENT" ? 4 : texcoord ? 2 : 3;
    if (!LoadAttribute(model, prim->attributes, name, components, vertexCount, data, error))
    {
      error = PrimitiveName(id) + " " + error;
      return nullptr;
    }
    if (name == "POSITION")
    {
      vtkNew<vtkPoints> points;
      points->SetData(ToArray<vtkFloatArray>(data, "Points", 0, 3));
      mesh->SetPoints(points);
    }
    else if (name == "NORMAL")
    {
      pd->SetNormals(ToArray<vtkFloatArray>(data, "Normals", 0, 3));
    }
    else if (name == "TANGENT")
    {
      pd->SetTangents(
        ToArray<vtkFloatArray>(data, vtkPolyDataTangentFrames::TangentsArrayName(), 0, 3));
      pd->AddArray(ToArray<vtkFloatArray>(data, vtkPolyDataTangentFrames::SignsArrayName(), 3, 1));
    }
    else
    {
      auto uv = ToArray<vtkFloatArray>(data, name.c_str(), 0, 2);
      if (name == "TEXCOORD_0")
      {
        pd->SetTCoords(uv);
      }
      else
      {
        pd->AddArray(uv);
      }
    }
  }
  vtkNew<vtkIdTypeArray> vertexIds;
  vertexIds->SetName(VertexIdArrayName);
  vertexIds->SetNumberOfTuples(static_cast<vtkIdType>(vertexCount));
  for (size_t i = 0; i < vertexCount; ++i)
  {
    vertexIds->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(i));
  }
  pd->AddArray(vertexIds);

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfTuples(static_cast<vtkIdType>(triangles.size() / 3 + 1));
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(triangles.size()));
  for (size_t i = 0; i <= triangles.size() / 3; ++i)
  {
    offsets->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(3 * i));
  }
  for (size_t i = 0; i < triangles.size(); ++i)
  {
    connectivity->SetValue(static_cast<vtkIdType>(i), triangles[i]);
  }
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  mesh->SetPolys(polys);

  vtkFieldData* fd = mesh->GetFieldData();
  AddField(fd, NormalMapTangents::VDownArrayName, 1);
  AddField(fd, "GLTFMesh", id.Mesh);
  AddField(fd, "GLTFPrimitive", id.Primitive);
  AddMaterialFields(doc, *prim, fd);
  return mesh;
}

bool UpdatePrimitive(Document& doc, PrimitiveId id, vtkPolyData* frames, std::string& error)
{
  tinygltf::Model& model = doc.Model;
  const tinygltf::Primitive* found = FindPrimitive(model, id, error);
  size_t vertexCount = 0;
  std::vector<uint32_t> original, corners;
  if (!found || !VertexCount(model, *found, id, vertexCount, error) ||
    !PrimitiveTriangles(model, *found, id, vertexCount, original, error))
  {
    return false;
  }
  std::vector<float> tangents;
  if (!frames || !TangentVec4(frames, tangents, error) ||
    !PolyDataTriangles(frames, corners, error))
  {
    error = PrimitiveName(id) + ": " + error;
    return false;
  }
  vtkDataArray* ids = frames->GetPointData()->GetArray(VertexIdArrayName);
  const vtkIdType n = frames->GetNumberOfPoints();
  if (!ids || ids->GetNumberOfComponents() != 1 || ids->GetNumberOfTuples() != n)
  {
    error = PrimitiveName(id) + ": the mesh has no point array '" + VertexIdArrayName + "'";
    return false;
  }
  std::vector<size_t> source(static_cast<size_t>(n));
  bool identity = static_cast<size_t>(n) == vertexCount;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double v = ids->GetComponent(i, 0);
    if (!(v >= 0.0 && v < static_cast<double>(vertexCount)))
    {
      error = PrimitiveName(id) + ": '" + VertexIdArrayName + "' value out of range";
      return false;
    }
    source[static_cast<size_t>(i)] = static_cast<size_t>(v);
    identity = identity && source[static_cast<size_t>(i)] == static_cast<size_t>(i);
  }

  tinygltf::Primitive prim = *found;
  const auto replace = [&](int& slot, int with)
  {
    if (slot >= 0)
    {
      doc.ReplacedAccessors.push_back(slot);
    }
    slot = with;
  };
  if (!identity)
  {
    for (auto& attribute : prim.attributes)
    {
      int gathered = -1;
      if (attribute.first != "TANGENT")
      {
        if (!GatherAccessor(model, attribute.second, source, gathered, error))
        {
          error = PrimitiveName(id) + " " + attribute.first + ": " + error;
          return false;
        }
        replace(attribute.second, gathered);
      }
    }
    for (auto& target : prim.targets)
    {
      for (auto& attribute : target)
      {
        int gathered = -1;
        if (!GatherAccessor(model, attribute.second, source, gathered, error))
        {
          error = PrimitiveName(id) + " morph target " + attribute.first + ": " + error;
          return false;
        }
        replace(attribute.second, gathered);
      }
    }
  }
  if (!identity || prim.mode != TINYGLTF_MODE_TRIANGLES || corners != original)
  {
    replace(prim.indices, AppendIndices(model, corners, static_cast<size_t>(n)));
    prim.mode = TINYGLTF_MODE_TRIANGLES;
  }
  vtkDataArray* normals = frames->GetPointData()->GetNormals();
  if (!prim.attributes.count("NORMAL") && normals && normals->GetNumberOfComponents() == 3 &&
    normals->GetNumberOfTuples() == n)
  {
    prim.attributes["NORMAL"] = AppendFloats(model, UnitNormals(normals), 3, false);
  }
  auto tangent = prim.attributes.find("TANGENT");
  const int tangentAccessor = AppendFloats(model, tangents, 4, true);
  if (tangent != prim.attributes.end())
  {
    replace(tangent->second, tangentAccessor);
  }
  else
  {
    prim.attributes["TANGENT"] = tangentAccessor;
  }
  model.meshes[static_cast<size_t>(id.Mesh)].primitives[static_cast<size_t>(id.Primitive)] = prim;
  return true;
}

bool DocumentFromPolyData(vtkPolyData* frames,
  const std::string& tcoordsName,
  Document& doc,
  std::string& error)
{
  doc = Document();
  std::vector<uint32_t> corners;
  std::vector<float> tangents;
  vtkDataArray* uv = frames ? NormalMapTangents::FindTCoords(frames, tcoordsName) : nullptr;
  if (!frames || !frames->GetPoints() || !uv)
  {
    error = "the mesh has no points or no texture coordinates";
    return false;
  }
  if (!PolyDataTriangles(frames, corners, error) || !TangentVec4(frames, tangents, error))
  {
    return false;
  }
  tinygltf::Model& model = doc.Model;
  model.asset.version = "2.0";
  model.asset.generator = "normalmap tangents (VTK::NormalMapping)";
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  const vtkIdType n = frames->GetNumberOfPoints();
  prim.attributes["POSITION"] =
    AppendFloats(model, FloatTuples(frames->GetPoints()->GetData(), 3), 3, true);
  vtkDataArray* normals = frames->GetPointData()->GetNormals();
  if (normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == n)
  {
    prim.attributes["NORMAL"] = AppendFloats(model, UnitNormals(normals), 3, false);
  }
  std::vector<float> texcoords = FloatTuples(uv, 2);
  texcoords.resize(static_cast<size_t>(n) * 2);
  if (!NormalMapTangents::IsVDown(frames))
  {
    for (size_t i = 1; i < texcoords.size(); i += 2)
    {
      texcoords[i] = 1.0f - texcoords[i];
    }
  }
  prim.attributes["TEXCOORD_0"] = AppendFloats(model, texcoords, 2, false);
  prim.attributes["TANGENT"] = AppendFloats(model, tangents, 4, true);
  prim.indices = AppendIndices(model, corners, static_cast<size_t>(n));
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return true;
}

bool WriteDocument(Document& doc, NormalMapFiles::OutputTransaction& output, std::string& error)
{
  const std::string ext = NormalMapFiles::Extension(output.FinalPath());
  if (ext != ".gltf" && ext != ".glb")
  {
    error = "'" + output.FinalPath() + "': a glTF output must end in .gltf or .glb";
    return false;
  }
  const bool binary = ext == ".glb";
  RemoveReplacedAccessors(doc);
  KeepEmptyObjects(doc.Model);
  KeepWritableBounds(doc.Model);
  if (!PackBuffers(doc.Model, error))
  {
    error = "cannot write '" + output.FinalPath() + "': " + error;
    return false;
  }
  if (!doc.Model.buffers.empty())
  {
    // tinygltf writes the buffer to the file its URI names, without encoding the URI: the
    // name keeps only characters that mean the same in both ("my model#1.gltf":
    // "my_model_1.bin").
    std::string name = fs::path(output.FinalPath()).stem().string();
    std::replace_if(
      name.begin(),
      name.end(),
      [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.'; },
      '_');
    doc.Model.buffers[0].uri = binary ? std::string() : name + ".bin";
  }
  ImageFolders folders{ doc.Path.empty() ? AbsoluteFolder(output.FinalPath())
                                         : AbsoluteFolder(doc.Path),
    AbsoluteFolder(output.FinalPath()) };
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(&RewriteImageURI, &folders);
  bool ok = false;
  try
  {
    ok = writer.WriteGltfSceneToFile(&doc.Model, output.MainPath(), false, false, true, binary);
  }
  catch (const std::exception& e)
  {
    error = "cannot write '" + output.FinalPath() + "': " + e.what();
    return false;
  }
  if (!ok)
  {
    error = "cannot write '" + output.FinalPath() + "'";
    return false;
  }
  return true;
}

bool WriteDocument(Document& doc, const std::string& path, std::string& error)
{
  NormalMapFiles::OutputTransaction output;
  return output.Begin(path, error) && WriteDocument(doc, output, error) && output.Commit(error);
}

bool EmbeddedImage(const Document& doc,
  int index,
  std::vector<unsigned char>& bytes,
  std::string& mimeType,
  std::string& error)
{
  bytes.clear();
  const tinygltf::Model& model = doc.Model;
  if (index < 0 || static_cast<size_t>(index) >= model.images.size())
  {
    error = Where("image", index) + " does not exist";
    return false;
  }
  const tinygltf::Image& image = model.images[static_cast<size_t>(index)];
  mimeType = image.mimeType;
  if (image.bufferView >= 0)
  {
    // tinygltf 2.7.0 checks only that the view and its buffer exist: check the byte range too.
    const unsigned char* first = nullptr;
    if (!CheckView(model, image.bufferView, 0, 1, 0, 0, first, Where("image", index), error))
    {
      return false;
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(image.bufferView)];
    bytes.assign(first, first + view.byteLength);
  }
  else if (image.uri.empty() && !image.image.empty())
  {
    bytes = image.image; // a data: URI, decoded by tinygltf and kept by KeepImageBytes
  }
  else
  {
    error = Where("image", index) +
      (image.uri.empty() ? " has no data" : " is not embedded (uri '" + image.uri + "')");
    return false;
  }
  if (bytes.empty())
  {
    error = Where("image", index) + " is empty";
    return false;
  }
  return true;
}
}
