// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames on composite input: every polydata block as if filtered alone, the
// counts summed over the blocks.
#include "NormalMappingMessages.h"
#include "NormalMappingProgress.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkMultiPieceDataSet.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace
{
/// The counts a filter reports, in one comparable value.
struct Counts
{
  vtkIdType Degenerate = 0, Fallback = 0, Conflicts = 0, Splits = 0, InvalidNormals = 0;

  static Counts Of(vtkPolyDataTangentFrames* f)
  {
    return { f->GetNumberOfDegenerateTriangles(),
      f->GetNumberOfFallbackPoints(),
      f->GetNumberOfHandednessConflicts(),
      f->GetNumberOfSplitPoints(),
      f->GetNumberOfInvalidNormals() };
  }
  Counts& operator+=(const Counts& o)
  {
    this->Degenerate += o.Degenerate;
    this->Fallback += o.Fallback;
    this->Conflicts += o.Conflicts;
    this->Splits += o.Splits;
    this->InvalidNormals += o.InvalidNormals;
    return *this;
  }
};

void ExpectCounts(const Counts& a, const Counts& b)
{
  EXPECT_EQ(a.Degenerate, b.Degenerate);
  EXPECT_EQ(a.Fallback, b.Fallback);
  EXPECT_EQ(a.Conflicts, b.Conflicts);
  EXPECT_EQ(a.Splits, b.Splits);
  EXPECT_EQ(a.InvalidNormals, b.InvalidNormals);
}

/// The same bytes in two data arrays (both present or both absent).
void ExpectSameArray(vtkDataArray* a, vtkDataArray* b, const char* name)
{
  ASSERT_EQ(a == nullptr, b == nullptr) << name;
  if (!a)
  {
    return;
  }
  ASSERT_EQ(a->GetDataType(), b->GetDataType()) << name;
  ASSERT_EQ(a->GetNumberOfValues(), b->GetNumberOfValues()) << name;
  if (a->GetNumberOfValues() == 0)
  {
    return; // an empty array may have no storage at all
  }
  EXPECT_EQ(0,
    std::memcmp(a->GetVoidPointer(0),
      b->GetVoidPointer(0),
      static_cast<size_t>(a->GetNumberOfValues() * a->GetDataTypeSize())))
    << name;
}

vtkSmartPointer<vtkPolyData> Torus(bool mirrored, int u)
{
  vtkNormalMapping::TorusOptions options;
  options.U = u;
  options.V = 8;
  options.MirrorU = mirrored;
  return vtkNormalMapping::MakeTorus(options);
}
} // namespace

TEST(TangentFramesComposite, BlocksAsAloneAndCountsSummed)
{
  // Two mirrored tori (seams: conflicts and split points in both), an unmirrored one, one whose
  // texture coordinates all collapse to one value (every triangle degenerate, every point a
  // fallback) with a zero normal, an empty polydata, an image (not polydata) and a null block,
  // one level nested. The last polydata block has no conflicts, so counts reset per block
  // (each block's execution overwriting them) would not give the sums.
  auto degenerate = Torus(false, 6);
  vtkDataArray* uv = degenerate->GetPointData()->GetTCoords();
  for (vtkIdType p = 0; p < uv->GetNumberOfTuples(); ++p)
  {
    uv->SetTuple2(p, 0.25, 0.5);
  }
  degenerate->GetPointData()->GetNormals()->SetTuple3(0, 0.0, 0.0, 0.0);
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 2);
  vtkNew<vtkPolyData> empty;

  const std::vector<vtkSmartPointer<vtkPolyData>> polyBlocks = {
    Torus(true, 16), Torus(true, 12), degenerate, empty, Torus(false, 10)
  };
  vtkNew<vtkMultiBlockDataSet> inner;
  inner->SetNumberOfBlocks(3);
  inner->SetBlock(0, polyBlocks[1]);
  inner->SetBlock(1, image);
  inner->SetBlock(2, polyBlocks[2]);
  vtkNew<vtkMultiBlockDataSet> input;
  input->SetNumberOfBlocks(5);
  input->SetBlock(0, polyBlocks[0]);
  input->SetBlock(1, inner);
  input->SetBlock(2, nullptr);
  input->SetBlock(3, polyBlocks[3]);
  input->SetBlock(4, polyBlocks[4]);

  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->ComputeBitangentsOn();
  filter->SetInputData(input);
  Messages warnings(filter);
  filter->Update();
  // The blocks alone: their counts, and their outputs for the comparison below.
  std::vector<vtkSmartPointer<vtkPolyData>> alone;
  Counts sum;
  Counts last;
  for (const auto& block : polyBlocks)
  {
    vtkNew<vtkPolyDataTangentFrames> single;
    single->ComputeBitangentsOn();
    single->SetInputData(block);
    single->Update();
    last = Counts::Of(single);
    sum += last;
    alone.push_back(single->GetOutput());
  }
  // The blocks were chosen so that every count is non-zero in the sum and the conflicts differ
  // from the last block's alone.
  EXPECT_GT(sum.Conflicts, 0);
  EXPECT_GT(sum.Splits, 0);
  EXPECT_GT(sum.Degenerate, 0);
  EXPECT_GT(sum.Fallback, 0);
  EXPECT_GT(sum.InvalidNormals, 0);
  EXPECT_EQ(last.Conflicts, 0);
  ExpectCounts(Counts::Of(filter), sum);

  auto* output = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr) << "composite input must give composite output";
  EXPECT_TRUE(warnings.Errors.empty()) << warnings.Errors.front();
  EXPECT_EQ(warnings.Warnings.size(), 2u)
    << "two warnings: the image block, and the block where no triangle has a frame";
  // The image's flat index: the root 0, the first torus 1, the inner dataset 2, its torus 3.
  EXPECT_NE(warnings.WarningText().find(
              "Block 4 is a vtkImageData, not polydata; passing it through without frames."),
    std::string::npos)
    << warnings.WarningText();
  ASSERT_EQ(output->GetNumberOfBlocks(), 5u);
  auto* outInner = vtkMultiBlockDataSet::SafeDownCast(output->GetBlock(1));
  ASSERT_NE(outInner, nullptr);
  ASSERT_EQ(outInner->GetNumberOfBlocks(), 3u);
  EXPECT_EQ(output->GetBlock(2), nullptr);
  auto* outImage = vtkImageData::SafeDownCast(outInner->GetBlock(1));
  ASSERT_NE(outImage, nullptr) << "a non-polydata block passes through";
  EXPECT_EQ(outImage->GetNumberOfPoints(), 8);

  const std::vector<vtkDataObject*> outBlocks = { output->GetBlock(0),
    outInner->GetBlock(0),
    outInner->GetBlock(2),
    output->GetBlock(3),
    output->GetBlock(4) };
  for (size_t b = 0; b < polyBlocks.size(); ++b)
  {
    SCOPED_TRACE("block " + std::to_string(b));
    auto* got = vtkPolyData::SafeDownCast(outBlocks[b]);
    ASSERT_NE(got, nullptr);
    vtkPolyData* expected = alone[b];
    ASSERT_EQ(got->GetNumberOfPoints(), expected->GetNumberOfPoints());
    ASSERT_EQ(got->GetNumberOfCells(), expected->GetNumberOfCells());
    for (const char* name : { "Tangents", "TangentSigns", "Bitangents", "Normals" })
    {
      ExpectSameArray(
        got->GetPointData()->GetArray(name), expected->GetPointData()->GetArray(name), name);
    }
    ExpectSameArray(got->GetPolys()->GetConnectivityArray(),
      expected->GetPolys()->GetConnectivityArray(),
      "polygon connectivity");
  }

  // Polydata input still gives polydata output from the same filter.
  filter->SetInputData(polyBlocks[0]);
  filter->Update();
  ASSERT_NE(filter->GetOutput(), nullptr);
  EXPECT_GT(filter->GetOutput()->GetNumberOfPoints(), polyBlocks[0]->GetNumberOfPoints());
}

TEST(TangentFramesComposite, BlockWithoutTextureCoordinatesPassesWithAWarning)
{
  // A scene's untextured part is no error: the block passes through with a warning naming it,
  // and the textured block still gets its frames.
  auto untextured = Torus(false, 6);
  untextured->GetPointData()->SetTCoords(nullptr);
  vtkNew<vtkMultiBlockDataSet> input;
  input->SetNumberOfBlocks(2);
  input->SetBlock(0, Torus(true, 8));
  input->SetBlock(1, untextured);

  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  Messages warnings(filter);
  int errors = 0;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  filter->AddObserver(vtkCommand::ErrorEvent, onError);
  filter->Update();

  EXPECT_EQ(errors, 0);
  EXPECT_EQ(warnings.Warnings.size(), 1u) << warnings.WarningText();
  EXPECT_NE(warnings.WarningText().find("Block 2 has no point array texture coordinates (no active "
                                        "TCoords); passing it through without frames."),
    std::string::npos)
    << warnings.WarningText();
  auto* output = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr);
  auto* framed = vtkPolyData::SafeDownCast(output->GetBlock(0));
  auto* passed = vtkPolyData::SafeDownCast(output->GetBlock(1));
  ASSERT_NE(framed, nullptr);
  ASSERT_NE(passed, nullptr);
  EXPECT_NE(framed->GetPointData()->GetArray("Tangents"), nullptr);
  EXPECT_EQ(passed->GetPointData()->GetArray("Tangents"), nullptr);
  EXPECT_EQ(passed->GetNumberOfPoints(), untextured->GetNumberOfPoints());
  EXPECT_EQ(passed->GetNumberOfPolys(), untextured->GetNumberOfPolys());

  // Alone, the same polydata cannot get what the filter is for: an error.
  vtkNew<vtkPolyDataTangentFrames> single;
  single->SetInputData(untextured);
  single->AddObserver(vtkCommand::ErrorEvent, onError);
  single->Update();
  EXPECT_EQ(errors, 1);
}

TEST(TangentFramesComposite, OutputHasTheInputsExactType)
{
  // vtkMultiPieceDataSet derives from vtkPartitionedDataSet in VTK 9.1: an output made for one
  // must not be kept for the other.
  vtkNew<vtkPolyDataTangentFrames> filter;
  for (const char* type : { "vtkMultiPieceDataSet",
         "vtkPartitionedDataSet",
         "vtkMultiPieceDataSet",
         "vtkMultiBlockDataSet" })
  {
    vtkSmartPointer<vtkCompositeDataSet> input;
    if (std::strcmp(type, "vtkMultiBlockDataSet") == 0)
    {
      auto blocks = vtkSmartPointer<vtkMultiBlockDataSet>::New();
      blocks->SetBlock(0, Torus(false, 6));
      input = blocks;
    }
    else
    {
      auto pieces = vtkSmartPointer<vtkPartitionedDataSet>::Take(
        std::strcmp(type, "vtkMultiPieceDataSet") == 0 ? vtkMultiPieceDataSet::New()
                                                       : vtkPartitionedDataSet::New());
      pieces->SetPartition(0, Torus(false, 6));
      input = pieces;
    }
    filter->SetInputData(input);
    filter->Update();
    EXPECT_STREQ(filter->GetOutputDataObject(0)->GetClassName(), type);
  }
}

TEST(TangentFramesComposite, ProgressRisesOnceOverAllBlocks)
{
  // Three polydata blocks: each block's execution reports progress within its own share, so the
  // events over the whole input never go back and end at 1.
  vtkNew<vtkMultiBlockDataSet> input;
  input->SetNumberOfBlocks(3);
  for (unsigned int b = 0; b < 3; ++b)
  {
    input->SetBlock(b, Torus(b == 1, 16));
  }
  for (int method = vtkPolyDataTangentFrames::UNWEIGHTED;
       method <= vtkPolyDataTangentFrames::MIKKTSPACE;
       ++method)
  {
    SCOPED_TRACE(vtkPolyDataTangentFrames::GetMethodName(method));
    vtkNew<vtkPolyDataTangentFrames> filter;
    filter->SetMethod(method);
    filter->SetInputData(input);
    NormalMappingTesting::ProgressRecorder recorder(filter);
    filter->Update();
    recorder.ExpectRisesToOne(2);
    // Each block reports several steps, so the first block's all lie in its third.
    EXPECT_LE(recorder.Values[1], 1.0 / 3.0);
  }
}

TEST(TangentFramesComposite, BlocksKeepTheirFieldData)
{
  // Readers keep a block's metadata (material and mesh names) in its field data, which the
  // block's output keeps, as a polydata filtered alone does, split or not.
  vtkNew<vtkMultiBlockDataSet> input;
  input->SetNumberOfBlocks(2);
  for (unsigned int b = 0; b < 2; ++b)
  {
    auto block = Torus(b == 1, 8);
    vtkNew<vtkStringArray> name;
    name->SetName("MaterialName");
    name->InsertNextValue("material " + std::to_string(b));
    block->GetFieldData()->AddArray(name);
    input->SetBlock(b, block);
  }
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  filter->Update();
  auto* output = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr);
  for (unsigned int b = 0; b < 2; ++b)
  {
    auto* block = vtkPolyData::SafeDownCast(output->GetBlock(b));
    ASSERT_NE(block, nullptr);
    auto* name =
      vtkStringArray::SafeDownCast(block->GetFieldData()->GetAbstractArray("MaterialName"));
    ASSERT_NE(name, nullptr) << "block " << b;
    EXPECT_EQ(name->GetValue(0), "material " + std::to_string(b));
  }
  EXPECT_GT(filter->GetNumberOfSplitPoints(), 0);
}

TEST(TangentFramesComposite, AbortLeavesAnEmptyOutput)
{
  // Aborted in the second of three blocks: no block's frames are left, not even the first's,
  // as polydata input leaves an empty output.
  vtkNew<vtkMultiBlockDataSet> input;
  input->SetNumberOfBlocks(3);
  for (unsigned int b = 0; b < 3; ++b)
  {
    input->SetBlock(b, Torus(false, 16));
  }
  vtkNew<vtkPolyDataTangentFrames> filter;
  filter->SetInputData(input);
  NormalMappingTesting::AbortAfter abort(filter, 0.5);
  filter->Update();
  auto* output = vtkMultiBlockDataSet::SafeDownCast(filter->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr);
  EXPECT_EQ(output->GetNumberOfBlocks(), 0u);
}
