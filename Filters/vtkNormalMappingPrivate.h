// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   vtkNormalMappingPrivate.h
 * @brief  Private helpers shared by the filter's translation units (not installed).
 */
#ifndef vtkNormalMappingPrivate_h
#define vtkNormalMappingPrivate_h

#include "vtkAbstractArray.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkNew.h"
#include "vtkNormalMappingMultiversioning.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataTangentFrames.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTangentFrameKernels.h"
#include "vtkType.h"
#include "vtkVersionMacros.h"

#include <algorithm>
#include <cfloat>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace vtkNormalMapping
{
namespace detail
{
/**
 * The number of threads a vtkSMPTools::For can use from here: 1 inside a vtkSMPTools parallel scope
 * with nested parallelism turned off (VTK then runs the inner loops serially, on the calling
 * thread), else vtkSMPTools' estimate.
 */
int UsableThreads();

/// Whether this build of the module compiled its block loops for several instruction sets
/// (VTK_NORMALMAPPING_TARGET_CLONES): for the benchmark's description of a build.
bool MultiversionedLoops();

/**
 * `array` when it has `components` components (0: any number) and a tuple for every point of
 * `mesh`, else null with `problem` saying why ("<what> array 'name' has ..."). A null `array`
 * gives null and leaves `problem` as it is.
 */
vtkDataArray* PointArray(vtkPolyData* mesh,
  vtkDataArray* array,
  const char* what,
  int components,
  std::string& problem);

/// The degeneracy tolerances for positions and texture coordinates stored in these arrays: those
/// of double for double arrays, of float for any other type.
inline DegeneracyTolerance ToleranceFor(vtkDataArray* points, vtkDataArray* uvs)
{
  const auto epsilon = [](vtkDataArray* array)
  { return array->GetDataType() == VTK_DOUBLE ? DBL_EPSILON : static_cast<double>(FLT_EPSILON); };
  return DegeneracyTolerance::ForEpsilons(epsilon(points), epsilon(uvs));
}

/**
 * The layout of the triangles of a cell whose points are pts: triangle j of a polygon is the fan
 * triangle (0, j + 1, j + 2); of a strip (j, j + 1, j + 2), every odd one reversed so that all
 * triangles of a strip share its winding. A cell of n points holds max(n - 2, 0) triangles.
 */
template<typename IdT, typename OutT>
void CellTriangle(const IdT* pts, vtkIdType j, bool strip, OutT tri[3])
{
  const bool odd = (j & 1) != 0;
  tri[0] = static_cast<OutT>(pts[strip ? (odd ? j + 1 : j) : 0]);
  tri[1] = static_cast<OutT>(pts[strip && odd ? j : j + 1]);
  tri[2] = static_cast<OutT>(pts[j + 2]);
}

/// The position (0, 1 or 2) of strip corner i in strip triangle j, which holds it (CellTriangle).
inline int PositionInStripTriangle(vtkIdType i, vtkIdType j)
{
  if ((j & 1) == 0)
  {
    return static_cast<int>(i - j);
  }
  return i == j + 1 ? 0 : (i == j ? 1 : 2);
}

/**
 * The triangles [first, last] of a cell with n points that hold its corner k (CellTriangle): a
 * polygon's corner 0 is in every triangle and its corner k > 0 in triangles k - 2 and k - 1;
 * strip triangle j holds corners j to j + 2.
 */
inline void TrianglesAtCorner(vtkIdType k,
  vtkIdType n,
  bool strip,
  vtkIdType& first,
  vtkIdType& last)
{
  first = std::max<vtkIdType>(k - 2, 0);
  last =
    strip ? std::min<vtkIdType>(k, n - 3) : (k == 0 ? n - 3 : std::min<vtkIdType>(k - 1, n - 3));
}

/// Calls worker(typed array, args...) through vtkArrayDispatch for the arrays whose value type is
/// in ValueTypes (every type by default), else worker(array, args...) with the generic
/// vtkDataArray API.
template<typename ValueTypes = vtkArrayDispatch::AllTypes, typename Worker, typename... Args>
void DispatchArray(vtkDataArray* array, Worker&& worker, Args&&... args)
{
  if (!vtkArrayDispatch::DispatchByValueType<ValueTypes>::Execute(array, worker, args...))
  {
    worker(array, args...);
  }
}

/**
 * Calls f(begin, end, normal) on ranges of [0, n) in parallel, where normal(p) is point p's
 * normal from a 3-component array, as a glm vector of the floats or doubles it stores (read
 * through its concrete type), or of doubles for arrays of any other type.
 */
template<typename F>
void ForEachNormalRange(vtkDataArray* array, vtkIdType n, const F& f)
{
  DispatchArray<vtkArrayDispatch::Reals>(array,
    [&](auto* typed)
    {
      const auto normals = vtk::DataArrayTupleRange<3>(typed, 0, n);
      using T = typename decltype(normals)::ComponentType;
      const auto normal = [&](vtkIdType p)
      {
        const auto v = normals[p];
        return glm::vec<3, T>(v[0], v[1], v[2]);
      };
      vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) { f(begin, end, normal); });
    });
}

/// Returns f(offsets, connectivity) with the typed raw storage of a cell array (32 or 64 bit:
/// see WithPlainCellStorage), so that cells are read without a virtual call per cell.
template<typename F>
decltype(auto) WithCellStorage(vtkCellArray* cells, F&& f)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  if (cells->IsStorage64Bit())
  {
    return f(cells->GetOffsetsAOSArray64()->GetPointer(0),
      cells->GetConnectivityAOSArray64()->GetPointer(0));
  }
  return f(cells->GetOffsetsAOSArray32()->GetPointer(0),
    cells->GetConnectivityAOSArray32()->GetPointer(0));
#else
  if (cells->IsStorage64Bit())
  {
    return f(
      cells->GetOffsetsArray64()->GetPointer(0), cells->GetConnectivityArray64()->GetPointer(0));
  }
  return f(
    cells->GetOffsetsArray32()->GetPointer(0), cells->GetConnectivityArray32()->GetPointer(0));
#endif
}

/**
 * Per cell of `cells`, the index of its first triangle (CellTriangle), counted on from first[0]:
 * first[c + 1] is where cell c's triangles end.
 */
template<typename T>
void CellTriangleStarts(vtkCellArray* cells, T* first)
{
  WithCellStorage(cells,
    [&](const auto* offsets, const auto*)
    {
      for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
      {
        const T n = static_cast<T>(offsets[c + 1] - offsets[c]);
        first[c + 1] = first[c] + std::max<T>(n - 2, 0);
      }
    });
}

/**
 * A shallow copy of `input` in which each cell of `cells` (ascending indices over the polygons,
 * then the strips) is replaced, in place, by its triangles (CellTriangle) as cells of its kind
 * with 3 points each, so that the triangles keep their order. The cell data of a replaced cell
 * repeats for each of its triangles; cell arrays shorter than the cells pass as they are, and
 * global cell ids are dropped (the triangles of a cell would repeat its id).
 */
vtkSmartPointer<vtkPolyData> CutIntoTriangles(vtkPolyData* input,
  const std::vector<vtkIdType>& cells);

/// An empty array of the class of `array` with its name, components, component names,
/// information and lookup table.
vtkSmartPointer<vtkAbstractArray> EmptyCopyOf(vtkAbstractArray* array);

/**
 * A copy of a point array cut to its first numIn tuples, with source.size() more: tuple
 * numIn + i copies tuple source[i] (a point split in two takes all its point data along).
 * The copy keeps the array's name, component names, information and lookup table, and holds
 * exactly its tuples. An array shorter than numIn cannot follow the points and is returned as
 * it is.
 */
vtkSmartPointer<vtkAbstractArray> ExtendPointArray(vtkAbstractArray* array,
  vtkIdType numIn,
  const std::vector<vtkIdType>& source);

/**
 * The output's structure and cell data from the input; its points and point data from the
 * input's with source.size() points appended (ExtendPointArray), attributes kept. A point array
 * named in `replaced` is not extended: the caller adds its own array of that name, which takes
 * the input array's place, so until then the input's array stands there. The caller re-points
 * the cells to the new points.
 */
void CopyWithAppendedPoints(vtkPolyData* input,
  vtkPolyData* output,
  const std::vector<vtkIdType>& source,
  const std::vector<std::string>& replaced);

/**
 * Adds a frame array to `attributes` in place of an array of its name. An array of that name that
 * holds the normals or texture coordinates (named like a frame array; ExecuteBlock warns) is
 * removed first, so that the attribute does not come to name frame data; another attribute (the
 * scalars, say) moves to the frame array, as AddArray leaves it.
 */
void AddFrameArray(vtkDataSetAttributes* attributes, vtkDataArray* array);

/**
 * Adds `tangents` to `attributes` (AddFrameArray) as the active tangents. An array of another
 * name that held the attribute (a reader's tangents) stays, as other point or cell data does:
 * SetTangents would remove it.
 */
void AddActiveTangents(vtkDataSetAttributes* attributes, vtkDataArray* tangents);

/// A new array of class ArrayT with the given name, components and tuples (values not set).
template<typename ArrayT>
vtkSmartPointer<ArrayT> NewArray(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

/**
 * The output's cell tangents, of array class ArrayT: per polygon, then per strip (cell c of
 * them), sums(c, t, n) adds the cell's tangents to t and its normals, weighted by area, to n, and
 * the cell's tangent is the part of t perpendicular to the unit n (PerpendicularTangent);
 * (0, 0, 0) for vertex and line cells.
 */
template<typename ArrayT, typename Sums>
vtkSmartPointer<ArrayT> NewCellTangents(vtkPolyData* input, const Sums& sums)
{
  using T = typename ArrayT::ValueType;
  const vtkIdType numCells = input->GetNumberOfCells();
  auto array = NewArray<ArrayT>(vtkPolyDataTangentFrames::TangentsArrayName(), 3, numCells);
  T* out = array->GetPointer(0);
  std::fill(out, out + 3 * numCells, T(0));
  out += 3 * (input->GetNumberOfVerts() + input->GetNumberOfLines());
  vtkSMPTools::For(0,
    input->GetNumberOfPolys() + input->GetNumberOfStrips(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType c = begin; c < end; ++c)
      {
        glm::dvec3 t(0.0), n(0.0);
        sums(c, t, n);
        const glm::dvec3 unit = PerpendicularTangent(SafeNormalize(n), t);
        for (int k = 0; k < 3; ++k)
        {
          out[3 * c + k] = static_cast<T>(unit[k]);
        }
      }
    });
  return array;
}

/// The storage of the frame arrays (OutputFrames::Storage), point p at index p.
template<typename T>
struct FrameStorage
{
  T* Tangents;
  T* Signs;
  T* Bitangents; // null when not asked for

  /// Point p's frame: unit tangent t, its sign, and the bitangent from the unit normal n.
  void Write(vtkIdType p, const glm::dvec3& n, const glm::dvec3& t, double sign) const
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Tangents[3 * p + c] = static_cast<T>(t[c]);
    }
    this->Signs[p] = static_cast<T>(sign);
    if (this->Bitangents)
    {
      const glm::dvec3 b = Bitangent(n, t, sign);
      for (int c = 0; c < 3; ++c)
      {
        this->Bitangents[3 * p + c] = static_cast<T>(b[c]);
      }
    }
  }
};

/**
 * The output's point frame arrays, `tuples` long, of one array class (vtkFloatArray or
 * vtkDoubleArray): tangents, signs and, when asked for, bitangents, named as
 * vtkPolyDataTangentFrames names them. The one place the filter's paths make them.
 */
template<typename ArrayT>
struct OutputFrames
{
  vtkSmartPointer<ArrayT> Tangents;
  vtkSmartPointer<ArrayT> Signs;
  vtkSmartPointer<ArrayT> Bitangents; // null when not asked for

  OutputFrames(vtkIdType tuples, bool bitangents)
    : Tangents(NewArray<ArrayT>(vtkPolyDataTangentFrames::TangentsArrayName(), 3, tuples))
    , Signs(NewArray<ArrayT>(vtkPolyDataTangentFrames::SignsArrayName(), 1, tuples))
    , Bitangents(bitangents
          ? NewArray<ArrayT>(vtkPolyDataTangentFrames::BitangentsArrayName(), 3, tuples)
          : nullptr)
  {
  }

  /// Their storage, to write frames into.
  FrameStorage<typename ArrayT::ValueType> Storage() const
  {
    return { this->Tangents->GetPointer(0),
      this->Signs->GetPointer(0),
      this->Bitangents ? this->Bitangents->GetPointer(0) : nullptr };
  }

  /// Their names, the point arrays AddTo replaces.
  std::vector<std::string> Names() const
  {
    std::vector<std::string> names;
    for (ArrayT* array : { this->Tangents.Get(), this->Signs.Get(), this->Bitangents.Get() })
    {
      if (array)
      {
        names.emplace_back(array->GetName());
      }
    }
    return names;
  }

  /// Gives them `tuples` tuples, keeping the values of the first ones.
  void Resize(vtkIdType tuples) const
  {
    for (ArrayT* array : { this->Tangents.Get(), this->Signs.Get(), this->Bitangents.Get() })
    {
      if (array)
      {
        // Both keep the values and can leave room beyond; VTK 9.7 deprecates Resize.
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 7, 0)
        array->ReserveTuples(tuples);
#else
        array->Resize(tuples);
#endif
        array->SetNumberOfTuples(tuples);
        array->Squeeze(); // gives that room back
      }
    }
  }

  /// Adds them to `pd`, the tangents as its active tangents.
  void AddTo(vtkPointData* pd) const
  {
    AddActiveTangents(pd, this->Tangents);
    AddFrameArray(pd, this->Signs);
    if (this->Bitangents)
    {
      AddFrameArray(pd, this->Bitangents);
    }
  }
};

/**
 * A copy of `cells` whose connectivity positions [base, base + size) listed in `repoint`
 * (position, new point id) refer to the new ids: the corners of split points that move to the
 * points' copies. 64-bit storage when maxId does not fit in 32 bits. The copy shares the
 * offsets; `cells` itself is returned when none of its positions moves.
 */
vtkSmartPointer<vtkCellArray> RepointCells(vtkCellArray* cells,
  const std::vector<std::pair<vtkIdType, vtkIdType>>& repoint,
  vtkIdType base,
  vtkIdType size,
  vtkIdType maxId);

/**
 * The output of a method that splits points: the input with a copy of each point of `source`
 * appended (CopyWithAppendedPoints), the connectivity positions of `repoint` (counted over the
 * polygons' connectivity, then the strips') re-pointed to the copies, and `frames` as its frame
 * arrays, whose tuples the caller has written. `computedNormals`, the normals the filter computed
 * for the input points (null when the input had its own), follow the point data and become the
 * output's normals.
 */
template<typename ArrayT>
void WriteSplitOutput(vtkPolyData* input,
  vtkPolyData* output,
  const std::vector<vtkIdType>& source,
  const std::vector<std::pair<vtkIdType, vtkIdType>>& repoint,
  const OutputFrames<ArrayT>& frames,
  vtkDataArray* computedNormals)
{
  CopyWithAppendedPoints(input, output, source, frames.Names());
  vtkPointData* outPD = output->GetPointData();
  if (!source.empty())
  {
    const vtkIdType numIn = input->GetNumberOfPoints();
    const vtkIdType maxId = numIn + static_cast<vtkIdType>(source.size()) - 1;
    const vtkIdType polySize = input->GetPolys()->GetNumberOfConnectivityIds();
    const vtkIdType stripSize = input->GetStrips()->GetNumberOfConnectivityIds();
    output->SetPolys(RepointCells(input->GetPolys(), repoint, 0, polySize, maxId));
    output->SetStrips(RepointCells(input->GetStrips(), repoint, polySize, stripSize, maxId));
    if (computedNormals)
    {
      outPD->SetNormals(
        vtkDataArray::SafeDownCast(ExtendPointArray(computedNormals, numIn, source)));
    }
  }
  else if (computedNormals)
  {
    outPD->SetNormals(computedNormals);
  }
  frames.AddTo(outPD);
}
}
}

#endif
