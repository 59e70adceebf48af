// SPDX-License-Identifier: BSD-3-Clause
// The errors and warnings a filter emits, collected instead of printed, for tests that check
// them.
#ifndef NormalMappingMessages_h
#define NormalMappingMessages_h

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <algorithm>
#include <string>
#include <vector>

/// Collects the messages an object emits from its construction on.
struct Messages
{
  std::vector<std::string> Errors, Warnings;
  vtkNew<vtkCallbackCommand> Callback;

  explicit Messages(vtkObject* object)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject*, unsigned long event, void* self, void* data)
      {
        auto* m = static_cast<Messages*>(self);
        (event == vtkCommand::ErrorEvent ? m->Errors : m->Warnings)
          .emplace_back(static_cast<const char*>(data));
      });
    object->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    object->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }

  /// Whether one of the messages in `list` contains `text`.
  static bool Has(const std::vector<std::string>& list, const std::string& text)
  {
    return std::any_of(list.begin(),
      list.end(),
      [&](const std::string& m) { return m.find(text) != std::string::npos; });
  }

  /// The warnings, one after the other (for test failure messages).
  std::string WarningText() const
  {
    std::string text;
    for (const std::string& w : this->Warnings)
    {
      text += w;
    }
    return text;
  }
};

#endif
