// SPDX-License-Identifier: BSD-3-Clause
// Image test: a rivets-mapped quad from the front and from the back (turned 180 degrees about
// y) with two-sided lighting: the back sees the mirror of the front's perturbed normal (a dome
// seen from behind is a dimple), so it is lit and shows the relief. It fails when the back's
// relief is inverted (the map's tangent-plane components not mirrored) or the back is drawn
// without the map.
#include "NormalMapImageTest.h"

#include "vtkImageData.h"

int TestNormalMapBackFaces(int argc, char* argv[])
{
  auto image = nmtest::MakeNormalMapImage(nmtest::Pattern::Rivets, 256, nmtest::Storage::OpenGL);
  auto map = nmtest::MakeNormalTexture(image);
  // The same map with its x and y inverted: the relief of the negated height field.
  auto invertedImage = vtkSmartPointer<vtkImageData>::New();
  invertedImage->DeepCopy(image);
  auto* texels = static_cast<unsigned char*>(invertedImage->GetScalarPointer());
  for (vtkIdType i = 0; i < invertedImage->GetNumberOfPoints(); ++i)
  {
    texels[3 * i] = 255 - texels[3 * i];
    texels[3 * i + 1] = 255 - texels[3 * i + 1];
  }
  auto inverted = nmtest::MakeNormalTexture(invertedImage);
  auto quad = nmtest::WithTangents(nmtest::MakeQuad(4));
  return nmtest::RunImageTest(argc,
    argv,
    { "the back's relief inverted", "the back without the map" },
    [&](int alteration)
    {
      auto window = nmtest::MakeWindow(400, 200);
      nmtest::Panel p;
      p.Mesh = quad;
      p.Texture = map;
      p.RotateX = -30.0;
      p.Zoom = 1.2;
      nmtest::AddPanel(window, 2, 1, 0, 0, p);
      p.RotateY = 180.0;
      p.Texture = alteration == 0 ? inverted.Get() : (alteration == 1 ? nullptr : map.Get());
      nmtest::AddPanel(window, 2, 1, 1, 0, p);
      return window;
    });
}
