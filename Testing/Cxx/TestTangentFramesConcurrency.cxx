// SPDX-License-Identifier: BSD-3-Clause
// vtkPolyDataTangentFrames run from several std::threads at once, each on its own input, while
// each filter also runs its own vtkSMPTools loops: every output must be bit-identical to the
// output of the same filter run alone. (Thread counts of one filter: the BitIdentical* tests.)
#include "NormalMappingThreads.h"
#include "vtkNormalMappingMeshes.h"
#include "vtkNormalMappingPrivate.h"
#include "vtkPolyDataTangentFrames.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace
{
const int EveryMethod[] = { vtkPolyDataTangentFrames::UNWEIGHTED,
  vtkPolyDataTangentFrames::AREA_WEIGHTED,
  vtkPolyDataTangentFrames::ANGLE_WEIGHTED,
  vtkPolyDataTangentFrames::MIKKTSPACE };

/// The raw bytes of an array's values (empty for a missing array), so that comparisons are
/// bitwise: -0 differs from +0 and NaN equals itself.
std::vector<unsigned char> Bytes(vtkDataArray* array)
{
  if (!array)
  {
    return {};
  }
  const auto* begin = static_cast<const unsigned char*>(array->GetVoidPointer(0));
  return std::vector<unsigned char>(
    begin, begin + array->GetNumberOfValues() * array->GetDataTypeSize());
}

/// Everything the filter writes, for every method with and without splitting, as bytes.
std::vector<std::vector<unsigned char>> AllOutputs(vtkPolyData* input)
{
  std::vector<std::vector<unsigned char>> outputs;
  for (int method : EveryMethod)
  {
    for (bool splitting : { true, false })
    {
      vtkNew<vtkPolyDataTangentFrames> filter;
      filter->SetInputData(input);
      filter->SetMethod(method);
      filter->SetSplitting(splitting);
      filter->ComputeBitangentsOn();
      filter->ComputeCellTangentsOn();
      filter->Update();
      vtkPolyData* out = filter->GetOutput();
      vtkPointData* pd = out->GetPointData();
      for (vtkDataArray* array : { out->GetPoints()->GetData(),
             pd->GetTangents(),
             pd->GetArray("TangentSigns"),
             pd->GetArray("Bitangents"),
             out->GetCellData()->GetTangents(),
             out->GetPolys()->GetConnectivityArray() })
      {
        outputs.push_back(Bytes(array));
      }
    }
  }
  return outputs;
}
}

TEST(TangentFramesConcurrency, SeparateInputsOnSeveralThreadsAtOnce)
{
  // Four different meshes (mirror seams, float and double, sizes that give one or several
  // blocks of the ordered scatter and runs of different lengths, see ScanBlocks::Choose).
  std::vector<vtkSmartPointer<vtkPolyData>> inputs;
  for (int i = 0; i < 4; ++i)
  {
    vtkNormalMapping::TorusOptions options;
    options.U = 64 + 48 * i;
    options.V = 24 + 16 * i;
    options.MirrorU = i != 1;
    options.DoublePrecision = i % 2 == 1;
    inputs.push_back(vtkNormalMapping::MakeTorus(options));
  }
  // References: one filter at a time, with as many vtkSMPTools threads as there are.
  std::vector<std::vector<std::vector<unsigned char>>> expected;
  for (auto& input : inputs)
  {
    expected.push_back(AllOutputs(input));
  }
  // The same with one vtkSMPTools thread (a different schedule and block split).
  NormalMappingTesting::WithThreads(1,
    [&]()
    {
      for (size_t i = 0; i < inputs.size(); ++i)
      {
        EXPECT_TRUE(AllOutputs(inputs[i]) == expected[i]) << "mesh " << i << ", one thread";
      }
    });
  // All four at once, twice over (each thread a different mesh each round).
  for (int round = 0; round < 2; ++round)
  {
    std::vector<std::vector<std::vector<unsigned char>>> results(inputs.size());
    std::vector<std::thread> threads;
    for (size_t t = 0; t < inputs.size(); ++t)
    {
      const size_t mesh = (t + round) % inputs.size();
      threads.emplace_back([&, t, mesh]() { results[t] = AllOutputs(inputs[mesh]); });
    }
    for (std::thread& thread : threads)
    {
      thread.join();
    }
    for (size_t t = 0; t < inputs.size(); ++t)
    {
      const size_t mesh = (t + round) % inputs.size();
      ASSERT_EQ(results[t].size(), expected[mesh].size());
      for (size_t k = 0; k < results[t].size(); ++k)
      {
        EXPECT_FALSE(results[t][k].empty() && k % 6 < 3) << "mesh " << mesh << " output " << k;
        EXPECT_TRUE(results[t][k] == expected[mesh][k])
          << "round " << round << ", mesh " << mesh << ", output " << k;
      }
    }
  }
}

TEST(TangentFramesConcurrency, InsideAParallelLoopWithAndWithoutNestedParallelism)
{
  // Filters updated inside a vtkSMPTools::For, one mesh per iteration. With nested parallelism
  // (VTK 9.1's default) their own loops run in parallel too; without it VTK runs them serially
  // and the filters split their work for one thread (UsableThreads). Either way every output
  // must be bit-identical to the filter run alone. Meshes large enough that two threads split
  // the scan into several blocks (8 blocks in runs of 2^11 ids for 36,300 points).
  std::vector<vtkSmartPointer<vtkPolyData>> inputs;
  for (int i = 0; i < 2; ++i)
  {
    vtkNormalMapping::TorusOptions options;
    options.U = 300;
    options.V = 120;
    options.MirrorU = true;
    options.DoublePrecision = i == 1;
    inputs.push_back(vtkNormalMapping::MakeTorus(options));
  }
  ASSERT_EQ(inputs[0]->GetNumberOfPoints(), 36300);
  std::vector<std::vector<std::vector<unsigned char>>> expected;
  for (auto& input : inputs)
  {
    expected.push_back(AllOutputs(input));
  }
  const bool nestedBefore = vtkSMPTools::GetNestedParallelism();
  NormalMappingTesting::WithThreads(2,
    [&]()
    {
      EXPECT_EQ(vtkNormalMapping::detail::UsableThreads(), 2) << "outside any parallel loop";
      for (bool nested : { true, false })
      {
        vtkSMPTools::SetNestedParallelism(nested);
        std::vector<std::vector<std::vector<unsigned char>>> results(inputs.size());
        std::vector<int> usable(inputs.size(), 0);
        vtkSMPTools::For(0,
          static_cast<vtkIdType>(inputs.size()),
          1,
          [&](vtkIdType begin, vtkIdType end)
          {
            for (vtkIdType i = begin; i < end; ++i)
            {
              usable[i] = vtkNormalMapping::detail::UsableThreads();
              results[i] = AllOutputs(inputs[i]);
            }
          });
        for (size_t i = 0; i < inputs.size(); ++i)
        {
          SCOPED_TRACE(
            std::string("nested ") + (nested ? "on" : "off") + ", mesh " + std::to_string(i));
          EXPECT_EQ(usable[i], nested ? 2 : 1);
          EXPECT_TRUE(results[i] == expected[i]);
        }
      }
    });
  vtkSMPTools::SetNestedParallelism(nestedBefore);
}
