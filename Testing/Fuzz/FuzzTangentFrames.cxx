// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: arbitrary bytes -> vtkPolyData -> vtkPolyDataTangentFrames with every method,
// with and without splitting, and the documented invariants checked on every output. Any
// violation aborts, so libFuzzer reports it with the input that caused it.
//
// Input layout (read front to back; a missing byte reads as 0; make_corpus.py writes seeds):
//   byte 0  bit 0: double points; bits 1-2: output precision (0 single, 1 double, 2 default);
//           bit 3: bitangents; bit 4: cell tangents; bit 5: 32-bit cell storage;
//           bit 6: one cell array made malformed (the "malformed" bytes below)
//   byte 1  TCoords: (b % 8 % 6) 0 active float, 1 active double, 2 active short, 3 float named
//           "UV2" (chosen by name), 4 none, 5 a string array named "UV2"; 1 + (b / 8) % 3
//           components
//   byte 2  normals: (b % 6) 0 none, 1 point float, 2 point double, 3 point short integers,
//           4 cell normals (float), 5 point float and cell normals
//   byte 3  tuple count deltas (added to the point / cell count): bits 0-2 TCoords, bits 3-5
//           normals, each from {0, 0, 0, 0, -1, -2, +1, +3}; bits 6-7 an extra point array
//           "Extra": none, exact, one short, two long
//   byte 4  number of points (b % 65)
//   values  points (3 per point), TCoords, normals, Extra; each value one byte:
//           < 200: (b - 100) / 8; 200-231: a special value (NaN, Inf, 1e-300, FLT_MAX, ...);
//           >= 232: the next 8 bytes as a raw double
//   cells   a count byte (b % 49), then per cell a byte (kind b % 4: vertex, line, polygon,
//           strip; size (b / 4) % 9) and one byte per id: < 240 a valid id (b % points),
//           else an out-of-range id (-1, points, 2^31 - 1, ...)
//   malformed (bit 6 only) a byte b: the cell array b % 4 (vertices, lines, polygons, strips)
//           and the defect (b / 4) % 8: first offset + 1; last offset + 1; last offset - 1;
//           offsets i and i + 1 swapped; offset i negative; offset i past the connectivity;
//           no offsets at all; offset i far past it (2^31 - 1, or 2^40 in 64-bit storage); then
//           a byte choosing i. Whether the result is malformed is judged by VTK's own
//           vtkCellArray::IsValid (a swap of equal offsets, say, changes nothing).
//   cell normals (normals mode 4 or 5) after everything else
//   supplied tangents, last: a byte s; the filter's SuppliedTangents is s % 3 (RECOMPUTE, KEEP,
//           KEEP_VALID); with KEEP or KEEP_VALID the input gets a point array "Tangents" of floats
//           ((s / 3) % 2 == 0) or doubles, with 3 + (s / 6) % 2 components (3: the active
//           tangents, and a float "TangentSigns" array; 4: found by its name, as VTK's active
//           tangents have 3 components) and the point count plus
//           {0, 0, 0, 0, -1, -2, +1, +3}[(s / 12) % 8] tuples, then their values
#include "vtkPolyDataTangentFrames.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace
{
/// Reads the input front to back; past the end every byte is 0.
class ByteReader
{
public:
  ByteReader(const uint8_t* data, size_t size)
    : Data(data)
    , Size(size)
  {
  }
  uint8_t Byte() { return this->Position < this->Size ? this->Data[this->Position++] : 0; }
  double Value()
  {
    static const double specials[32] = { std::numeric_limits<double>::quiet_NaN(),
      -std::numeric_limits<double>::quiet_NaN(),
      std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(),
      0.0,
      -0.0,
      1.0,
      -1.0,
      1e-300,
      -1e-300,
      1e300,
      -1e300,
      DBL_MIN,
      std::numeric_limits<double>::denorm_min(),
      DBL_MAX,
      -DBL_MAX,
      FLT_MIN,
      std::numeric_limits<float>::denorm_min(),
      FLT_MAX,
      -FLT_MAX,
      1e-30,
      1e30,
      1e-10,
      1e10,
      1e7,
      -1e7,
      0.1,
      1.0 + DBL_EPSILON,
      1.0 + FLT_EPSILON,
      3.4e38,
      1e-45,
      0.5 };
    const uint8_t b = this->Byte();
    if (b < 200)
    {
      return (b - 100) / 8.0;
    }
    if (b < 232)
    {
      return specials[b - 200];
    }
    uint8_t raw[8];
    for (uint8_t& r : raw)
    {
      r = this->Byte();
    }
    double v;
    std::memcpy(&v, raw, sizeof(v));
    return v;
  }

private:
  const uint8_t* Data;
  size_t Size;
  size_t Position = 0;
};

[[noreturn]] void Fail(const std::string& what)
{
  std::fprintf(stderr, "FuzzTangentFrames invariant violated: %s\n", what.c_str());
  std::abort();
}

void Require(bool ok, const std::string& what)
{
  if (!ok)
  {
    Fail(what);
  }
}

/// A double stored in a float array without the undefined behaviour of an out-of-range
/// conversion: beyond the float range it becomes +-Inf, as the hardware conversion would.
float ToFloat(double v)
{
  if (v > FLT_MAX)
  {
    return std::numeric_limits<float>::infinity();
  }
  if (v < -FLT_MAX)
  {
    return -std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(v);
}

/// Fills `array` (components already set) with `tuples` tuples of values from the reader.
void FillArray(vtkDataArray* array, vtkIdType tuples, ByteReader& in)
{
  array->SetNumberOfTuples(std::max<vtkIdType>(tuples, 0));
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    const double v = in.Value();
    if (auto* f = vtkFloatArray::SafeDownCast(array))
    {
      f->SetValue(i, ToFloat(v));
    }
    else if (auto* s = vtkShortArray::SafeDownCast(array))
    {
      s->SetValue(i, static_cast<short>(std::isfinite(v) ? std::fmod(v, 32768.0) : 0.0));
    }
    else
    {
      array->SetVariantValue(i, v);
    }
  }
}

vtkSmartPointer<vtkDataArray> MakeArray(int type, const char* name, int components)
{
  auto array = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(type));
  array->SetName(name);
  array->SetNumberOfComponents(components);
  return array;
}

/// What the decoder built, and what it implies for the filter.
struct FuzzInput
{
  vtkNew<vtkPolyData> Mesh;
  std::string TCoordsName; // the filter's TCoordsArrayName
  int OutputPrecision = vtkAlgorithm::DEFAULT_PRECISION;
  bool Bitangents = false;
  bool CellTangents = false;
  bool UsableTCoords = false;  // present, numeric and at least one tuple per point
  bool BadIds = false;         // a polygon or strip has a point id outside [0, points)
  bool MalformedCells = false; // a cell array that vtkCellArray::IsValid rejects
  int SuppliedTangents = vtkPolyDataTangentFrames::RECOMPUTE;
  /// The supplied arrays, which the output's frame arrays of the same names replace.
  std::vector<vtkAbstractArray*> Supplied;
};

/// Makes `cells` malformed as the "malformed" bytes of the input layout say.
void Malform(vtkCellArray* cells, int defect, uint8_t where)
{
  vtkDataArray* offsets = cells->GetOffsetsArray();
  const vtkIdType n = offsets->GetNumberOfValues(); // >= 1
  const vtkIdType i = where % n;
  const vtkIdType size = cells->GetConnectivityArray()->GetNumberOfValues();
  const double far = cells->IsStorage64Bit() ? 1099511627776.0 : 2147483647.0;
  switch (defect)
  {
    case 0:
      offsets->SetComponent(0, 0, offsets->GetComponent(0, 0) + 1);
      break;
    case 1:
      offsets->SetComponent(n - 1, 0, offsets->GetComponent(n - 1, 0) + 1);
      break;
    case 2:
      offsets->SetComponent(n - 1, 0, offsets->GetComponent(n - 1, 0) - 1);
      break;
    case 3:
    {
      const vtkIdType j = std::min(i + 1, n - 1);
      const double a = offsets->GetComponent(i, 0);
      offsets->SetComponent(i, 0, offsets->GetComponent(j, 0));
      offsets->SetComponent(j, 0, a);
      break;
    }
    case 4:
      offsets->SetComponent(i, 0, -1.0 - where);
      break;
    case 5:
      offsets->SetComponent(i, 0, static_cast<double>(size + 1 + where));
      break;
    case 6:
      offsets->SetNumberOfValues(0);
      break;
    default:
      offsets->SetComponent(i, 0, far);
  }
}

void Decode(const uint8_t* data, size_t size, FuzzInput& fuzz)
{
  ByteReader in(data, size);
  const uint8_t flags = in.Byte();
  const uint8_t uvByte = in.Byte();
  const uint8_t normalByte = in.Byte();
  const uint8_t deltaByte = in.Byte();
  const vtkIdType numPoints = in.Byte() % 65;
  static const int deltas[8] = { 0, 0, 0, 0, -1, -2, 1, 3 };
  const int uvDelta = deltas[deltaByte & 7];
  const int normalDelta = deltas[(deltaByte >> 3) & 7];
  const int extraMode = deltaByte >> 6;

  fuzz.OutputPrecision = std::min((flags >> 1) & 3, 2);
  fuzz.Bitangents = (flags & 8) != 0;
  fuzz.CellTangents = (flags & 16) != 0;
  vtkPolyData* mesh = fuzz.Mesh;
  vtkPointData* pd = mesh->GetPointData();

  vtkNew<vtkPoints> points;
  points->SetDataType((flags & 1) ? VTK_DOUBLE : VTK_FLOAT);
  FillArray(points->GetData(), numPoints, in);
  mesh->SetPoints(points);

  const int uvMode = (uvByte & 7) % 6;
  const int uvComponents = 1 + (uvByte / 8) % 3;
  const vtkIdType uvTuples = numPoints + uvDelta;
  if (uvMode <= 3)
  {
    static const int types[4] = { VTK_FLOAT, VTK_DOUBLE, VTK_SHORT, VTK_FLOAT };
    auto uv = MakeArray(types[uvMode], uvMode == 3 ? "UV2" : "TCoords", uvComponents);
    FillArray(uv, uvTuples, in);
    if (uvMode == 3)
    {
      pd->AddArray(uv);
      fuzz.TCoordsName = "UV2";
    }
    else
    {
      pd->SetTCoords(uv);
    }
    fuzz.UsableTCoords = uvTuples >= numPoints;
  }
  else if (uvMode == 5)
  {
    vtkNew<vtkStringArray> text;
    text->SetName("UV2");
    text->SetNumberOfValues(std::max<vtkIdType>(uvTuples, 0));
    pd->AddArray(text);
    fuzz.TCoordsName = "UV2";
  }

  const int normalMode = normalByte % 6;
  vtkSmartPointer<vtkDataArray> cellNormals;
  if ((normalMode >= 1 && normalMode <= 3) || normalMode == 5)
  {
    static const int types[6] = { 0, VTK_FLOAT, VTK_DOUBLE, VTK_SHORT, 0, VTK_FLOAT };
    auto n = MakeArray(types[normalMode], "Normals", 3);
    FillArray(n, numPoints + normalDelta, in);
    pd->SetNormals(n);
  }
  if (normalMode >= 4)
  {
    cellNormals = MakeArray(VTK_FLOAT, "Normals", 3); // filled once the cells are known
  }

  if (extraMode > 0)
  {
    static const int extraDelta[4] = { 0, 0, -1, 2 };
    auto extra = MakeArray(VTK_DOUBLE, "Extra", 1);
    FillArray(extra, numPoints + extraDelta[extraMode], in);
    pd->AddArray(extra);
  }

  vtkNew<vtkCellArray> cells[4]; // vertices, lines, polygons, strips
  const int numCells = in.Byte() % 49;
  std::vector<vtkIdType> ids;
  for (int c = 0; c < numCells; ++c)
  {
    const uint8_t cellByte = in.Byte();
    const int kind = cellByte % 4;
    const int n = (cellByte / 4) % 9;
    ids.clear();
    for (int k = 0; k < n; ++k)
    {
      const uint8_t b = in.Byte();
      const vtkIdType outside[16] = { -1,
        numPoints,
        numPoints + 1,
        -2,
        VTK_INT_MAX,
        VTK_INT_MIN,
        numPoints + 64,
        -64,
        -1,
        numPoints,
        -1,
        numPoints,
        -1,
        numPoints,
        -1,
        numPoints };
      vtkIdType id = b < 240 && numPoints > 0 ? b % numPoints : outside[(b - 240) & 15];
      ids.push_back(id);
      fuzz.BadIds |= kind >= 2 && (id < 0 || id >= numPoints);
    }
    cells[kind]->InsertNextCell(n, ids.data());
  }
  if (flags & 32)
  {
    for (auto& c : cells)
    {
      c->ConvertTo32BitStorage();
    }
  }
  if (flags & 64)
  {
    const uint8_t what = in.Byte();
    Malform(cells[what % 4], (what / 4) % 8, in.Byte());
    for (auto& c : cells)
    {
      fuzz.MalformedCells |= !c->IsValid();
    }
  }
  mesh->SetVerts(cells[0]);
  mesh->SetLines(cells[1]);
  mesh->SetPolys(cells[2]);
  mesh->SetStrips(cells[3]);
  if (cellNormals)
  {
    FillArray(cellNormals, mesh->GetNumberOfCells() + normalDelta, in);
    mesh->GetCellData()->SetNormals(cellNormals);
  }

  const uint8_t suppliedByte = in.Byte();
  fuzz.SuppliedTangents = suppliedByte % 3;
  if (fuzz.SuppliedTangents != vtkPolyDataTangentFrames::RECOMPUTE)
  {
    const int components = 3 + (suppliedByte / 6) % 2;
    const vtkIdType tuples = numPoints + deltas[(suppliedByte / 12) % 8];
    auto tangents =
      MakeArray((suppliedByte / 3) % 2 == 0 ? VTK_FLOAT : VTK_DOUBLE, "Tangents", components);
    FillArray(tangents, tuples, in);
    fuzz.Supplied.push_back(tangents);
    if (components == 4)
    {
      pd->AddArray(tangents);
    }
    else
    {
      pd->SetTangents(tangents);
      auto signs = MakeArray(VTK_FLOAT, "TangentSigns", 1);
      FillArray(signs, tuples, in);
      pd->AddArray(signs);
      fuzz.Supplied.push_back(signs);
    }
  }
}

/// Errors of one filter run (the observer also keeps the filter's messages off the console).
struct ErrorLog
{
  int Errors = 0;
  std::string First;
  vtkNew<vtkCallbackCommand> Callback;
  explicit ErrorLog(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject*, unsigned long event, void* self, void* message)
      {
        auto* log = static_cast<ErrorLog*>(self);
        if (event == vtkCommand::ErrorEvent && log->Errors++ == 0)
        {
          log->First = static_cast<const char*>(message);
        }
      });
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
};

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

bool SameTuple(vtkAbstractArray* a, vtkIdType i, vtkAbstractArray* b, vtkIdType j)
{
  auto* da = vtkDataArray::SafeDownCast(a);
  auto* db = vtkDataArray::SafeDownCast(b);
  if (!da || !db)
  {
    return true; // string arrays: only their length is checked
  }
  for (int k = 0; k < da->GetNumberOfComponents(); ++k)
  {
    if (!SameBits(da->GetComponent(i, k), db->GetComponent(j, k)))
    {
      return false;
    }
  }
  return true;
}

/// The input handed through unchanged (the documented result of an error or of nothing to do).
void RequirePassThrough(vtkPolyData* input, vtkPolyData* output, const std::string& context)
{
  Require(output->GetPoints() == input->GetPoints(), context + ": points not passed through");
  Require(output->GetPolys() == input->GetPolys() && output->GetStrips() == input->GetStrips() &&
      output->GetVerts() == input->GetVerts() && output->GetLines() == input->GetLines(),
    context + ": cells not passed through");
  vtkPointData* in = input->GetPointData();
  vtkPointData* out = output->GetPointData();
  Require(out->GetNumberOfArrays() == in->GetNumberOfArrays(), context + ": point data changed");
  for (int a = 0; a < in->GetNumberOfArrays(); ++a)
  {
    Require(out->GetAbstractArray(a) == in->GetAbstractArray(a), context + ": point data changed");
  }
}

/// Unit vector of v in double, or false when v is zero or not finite.
bool Normalized(const double v[3], double u[3])
{
  const double m = std::max({ std::abs(v[0]), std::abs(v[1]), std::abs(v[2]) });
  if (!(m > 0.0) || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
  {
    return false;
  }
  const double s[3] = { v[0] / m, v[1] / m, v[2] / m };
  const double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int k = 0; k < 3; ++k)
  {
    u[k] = s[k] / len;
  }
  return true;
}

double Length(const double v[3])
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/// The point ids of cell c, read through the arrays' generic API.
std::vector<vtkIdType> CellAt(vtkCellArray* cells, vtkIdType c)
{
  const vtkIdType begin = static_cast<vtkIdType>(cells->GetOffsetsArray()->GetComponent(c, 0));
  const vtkIdType end = static_cast<vtkIdType>(cells->GetOffsetsArray()->GetComponent(c + 1, 0));
  std::vector<vtkIdType> ids;
  for (vtkIdType i = begin; i < end; ++i)
  {
    ids.push_back(static_cast<vtkIdType>(cells->GetConnectivityArray()->GetComponent(i, 0)));
  }
  return ids;
}

/// Cells of `out` against `in`: vertices and lines identical; polygons and strips the same
/// cells, in order, with every id either the input id or (splitting) an appended copy of it,
/// except that with splitting a cell of 4 or more points may come out as its triangles
/// (3-point cells of its kind, in the filter's order: fans of polygons, strip triangles with
/// every odd one reversed). Returns, per appended point, the input point it copies (-1 where no
/// corner tells).
std::vector<vtkIdType> CheckCells(vtkPolyData* in,
  vtkPolyData* out,
  bool splitting,
  const std::string& context)
{
  const vtkIdType numIn = in->GetNumberOfPoints();
  const vtkIdType numOut = out->GetNumberOfPoints();
  std::vector<vtkIdType> source(static_cast<size_t>(numOut - numIn), -1);
  vtkCellArray* inCells[4] = { in->GetVerts(), in->GetLines(), in->GetPolys(), in->GetStrips() };
  vtkCellArray* outCells[4] = {
    out->GetVerts(), out->GetLines(), out->GetPolys(), out->GetStrips()
  };
  for (int kind = 0; kind < 4; ++kind)
  {
    vtkCellArray* a = inCells[kind];
    vtkCellArray* b = outCells[kind];
    vtkIdType next = 0; // the output cell where the next input cell's cells start
    for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c)
    {
      const std::vector<vtkIdType> cell = CellAt(a, c);
      Require(next < b->GetNumberOfCells(), context + ": cells lost");
      std::vector<std::vector<vtkIdType>> expected;
      if (CellAt(b, next).size() == cell.size())
      {
        expected.push_back(cell);
      }
      else
      {
        Require(splitting && kind >= 2 && cell.size() > 3, context + ": cell sizes changed");
        const size_t n = cell.size();
        for (size_t j = 0; j + 2 < n; ++j)
        {
          const bool odd = kind == 3 && (j & 1) != 0;
          expected.push_back(
            { cell[kind == 3 ? (odd ? j + 1 : j) : 0], cell[odd ? j : j + 1], cell[j + 2] });
        }
      }
      for (const std::vector<vtkIdType>& want : expected)
      {
        Require(next < b->GetNumberOfCells(), context + ": cells lost");
        const std::vector<vtkIdType> got = CellAt(b, next++);
        Require(got.size() == want.size(), context + ": cell sizes changed");
        for (size_t k = 0; k < want.size(); ++k)
        {
          const vtkIdType p = want[k];
          const vtkIdType q = got[k];
          if (p == q)
          {
            continue;
          }
          Require(splitting && kind >= 2 && p >= 0 && p < numIn && q >= numIn && q < numOut,
            context + ": a corner moved to a point that is not a copy of its own");
          vtkIdType& s = source[static_cast<size_t>(q - numIn)];
          Require(s < 0 || s == p, context + ": one copy stands for two input points");
          s = p;
        }
      }
    }
    Require(next == b->GetNumberOfCells(), context + ": cells added");
  }
  return source;
}

/// Point data of `out` against `in`: every array still there; arrays with a tuple per input
/// point keep their tuples, and with appended points gain exactly one tuple per appended point,
/// a copy of its source; shorter arrays pass as they are. The `replaced` arrays (unusable input
/// normals, supplied tangents and signs) give way to the output's frames (checked with them).
void CheckPointData(vtkPolyData* in,
  vtkPolyData* out,
  const std::vector<vtkIdType>& source,
  const std::vector<vtkAbstractArray*>& replaced,
  const std::string& context)
{
  const vtkIdType numIn = in->GetNumberOfPoints();
  const vtkIdType numOut = out->GetNumberOfPoints();
  for (vtkIdType q = numIn; q < numOut; ++q)
  {
    const vtkIdType s = source[static_cast<size_t>(q - numIn)];
    Require(s < 0 || SameTuple(in->GetPoints()->GetData(), s, out->GetPoints()->GetData(), q),
      context + ": a copied point moved");
  }
  vtkPointData* pin = in->GetPointData();
  vtkPointData* pout = out->GetPointData();
  for (int a = 0; a < pin->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* x = pin->GetAbstractArray(a);
    if (std::find(replaced.begin(), replaced.end(), x) != replaced.end())
    {
      continue;
    }
    vtkAbstractArray* y = pout->GetAbstractArray(x->GetName());
    Require(y != nullptr, context + ": point array '" + x->GetName() + "' lost");
    if (x->GetNumberOfTuples() < numIn || numOut == numIn)
    {
      Require(y->GetNumberOfTuples() == x->GetNumberOfTuples(),
        context + ": point array '" + x->GetName() + "' resized");
      continue;
    }
    Require(y->GetNumberOfTuples() == numOut,
      context + ": point array '" + x->GetName() + "' does not match the output points");
    for (vtkIdType q = 0; q < numOut; ++q)
    {
      const vtkIdType s = q < numIn ? q : source[static_cast<size_t>(q - numIn)];
      Require(s < 0 || SameTuple(x, s, y, q),
        context + ": point array '" + x->GetName() + "' tuple " + std::to_string(q) + " wrong");
    }
  }
}

/// Frames of one successful run.
void CheckFrames(vtkPolyData* in,
  vtkPolyData* out,
  vtkPolyDataTangentFrames* filter,
  const FuzzInput& fuzz,
  bool inputHadUsableNormals,
  const std::string& context)
{
  const bool mikk = filter->GetMethod() == vtkPolyDataTangentFrames::MIKKTSPACE;
  const vtkIdType numIn = in->GetNumberOfPoints();
  const vtkIdType numOut = out->GetNumberOfPoints();
  Require(numOut == numIn + filter->GetNumberOfSplitPoints(), context + ": point count");
  Require(filter->GetSplitting() || filter->GetNumberOfSplitPoints() == 0,
    context + ": split points without splitting");
  // With splitting, every conflict point of the weighted methods is split (cells whose corners
  // need both sides are cut into triangles first).
  Require(mikk || !filter->GetSplitting() ||
      filter->GetNumberOfSplitPoints() == filter->GetNumberOfHandednessConflicts(),
    context + ": split points other than the conflicts");
  std::vector<char> used(static_cast<size_t>(std::max<vtkIdType>(numOut - numIn, 0)), 0);
  for (vtkCellArray* cells : { out->GetPolys(), out->GetStrips() })
  {
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
    {
      cells->GetCellAtId(c, ids);
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        const vtkIdType id = ids->GetId(k);
        if (id >= numIn && id < numOut)
        {
          used[static_cast<size_t>(id - numIn)] = 1;
        }
      }
    }
  }
  Require(
    std::find(used.begin(), used.end(), 0) == used.end(), context + ": a split point no cell uses");
  Require(filter->GetNumberOfDegenerateTriangles() >= 0 &&
      filter->GetNumberOfFallbackPoints() >= 0 && filter->GetNumberOfInvalidNormals() >= 0 &&
      filter->GetNumberOfHandednessConflicts() >= 0,
    context + ": negative count");
  const std::vector<vtkIdType> source = CheckCells(in, out, filter->GetSplitting(), context);
  std::vector<vtkAbstractArray*> replaced = fuzz.Supplied;
  if (!inputHadUsableNormals)
  {
    replaced.push_back(in->GetPointData()->GetNormals());
  }
  CheckPointData(in, out, source, replaced, context);

  vtkPointData* pd = out->GetPointData();
  vtkDataArray* t = pd->GetTangents();
  vtkDataArray* s = pd->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  vtkDataArray* b = pd->GetArray(vtkPolyDataTangentFrames::BitangentsArrayName());
  vtkDataArray* n = pd->GetNormals();
  Require(t && s && n, context + ": Tangents, TangentSigns or Normals missing");
  Require(t->GetNumberOfTuples() == numOut && s->GetNumberOfTuples() == numOut &&
      t->GetNumberOfComponents() == 3,
    context + ": frame arrays do not match the output points");
  Require(!fuzz.Bitangents || (b && b->GetNumberOfTuples() == numOut), context + ": Bitangents");
  const int expectedType = fuzz.OutputPrecision == vtkAlgorithm::DOUBLE_PRECISION ||
      (fuzz.OutputPrecision == vtkAlgorithm::DEFAULT_PRECISION &&
        in->GetPoints()->GetDataType() == VTK_DOUBLE)
    ? VTK_DOUBLE
    : VTK_FLOAT;
  Require(t->GetDataType() == expectedType && s->GetDataType() == expectedType,
    context + ": output precision");

  // Tolerances. Float output: a unit vector rounded to float is off by up to 2^-24 per
  // component, |T| - 1 and T.N by up to ~2e-7; 1e-6 bounds both. Double output of the weighted
  // methods: Gram-Schmidt keeps a tangent whose part perpendicular to N is down to 1e-9 of its
  // length (OrthonormalizeTangent), so cancellation leaves T.N up to 2^-53 / 1e-9 ~ 1.1e-7;
  // the same 1e-6 bounds it. MikkTSpace works in float: its normalisation is within a few
  // float ulps of unit (1e-6 again), and the filter keeps its tangents bit for bit while |T.N|
  // is at most 1e-4 (the documented contract: real files' normals are unit only to ~1e-5,
  // which MikkTSpace projects with as they are), Gram-Schmidt-ing the others.
  const double tolerance = 1e-6;
  double unitTolerance = tolerance;
  double perpendicularTolerance = mikk ? 1e-4 : tolerance;
  // Supplied frames: KEEP writes them as they are, promising only finite values and signs of
  // +1 or -1; KEEP_VALID keeps those within the checks' default tolerances (FrameCheckTolerances:
  // | |T| - 1 | <= 1e-2, |T.N| / |T| <= 2e-2, so |T.N| <= 2e-2 * 1.01) and computes the others.
  if (fuzz.SuppliedTangents == vtkPolyDataTangentFrames::KEEP)
  {
    unitTolerance = perpendicularTolerance = std::numeric_limits<double>::infinity();
  }
  else if (fuzz.SuppliedTangents == vtkPolyDataTangentFrames::KEEP_VALID)
  {
    unitTolerance = 1e-2 + tolerance;
    perpendicularTolerance = 2e-2 * 1.01 + tolerance;
  }
  for (vtkIdType p = 0; p < numOut; ++p)
  {
    double tv[3], nv[3], nu[3];
    t->GetTuple(p, tv);
    n->GetTuple(p, nv);
    char values[256];
    std::snprintf(values,
      sizeof(values),
      " T (%.9g, %.9g, %.9g) N (%.9g, %.9g, %.9g)",
      tv[0],
      tv[1],
      tv[2],
      nv[0],
      nv[1],
      nv[2]);
    const std::string at = context + " point " + std::to_string(p) + values;
    Require(std::isfinite(tv[0]) && std::isfinite(tv[1]) && std::isfinite(tv[2]),
      at + ": tangent not finite");
    // Every method, MikkTSpace included: where the reference's sum cancels or it keeps its
    // default (1, 0, 0), the filter gives the documented fallback frame.
    Require(std::abs(Length(tv) - 1.0) <= unitTolerance, at + ": tangent not unit");
    const double sign = s->GetComponent(p, 0);
    Require(sign == 1.0 || sign == -1.0, at + ": sign not +1 or -1");
    // Every tangent is perpendicular to the point normal it used: the output normal, unless
    // that is zero or not finite (then the weighted methods use the geometric normal).
    if (Normalized(nv, nu))
    {
      const double dot = tv[0] * nu[0] + tv[1] * nu[1] + tv[2] * nu[2];
      Require(
        std::abs(dot) <= perpendicularTolerance, at + ": tangent not perpendicular to the normal");
    }
    if (!inputHadUsableNormals)
    {
      // Computed normals are unit (a point without area gets (0, 0, 1)).
      Require(std::abs(Length(nv) - 1.0) <= tolerance, at + ": computed normal not unit");
    }
    if (b)
    {
      double bv[3];
      b->GetTuple(p, bv);
      // B = sign * cross(unit N, T), no longer than T
      Require(std::isfinite(bv[0]) && std::isfinite(bv[1]) && std::isfinite(bv[2]) &&
          Length(bv) <= 1.0 + unitTolerance,
        at + ": bitangent not finite or longer than the tangent may be");
    }
  }
  if (fuzz.CellTangents)
  {
    vtkDataArray* ct = out->GetCellData()->GetTangents();
    Require(ct && ct->GetNumberOfTuples() == out->GetNumberOfCells(), context + ": cell tangents");
    const vtkIdType firstSurface = out->GetNumberOfVerts() + out->GetNumberOfLines();
    for (vtkIdType c = 0; c < ct->GetNumberOfTuples(); ++c)
    {
      double cv[3];
      ct->GetTuple(c, cv);
      const double len = Length(cv);
      Require(
        std::isfinite(len) && (c < firstSurface ? len == 0.0 : std::abs(len - 1.0) <= tolerance),
        context + " cell " + std::to_string(c) + ": cell tangent");
    }
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  // Messages of objects other than the filter stay off the console. (Not
  // GlobalWarningDisplayOff: in VTK 9.1 that also stops the filter's ErrorEvents.)
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  FuzzInput fuzz;
  Decode(data, size, fuzz);
  vtkPolyData* input = fuzz.Mesh;
  const bool nothingToDo =
    input->GetNumberOfPoints() == 0 || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0;
  const bool expectError =
    fuzz.MalformedCells || (!nothingToDo && (!fuzz.UsableTCoords || fuzz.BadIds));
  vtkDataArray* inNormals = input->GetPointData()->GetNormals();
  const bool usableNormals = inNormals && inNormals->GetNumberOfComponents() == 3 &&
    inNormals->GetNumberOfTuples() >= input->GetNumberOfPoints();

  for (int method : { vtkPolyDataTangentFrames::UNWEIGHTED,
         vtkPolyDataTangentFrames::AREA_WEIGHTED,
         vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
         vtkPolyDataTangentFrames::MIKKTSPACE })
  {
    for (bool splitting : { true, false })
    {
      vtkNew<vtkPolyDataTangentFrames> filter;
      ErrorLog log(filter);
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->SetSplitting(splitting);
      filter->SetTCoordsArrayName(fuzz.TCoordsName);
      filter->SetOutputPrecision(fuzz.OutputPrecision);
      filter->SetComputeBitangents(fuzz.Bitangents);
      filter->SetComputeCellTangents(fuzz.CellTangents);
      filter->SetSuppliedTangents(fuzz.SuppliedTangents);
      filter->Update();
      vtkPolyData* output = filter->GetOutput();
      const std::string context = std::string(vtkPolyDataTangentFrames::GetMethodName(method)) +
        (splitting ? " splitting" : " no splitting");
      Require((log.Errors > 0) == expectError,
        context +
          (expectError ? ": no error for bad input" : ": error for good input: " + log.First));
      if (expectError || nothingToDo)
      {
        RequirePassThrough(input, output, context);
        continue;
      }
      CheckFrames(input, output, filter, fuzz, usableNormals, context);
    }
  }
  return 0;
}
