/**
 * @file   vtkNormalMappingPrivate.h
 * @brief  Private helpers shared by the filter's translation units (not installed).
 */
#ifndef vtkNormalMappingPrivate_h
#define vtkNormalMappingPrivate_h

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <type_traits>
#include <vector>

namespace vtkNormalMapping
{
namespace detail
{
/**
 * A reference to a callable on an id range [begin, end), without its type, for ParallelFor. The
 * callable must outlive the call (a lambda passed straight to ParallelFor does).
 */
class RangeFunction
{
public:
  /// f: a callable object, const or not (a non-const one is called as vtkSMPTools calls a
  /// functor passed by reference: the same object from every thread).
  template<typename F,
    typename = std::enable_if_t<!std::is_same<std::decay_t<F>, RangeFunction>::value>>
  RangeFunction(F&& f)
    : Object(const_cast<void*>(static_cast<const void*>(&f)))
    , Call([](void* o, vtkIdType begin, vtkIdType end)
        { (*static_cast<std::remove_reference_t<F>*>(o))(begin, end); })
  {
  }
  void operator()(vtkIdType begin, vtkIdType end) const { this->Call(this->Object, begin, end); }

private:
  void* Object;
  void (*Call)(void*, vtkIdType, vtkIdType);
};

/**
 * vtkSMPTools::For(0, n, grain, f) (grain 0: the backend chooses), compiled once, in
 * vtkNormalMappingPrivate.cxx. The filters' parallel loops go through it, so that the SMP
 * backends' templates (sequential, STDThread and TBB in Debian's VTK) are instantiated once rather
 * than for every loop body, mesh type and output precision: they were most of the filters'
 * compile time. The cost is one indirect call per range a thread takes.
 */
void ParallelFor(vtkIdType n, vtkIdType grain, RangeFunction f);
inline void ParallelFor(vtkIdType n, RangeFunction f)
{
  ParallelFor(n, 0, f);
}

/// The number of ranges of `size` ids (the last one shorter) that cover [0, n).
inline vtkIdType ChunkCount(vtkIdType n, vtkIdType size)
{
  return n <= 0 ? 0 : (n + size - 1) / size;
}

/**
 * f(chunk, begin, end) for each of the ChunkCount(n, size) ranges [chunk size, ...) of [0, n), in
 * parallel: for results kept per chunk (in a vector of ChunkCount entries, combined in chunk order
 * afterwards) instead of per thread. Constructing a vtkSMPThreadLocal asks
 * std::thread::hardware_concurrency for the CPU count, which glibc 2.36 answers by opening and
 * reading /sys/devices/system/cpu/online every time: the seven thread-local objects an Update of
 * vtkPolyDataTangentFrames made cost 35-40 us, a quarter of an Update of 10K triangles.
 */
template<typename F>
void ParallelChunks(vtkIdType n, vtkIdType size, F&& f)
{
  ParallelFor(ChunkCount(n, size),
    1,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType chunk = first; chunk < last; ++chunk)
      {
        const vtkIdType begin = chunk * size;
        f(chunk, begin, n - begin < size ? n : begin + size);
      }
    });
}

/**
 * The number of threads ParallelFor can use from here: 1 inside a vtkSMPTools parallel scope
 * with nested parallelism turned off (VTK then runs the inner loops serially, on the calling
 * thread), else vtkSMPTools' estimate. The filters split their work for this many threads:
 * splitting for more than run it only adds work. Measured with nested parallelism off: two
 * 1M-triangle tori updated inside one vtkSMPTools::For, one per thread, took 14.0-15.8 ms per
 * pair of Updates (median of 6 runs 14.3) with the scan in one block, 15.8-17.7 (15.95) in the 8
 * blocks of two threads. VTK 9.1's TBB and STDThread backends nest by default, and then nothing
 * changes. The scope can begin or end on another thread meanwhile: the output does not depend on
 * the split, only the speed.
 */
int UsableThreads();

/// Calls f(offsets, connectivity) with the typed raw storage of a cell array (32 or 64 bit),
/// so that cells are read without a virtual call per cell.
template<typename F>
void WithCellStorage(vtkCellArray* cells, F&& f)
{
  if (cells->IsStorage64Bit())
  {
    f(cells->GetOffsetsArray64()->GetPointer(0), cells->GetConnectivityArray64()->GetPointer(0));
  }
  else
  {
    f(cells->GetOffsetsArray32()->GetPointer(0), cells->GetConnectivityArray32()->GetPointer(0));
  }
}

/**
 * A copy of a point array cut to its first numIn tuples, with source.size() more: tuple
 * numIn + i copies tuple source[i] (a point split in two takes all its point data along).
 * An array shorter than numIn cannot follow the points and is returned as it is.
 */
inline vtkSmartPointer<vtkAbstractArray> ExtendPointArray(vtkAbstractArray* array,
  vtkIdType numIn,
  const std::vector<vtkIdType>& source)
{
  if (array->GetNumberOfTuples() < numIn)
  {
    return array;
  }
  const vtkIdType extra = static_cast<vtkIdType>(source.size());
  vtkNew<vtkIdList> src, dst;
  src->SetNumberOfIds(extra);
  dst->SetNumberOfIds(extra);
  for (vtkIdType i = 0; i < extra; ++i)
  {
    src->SetId(i, source[static_cast<size_t>(i)]);
    dst->SetId(i, numIn + i);
  }
  vtkSmartPointer<vtkAbstractArray> copy = vtk::TakeSmartPointer(array->NewInstance());
  copy->DeepCopy(array);
  copy->SetNumberOfTuples(numIn); // appended tuples follow the points, not extra input tuples
  copy->Resize(numIn + extra);
  copy->InsertTuples(dst, src, array);
  return copy;
}

/**
 * The output's structure and cell data from the input; its points and point data from the
 * input's with source.size() points appended (ExtendPointArray), attributes kept. The caller
 * re-points the cells to the new points.
 */
inline void CopyWithAppendedPoints(vtkPolyData* input,
  vtkPolyData* output,
  const std::vector<vtkIdType>& source)
{
  output->CopyStructure(input);
  output->GetCellData()->PassData(input->GetCellData());
  vtkPointData* inPD = input->GetPointData();
  vtkPointData* outPD = output->GetPointData();
  if (source.empty())
  {
    outPD->PassData(inPD);
    return;
  }
  const vtkIdType numIn = input->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetData(
    vtkDataArray::SafeDownCast(ExtendPointArray(input->GetPoints()->GetData(), numIn, source)));
  output->SetPoints(points);
  outPD->Initialize();
  for (int k = 0; k < inPD->GetNumberOfArrays(); ++k)
  {
    outPD->AddArray(ExtendPointArray(inPD->GetAbstractArray(k), numIn, source));
    const int attribute = inPD->IsArrayAnAttribute(k);
    if (attribute >= 0)
    {
      outPD->SetActiveAttribute(outPD->GetNumberOfArrays() - 1, attribute);
    }
  }
}
}
}

#endif
