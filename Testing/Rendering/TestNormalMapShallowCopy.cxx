// SPDX-License-Identifier: BSD-3-Clause
// ShallowCopy gives a mapper the normal-mapping settings of another of its class, as VTK's
// mappers copy theirs, for the single and the composite mapper: every setting set away from its
// default on the source must arrive on the copy, and the superclass's settings with them.
#include "vtkNew.h"
#include "vtkNormalMapCompositePolyDataMapper.h"
#include "vtkNormalMapPolyDataMapper.h"

#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
template<class Mapper>
bool CopiesSettings(const char* name)
{
  vtkNew<Mapper> source;
  source->SetMapEncoding(vtkNormalMapPolyDataMapper::TWO_CHANNEL_DIRECTX);
  source->SetFrameSource(vtkNormalMapPolyDataMapper::POINT_TANGENTS);
  source->SetTangentsArrayName("MyTangents");
  source->SetTangentSignsArrayName("MySigns");
  source->SetScalarVisibility(false); // a vtkMapper setting, copied by the superclass
  vtkNew<Mapper> copy;
  copy->ShallowCopy(source);
  const bool ok = copy->GetMapEncoding() == vtkNormalMapPolyDataMapper::TWO_CHANNEL_DIRECTX &&
    copy->GetFrameSource() == vtkNormalMapPolyDataMapper::POINT_TANGENTS &&
    copy->GetTangentsArrayName() == "MyTangents" && copy->GetTangentSignsArrayName() == "MySigns" &&
    !copy->GetScalarVisibility();
  if (!ok)
  {
    std::cerr << name << ": ShallowCopy lost a setting: encoding " << copy->GetMapEncoding()
              << ", frame source " << copy->GetFrameSource() << ", tangents '"
              << copy->GetTangentsArrayName() << "', signs '" << copy->GetTangentSignsArrayName()
              << "', scalar visibility " << copy->GetScalarVisibility() << "\n";
  }
  return ok;
}
}

int TestNormalMapShallowCopy(int, char*[])
{
  const bool single = CopiesSettings<vtkNormalMapPolyDataMapper>("vtkNormalMapPolyDataMapper");
  const bool composite =
    CopiesSettings<vtkNormalMapCompositePolyDataMapper>("vtkNormalMapCompositePolyDataMapper");
  return single && composite ? EXIT_SUCCESS : EXIT_FAILURE;
}
