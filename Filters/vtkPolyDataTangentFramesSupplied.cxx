// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames with supplied tangents (SuppliedTangents KEEP and KEEP_VALID): the
// input's frames are checked (vtkTangentFrameChecks.h), written to the outputs, and the frames
// of the points that need one come from ComputeBlock.
#include "vtkPolyDataTangentFrames.h"

#include "vtkTangentFrameChecks.h"
#include "vtkTangentFrameKernels.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <vector>

namespace
{
/// The point array that carries every output point's input point id through ComputeBlock,
/// which copies all point data to the points it splits.
constexpr const char* SourceIdsName = "vtkPolyDataTangentFrames_SourcePointIds";

/// The output's frame arrays, and how kept frames are written into them.
struct FrameOutput
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
      const glm::dvec3 b = sign *
        glm::cross(vtkNormalMapping::SafeNormalize(glm::dvec3(n[0], n[1], n[2])),
          glm::dvec3(t[0], t[1], t[2]));
      this->Bitangents->SetTuple3(out, b.x, b.y, b.z);
    }
  }
};

vtkSmartPointer<vtkDataArray> NewArray(bool doublePrecision,
  const char* name,
  int components,
  vtkIdType tuples)
{
  vtkSmartPointer<vtkDataArray> array;
  if (doublePrecision)
  {
    array = vtkSmartPointer<vtkDoubleArray>::New();
  }
  else
  {
    array = vtkSmartPointer<vtkFloatArray>::New();
  }
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}
} // namespace

const char* vtkPolyDataTangentFrames::GetSuppliedTangentsName(int mode)
{
  switch (mode)
  {
    case RECOMPUTE:
      return "Recompute";
    case KEEP:
      return "Keep";
    case KEEP_VALID:
      return "KeepValid";
    default:
      return "Unknown";
  }
}

void vtkPolyDataTangentFrames::SetSuppliedTangentsArrayName(const std::string& name)
{
  if (name != this->SuppliedTangentsArrayName)
  {
    this->SuppliedTangentsArrayName = name;
    this->Modified();
  }
}

int vtkPolyDataTangentFrames::ExecuteSupplied(const BlockInput& block)
{
  vtkPolyData* input = block.Input;
  vtkPolyData* output = block.Output;
  vtkDataArray* normals = block.Normals;
  const auto compute = [&](vtkPolyData* mesh)
  {
    BlockInput withMesh = block;
    withMesh.Input = mesh;
    return this->ComputeBlock(withMesh);
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
    return compute(input);
  }

  // Which points keep their frames.
  const bool keepValid = this->SuppliedTangents == KEEP_VALID;
  const vtkNormalMapping::FrameCheck check = vtkNormalMapping::CheckSuppliedFrames(
    input, normals, keepValid ? block.UVs : nullptr, supplied, this->GLTFSignConvention);
  const vtkNormalMapping::FrameCheckCounts& counts = check.Counts;
  this->NumberOfNonFiniteTangents += counts.NonFinite;
  this->NumberOfNonUnitTangents += counts.NotUnit;
  this->NumberOfNonPerpendicularTangents += counts.NotPerpendicular;
  const unsigned char wrongSign = vtkNormalMapping::DefectSignNotUnit |
    vtkNormalMapping::DefectSignAgainstWinding | vtkNormalMapping::DefectMixedWinding;
  const unsigned char replaced = keepValid ? 0xff : vtkNormalMapping::DefectNonFinite;
  const vtkIdType numPoints = input->GetNumberOfPoints();
  vtkIdType numReplaced = 0;
  for (vtkIdType p = 0; p < numPoints; ++p)
  {
    this->NumberOfWrongSignTangents += (check.Defects[p] & wrongSign) ? 1 : 0;
    numReplaced += (check.Defects[p] & replaced) ? 1 : 0;
  }
  this->NumberOfReplacedTangents += numReplaced;
  if (!keepValid && numReplaced > 0)
  {
    vtkWarningMacro(<< numReplaced << " supplied tangents have NaN or infinite values; computing "
                    << "their frames with the " << GetMethodName(this->Method) << " method.");
  }

  // Computed frames first, where some are needed; then the kept frames over them.
  const bool needsComputation = numReplaced > 0 || this->ComputeCellTangents;
  vtkSmartPointer<vtkIdTypeArray> sourceIds;
  if (needsComputation)
  {
    vtkNew<vtkPolyData> marked;
    marked->ShallowCopy(input);
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName(SourceIdsName);
    ids->SetNumberOfTuples(numPoints);
    for (vtkIdType p = 0; p < numPoints; ++p)
    {
      ids->SetValue(p, p);
    }
    marked->GetPointData()->AddArray(ids);
    compute(marked);
    sourceIds = vtkIdTypeArray::SafeDownCast(output->GetPointData()->GetArray(SourceIdsName));
    output->GetPointData()->RemoveArray(SourceIdsName);
  }
  else
  {
    output->ShallowCopy(input);
  }

  vtkPointData* outPD = output->GetPointData();
  const vtkIdType numOut = output->GetNumberOfPoints();
  FrameOutput out;
  // The weighted methods' signs with GLTFSignConvention follow the v-down coordinates as stored:
  // the opposite of the supplied (glTF) convention.
  out.SignFactor = this->GLTFSignConvention && this->Method != MIKKTSPACE ? -1.0 : 1.0;
  if (needsComputation)
  {
    out.Tangents = outPD->GetArray(TangentsArrayName());
    out.Signs = outPD->GetArray(SignsArrayName());
    out.Bitangents = outPD->GetArray(BitangentsArrayName());
    // After an error ComputeBlock passes the input through (its arrays, shared: never written)
    // and after an abort the output is empty.
    vtkPointData* inPD = input->GetPointData();
    if (!sourceIds || !out.Tangents || !out.Signs || sourceIds->GetNumberOfTuples() != numOut ||
      out.Tangents == inPD->GetArray(TangentsArrayName()) ||
      out.Signs == inPD->GetArray(SignsArrayName()))
    {
      return 1;
    }
  }
  else
  {
    const bool doublePrecision = this->DoubleOutput(input);
    auto tangents = NewArray(doublePrecision, TangentsArrayName(), 3, numOut);
    auto signs = NewArray(doublePrecision, SignsArrayName(), 1, numOut);
    outPD->SetTangents(tangents);
    outPD->AddArray(signs);
    out.Tangents = tangents;
    out.Signs = signs;
    if (this->ComputeBitangents)
    {
      auto bitangents = NewArray(doublePrecision, BitangentsArrayName(), 3, numOut);
      outPD->AddArray(bitangents);
      out.Bitangents = bitangents;
    }
  }
  vtkSMPTools::For(0,
    numOut,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType p = begin; p < end; ++p)
      {
        const vtkIdType source = sourceIds ? sourceIds->GetValue(p) : p;
        if (!(check.Defects[source] & replaced))
        {
          out.Keep(supplied, normals, source, p);
        }
      }
    });
  this->UpdateProgress(block.ProgressEnd);
  return 1;
}
