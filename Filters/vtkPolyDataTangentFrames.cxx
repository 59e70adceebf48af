#include "vtkPolyDataTangentFramesInternals.h"

vtkStandardNewMacro(vtkPolyDataTangentFrames);

namespace
{
using namespace vtkNormalMapping::frames;

/// Checks a numeric point array: exists, numeric, long enough.
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
  if (array->GetNumberOfTuples() < input->GetNumberOfPoints())
  {
    problem = std::string("point array '") + (array->GetName() ? array->GetName() : "") + "' has " +
      std::to_string(array->GetNumberOfTuples()) + " tuples for " +
      std::to_string(input->GetNumberOfPoints()) + " points";
    return nullptr;
  }
  return array;
}

/**
 * Why a cell array cannot be read safely, or an empty string when it can: single-component
 * offsets and connectivity, at least one offset, the first 0, none smaller than the one before
 * it (a negative cell size), the last equal to the connectivity size (no cell reaches past it).
 * VTK's vtkCellArray::SetData accepts any arrays; the readers below rely on all of this.
 * `sizes` gets the array's cell sizes, in the same pass.
 */
std::string CellArrayProblem(vtkCellArray* cells, CellSizes& sizes)
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
      // Sizes as unsigned differences and sign bits only (no branch), so that the compiler
      // vectorizes the pass: the sign bit of n is set for a negative size, that of n - 3 for a
      // size below 3, and that of d | -d for d = n - 3 != 0. In parallel ranges: the pass reads
      // 8 bytes per cell and is memory-bound.
      struct Counts
      {
        std::uint64_t Negative = 0, Below3 = 0, NotThree = 0;
      };
      constexpr vtkIdType grain = 1 << 16;
      std::vector<Counts> chunks(
        static_cast<size_t>(vtkNormalMapping::detail::ChunkCount(numCells, grain)));
      vtkNormalMapping::detail::ParallelChunks(numCells,
        grain,
        [&](vtkIdType chunk, vtkIdType begin, vtkIdType end)
        {
          std::uint64_t negative = 0, below3 = 0, notThree = 0;
          for (vtkIdType c = begin; c < end; ++c)
          {
            const std::uint64_t n =
              static_cast<std::uint64_t>(static_cast<std::int64_t>(offsets[c + 1])) -
              static_cast<std::uint64_t>(static_cast<std::int64_t>(offsets[c]));
            const std::uint64_t d = n - 3;
            negative |= n;
            below3 += d >> 63;
            notThree += (d | (0 - d)) >> 63;
          }
          chunks[chunk] = Counts{ negative, below3, notThree };
        });
      std::uint64_t negative = 0, below3 = 0, notThree = 0;
      for (const Counts& counts : chunks)
      {
        negative |= counts.Negative;
        below3 += counts.Below3;
        notThree += counts.NotThree;
      }
      if (negative >> 63)
      {
        for (vtkIdType c = 0; c < numCells; ++c)
        {
          if (offsets[c + 1] < offsets[c])
          {
            problem = "the offsets decrease at cell " + std::to_string(c) + " (" +
              std::to_string(offsets[c]) + ", then " + std::to_string(offsets[c + 1]) + ")";
            return;
          }
        }
      }
      sizes.Short = static_cast<vtkIdType>(below3);
      sizes.TrianglesOnly = notThree == 0;
      if (static_cast<vtkIdType>(offsets[numCells]) != size)
      {
        problem = "its last offset is " + std::to_string(offsets[numCells]) +
          " but the connectivity holds " + std::to_string(size) + " ids";
      }
    });
  return problem;
}

} // namespace

vtkPolyDataTangentFrames::vtkPolyDataTangentFrames() = default;
vtkPolyDataTangentFrames::~vtkPolyDataTangentFrames() = default;

const char* vtkPolyDataTangentFrames::GetMethodName(int method)
{
  switch (method)
  {
    case UNWEIGHTED:
      return "Unweighted";
    case AREA_WEIGHTED:
      return "AreaWeighted";
    case ANGLE_WEIGHTED:
      return "AngleWeighted";
    case MIKKTSPACE:
      return "MikkTSpace";
    default:
      return "Unknown";
  }
}

void vtkPolyDataTangentFrames::SetTCoordsArrayName(const std::string& name)
{
  if (name != this->TCoordsArrayName)
  {
    this->TCoordsArrayName = name;
    this->Modified();
  }
}

int vtkPolyDataTangentFrames::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->NumberOfDegenerateTriangles = 0;
  this->NumberOfFallbackPoints = 0;
  this->NumberOfHandednessConflicts = 0;
  this->NumberOfSplitPoints = 0;
  this->NumberOfInvalidNormals = 0;
  if (!input || !output)
  {
    return 0;
  }
  const auto passThrough = [&]()
  {
    output->ShallowCopy(input);
    return 1;
  };
  // Malformed cell arrays first: nothing below (not even the cell counts) can be trusted.
  const std::pair<const char*, vtkCellArray*> cellArrays[] = { { "vertex", input->GetVerts() },
    { "line", input->GetLines() },
    { "polygon", input->GetPolys() },
    { "triangle strip", input->GetStrips() } };
  CellSizes sizes[4]; // polygons: 2, strips: 3
  for (int a = 0; a < 4; ++a)
  {
    const auto& named = cellArrays[a];
    const std::string problem = CellArrayProblem(named.second, sizes[a]);
    if (!problem.empty())
    {
      vtkErrorMacro("Cannot compute tangent frames: the " << named.first
                                                          << " cell array is malformed: " << problem
                                                          << "; passing the input through.");
      return passThrough();
    }
  }
  if (input->GetNumberOfPoints() == 0 ||
    input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    // Nothing to give frames to; not an error (vertices and lines only, or empty input).
    return passThrough();
  }

  // Texture coordinates.
  vtkPointData* pd = input->GetPointData();
  std::string problem;
  vtkAbstractArray* uvAbstract = this->TCoordsArrayName.empty()
    ? pd->GetTCoords()
    : pd->GetAbstractArray(this->TCoordsArrayName.c_str());
  const std::string uvLabel = this->TCoordsArrayName.empty()
    ? std::string("texture coordinates (no active TCoords)")
    : "texture coordinates '" + this->TCoordsArrayName + "'";
  vtkDataArray* uvs = NumericPointArray(input, uvLabel.c_str(), uvAbstract, problem);
  if (!uvs)
  {
    vtkErrorMacro("Cannot compute tangent frames: " << problem << "; passing the input through.");
    return passThrough();
  }
  if (uvs->GetNumberOfComponents() == 1)
  {
    vtkWarningMacro("Texture coordinates '"
      << (uvs->GetName() ? uvs->GetName() : "")
      << "' have 1 component; using (u, 0), so every "
         "triangle has zero UV area and gets a fallback frame.");
  }
  else if (uvs->GetNumberOfComponents() > 2)
  {
    vtkWarningMacro("Texture coordinates '" << (uvs->GetName() ? uvs->GetName() : "") << "' have "
                                            << uvs->GetNumberOfComponents()
                                            << " components; using the first two.");
  }

  // Normals: point normals, else cell normals, else computed.
  vtkDataArray* normals = pd->GetNormals();
  vtkDataArray* cellNormals = nullptr;
  if (normals)
  {
    normals = NumericPointArray(input, "Normals", normals, problem);
    if (normals && normals->GetNumberOfComponents() != 3)
    {
      problem = "point normals have " + std::to_string(normals->GetNumberOfComponents()) +
        " components instead of 3";
      normals = nullptr;
    }
    if (!normals)
    {
      vtkWarningMacro("Ignoring the point normals: " << problem << ".");
    }
  }
  if (!normals)
  {
    vtkDataArray* cn = input->GetCellData()->GetNormals();
    if (cn && cn->GetNumberOfComponents() == 3 &&
      cn->GetNumberOfTuples() >= input->GetNumberOfCells())
    {
      cellNormals = cn;
      vtkWarningMacro("The input has cell normals but no point normals; averaging the cell "
                      "normals to points (area-weighted) and adding them as point 'Normals'.");
    }
    else
    {
      vtkWarningMacro("The input has no point normals; computing smooth area-weighted point "
                      "normals (without splitting) and adding them as point 'Normals'.");
    }
  }

  const bool doublePrecision = this->OutputPrecision == DOUBLE_PRECISION ||
    (this->OutputPrecision == DEFAULT_PRECISION && input->GetPoints()->GetDataType() == VTK_DOUBLE);
  return doublePrecision
    ? Internals::Run<double>(this, input, output, uvs, normals, cellNormals, sizes + 2)
    : Internals::Run<float>(this, input, output, uvs, normals, cellNormals, sizes + 2);
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
  os << indent << "NumberOfDegenerateTriangles: " << this->NumberOfDegenerateTriangles << "\n";
  os << indent << "NumberOfFallbackPoints: " << this->NumberOfFallbackPoints << "\n";
  os << indent << "NumberOfHandednessConflicts: " << this->NumberOfHandednessConflicts << "\n";
  os << indent << "NumberOfSplitPoints: " << this->NumberOfSplitPoints << "\n";
  os << indent << "NumberOfInvalidNormals: " << this->NumberOfInvalidNormals << "\n";
}
