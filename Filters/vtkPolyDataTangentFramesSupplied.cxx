// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames with supplied tangents (SuppliedTangents KEEP and KEEP_VALID): the
// input's frames are checked (vtkTangentFrameChecks.h), written to the outputs, and the frames
// of the points that need one come from ComputeBlock.
#include "vtkPolyDataTangentFrames.h"

#include "vtkNormalMappingPrivate.h"
#include "vtkTangentFrameChecks.h"
#include "vtkTangentFrameKernels.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cfloat>
#include <vector>

namespace
{
/// Writes kept frames into the output's frame arrays.
struct KeptFrameWriter
{
  vtkDataArray* Tangents = nullptr;
  vtkDataArray* Signs = nullptr;
  vtkDataArray* Bitangents = nullptr; // when ComputeBitangents is on
  /// -1 when the output's signs are the opposite of the supplied convention (see the header).
  double SignFactor = 1.0;

  /// Output point `out` takes the supplied frame of input point `in`.
  void Keep(const vtkNormalMapping::SuppliedFrameArrays& supplied,
    vtkDataArray* normals,
    vtkIdType in,
    vtkIdType out) const
  {
    double t[3], w;
    vtkNormalMapping::SuppliedFrame(supplied, in, t, w);
    const double sign = (w < 0.0 ? -1.0 : 1.0) * this->SignFactor;
    this->Tangents->SetTuple(out, t);
    this->Signs->SetComponent(out, 0, sign);
    if (this->Bitangents)
    {
      double n[3];
      normals->GetTuple(in, n);
      const glm::dvec3 b =
        vtkNormalMapping::Bitangent(vtkNormalMapping::SafeNormalize(glm::dvec3(n[0], n[1], n[2])),
          glm::dvec3(t[0], t[1], t[2]),
          sign);
      this->Bitangents->SetTuple3(out, b.x, b.y, b.z);
    }
  }
};

/// The number of points whose defects include any bit of `mask`.
vtkIdType CountPointsWith(const vtkNormalMapping::FrameCheck& check, unsigned char mask)
{
  return static_cast<vtkIdType>(std::count_if(check.Defects.begin(),
    check.Defects.end(),
    [mask](unsigned char defects) { return (defects & mask) != 0; }));
}

/// New frame arrays of `tuples` tuples of class ArrayT in `pd`.
template<typename ArrayT>
KeptFrameWriter NewKeptFrameWriter(vtkPointData* pd, bool bitangents, vtkIdType tuples)
{
  const vtkNormalMapping::detail::OutputFrames<ArrayT> arrays(tuples, bitangents);
  arrays.AddTo(pd);
  KeptFrameWriter out;
  out.Tangents = arrays.Tangents;
  out.Signs = arrays.Signs;
  out.Bitangents = arrays.Bitangents;
  return out;
}

/**
 * Points `out` at the frame arrays ComputeBlock wrote to `output` from `input`, which holds the
 * input points and a copy of each of `splitSources`. False when there are none to write into:
 * after an error ComputeBlock passes the input through (its arrays, shared: never written) and
 * after an abort the output is empty.
 */
bool FindComputedFrames(vtkPolyData* input,
  vtkPolyData* output,
  bool bitangents,
  const std::vector<vtkIdType>& splitSources,
  KeptFrameWriter& out)
{
  vtkPointData* outPD = output->GetPointData();
  vtkPointData* inPD = input->GetPointData();
  out.Tangents = outPD->GetArray(vtkPolyDataTangentFrames::TangentsArrayName());
  out.Signs = outPD->GetArray(vtkPolyDataTangentFrames::SignsArrayName());
  // Without ComputeBitangents an array of that name is the input's, passed through.
  out.Bitangents =
    bitangents ? outPD->GetArray(vtkPolyDataTangentFrames::BitangentsArrayName()) : nullptr;
  return out.Tangents && out.Signs &&
    output->GetNumberOfPoints() ==
    input->GetNumberOfPoints() + static_cast<vtkIdType>(splitSources.size()) &&
    out.Tangents != inPD->GetArray(vtkPolyDataTangentFrames::TangentsArrayName()) &&
    out.Signs != inPD->GetArray(vtkPolyDataTangentFrames::SignsArrayName()) &&
    (!out.Bitangents ||
      out.Bitangents != inPD->GetArray(vtkPolyDataTangentFrames::BitangentsArrayName()));
}

/**
 * Output points [0, numOut) keep the supplied frames of their input points (the first numIn are
 * the input points, the others copies of `splitSources`), except those whose defects include a
 * bit of `replaced`.
 */
void KeepFrames(const KeptFrameWriter& out,
  const vtkNormalMapping::SuppliedFrameArrays& supplied,
  vtkDataArray* normals,
  const vtkNormalMapping::FrameCheck& check,
  unsigned char replaced,
  vtkIdType numIn,
  const std::vector<vtkIdType>& splitSources)
{
  const vtkIdType numOut = numIn + static_cast<vtkIdType>(splitSources.size());
  vtkSMPTools::For(0,
    numOut,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType p = begin; p < end; ++p)
      {
        const vtkIdType source = p < numIn ? p : splitSources[static_cast<size_t>(p - numIn)];
        if (!(check.Defects[source] & replaced))
        {
          out.Keep(supplied, normals, source, p);
        }
      }
    });
}
} // namespace

void vtkPolyDataTangentFrames::ExecuteSupplied(const BlockInput& block)
{
  vtkPolyData* input = block.Input;
  vtkPolyData* output = block.Output;
  vtkDataArray* normals = block.Normals;
  // Frames computed for the input's points, except that the points of `kept` (null: none) keep
  // theirs: they are neither split nor counted as conflicts.
  std::vector<vtkIdType> splitSources;
  const auto compute = [&](const unsigned char* kept)
  {
    BlockInput withKept = block;
    withKept.KeptPoints = kept;
    withKept.SplitSources = &splitSources;
    this->ComputeBlock(withKept);
  };
  std::string problem;
  const vtkNormalMapping::SuppliedFrameArrays supplied =
    vtkNormalMapping::FindSuppliedFrames(input, this->SuppliedTangentsArrayName, problem);
  if (!supplied.IsUsable() || !normals)
  {
    vtkWarningMacro("Cannot use the supplied tangents: "
      << (normals ? problem
                  : "the input has no usable point normals (the tangents are only meaningful "
                    "with the normals they were made for)")
      << "; computing every frame with the " << GetMethodName(this->Method) << " method.");
    compute(nullptr);
    return;
  }

  // Which points keep their frames: only tangents the output's precision holds, with room for
  // the rounding of a bitangent as long.
  const bool keepValid = this->SuppliedTangents == KEEP_VALID;
  const double largest = 0.5 * (this->DoubleOutput(input) ? DBL_MAX : FLT_MAX);
  const vtkNormalMapping::FrameCheck check = vtkNormalMapping::CheckSuppliedFrames(input,
    normals,
    keepValid ? block.UVs : nullptr,
    supplied,
    this->GLTFSignConvention,
    vtkNormalMapping::FrameCheckTolerances(),
    largest);
  const vtkNormalMapping::FrameCheckCounts& counts = check.Counts;
  this->NumberOfNonFiniteTangents += counts.NonFinite;
  this->NumberOfNonUnitTangents += counts.NotUnit;
  this->NumberOfNonPerpendicularTangents += counts.NotPerpendicular;
  this->NumberOfWrongSignTangents += CountPointsWith(check,
    vtkNormalMapping::DefectSignNotUnit | vtkNormalMapping::DefectSignAgainstWinding |
      vtkNormalMapping::DefectMixedWinding);
  const unsigned char replaced = keepValid ? 0xff : vtkNormalMapping::DefectNonFinite;
  const vtkIdType numReplaced = keepValid ? counts.Failed : counts.NonFinite;
  this->NumberOfReplacedTangents += numReplaced;
  if (!keepValid && numReplaced > 0)
  {
    vtkWarningMacro(<< numReplaced
                    << " supplied tangents have NaN or infinite values, or values too large for "
                       "the output's precision; computing their frames with the "
                    << GetMethodName(this->Method) << " method.");
  }

  // Computed frames first, where some are needed; then the kept frames over them.
  KeptFrameWriter out;
  if (numReplaced > 0 || this->ComputeCellTangents)
  {
    std::vector<unsigned char> kept(check.Defects.size());
    std::transform(check.Defects.begin(),
      check.Defects.end(),
      kept.begin(),
      [replaced](unsigned char defects) { return (defects & replaced) == 0; });
    compute(kept.data());
    if (!FindComputedFrames(input, output, this->ComputeBitangents, splitSources, out))
    {
      return;
    }
  }
  else
  {
    output->ShallowCopy(input);
    const auto make = this->DoubleOutput(input) ? NewKeptFrameWriter<vtkDoubleArray>
                                                : NewKeptFrameWriter<vtkFloatArray>;
    out = make(output->GetPointData(), this->ComputeBitangents, output->GetNumberOfPoints());
  }
  // The weighted methods' signs with GLTFSignConvention follow the v-down coordinates as stored:
  // the opposite of the supplied (glTF) convention.
  out.SignFactor = this->GLTFSignConvention && this->Method != MIKKTSPACE ? -1.0 : 1.0;
  KeepFrames(out, supplied, normals, check, replaced, input->GetNumberOfPoints(), splitSources);
  this->UpdateProgress(block.ProgressEnd);
}
