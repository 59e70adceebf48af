// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapFiles.h"

#include <vtkAbstractPolyDataReader.h>
#include <vtkCellArray.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPLYReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSTLReader.h>
#include <vtkStringArray.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLMultiBlockDataWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <system_error>
#include <utility>

#include <unistd.h>

namespace fs = std::filesystem;

namespace NormalMapFiles
{
namespace
{
// Collects VTK's messages (one line each) instead of printing them.
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);

  void DisplayText(const char* text) override
  {
    const std::string line = OneLine(text ? text : "");
    switch (this->GetCurrentMessageType())
    {
      case MESSAGE_TYPE_ERROR:
        this->Errors.push_back(line);
        break;
      case MESSAGE_TYPE_WARNING:
      case MESSAGE_TYPE_GENERIC_WARNING:
        this->Warnings.push_back(line);
        break;
      default:
        break; // text and debug output are dropped
    }
  }

  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

protected:
  CaptureWindow() = default;
  ~CaptureWindow() override = default;
};
vtkStandardNewMacro(CaptureWindow);

bool FileIsReadable(const std::string& path, std::string& error)
{
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
  {
    error = "cannot open '" + path + "': no such file";
    return false;
  }
  if (fs::is_directory(status))
  {
    error = "cannot read '" + path + "': it is a directory";
    return false;
  }
  if (std::FILE* f = std::fopen(path.c_str(), "rb"))
  {
    std::fclose(f);
    return true;
  }
  error = "cannot open '" + path + "': " + std::strerror(errno);
  return false;
}

// VTK 9.1's PLY reader crashes (invalid free, segfault) on truncated bodies, missing x/y/z
// properties and out-of-range face indices, so a PLY file is walked here first: the header,
// then every element of the body, checking that it is complete and that faces refer to
// existing vertices.
bool CheckPLY(const std::string& path, std::string& error)
{
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto fail = [&](const std::string& why)
  {
    error = "'" + path + "' is not a valid PLY file: " + why;
    return false;
  };
  const size_t headerEnd = bytes.find("end_header");
  if (bytes.compare(0, 3, "ply") != 0 || headerEnd == std::string::npos)
  {
    return fail("no 'ply' ... 'end_header' header");
  }
  struct Property
  {
    std::string Name;
    int Size = 0;      // bytes of the value (of the items, for a list)
    int CountSize = 0; // bytes of the count of a list; 0: not a list
  };
  struct Element
  {
    std::string Name;
    uint64_t Count = 0;
    std::vector<Property> Properties;
  };
  const auto typeSize = [](const std::string& t)
  {
    static const std::pair<const char*, int> sizes[] = { { "char", 1 },
      { "uchar", 1 },
      { "int8", 1 },
      { "uint8", 1 },
      { "short", 2 },
      { "ushort", 2 },
      { "int16", 2 },
      { "uint16", 2 },
      { "int", 4 },
      { "uint", 4 },
      { "int32", 4 },
      { "uint32", 4 },
      { "float", 4 },
      { "float32", 4 },
      { "double", 8 },
      { "float64", 8 } };
    for (const auto& s : sizes)
    {
      if (t == s.first)
      {
        return s.second;
      }
    }
    return 0;
  };
  std::istringstream header(bytes.substr(0, headerEnd));
  std::string line, format;
  std::vector<Element> elements;
  while (std::getline(header, line))
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format")
    {
      words >> format;
    }
    else if (keyword == "element")
    {
      Element e;
      if (!(words >> e.Name >> e.Count))
      {
        return fail("bad element line '" + line + "'");
      }
      elements.push_back(e);
    }
    else if (keyword == "property")
    {
      std::string type, name;
      words >> type;
      Property p;
      if (type == "list")
      {
        std::string countType, itemType;
        words >> countType >> itemType;
        p.CountSize = typeSize(countType);
        p.Size = typeSize(itemType);
      }
      else
      {
        p.Size = typeSize(type);
      }
      words >> p.Name;
      if (elements.empty() || p.Size == 0 || (type == "list" && p.CountSize == 0))
      {
        return fail("bad property line '" + line + "'");
      }
      elements.back().Properties.push_back(p);
    }
  }
  const bool ascii = format == "ascii";
  const bool little = format == "binary_little_endian";
  if (!ascii && !little && format != "binary_big_endian")
  {
    return fail("unknown format '" + format + "'");
  }
  const Element* vertex = nullptr;
  for (const Element& e : elements)
  {
    vertex = e.Name == "vertex" ? &e : vertex;
  }
  int xyz = 0;
  for (const Property& p : vertex ? vertex->Properties : std::vector<Property>())
  {
    xyz += (p.Name == "x" || p.Name == "y" || p.Name == "z") && p.CountSize == 0 ? 1 : 0;
  }
  if (xyz != 3)
  {
    return fail("no vertex element with x, y and z");
  }

  // The body: one value at a time, as text or binary.
  size_t at = bytes.find('\n', headerEnd);
  at = at == std::string::npos ? bytes.size() : at + 1;
  const auto next = [&](int size, bool integer, double& value)
  {
    if (ascii)
    {
      while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at])))
      {
        ++at;
      }
      const size_t start = at;
      while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at])))
      {
        ++at;
      }
      if (start == at)
      {
        return false;
      }
      char* end = nullptr;
      const std::string word = bytes.substr(start, at - start);
      value = std::strtod(word.c_str(), &end);
      return end && *end == '\0' && (!integer || value == std::floor(value));
    }
    if (bytes.size() - at < static_cast<size_t>(size))
    {
      return false;
    }
    unsigned char raw[8];
    for (int k = 0; k < size; ++k)
    {
      raw[k] = static_cast<unsigned char>(bytes[at + (little ? k : size - 1 - k)]);
    }
    at += static_cast<size_t>(size);
    uint64_t u = 0;
    for (int k = size - 1; k >= 0; --k)
    {
      u = (u << 8) | raw[k];
    }
    value = static_cast<double>(u); // counts and indices: unsigned is enough to bound them
    return true;
  };
  for (const Element& e : elements)
  {
    for (uint64_t i = 0; i < e.Count; ++i)
    {
      for (const Property& p : e.Properties)
      {
        double count = 1, value = 0;
        if (p.CountSize && (!next(p.CountSize, true, count) || count < 0))
        {
          return fail("element '" + e.Name + "' ends early (truncated file?)");
        }
        const bool indices = p.CountSize && e.Name == "face";
        for (double k = 0; k < count; ++k)
        {
          if (!next(p.Size, indices, value))
          {
            return fail("element '" + e.Name + "' ends early (truncated file?)");
          }
          if (indices && (value < 0 || value >= static_cast<double>(vertex->Count)))
          {
            return fail("a face refers to vertex " + std::to_string(value) + " of " +
              std::to_string(vertex->Count));
          }
        }
      }
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
std::string Extension(const std::string& path)
{
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(),
    ext.end(),
    ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string OneLine(const std::string& text)
{
  std::string body = text;
  // VTK's "ERROR: In <file>, line <n>\n<class> (<address>): <reason>" -> "<reason>".
  if (body.compare(0, 4, "ERRO") == 0 || body.compare(0, 4, "Warn") == 0 ||
    body.compare(0, 4, "Gene") == 0)
  {
    const size_t newline = body.find('\n');
    if (newline != std::string::npos)
    {
      body = body.substr(newline + 1);
    }
    const size_t close = body.find("): ");
    if (close != std::string::npos && close < body.find('\n'))
    {
      body = body.substr(close + 3);
    }
  }
  std::string line;
  bool space = false;
  for (char c : body)
  {
    if (c == '\n' || c == '\r' || c == '\t' || c == ' ')
    {
      space = !line.empty();
      continue;
    }
    if (space)
    {
      line += ' ';
      space = false;
    }
    line += c;
  }
  // A message quoting a whole embedded buffer (a data URI) stays readable.
  constexpr size_t maxLength = 400;
  if (line.size() > maxLength)
  {
    line.resize(maxLength);
    line += "...";
  }
  return line;
}

//------------------------------------------------------------------------------
struct VTKMessageCapture::Internals
{
  vtkSmartPointer<CaptureWindow> Window = vtkSmartPointer<CaptureWindow>::New();
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkLogger::Verbosity PreviousStderr = vtkLogger::VERBOSITY_OFF;
};

VTKMessageCapture::VTKMessageCapture()
  : Internal(new Internals)
{
  this->Internal->Previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(this->Internal->Window);
  // VTK 9.1 also logs errors and warnings through vtkLogger, which prints them to stderr. (It has
  // no getter for the stderr verbosity; the cutoff equals it when no log file is open.)
  this->Internal->PreviousStderr = vtkLogger::GetCurrentVerbosityCutoff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VTKMessageCapture::~VTKMessageCapture()
{
  vtkLogger::SetStderrVerbosity(this->Internal->PreviousStderr);
  vtkOutputWindow::SetInstance(this->Internal->Previous);
  delete this->Internal;
}

const std::vector<std::string>& VTKMessageCapture::Errors() const
{
  return this->Internal->Window->Errors;
}

const std::vector<std::string>& VTKMessageCapture::Warnings() const
{
  return this->Internal->Window->Warnings;
}

//------------------------------------------------------------------------------
// VTK 9.1's OBJ reader does not check face indices: one past the vertices, texture coordinates
// or normals reads outside them (a crash, or garbage in the output). So every index of the
// faces, lines and points of an OBJ file is checked here first: not 0, and within the elements
// the file defines (a negative index counts back from the last defined before it).
bool CheckOBJ(const std::string& path, std::string& error)
{
  std::ifstream file(path);
  std::string line;
  // Elements defined so far, then in the whole file, of v, vt and vn.
  long long sofar[3] = { 0, 0, 0 };
  struct Reference
  {
    long long Line, Index, Before;
    int Kind;
  };
  std::vector<Reference> references;
  static const char* const kinds[3] = { "vertex", "texture coordinate", "normal" };
  for (long long number = 1; std::getline(file, line); ++number)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const int defines = keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1;
    if (defines >= 0)
    {
      ++sofar[defines];
      continue;
    }
    if (keyword != "f" && keyword != "l" && keyword != "p")
    {
      continue;
    }
    for (std::string group; words >> group;)
    {
      // "v", "v/vt", "v//vn" or "v/vt/vn"
      std::istringstream parts(group);
      std::string part;
      for (int kind = 0; kind < 3 && std::getline(parts, part, '/'); ++kind)
      {
        if (!part.empty())
        {
          references.push_back({ number, std::atoll(part.c_str()), sofar[kind], kind });
        }
      }
    }
  }
  for (const Reference& r : references)
  {
    const long long defined = sofar[r.Kind];
    const long long index = r.Index < 0 ? r.Before + r.Index + 1 : r.Index;
    if (index < 1 || index > defined)
    {
      error = "'" + path + "' is not a valid OBJ file: line " + std::to_string(r.Line) +
        " refers to " + kinds[r.Kind] + " " + std::to_string(r.Index) + " of " +
        std::to_string(defined);
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkPolyData> ReadVTKMesh(const std::string& path, std::string& error)
{
  if (!FileIsReadable(path, error))
  {
    return nullptr;
  }
  const std::string ext = Extension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".vtp")
  {
    auto xml = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    if (!xml->CanReadFile(path.c_str()))
    {
      error = "'" + path + "' is not a VTK XML polydata file";
      return nullptr;
    }
    xml->SetFileName(path.c_str());
    reader = xml;
  }
  else if (ext == ".vtk")
  {
    auto legacy = vtkSmartPointer<vtkPolyDataReader>::New();
    legacy->SetFileName(path.c_str());
    if (!legacy->IsFilePolyData())
    {
      error = "'" + path + "' is not a legacy VTK polydata file";
      return nullptr;
    }
    legacy->ReadAllTCoordsOn();
    legacy->ReadAllNormalsOn();
    reader = legacy;
  }
  else if (ext == ".ply" || ext == ".obj" || ext == ".stl")
  {
    if ((ext == ".ply" && !CheckPLY(path, error)) || (ext == ".obj" && !CheckOBJ(path, error)))
    {
      return nullptr;
    }
    vtkSmartPointer<vtkAbstractPolyDataReader> r;
    if (ext == ".ply")
    {
      r = vtkSmartPointer<vtkPLYReader>::New();
    }
    else if (ext == ".obj")
    {
      r = vtkSmartPointer<vtkOBJReader>::New();
    }
    else
    {
      r = vtkSmartPointer<vtkSTLReader>::New();
    }
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    error = "'" + path + "': unknown input format '" + ext +
      "' (.vtp, .vtk, .ply, .obj, .stl, .gltf, .glb)";
    return nullptr;
  }

  vtkSmartPointer<vtkPolyData> mesh;
  {
    VTKMessageCapture messages;
    reader->Update();
    if (!messages.Errors().empty())
    {
      error = "cannot read '" + path + "': " + messages.Errors().front();
      return nullptr;
    }
    mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  }
  if (!mesh || mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
  {
    error = "'" + path + "' has no polygons";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(mesh);
  return copy;
}

namespace
{
bool WriteXML(vtkXMLWriter* writer,
  vtkDataObject* data,
  const std::string& path,
  std::string& error)
{
  VTKMessageCapture messages;
  writer->SetInputData(data);
  // Arrays inline (base64, compressed), not in VTK's default appended section: the XML reader of
  // ParaView 5.11 (VTK 9.2) stops expat at that section, which fails ("junk after document
  // element", or an empty mesh) with the libexpat1 of Debian bookworm's security updates, whose
  // reparse deferral holds back the parser's callbacks. A multiblock writer passes the mode on
  // to the writers of its blocks.
  writer->SetDataModeToBinary();
  writer->SetFileName(path.c_str());
  const int ok = writer->Write();
  if (!ok || !messages.Errors().empty())
  {
    error = "cannot write '" + path +
      "': " + (messages.Errors().empty() ? "write failed" : messages.Errors().front());
    return false;
  }
  return true;
}

// Why `folder`, the block folder of a .vtm output, cannot be replaced; empty when it can: it
// does not exist, or holds only .vtp files (what a multiblock writer puts there).
std::string BlockFolderConflict(const fs::path& folder)
{
  std::error_code ec;
  const fs::file_status status = fs::status(folder, ec);
  if (!fs::exists(status))
  {
    return std::string();
  }
  if (!fs::is_directory(status))
  {
    return "'" + folder.string() + "', where its blocks go, exists and is not a folder";
  }
  ec.clear();
  for (const auto& entry : fs::directory_iterator(folder, ec))
  {
    std::error_code entryError;
    if (!entry.is_regular_file(entryError) || Extension(entry.path().string()) != ".vtp")
    {
      return "its block folder '" + folder.string() +
        "' holds files other than .vtp, which replacing it would delete";
    }
  }
  return ec ? "cannot read its block folder '" + folder.string() + "': " + ec.message()
            : std::string();
}

// A block's NormalTextureFile is relative to its file's folder; in memory, as NormalMapGLTF's
// polydata, it is resolved against that folder.
void ResolveTextureFile(vtkPolyData* mesh, const fs::path& folder)
{
  const fs::path file = FieldString(mesh, "NormalTextureFile");
  if (!file.empty() && file.is_relative())
  {
    SetFieldString(mesh, "NormalTextureFile", (folder / file).lexically_normal().string());
  }
}
}

std::string FieldString(vtkPolyData* mesh, const char* name)
{
  auto* array = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}

void SetFieldString(vtkPolyData* mesh, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(mesh->GetFieldData());
  fields->AddArray(array); // replaces the array of that name
  mesh->SetFieldData(fields);
}

bool WriteVTP(vtkPolyData* mesh, const std::string& path, std::string& error)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  return WriteXML(writer, mesh, path, error);
}

std::string BlockFolder(const std::string& vtmPath)
{
  const fs::path path(vtmPath);
  return (path.parent_path() / path.stem()).string();
}

bool WriteVTM(vtkMultiBlockDataSet* blocks, const std::string& path, std::string& error)
{
  vtkNew<vtkXMLMultiBlockDataWriter> writer;
  return WriteXML(writer, blocks, path, error);
}

bool ReadVTMBlocks(const std::string& path,
  std::vector<Block>& blocks,
  std::vector<std::string>& warnings,
  std::string& error)
{
  if (!FileIsReadable(path, error))
  {
    return false;
  }
  vtkNew<vtkXMLMultiBlockDataReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    error = "'" + path + "' is not a VTK XML multiblock file";
    return false;
  }
  reader->SetFileName(path.c_str());
  {
    VTKMessageCapture messages;
    reader->Update();
    if (!messages.Errors().empty())
    {
      error = "cannot read '" + path + "': " + messages.Errors().front();
      return false;
    }
  }
  auto* tree = vtkDataObjectTree::SafeDownCast(reader->GetOutputDataObject(0));
  if (tree)
  {
    vtkSmartPointer<vtkDataObjectTreeIterator> it = vtk::TakeSmartPointer(tree->NewTreeIterator());
    it->VisitOnlyLeavesOn();
    it->SkipEmptyNodesOff();
    int index = 0;
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem(), ++index)
    {
      std::string name = "block " + std::to_string(index);
      if (it->HasCurrentMetaData() && it->GetCurrentMetaData()->Has(vtkCompositeDataSet::NAME()))
      {
        name = it->GetCurrentMetaData()->Get(vtkCompositeDataSet::NAME());
      }
      vtkDataObject* data = it->GetCurrentDataObject();
      auto* mesh = vtkPolyData::SafeDownCast(data);
      if (!mesh || mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0)
      {
        warnings.push_back("'" + path + "': " + name +
          (!data ? " is empty" : (mesh ? " has no polygons" : std::string(" is not polydata"))) +
          "; skipped");
        continue;
      }
      auto copy = vtkSmartPointer<vtkPolyData>::New();
      copy->ShallowCopy(mesh);
      ResolveTextureFile(copy, fs::path(path).parent_path());
      std::string tcoords;
      vtkDataArray* set = mesh->GetFieldData()->GetArray("NormalTextureTexCoord");
      const double number = set && set->GetNumberOfTuples() == 1 ? set->GetComponent(0, 0) : -1.0;
      if (number >= 0.0 && number <= VTK_INT_MAX) // a value the cast takes (not NaN)
      {
        tcoords = "TEXCOORD_" + std::to_string(static_cast<int>(number));
        tcoords = mesh->GetPointData()->GetArray(tcoords.c_str()) ? tcoords : std::string();
      }
      vtkDataArray* scaleArray = mesh->GetFieldData()->GetArray("NormalTextureScale");
      double scale =
        scaleArray && scaleArray->GetNumberOfTuples() == 1 ? scaleArray->GetComponent(0, 0) : 1.0;
      if (!std::isfinite(scale))
      {
        warnings.push_back(
          "'" + path + "': " + name + ": NormalTextureScale is not finite; using 1");
        scale = 1.0;
      }
      blocks.push_back({ name, copy, tcoords, scale });
    }
  }
  if (blocks.empty())
  {
    error = "'" + path + "' has no polydata block with polygons";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
OutputTransaction::~OutputTransaction()
{
  this->Discard();
}

bool OutputTransaction::Begin(const std::string& finalPath, std::string& error)
{
  this->Discard();
  const fs::path target(finalPath);
  if (target.filename().empty())
  {
    error = "invalid output path '" + finalPath + "'";
    return false;
  }
  std::error_code ec;
  if (fs::is_directory(target, ec))
  {
    error = "cannot write '" + finalPath + "': it is a directory";
    return false;
  }
  if (Extension(finalPath) == ".vtm")
  {
    const std::string conflict = BlockFolderConflict(BlockFolder(finalPath));
    if (!conflict.empty())
    {
      error = "cannot write '" + finalPath + "': " + conflict;
      return false;
    }
  }
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::string pattern = (folder / ("." + target.filename().string() + ".tmp-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data()))
  {
    error = "cannot write in '" + folder.string() + "': " + std::strerror(errno);
    return false;
  }
  this->Final = finalPath;
  this->TempDir = buffer.data();
  return true;
}

std::string OutputTransaction::PathFor(const std::string& fileName) const
{
  return (fs::path(this->TempDir) / fileName).string();
}

std::string OutputTransaction::MainPath() const
{
  return this->PathFor(fs::path(this->Final).filename().string());
}

bool OutputTransaction::Commit(std::string& error)
{
  if (this->TempDir.empty())
  {
    error = "no output to commit";
    return false;
  }
  const fs::path main = this->MainPath();
  const fs::path folder =
    fs::path(this->Final).has_parent_path() ? fs::path(this->Final).parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_regular_file(main, ec))
  {
    error = "cannot write '" + this->Final + "': nothing was written";
    return false;
  }
  // Side files (a .gltf's .bin, a .vtm's block folder) first, so the main file never refers to
  // a missing one.
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(this->TempDir, ec))
  {
    if (entry.path() != main)
    {
      files.push_back(entry.path());
    }
  }
  files.push_back(main);
  for (const fs::path& file : files)
  {
    const fs::path target = folder / file.filename();
    std::error_code ignored; // a path that does not exist is not a folder
    if (fs::is_directory(file, ignored) && fs::is_directory(target, ignored))
    {
      // A block folder of an earlier run (Begin checked it): moved aside, deleted below.
      fs::rename(target, fs::path(this->TempDir) / ".replaced", ec);
    }
    if (!ec)
    {
      fs::rename(file, target, ec);
    }
    if (ec)
    {
      error = "cannot write '" + target.string() + "': " + ec.message();
      return false;
    }
  }
  fs::remove_all(this->TempDir, ec);
  this->TempDir.clear();
  return true;
}

void OutputTransaction::Discard()
{
  if (!this->TempDir.empty())
  {
    std::error_code ec;
    fs::remove_all(this->TempDir, ec);
    this->TempDir.clear();
  }
}
}
