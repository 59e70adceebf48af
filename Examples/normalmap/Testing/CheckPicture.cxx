// SPDX-License-Identifier: BSD-3-Clause
// Checks a picture written by normalmap render / demo: it reads back as PNG with the expected
// size, and more than a given share of its pixels differ from the background colour.
//
//   NormalMapCheckPicture PNG WIDTH HEIGHT MIN_SHARE
#include "NormalMapRender.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  if (argc != 5)
  {
    std::cerr << "usage: NormalMapCheckPicture PNG WIDTH HEIGHT MIN_SHARE\n";
    return EXIT_FAILURE;
  }
  const std::string path = argv[1];
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]);
  const double minShare = std::atof(argv[4]);
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    std::cerr << "FAIL: " << path << " is not a readable PNG file\n";
    return EXIT_FAILURE;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  const int components = image->GetNumberOfScalarComponents();
  if (dims[0] != width || dims[1] != height || components < 3 ||
    image->GetScalarType() != VTK_UNSIGNED_CHAR)
  {
    std::cerr << "FAIL: " << path << " is " << dims[0] << "x" << dims[1] << " with " << components
              << " components; expected " << width << "x" << height << " RGB\n";
    return EXIT_FAILURE;
  }
  // A pixel counts as background within 3 levels per channel of the background colour (8-bit
  // rounding of 0.1 and 0.12, and multisample resolve, stay within 1).
  int background[3];
  for (int c = 0; c < 3; ++c)
  {
    background[c] = static_cast<int>(NormalMapRender::Background[c] * 255.0 + 0.5);
  }
  const auto* pixels = static_cast<const unsigned char*>(image->GetScalarPointer());
  const long count = static_cast<long>(width) * height;
  long differing = 0;
  for (long p = 0; p < count; ++p)
  {
    const unsigned char* rgb = pixels + p * components;
    bool same = true;
    for (int c = 0; c < 3; ++c)
    {
      same = same && std::abs(int(rgb[c]) - background[c]) <= 3;
    }
    differing += same ? 0 : 1;
  }
  const double share = static_cast<double>(differing) / count;
  std::cout << path << ": " << width << "x" << height << ", " << 100.0 * share
            << "% of the pixels differ from the background (need > " << 100.0 * minShare << "%)\n";
  if (share <= minShare)
  {
    std::cerr << "FAIL: the picture is (nearly) all background\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
