// SPDX-License-Identifier: BSD-3-Clause
#include "NormalMapImages.h"

#include <vtkImageData.h>
#include <vtkType.h>

#include <csetjmp>
#include <cstdio> // before jpeglib.h, which needs FILE
#include <cstring>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <png.h>

namespace NormalMapImages
{
namespace
{
// Everything a decode touches lives in one of these, owned by the caller of the function that
// sets the error jump: that function changes none of its own locals after setjmp, so a jump back
// into it leaves nothing indeterminate, and no C++ object's lifetime is skipped by the jump.
struct Decoded
{
  std::string Message; // the library's error text
  std::string Warning; // its first warning (libpng: often the reason for the error that follows)
  unsigned int Width = 0;
  unsigned int Height = 0;
  int Components = 0;
  bool SixteenBit = false;
  std::vector<unsigned char> Pixels; // top row first, as the libraries give them
  std::vector<unsigned char*> Rows;  // libpng's row pointers into Pixels
};

vtkSmartPointer<vtkImageData> ToImage(Decoded& decoded)
{
  const size_t sampleSize = decoded.SixteenBit ? 2 : 1;
  const size_t rowBytes = sampleSize * decoded.Components * decoded.Width;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(decoded.Width), static_cast<int>(decoded.Height), 1);
  image->AllocateScalars(
    decoded.SixteenBit ? VTK_UNSIGNED_SHORT : VTK_UNSIGNED_CHAR, decoded.Components);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  for (unsigned int y = 0; y < decoded.Height; ++y)
  {
    // VTK images start at the bottom row (v = 0).
    std::memcpy(
      out + rowBytes * (decoded.Height - 1 - y), decoded.Pixels.data() + rowBytes * y, rowBytes);
  }
  return image;
}

//------------------------------------------------------------------------------ PNG
struct PngSource
{
  const unsigned char* Data;
  size_t Size;
  size_t Position;
  Decoded* Out;
};

void PngRead(png_structp png, png_bytep out, png_size_t length)
{
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > source->Size - source->Position)
  {
    png_error(png, "the image data ends early");
  }
  std::memcpy(out, source->Data + source->Position, length);
  source->Position += length;
}

void PngError(png_structp png, png_const_charp message)
{
  static_cast<PngSource*>(png_get_error_ptr(png))->Out->Message = message;
  png_longjmp(png, 1);
}

void PngWarning(png_structp png, png_const_charp message)
{
  // Warnings alone (a known-bad ICC profile, an ancillary chunk with a bad CRC, which libpng
  // skips) leave the pixels intact; the first is kept to explain an error that follows it.
  Decoded* out = static_cast<PngSource*>(png_get_error_ptr(png))->Out;
  if (out->Warning.empty())
  {
    out->Warning = message;
  }
}

// Runs libpng; false when it reported an error (source.Out->Message says which).
bool RunPng(png_structp png, png_infop info, PngSource* source)
{
  if (setjmp(png_jmpbuf(png)))
  {
    return false;
  }
  Decoded* out = source->Out;
  png_set_read_fn(png, source, &PngRead);
  png_set_user_limits(png, MaxSide, MaxSide);
  png_read_info(png, info);
  const int colorType = png_get_color_type(png, info);
  const int bitDepth = png_get_bit_depth(png, info);
  if (colorType == PNG_COLOR_TYPE_PALETTE)
  {
    png_set_palette_to_rgb(png);
  }
  if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8)
  {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  if (png_get_valid(png, info, PNG_INFO_tRNS))
  {
    png_set_tRNS_to_alpha(png);
  }
  if (bitDepth > 8)
  {
    png_set_swap(png); // PNG stores 16-bit samples big-endian; VTK wants the host's order
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  out->Width = png_get_image_width(png, info);
  out->Height = png_get_image_height(png, info);
  out->Components = png_get_channels(png, info);
  out->SixteenBit = png_get_bit_depth(png, info) > 8;
  const size_t rowBytes = png_get_rowbytes(png, info);
  out->Pixels.resize(rowBytes * out->Height);
  out->Rows.resize(out->Height);
  for (unsigned int y = 0; y < out->Height; ++y)
  {
    out->Rows[y] = out->Pixels.data() + rowBytes * y;
  }
  png_read_image(png, out->Rows.data());
  png_read_end(png, nullptr);
  return true;
}

vtkSmartPointer<vtkImageData> DecodePNG(const unsigned char* data, size_t size, std::string& error)
{
  Decoded decoded;
  PngSource source{ data, size, 0, &decoded };
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, &PngError, &PngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info)
  {
    png_destroy_read_struct(&png, nullptr, nullptr);
    error = "out of memory for the PNG decoder";
    return nullptr;
  }
  const bool ok = RunPng(png, info, &source);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok)
  {
    error = "corrupt PNG: " + decoded.Message +
      (decoded.Warning.empty() ? std::string() : " (" + decoded.Warning + ")");
    return nullptr;
  }
  return ToImage(decoded);
}

//------------------------------------------------------------------------------ JPEG
struct JpegErrors
{
  jpeg_error_mgr Manager; // first: libjpeg's err pointer is cast back to this struct
  jmp_buf Jump;
  Decoded* Out;
};

void JpegErrorExit(j_common_ptr cinfo)
{
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  char text[JMSG_LENGTH_MAX];
  (*cinfo->err->format_message)(cinfo, text);
  errors->Out->Message = text;
  std::longjmp(errors->Jump, 1);
}

void JpegOutputMessage(j_common_ptr cinfo)
{
  // Warnings ("premature end of data", "corrupt data: bad Huffman code") mean the decoder
  // filled in pixels it could not read; keep the first for the error, print nothing.
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  if (errors->Out->Message.empty())
  {
    char text[JMSG_LENGTH_MAX];
    (*cinfo->err->format_message)(cinfo, text);
    errors->Out->Message = text;
  }
}

// Runs libjpeg; false when it reported an error or a warning (errors->Out->Message says which).
bool RunJpeg(jpeg_decompress_struct* cinfo,
  JpegErrors* errors,
  const unsigned char* data,
  unsigned long size)
{
  if (setjmp(errors->Jump))
  {
    return false;
  }
  Decoded* out = errors->Out;
  jpeg_create_decompress(cinfo);
  // libjpeg-turbo's own memory source: reads stay inside [data, data + size).
  jpeg_mem_src(cinfo, data, size);
  jpeg_read_header(cinfo, TRUE);
  if (cinfo->image_width > MaxSide || cinfo->image_height > MaxSide)
  {
    out->Message = "larger than " + std::to_string(MaxSide) + " pixels a side";
    return false;
  }
  jpeg_start_decompress(cinfo);
  out->Width = cinfo->output_width;
  out->Height = cinfo->output_height;
  out->Components = cinfo->output_components;
  const size_t rowBytes = static_cast<size_t>(out->Components) * out->Width;
  out->Pixels.resize(rowBytes * out->Height);
  while (cinfo->output_scanline < cinfo->output_height)
  {
    JSAMPROW row = out->Pixels.data() + rowBytes * cinfo->output_scanline;
    jpeg_read_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_decompress(cinfo);
  return errors->Manager.num_warnings == 0;
}

vtkSmartPointer<vtkImageData> DecodeJPEG(const unsigned char* data, size_t size, std::string& error)
{
  Decoded decoded;
  JpegErrors errors;
  // Zeroed, so that destroying it is safe even if creating it failed.
  jpeg_decompress_struct cinfo{};
  cinfo.err = jpeg_std_error(&errors.Manager);
  errors.Manager.error_exit = &JpegErrorExit;
  errors.Manager.output_message = &JpegOutputMessage;
  errors.Out = &decoded;
  // unsigned long holds any size_t on the LP64 and ILP32 platforms this builds for.
  const bool ok = RunJpeg(&cinfo, &errors, data, static_cast<unsigned long>(size));
  jpeg_destroy_decompress(&cinfo);
  if (!ok)
  {
    error =
      "corrupt JPEG: " + (decoded.Message.empty() ? std::string("too large") : decoded.Message);
    return nullptr;
  }
  return ToImage(decoded);
}
} // namespace

std::string Format(const unsigned char* data, size_t size)
{
  static const unsigned char png[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
  if (size >= sizeof(png) && std::memcmp(data, png, sizeof(png)) == 0)
  {
    return "PNG";
  }
  if (size >= 3 && data[0] == 0xff && data[1] == 0xd8 && data[2] == 0xff)
  {
    return "JPEG";
  }
  return std::string();
}

vtkSmartPointer<vtkImageData> Decode(const unsigned char* data, size_t size, std::string& error)
{
  const std::string format = Format(data, size);
  if (format == "PNG")
  {
    return DecodePNG(data, size, error);
  }
  if (format == "JPEG")
  {
    return DecodeJPEG(data, size, error);
  }
  error = "not a PNG or JPEG image";
  return nullptr;
}
}
