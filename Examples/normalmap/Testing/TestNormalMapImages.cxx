// SPDX-License-Identifier: BSD-3-Clause
// Tests of NormalMapImages (PNG and JPEG decoding) and NormalMapGLTF::EmbeddedImage (the
// bounds-checked bytes of an image embedded in a glTF file), on the files that
// make_embedded_data.py writes into Data/embedded and on images made here with VTK's writers.
#include "NormalMapGLTF.h"
#include "NormalMapImages.h"

#include <vtkImageData.h>
#include <vtkJPEGReader.h>
#include <vtkJPEGWriter.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVersionMacros.h>
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
#include <vtkMemoryResourceStream.h>
#endif

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace
{
const std::string EmbeddedDir = std::string(NORMALMAP_TEST_DATA) + "/embedded";

std::vector<unsigned char> ReadBytes(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  return std::vector<unsigned char>(
    (std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// Size, scalar type, components and every sample equal.
void ExpectSameImage(vtkImageData* a, vtkImageData* b, const std::string& what)
{
  ASSERT_NE(a, nullptr) << what;
  ASSERT_NE(b, nullptr) << what;
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  ASSERT_EQ(std::vector<int>(da, da + 3), std::vector<int>(db, db + 3)) << what;
  ASSERT_EQ(a->GetScalarType(), b->GetScalarType()) << what;
  ASSERT_EQ(a->GetNumberOfScalarComponents(), b->GetNumberOfScalarComponents()) << what;
  const size_t bytes =
    static_cast<size_t>(da[0]) * da[1] * a->GetNumberOfScalarComponents() * a->GetScalarSize();
  EXPECT_EQ(0, std::memcmp(a->GetScalarPointer(), b->GetScalarPointer(), bytes)) << what;
}

// A test image with a different value in every sample (and row, so a flip shows).
vtkSmartPointer<vtkImageData> Gradient(int components, int scalarType)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(23, 17, 1);
  image->AllocateScalars(scalarType, components);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const double top = scalarType == VTK_UNSIGNED_SHORT ? 65535.0 : 255.0;
  for (vtkIdType t = 0; t < scalars->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < components; ++c)
    {
      scalars->SetComponent(t, c, static_cast<double>((t * 37 + c * 101) % 256) / 255.0 * top);
    }
  }
  return image;
}

template<typename Writer>
std::vector<unsigned char> Encode(Writer* writer, vtkImageData* image)
{
  writer->SetInputData(image);
  writer->WriteToMemoryOn();
  writer->Write();
  vtkUnsignedCharArray* result = writer->GetResult();
  return std::vector<unsigned char>(
    result->GetPointer(0), result->GetPointer(0) + result->GetNumberOfValues());
}

// CRC-32 as PNG chunks use it (ISO 3309), bit by bit.
uint32_t Crc32(const unsigned char* data, size_t size)
{
  uint32_t crc = 0xffffffffu;
  for (size_t i = 0; i < size; ++i)
  {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit)
    {
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
  }
  return crc ^ 0xffffffffu;
}

void PutBigEndian(unsigned char* at, uint32_t value, int bytes)
{
  for (int k = 0; k < bytes; ++k)
  {
    at[k] = static_cast<unsigned char>(value >> (8 * (bytes - 1 - k)));
  }
}

bool OneLine(const std::string& error)
{
  return !error.empty() && error.find('\n') == std::string::npos;
}

/// Runs a VTK image reader on encoded bytes in memory, through the API this VTK has.
void ReadFromMemory(vtkImageReader2* reader, const std::vector<unsigned char>& bytes)
{
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 6, 0)
  vtkNew<vtkMemoryResourceStream> stream;
  stream->SetBuffer(bytes.data(), bytes.size());
  reader->SetStream(stream);
#else
  reader->SetMemoryBuffer(bytes.data());
  reader->SetMemoryBufferLength(static_cast<vtkIdType>(bytes.size()));
#endif
  reader->Update();
}
}

// For valid files the decoder gives what VTK's readers give (the tool used them before).
TEST(NormalMapImages, DecodesLikeVTKReaders)
{
  for (int components = 1; components <= 4; ++components)
  {
    for (int type : { VTK_UNSIGNED_CHAR, VTK_UNSIGNED_SHORT })
    {
      vtkNew<vtkPNGWriter> writer;
      const std::vector<unsigned char> png =
        Encode(writer.GetPointer(), Gradient(components, type));
      vtkNew<vtkPNGReader> reader; // valid data: VTK's reader is safe here
      ReadFromMemory(reader, png);
      std::string error;
      auto ours = NormalMapImages::Decode(png.data(), png.size(), error);
      ExpectSameImage(ours,
        reader->GetOutput(),
        "PNG, " + std::to_string(components) + " components, type " + std::to_string(type));
    }
  }
  for (int components : { 1, 3 })
  {
    vtkNew<vtkJPEGWriter> writer;
    writer->SetQuality(90);
    const std::vector<unsigned char> jpeg =
      Encode(writer.GetPointer(), Gradient(components, VTK_UNSIGNED_CHAR));
    vtkNew<vtkJPEGReader> reader;
    ReadFromMemory(reader, jpeg);
    std::string error;
    auto ours = NormalMapImages::Decode(jpeg.data(), jpeg.size(), error);
    ExpectSameImage(
      ours, reader->GetOutput(), "JPEG, " + std::to_string(components) + " components");
  }
  // The checked-in maps, against VTK's file readers.
  for (const char* name : { "studs_normal.png", "studs_normal.jpg" })
  {
    const std::string path = EmbeddedDir + "/" + name;
    const std::vector<unsigned char> bytes = ReadBytes(path);
    std::string error;
    auto ours = NormalMapImages::Decode(bytes.data(), bytes.size(), error);
    vtkSmartPointer<vtkImageReader2> reader;
    if (std::string(name).find(".png") != std::string::npos)
    {
      reader = vtkSmartPointer<vtkPNGReader>::New();
    }
    else
    {
      reader = vtkSmartPointer<vtkJPEGReader>::New();
    }
    reader->SetFileName(path.c_str());
    reader->Update();
    ExpectSameImage(ours, reader->GetOutput(), path);
  }
}

// Corrupt input: no image and one line saying why; never a crash (run under ASan in CI).
TEST(NormalMapImages, RejectsCorruptImagesWithOneLine)
{
  const std::vector<unsigned char> png = ReadBytes(EmbeddedDir + "/studs_normal.png");
  const std::vector<unsigned char> jpeg = ReadBytes(EmbeddedDir + "/studs_normal.jpg");
  ASSERT_GT(png.size(), 100u);
  ASSERT_GT(jpeg.size(), 100u);
  struct Case
  {
    std::string Name;
    std::vector<unsigned char> Bytes;
    std::string Expect;
  };
  std::vector<Case> cases;
  cases.push_back({ "empty", {}, "not a PNG or JPEG" });
  cases.push_back({ "text", { 'h', 'e', 'l', 'l', 'o' }, "not a PNG or JPEG" });
  cases.push_back({ "PNG signature only", { png.begin(), png.begin() + 8 }, "corrupt PNG" });
  // Every truncation of the PNG: each cut lands in another chunk (header, data, end).
  for (size_t cut = 9; cut < png.size(); cut += 37)
  {
    cases.push_back(
      { "PNG cut at " + std::to_string(cut), { png.begin(), png.begin() + cut }, "corrupt PNG" });
  }
  for (size_t cut = 4; cut < jpeg.size(); cut += 97)
  {
    cases.push_back({ "JPEG cut at " + std::to_string(cut),
      { jpeg.begin(), jpeg.begin() + cut },
      "corrupt JPEG" });
  }
  // A flipped byte inside the PNG's compressed data: its chunk CRC no longer matches.
  std::vector<unsigned char> flipped = png;
  flipped[png.size() / 2] ^= 0x5a;
  cases.push_back({ "PNG with a flipped byte", flipped, "corrupt PNG" });
  // Headers claiming 100000 x 100000 pixels (valid otherwise: the IHDR chunk's CRC is
  // recomputed): refused before any allocation.
  std::vector<unsigned char> huge = png;
  ASSERT_EQ(0, std::memcmp(huge.data() + 12, "IHDR", 4));
  PutBigEndian(huge.data() + 16, 100000, 4);
  PutBigEndian(huge.data() + 20, 100000, 4);
  PutBigEndian(huge.data() + 29, Crc32(huge.data() + 12, 17), 4);
  cases.push_back({ "PNG of 100000 x 100000", huge, "exceeds user limit" });
  std::vector<unsigned char> hugeJpeg = jpeg;
  // The frame header: SOF0, SOF1 or SOF2 (VTK's writer makes progressive JPEGs, SOF2).
  size_t sof = 2;
  while (sof + 9 < hugeJpeg.size() &&
    !(hugeJpeg[sof] == 0xff && hugeJpeg[sof + 1] >= 0xc0 && hugeJpeg[sof + 1] <= 0xc2))
  {
    sof += 2 + (size_t(hugeJpeg[sof + 2]) << 8 | hugeJpeg[sof + 3]); // next marker segment
  }
  ASSERT_LT(sof + 9, hugeJpeg.size()) << "no frame header in studs_normal.jpg";
  PutBigEndian(hugeJpeg.data() + sof + 5, 60000, 2); // height
  PutBigEndian(hugeJpeg.data() + sof + 7, 60000, 2); // width
  cases.push_back({ "JPEG of 60000 x 60000", hugeJpeg, "larger than 8192" });
  for (const Case& c : cases)
  {
    std::string error;
    auto image = NormalMapImages::Decode(c.Bytes.data(), c.Bytes.size(), error);
    EXPECT_EQ(image, nullptr) << c.Name;
    EXPECT_TRUE(OneLine(error)) << c.Name << ": " << error;
    EXPECT_NE(error.find(c.Expect), std::string::npos) << c.Name << ": " << error;
  }
}

// The bytes of an embedded image are exactly the image file's, from a buffer view (GLB) and from
// a data: URI; a buffer view running past its buffer is refused.
TEST(NormalMapGLTF, EmbeddedImageBytesAreCheckedAndExact)
{
  struct Expected
  {
    const char* File;
    const char* Image;
  };
  for (const Expected& e : { Expected{ "quad_png.glb", "studs_normal.png" },
         Expected{ "quad_jpeg.gltf", "studs_normal.jpg" } })
  {
    NormalMapGLTF::Document doc;
    std::string error;
    ASSERT_TRUE(NormalMapGLTF::ReadDocument(EmbeddedDir + "/" + e.File, doc, error)) << error;
    std::vector<unsigned char> bytes;
    std::string mimeType;
    ASSERT_TRUE(NormalMapGLTF::EmbeddedImage(doc, 0, bytes, mimeType, error)) << error;
    EXPECT_EQ(bytes, ReadBytes(EmbeddedDir + "/" + e.Image)) << e.File;
    EXPECT_FALSE(NormalMapGLTF::EmbeddedImage(doc, 1, bytes, mimeType, error));
    EXPECT_TRUE(OneLine(error)) << error;
    EXPECT_FALSE(NormalMapGLTF::EmbeddedImage(doc, -1, bytes, mimeType, error));
  }

  NormalMapGLTF::Document doc;
  std::string error;
  ASSERT_TRUE(NormalMapGLTF::ReadDocument(EmbeddedDir + "/quad_outside.glb", doc, error)) << error;
  std::vector<unsigned char> bytes;
  std::string mimeType;
  EXPECT_FALSE(NormalMapGLTF::EmbeddedImage(doc, 0, bytes, mimeType, error));
  EXPECT_TRUE(OneLine(error)) << error;
  EXPECT_NE(error.find("outside buffer"), std::string::npos) << error;
  EXPECT_TRUE(bytes.empty());

  // An image that is a file beside the glTF is not embedded.
  ASSERT_TRUE(
    NormalMapGLTF::ReadDocument(std::string(NORMALMAP_TEST_DATA) + "/quad.gltf", doc, error))
    << error;
  EXPECT_FALSE(NormalMapGLTF::EmbeddedImage(doc, 0, bytes, mimeType, error));
  EXPECT_NE(error.find("not embedded"), std::string::npos) << error;
}
