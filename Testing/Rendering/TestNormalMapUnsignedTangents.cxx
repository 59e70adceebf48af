// SPDX-License-Identifier: BSD-3-Clause
// Image test: a sphere with rivets and three-component tangents without signs (as VTK's
// vtkPolyDataTangents writes them), whose handedness comes from the texture coordinates: +1 on
// this unmirrored surface, where every dome is lit from the upper left. It fails when the sign
// is taken as -1 (the bitangent flipped) or the map is dropped.
#include "NormalMapImageTest.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"

int TestNormalMapUnsignedTangents(int argc, char* argv[])
{
  using Layout = nmtest::TangentLayout;
  auto map = nmtest::MakeNormalTexture(
    nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL));
  auto withSigns = nmtest::WithTangents(nmtest::MakeSphere(48));
  auto unsignedSphere = nmtest::WithTangentLayout(withSigns, Layout::Unsigned);
  auto flipped = nmtest::WithTangentLayout(withSigns, Layout::ActiveWithSigns);
  vtkDataArray* signs = flipped->GetPointData()->GetArray("TangentSigns");
  for (vtkIdType i = 0; i < signs->GetNumberOfTuples(); ++i)
  {
    signs->SetTuple1(i, -1.0);
  }
  return nmtest::RunImageTest(argc,
    argv,
    { "the sign taken as -1", "the map dropped" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(200, 200);
      nmtest::Panel p;
      p.Mesh = alteration == 0 ? flipped.Get() : unsignedSphere.Get();
      p.Texture = alteration == 1 ? nullptr : map.Get();
      p.RotateX = -60.0;
      nmtest::AddPanel(window, 1, 1, 0, 0, p);
      return window;
    });
}
