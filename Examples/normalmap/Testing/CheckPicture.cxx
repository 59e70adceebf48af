// SPDX-License-Identifier: BSD-3-Clause
// Checks pictures written by normalmap render / demo.
//
//   NormalMapCheckPicture PNG WIDTH HEIGHT MIN_SHARE
//     it reads back as PNG with the expected size, and more than MIN_SHARE of its pixels differ
//     from the background colour;
//   NormalMapCheckPicture --same A.png B.png MAX_LEVELS
//     same size, and no channel of any pixel differs by more than MAX_LEVELS;
//   NormalMapCheckPicture --differ A.png B.png LEVELS MIN_SHARE
//     same size, and more than MIN_SHARE of the pixels differ by more than LEVELS in a channel.
#include "NormalMapRender.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
// An 8-bit RGB(A) picture, or nullptr (with a message) when `path` is not one.
vtkSmartPointer<vtkImageData> ReadPicture(const std::string& path)
{
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    std::cerr << "FAIL: " << path << " is not a readable PNG file\n";
    return nullptr;
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (image->GetNumberOfScalarComponents() < 3 || image->GetScalarType() != VTK_UNSIGNED_CHAR)
  {
    std::cerr << "FAIL: " << path << " is not an 8-bit RGB picture\n";
    return nullptr;
  }
  return image;
}

// --same / --differ: compares two pictures of the normalmap tool pixel by pixel.
int Compare(const std::string& mode, int argc, char* argv[])
{
  if ((mode == "--same" && argc != 5) || (mode == "--differ" && argc != 6))
  {
    std::cerr << "usage: NormalMapCheckPicture --same A B MAX_LEVELS | --differ A B LEVELS "
                 "MIN_SHARE\n";
    return EXIT_FAILURE;
  }
  vtkSmartPointer<vtkImageData> a = ReadPicture(argv[2]);
  vtkSmartPointer<vtkImageData> b = ReadPicture(argv[3]);
  if (!a || !b)
  {
    return EXIT_FAILURE;
  }
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    std::cerr << "FAIL: the pictures are " << da[0] << "x" << da[1] << " and " << db[0] << "x"
              << db[1] << "\n";
    return EXIT_FAILURE;
  }
  const int levels = std::atoi(argv[4]);
  const int ca = a->GetNumberOfScalarComponents(), cb = b->GetNumberOfScalarComponents();
  const auto* pa = static_cast<const unsigned char*>(a->GetScalarPointer());
  const auto* pb = static_cast<const unsigned char*>(b->GetScalarPointer());
  const long count = static_cast<long>(da[0]) * da[1];
  long differing = 0;
  int largest = 0;
  for (long p = 0; p < count; ++p)
  {
    int pixel = 0;
    for (int c = 0; c < 3; ++c)
    {
      pixel = std::max(pixel, std::abs(int(pa[p * ca + c]) - int(pb[p * cb + c])));
    }
    largest = std::max(largest, pixel);
    differing += pixel > levels ? 1 : 0;
  }
  const double share = static_cast<double>(differing) / count;
  std::cout << argv[2] << " vs " << argv[3] << ": largest difference " << largest << " levels; "
            << 100.0 * share << "% of the pixels differ by more than " << levels << "\n";
  if (mode == "--same" && differing > 0)
  {
    std::cerr << "FAIL: the pictures differ by more than " << levels << " levels\n";
    return EXIT_FAILURE;
  }
  if (mode == "--differ" && share <= std::atof(argv[5]))
  {
    std::cerr << "FAIL: the pictures differ in " << 100.0 * share << "% of the pixels, need > "
              << 100.0 * std::atof(argv[5]) << "%\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
}

int main(int argc, char* argv[])
{
  if (argc >= 2 && (std::string(argv[1]) == "--same" || std::string(argv[1]) == "--differ"))
  {
    return Compare(argv[1], argc, argv);
  }
  if (argc != 5)
  {
    std::cerr << "usage: NormalMapCheckPicture PNG WIDTH HEIGHT MIN_SHARE\n";
    return EXIT_FAILURE;
  }
  const std::string path = argv[1];
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]);
  const double minShare = std::atof(argv[4]);
  vtkSmartPointer<vtkImageData> image = ReadPicture(path);
  if (!image)
  {
    return EXIT_FAILURE;
  }
  int dims[3];
  image->GetDimensions(dims);
  const int components = image->GetNumberOfScalarComponents();
  if (dims[0] != width || dims[1] != height)
  {
    std::cerr << "FAIL: " << path << " is " << dims[0] << "x" << dims[1] << "; expected " << width
              << "x" << height << "\n";
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
