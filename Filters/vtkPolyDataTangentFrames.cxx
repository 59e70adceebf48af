// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames: settings, the pipeline (polydata and composite input), and the checks
// of each block's input before ComputeBlock (vtkPolyDataTangentFramesWeighted.cxx) or
// ExecuteSupplied (vtkPolyDataTangentFramesSupplied.cxx) computes its frames.
#include "vtkPolyDataTangentFrames.h"

#include "vtkNormalMappingPrivate.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVersionMacros.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPolyDataTangentFrames);

namespace
{
using vtkNormalMapping::detail::ForEachNormalRange;
using vtkNormalMapping::detail::WithCellStorage;

/// `abstract` when it is a numeric array with a tuple per point, else null with `problem` saying
/// why (`name` names it when it is missing).
vtkDataArray* NumericPointArray(vtkPolyData* input,
  const char* name,
  vtkAbstractArray* abstract,
  std::string& problem)
{
  if (!abstract)
  {
    problem = std::string("no point array ") + name;
    return nullptr;
  }
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  if (!array)
  {
    problem = std::string("point array '") + (abstract->GetName() ? abstract->GetName() : "") +
      "' is not numeric (" + abstract->GetClassName() + ")";
    return nullptr;
  }
  return vtkNormalMapping::detail::PointArray(input, array, "point", 0, problem);
}

/**
 * Why a cell array cannot be read safely, or an empty string when it can: single-component
 * offsets and connectivity, at least one offset, the first 0, none smaller than the one before
 * it (a negative cell size), the last equal to the connectivity size (no cell reaches past it).
 * VTK's vtkCellArray::SetData accepts any arrays; everything below relies on this. `shortCells`
 * gets the number of cells with fewer than 3 points, `trianglesOnly` whether all have 3.
 */
std::string CellArrayProblem(vtkCellArray* cells, vtkIdType& shortCells, bool& trianglesOnly)
{
  if (cells->GetOffsetsArray()->GetNumberOfComponents() != 1 ||
    cells->GetConnectivityArray()->GetNumberOfComponents() != 1)
  {
    return "its offsets or connectivity have more than one component";
  }
  if (cells->GetOffsetsArray()->GetNumberOfValues() == 0)
  {
    return "it has no offsets (not even the leading 0)";
  }
  std::string problem;
  WithCellStorage(cells,
    [&](const auto* offsets, const auto*)
    {
      const vtkIdType numCells = cells->GetOffsetsArray()->GetNumberOfValues() - 1;
      const vtkIdType size = cells->GetConnectivityArray()->GetNumberOfValues();
      if (offsets[0] != 0)
      {
        problem = "its first offset is " + std::to_string(offsets[0]) + ", not 0";
        return;
      }
      // One pass of unsigned tests that vectorizes with any instruction set (as IdsInRange), then
      // a search only when something is wrong. An offset outside [0, size] (a negative one is
      // huge as unsigned) means a decrease or a wrong last offset, found below; with every offset
      // inside, no size n overflows, n is negative when its top bit is set and, when no size is
      // negative, below 3 when n - 3 has its top bit set.
      using Bits = std::uint64_t;
      const auto bits = [](auto offset)
      { return static_cast<Bits>(static_cast<vtkIdType>(offset)); };
      bool outside = false;
      Bits negative = 0;
      Bits notThree = 0;
      Bits below3 = 0;
      for (vtkIdType c = 0; c < numCells; ++c)
      {
        const Bits n = bits(offsets[c + 1]) - bits(offsets[c]); // wraps, defined for unsigned
        outside |= bits(offsets[c + 1]) > static_cast<Bits>(size);
        negative |= n;
        notThree |= n ^ 3;
        below3 += (n - 3) >> 63;
      }
      const bool wrong = outside || (negative >> 63) != 0;
      shortCells += static_cast<vtkIdType>(below3);
      trianglesOnly = trianglesOnly && notThree == 0;
      for (vtkIdType c = 0; wrong && c < numCells; ++c)
      {
        if (offsets[c + 1] < offsets[c])
        {
          problem = "the offsets decrease at cell " + std::to_string(c) + " (" +
            std::to_string(offsets[c]) + ", then " + std::to_string(offsets[c + 1]) + ")";
          return;
        }
      }
      if (static_cast<vtkIdType>(offsets[numCells]) != size)
      {
        problem = "its last offset is " + std::to_string(offsets[numCells]) +
          " but the connectivity holds " + std::to_string(size) + " ids";
      }
    });
  return problem;
}

/**
 * Whether every cell array of `input` can be read safely (CellArrayProblem); if not, an error
 * says which and why. Warns about polygons and strips with fewer than 3 points.
 * `polysAreTriangles`: every polygon has 3 points.
 */
bool ReadableCells(vtkPolyDataTangentFrames* self, vtkPolyData* input, bool& polysAreTriangles)
{
  const std::pair<const char*, vtkCellArray*> cellArrays[] = { { "vertex", input->GetVerts() },
    { "line", input->GetLines() },
    { "polygon", input->GetPolys() },
    { "triangle strip", input->GetStrips() } };
  vtkIdType shortCells[4] = { 0, 0, 0, 0 };
  bool trianglesOnly[4] = { true, true, true, true };
  for (int a = 0; a < 4; ++a)
  {
    const std::string problem =
      CellArrayProblem(cellArrays[a].second, shortCells[a], trianglesOnly[a]);
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(self,
        "Cannot compute tangent frames: the " << cellArrays[a].first << " cell array is malformed: "
                                              << problem << "; passing the input through.");
      return false;
    }
  }
  if (shortCells[2] + shortCells[3] > 0)
  {
    vtkWarningWithObjectMacro(self,
      << shortCells[2] + shortCells[3]
      << " polygon or strip cells have fewer than 3 points; they pass through and give no "
         "frames.");
  }
  polysAreTriangles = trianglesOnly[2];
  return true;
}

/**
 * The texture coordinates the frames follow: the point array `name`, or the active TCoords when
 * `name` is empty. Null, with an error, when it is missing, not numeric or too short (a missing
 * array of a composite input's block, whose flat index is `flatIndex`, is a warning); warns when
 * it has one component (v = 0) or more than two (the first two are used).
 */
vtkDataArray* TextureCoordinatesOf(vtkPolyDataTangentFrames* self,
  vtkPolyData* input,
  const std::string& name,
  vtkIdType flatIndex)
{
  vtkPointData* pd = input->GetPointData();
  vtkAbstractArray* abstract = name.empty() ? pd->GetTCoords() : pd->GetAbstractArray(name.c_str());
  const std::string label = name.empty() ? std::string("texture coordinates (no active TCoords)")
                                         : "texture coordinates '" + name + "'";
  if (!abstract && flatIndex >= 0)
  {
    vtkWarningWithObjectMacro(self,
      "Block " << flatIndex << " has no point array " << label
               << "; passing it through without frames.");
    return nullptr;
  }
  std::string problem;
  vtkDataArray* uvs = NumericPointArray(input, label.c_str(), abstract, problem);
  if (!uvs)
  {
    vtkErrorWithObjectMacro(
      self, "Cannot compute tangent frames: " << problem << "; passing the input through.");
    return nullptr;
  }
  const char* uvName = uvs->GetName() ? uvs->GetName() : "";
  if (uvs->GetNumberOfComponents() == 1)
  {
    vtkWarningWithObjectMacro(self,
      "Texture coordinates '" << uvName
                              << "' have 1 component; using (u, 0), so every triangle has zero "
                                 "UV area and gets a fallback frame.");
  }
  else if (uvs->GetNumberOfComponents() > 2)
  {
    vtkWarningWithObjectMacro(self,
      "Texture coordinates '" << uvName << "' have " << uvs->GetNumberOfComponents()
                              << " components; using the first two.");
  }
  return uvs;
}

/**
 * Warns about the input's point normals, texture coordinates `uvs` and, with cell tangents, cell
 * normals when they are named like an output frame array, which replaces them: the output then
 * lacks them.
 */
void WarnAboutNameClashes(vtkPolyDataTangentFrames* self, vtkPolyData* input, vtkDataArray* uvs)
{
  std::vector<std::string> pointNames = { vtkPolyDataTangentFrames::TangentsArrayName(),
    vtkPolyDataTangentFrames::SignsArrayName() };
  if (self->GetComputeBitangents())
  {
    pointNames.emplace_back(vtkPolyDataTangentFrames::BitangentsArrayName());
  }
  const auto check = [&](
                       vtkDataArray* array, const char* what, const std::vector<std::string>& names)
  {
    const char* name = array ? array->GetName() : nullptr;
    if (name && std::find(names.begin(), names.end(), name) != names.end())
    {
      vtkWarningWithObjectMacro(self,
        "The input's " << what << " are named '" << name
                       << "', as an output frame array is: that array replaces them, so the "
                          "output has no "
                       << what << ". Rename them to keep them.");
    }
  };
  check(input->GetPointData()->GetNormals(), "point normals", pointNames);
  check(uvs, "texture coordinates", pointNames);
  if (self->GetComputeCellTangents())
  {
    check(input->GetCellData()->GetNormals(),
      "cell normals",
      { vtkPolyDataTangentFrames::TangentsArrayName() });
  }
}

/**
 * The input's point normals when they are usable as an array (numeric, 3 components, one per
 * point), else null with a warning that says what happens instead: the cell normals, when there
 * are usable ones (returned in `cellNormals`), averaged to points, or normals computed from the
 * triangles.
 */
vtkDataArray* PointNormalsOf(vtkPolyDataTangentFrames* self,
  vtkPolyData* input,
  vtkDataArray*& cellNormals)
{
  cellNormals = nullptr;
  if (vtkDataArray* normals = input->GetPointData()->GetNormals())
  {
    std::string problem;
    normals = vtkNormalMapping::detail::PointArray(input, normals, "point", 0, problem);
    if (normals && normals->GetNumberOfComponents() != 3)
    {
      problem = "point normals have " + std::to_string(normals->GetNumberOfComponents()) +
        " components instead of 3";
      normals = nullptr;
    }
    if (normals)
    {
      return normals;
    }
    vtkWarningWithObjectMacro(self, "Ignoring the point normals: " << problem << ".");
  }
  vtkDataArray* cn = input->GetCellData()->GetNormals();
  if (cn && cn->GetNumberOfComponents() == 3 &&
    cn->GetNumberOfTuples() >= input->GetNumberOfCells())
  {
    cellNormals = cn;
    vtkWarningWithObjectMacro(self,
      "The input has cell normals but no point normals; averaging the cell normals to points "
      "(area-weighted) and adding them as point 'Normals'.");
  }
  else
  {
    vtkWarningWithObjectMacro(self,
      "The input has no point normals; computing smooth area-weighted point normals (without "
      "splitting) and adding them as point 'Normals'.");
  }
  return nullptr;
}

/**
 * Whether every id of ids[begin, end) is in [0, numPoints), in one pass without an early exit.
 * An id is in range when neither id nor numPoints - 1 - id is negative: in unsigned arithmetic,
 * when neither has its top bit set. One OR per id collects those bits, in a loop that vectorizes
 * with any instruction set (a 64-bit signed comparison does not with SSE2).
 */
template<typename IdT>
bool IdsInRange(const IdT* ids, vtkIdType begin, vtkIdType end, vtkIdType numPoints)
{
  using Bits = std::uint64_t;
  const Bits last = static_cast<Bits>(numPoints - 1);
  Bits bits = 0;
  for (vtkIdType i = begin; i < end; ++i)
  {
    const Bits id = static_cast<Bits>(static_cast<vtkIdType>(ids[i]));
    bits |= id | (last - id);
  }
  return (bits >> 63) == 0;
}

/**
 * `input` itself when each of its cell arrays stores 32- or 64-bit offsets and connectivity
 * arrays; else a shallow copy of it whose other cell arrays are 64-bit copies. From VTK 9.6 a
 * cell array can also store fixed-size cells (no offsets array) or arrays of other types; the
 * filter reads only the first two storages (WithCellStorage).
 */
vtkSmartPointer<vtkPolyData> WithPlainCellStorage(vtkPolyData* input)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  using Setter = void (vtkPolyData::*)(vtkCellArray*);
  const std::pair<vtkCellArray*, Setter> cellArrays[] = { { input->GetVerts(),
                                                            &vtkPolyData::SetVerts },
    { input->GetLines(), &vtkPolyData::SetLines },
    { input->GetPolys(), &vtkPolyData::SetPolys },
    { input->GetStrips(), &vtkPolyData::SetStrips } };
  vtkSmartPointer<vtkPolyData> plain = input;
  for (const auto& cells : cellArrays)
  {
    if (!cells.first || cells.first->IsStorage64Bit() || cells.first->IsStorage32Bit())
    {
      continue;
    }
    if (plain == input)
    {
      plain = vtkSmartPointer<vtkPolyData>::New();
      plain->ShallowCopy(input);
    }
    vtkNew<vtkCellArray> copy;
    copy->DeepCopy(cells.first);
    copy->ConvertTo64BitStorage();
    (plain->*cells.second)(copy);
  }
  return plain;
#else
  return input; // VTK 9.1 to 9.5 store cells only as 32- or 64-bit arrays
#endif
}

/**
 * Whether every point id of the polygons and strips of `input` is in [0, its number of points)
 * (IdsInRange, in parallel); false after an error on `filter` that passes the input through to
 * `output`. Cell arrays must be readable (vtkPolyDataTangentFrames::ExecuteBlock checks both,
 * in that order, before any method runs).
 */
bool PointIdsInRange(vtkPolyDataTangentFrames* filter, vtkPolyData* input, vtkPolyData* output)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  std::atomic<bool> bad{ false };
  for (vtkCellArray* cells : { input->GetPolys(), input->GetStrips() })
  {
    WithCellStorage(cells,
      [&](const auto*, const auto* conn)
      {
        vtkSMPTools::For(0,
          cells->GetNumberOfConnectivityIds(),
          [&](vtkIdType begin, vtkIdType end)
          {
            if (!IdsInRange(conn, begin, end, numPoints))
            {
              bad = true;
            }
          });
      });
  }
  if (bad)
  {
    vtkErrorWithObjectMacro(filter,
      "Cannot compute tangent frames: a polygon or strip refers to a point id outside [0, "
        << numPoints << "); passing the input through.");
    output->ShallowCopy(input);
  }
  return !bad;
}

/// The number of unusable normals (zero or non-finite, IsUsableNormal) of a 3-component array.
vtkIdType CountUnusableNormals(vtkDataArray* array, vtkIdType n)
{
  std::atomic<vtkIdType> count{ 0 };
  ForEachNormalRange(array,
    n,
    [&](vtkIdType begin, vtkIdType end, const auto& normal)
    {
      vtkIdType here = 0;
      for (vtkIdType p = begin; p < end; ++p)
      {
        here += vtkNormalMapping::IsUsableNormal(normal(p)) ? 0 : 1;
      }
      count += here;
    });
  return count;
}

} // namespace

vtkPolyDataTangentFrames::vtkPolyDataTangentFrames() = default;
vtkPolyDataTangentFrames::~vtkPolyDataTangentFrames() = default;

const char* vtkPolyDataTangentFrames::GetMethodName(int method)
{
  static const char* const names[] = {
    "Unweighted", "AreaWeighted", "AngleWeighted", "MikkTSpace"
  };
  return method >= UNWEIGHTED && method <= MIKKTSPACE ? names[method] : "Unknown";
}

void vtkPolyDataTangentFrames::SetTCoordsArrayName(const std::string& name)
{
  if (name != this->TCoordsArrayName)
  {
    this->TCoordsArrayName = name;
    this->Modified();
  }
}

const char* vtkPolyDataTangentFrames::GetSuppliedTangentsName(int mode)
{
  static const char* const names[] = { "Recompute", "Keep", "KeepValid" };
  return mode >= RECOMPUTE && mode <= KEEP_VALID ? names[mode] : "Unknown";
}

void vtkPolyDataTangentFrames::SetSuppliedTangentsArrayName(const std::string& name)
{
  if (name != this->SuppliedTangentsArrayName)
  {
    this->SuppliedTangentsArrayName = name;
    this->Modified();
  }
}

int vtkPolyDataTangentFrames::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkPolyDataTangentFrames::FillOutputPortInformation(int, vtkInformation* info)
{
  // vtkPolyData for polydata input, the input's composite type for composite input.
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkDataObject");
  return 1;
}

vtkTypeBool vtkPolyDataTangentFrames::ProcessRequest(vtkInformation* request,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT()))
  {
    return this->RequestDataObject(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

int vtkPolyDataTangentFrames::RequestDataObject(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* output = vtkDataObject::GetData(outInfo);
  if (vtkCompositeDataSet::SafeDownCast(input))
  {
    // The exact class: a vtkMultiPieceDataSet output IsA vtkPartitionedDataSet.
    if (!output || std::strcmp(output->GetClassName(), input->GetClassName()) != 0)
    {
      auto composite = vtk::TakeSmartPointer(input->NewInstance());
      outInfo->Set(vtkDataObject::DATA_OBJECT(), composite);
    }
  }
  else if (!vtkPolyData::SafeDownCast(output))
  {
    vtkNew<vtkPolyData> polyData;
    outInfo->Set(vtkDataObject::DATA_OBJECT(), polyData);
  }
  return 1;
}

int vtkPolyDataTangentFrames::RequestUpdateExtent(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  using Pipeline = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Get(Pipeline::UPDATE_NUMBER_OF_PIECES()) > 1)
  {
    inputVector[0]->GetInformationObject(0)->Set(Pipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(),
      outInfo->Get(Pipeline::UPDATE_NUMBER_OF_GHOST_LEVELS()) + 1);
  }
  return 1;
}

int vtkPolyDataTangentFrames::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  this->NumberOfDegenerateTriangles = 0;
  this->NumberOfFallbackPoints = 0;
  this->NumberOfHandednessConflicts = 0;
  this->NumberOfSplitPoints = 0;
  this->NumberOfInvalidNormals = 0;
  this->NumberOfReplacedTangents = 0;
  this->NumberOfNonFiniteTangents = 0;
  this->NumberOfNonUnitTangents = 0;
  this->NumberOfNonPerpendicularTangents = 0;
  this->NumberOfWrongSignTangents = 0;
  vtkCompositeDataSet* inComposite = vtkCompositeDataSet::GetData(inputVector[0], 0);
  if (!inComposite)
  {
    vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
    vtkPolyData* output = vtkPolyData::GetData(outputVector);
    if (!input || !output)
    {
      return 0;
    }
    this->ExecuteBlock(input, output, 0.0, 1.0, -1);
    return 1;
  }

  // Composite input: every polydata leaf on its own, the counts summed over the leaves.
  vtkCompositeDataSet* outComposite = vtkCompositeDataSet::GetData(outputVector, 0);
  if (!outComposite)
  {
    return 0;
  }
  outComposite->CopyStructure(inComposite);
  auto it = vtk::TakeSmartPointer(inComposite->NewIterator());
  vtkIdType leaves = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    ++leaves;
  }
  vtkIdType leaf = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal() && !this->GetAbortExecute();
       it->GoToNextItem(), ++leaf)
  {
    vtkDataObject* block = it->GetCurrentDataObject();
    vtkPolyData* input = vtkPolyData::SafeDownCast(block);
    if (!input)
    {
      vtkWarningMacro("Block " << it->GetCurrentFlatIndex() << " is a " << block->GetClassName()
                               << ", not polydata; passing it through without frames.");
      auto copy = vtk::TakeSmartPointer(block->NewInstance());
      copy->ShallowCopy(block);
      outComposite->SetDataSet(it, copy);
      continue;
    }
    vtkNew<vtkPolyData> output;
    this->ExecuteBlock(input,
      output,
      static_cast<double>(leaf) / leaves,
      static_cast<double>(leaf + 1) / leaves,
      it->GetCurrentFlatIndex());
    // The executive passes a lone polydata's field data (names, metadata), not a block's.
    output->GetFieldData()->PassData(input->GetFieldData());
    outComposite->SetDataSet(it, output);
  }
  if (this->GetAbortExecute())
  {
    outComposite->Initialize(); // empty, as an aborted polydata execution leaves its output
  }
  return 1;
}

void vtkPolyDataTangentFrames::ExecuteBlock(vtkPolyData* inputAsGiven,
  vtkPolyData* output,
  double progressBegin,
  double progressEnd,
  vtkIdType flatIndex)
{
  const vtkSmartPointer<vtkPolyData> plain = WithPlainCellStorage(inputAsGiven);
  vtkPolyData* input = plain;
  const auto passThrough = [&]() { output->ShallowCopy(input); };
  // Malformed cell arrays first: nothing below (not even the cell counts) can be trusted.
  bool polysAreTriangles = true;
  if (!ReadableCells(this, input, polysAreTriangles))
  {
    return passThrough();
  }
  if (input->GetNumberOfPoints() == 0 ||
    input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    // Nothing to give frames to; not an error (vertices and lines only, or empty input).
    return passThrough();
  }
  vtkDataArray* uvs = TextureCoordinatesOf(this, input, this->TCoordsArrayName, flatIndex);
  if (!uvs)
  {
    return passThrough();
  }
  WarnAboutNameClashes(this, input, uvs);
  vtkDataArray* cellNormals = nullptr;
  vtkDataArray* normals = PointNormalsOf(this, input, cellNormals);
  // Checked once here for every method, and for kept supplied frames, which list no triangles.
  if (!PointIdsInRange(this, input, output))
  {
    return;
  }
  // Counted once here, whether the frames are computed or kept.
  const vtkIdType unusable =
    normals ? CountUnusableNormals(normals, input->GetNumberOfPoints()) : 0;
  this->NumberOfInvalidNormals += unusable;
  const BlockInput block{ input,
    output,
    uvs,
    normals,
    unusable,
    cellNormals,
    polysAreTriangles,
    nullptr,
    progressBegin,
    progressEnd };
  if (this->SuppliedTangents != RECOMPUTE)
  {
    this->ExecuteSupplied(block);
    return;
  }
  this->ComputeBlock(block);
}

bool vtkPolyDataTangentFrames::ContinueBlock(const BlockInput& block, double fraction)
{
  this->UpdateProgress(block.ProgressBegin + fraction * (block.ProgressEnd - block.ProgressBegin));
  if (this->GetAbortExecute())
  {
    block.Output->Initialize();
    return false;
  }
  return true;
}

bool vtkPolyDataTangentFrames::DoubleOutput(vtkPolyData* input) const
{
  return this->OutputPrecision == DOUBLE_PRECISION ||
    (this->OutputPrecision == DEFAULT_PRECISION && input->GetPoints()->GetDataType() == VTK_DOUBLE);
}

void vtkPolyDataTangentFrames::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << GetMethodName(this->Method) << "\n";
  os << indent << "TCoordsArrayName: "
     << (this->TCoordsArrayName.empty() ? "(active TCoords)" : this->TCoordsArrayName) << "\n";
  os << indent << "Splitting: " << (this->Splitting ? "On" : "Off") << "\n";
  os << indent << "GLTFSignConvention: " << (this->GLTFSignConvention ? "On" : "Off") << "\n";
  os << indent << "ComputeBitangents: " << (this->ComputeBitangents ? "On" : "Off") << "\n";
  os << indent << "ComputeCellTangents: " << (this->ComputeCellTangents ? "On" : "Off") << "\n";
  os << indent << "OutputPrecision: " << this->OutputPrecision << "\n";
  os << indent << "SuppliedTangents: " << GetSuppliedTangentsName(this->SuppliedTangents) << "\n";
  os << indent << "SuppliedTangentsArrayName: "
     << (this->SuppliedTangentsArrayName.empty() ? "(active tangents)"
                                                 : this->SuppliedTangentsArrayName)
     << "\n";
  os << indent << "NumberOfDegenerateTriangles: " << this->NumberOfDegenerateTriangles << "\n";
  os << indent << "NumberOfFallbackPoints: " << this->NumberOfFallbackPoints << "\n";
  os << indent << "NumberOfHandednessConflicts: " << this->NumberOfHandednessConflicts << "\n";
  os << indent << "NumberOfSplitPoints: " << this->NumberOfSplitPoints << "\n";
  os << indent << "NumberOfInvalidNormals: " << this->NumberOfInvalidNormals << "\n";
  os << indent << "NumberOfReplacedTangents: " << this->NumberOfReplacedTangents << "\n";
  os << indent << "NumberOfNonFiniteTangents: " << this->NumberOfNonFiniteTangents << "\n";
  os << indent << "NumberOfNonUnitTangents: " << this->NumberOfNonUnitTangents << "\n";
  os << indent << "NumberOfNonPerpendicularTangents: " << this->NumberOfNonPerpendicularTangents
     << "\n";
  os << indent << "NumberOfWrongSignTangents: " << this->NumberOfWrongSignTangents << "\n";
}
