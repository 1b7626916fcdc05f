// Loading environment images from disk into linear float RGB (prt::RgbImage).
//
// Formats are recognised by their first bytes, not by the file name: OpenEXR (any
// compression the installed OpenEXR reads, DWAA/DWAB included), Radiance RGBE (.hdr, .pic;
// radiance_hdr.h), PNG (8 or 16 bit) and JPEG (both through stb_image). PNG and JPEG are
// taken as sRGB-encoded and linearised; EXR and HDR values are used as stored. Alpha is
// dropped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "prt/image.h"
#include "prt/status.h"

namespace prt {

enum class ImageFormat { kUnknown, kOpenExr, kRadianceHdr, kPng, kJpeg };

// Human-readable name of a format ("OpenEXR", "Radiance HDR", ...).
const char* imageFormatName(ImageFormat format);

// Recognises a format from the first bytes of a file (at least 8 are needed for PNG).
ImageFormat detectImageFormat(const unsigned char* bytes, std::size_t size);

// Ok when both sides are in [1, kMaxImageSide]; otherwise "image has zero size (WxH)" or
// "image is too large (WxH); ...". Decoders call it before they allocate.
Status checkImageSize(std::int64_t width, std::int64_t height);

// Loads `path` into `out` (row 0 at the top). On success the image passes checkImage:
// 1..kMaxImageSide on each side, every value finite. Every failure (missing, unreadable,
// unknown format, corrupt or truncated data, zero or oversized dimensions, non-finite
// pixels, not a regular file) returns an error whose message names the file: kNotFound for
// a missing file, kIoError (or kNotFound, kResourceExhausted, by errno) when the system
// refuses a read, kResourceExhausted when out of memory, kNotFinite for inf/NaN pixels,
// kInvalidArgument for everything about the contents. Never throws; `out` is left empty on
// failure.
Status loadImage(const std::string& path, RgbImage* out);

}  // namespace prt
