// SPDX-License-Identifier: BSD-3-Clause
// Records the progress an algorithm reports, for tests.
#ifndef NormalMappingProgress_h
#define NormalMappingProgress_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace NormalMappingTesting
{
/// Every progress value `object` reports from now on, in order.
struct ProgressRecorder
{
  std::vector<double> Values;
  vtkNew<vtkCallbackCommand> Callback;

  explicit ProgressRecorder(vtkObject* object)
  {
    this->Callback->SetClientData(&this->Values);
    this->Callback->SetCallback([](vtkObject*, unsigned long, void* values, void* amount)
      { static_cast<std::vector<double>*>(values)->push_back(*static_cast<double*>(amount)); });
    object->AddObserver(vtkCommand::ProgressEvent, this->Callback);
  }

  /// Expects at least `minimum` values, in [0, 1], never decreasing, the last 1.
  void ExpectRisesToOne(size_t minimum = 1) const
  {
    ASSERT_GE(this->Values.size(), minimum);
    EXPECT_TRUE(std::is_sorted(this->Values.begin(), this->Values.end()));
    EXPECT_GE(this->Values.front(), 0.0);
    EXPECT_EQ(this->Values.back(), 1.0);
  }
};

/// Sets AbortExecute on `algorithm` once the progress it reports passes `threshold`.
struct AbortAfter
{
  double Threshold;
  vtkNew<vtkCallbackCommand> Callback;

  AbortAfter(vtkAlgorithm* algorithm, double threshold)
    : Threshold(threshold)
  {
    this->Callback->SetClientData(&this->Threshold);
    this->Callback->SetCallback(
      [](vtkObject* caller, unsigned long, void* limit, void* amount)
      {
        if (*static_cast<double*>(amount) > *static_cast<double*>(limit))
        {
          static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
        }
      });
    algorithm->AddObserver(vtkCommand::ProgressEvent, this->Callback);
  }
};
}

#endif
