// What the page shows of an environment map besides its SH: a small tone-mapped PNG
// preview, and the HDR background texture (RGB9E5) the page draws behind the scene.
#pragma once

#include <cstdint>
#include <string>

#include "prt/image.h"
#include "prt/status.h"

namespace prt::serve {

// Box-filters `image` down to at most `maxWidth` pixels wide (aspect kept), exposes it so
// the mean luminance lands at middle grey, applies Reinhard's x/(1+x) and the sRGB curve,
// and encodes an 8-bit RGB PNG into *png.
Status makePreviewPng(const RgbImage& image, int maxWidth, std::string* png);

// GL's RGB9_E5 packing of one linear RGB value (EXT_texture_shared_exponent: 9-bit
// mantissas, one 5-bit exponent, bias 15; negatives and NaN give 0, values clamp to 65408):
// red in bits 0-8, green 9-17, blue 18-26, the exponent 27-31.
std::uint32_t packRgb9e5(Rgb linear);

// Box-filters `image` down to at most `maxWidth` pixels wide (aspect kept) and packs every
// pixel with packRgb9e5, rows top first, little-endian uint32s: the bytes WebGL2 uploads as
// RGB9_E5 / UNSIGNED_INT_5_9_9_9_REV. Sets *width and *height to the texture's size.
Status makeBackgroundRgb9e5(const RgbImage& image, int maxWidth, std::string* bytes, int* width, int* height);

}  // namespace prt::serve
