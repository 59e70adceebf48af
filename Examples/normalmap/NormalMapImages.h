// SPDX-License-Identifier: BSD-3-Clause
// PNG and JPEG decoding for the normalmap tool, from memory (images embedded in glTF files) and
// from files (--normal-map), safe on corrupt and hostile input.
//
// Not VTK 9.1's readers: vtkPNGReader arms libpng's error jump (setjmp) in a helper that has
// returned before libpng reports an error, so a corrupt or truncated PNG makes libpng jump into
// a dead stack frame (a crash); vtkJPEGReader's memory source skips bytes past the end of its
// buffer when a segment's length says so. Here libpng and libjpeg report errors into the
// function that set the jump, the input is read only within its bounds, and the image size is
// limited before anything is allocated.
//
// The output matches vtkPNGReader's and vtkJPEGReader's for valid files: 8-bit samples as
// unsigned char, 16-bit PNG samples as unsigned short, palettes expanded to RGB, transparency
// to an alpha channel, gray below 8 bits to 8 bits, no gamma or colour conversion beyond
// JPEG's YCbCr to RGB, and row 0 at the bottom (v up).
#ifndef NormalMapImages_h
#define NormalMapImages_h

#include <vtkSmartPointer.h>

#include <cstddef>
#include <string>

class vtkImageData;

namespace NormalMapImages
{
/// Largest width and height decoded, so that a corrupt header cannot make the decoder allocate
/// without bound (at most 8192^2 pixels of 4 16-bit samples, 512 MB).
constexpr unsigned int MaxSide = 8192;

/// "PNG", "JPEG", or empty when the bytes start with neither signature.
std::string Format(const unsigned char* data, size_t size);

/// Decodes a PNG or JPEG image (told apart by its signature). Nullptr with `error` (one line,
/// e.g. "corrupt PNG: ...") for any other format, a corrupt or truncated image (libjpeg's
/// "corrupt data" warnings count as errors), or one larger than MaxSide.
vtkSmartPointer<vtkImageData> Decode(const unsigned char* data, size_t size, std::string& error);
}

#endif
