// A small tone-mapped PNG of an environment map, for the client's background while the
// SH lighting stands in for the real thing.
#pragma once

#include <string>

#include "prt/image.h"
#include "prt/status.h"

namespace prt::serve {

// Box-filters `image` down to at most `maxWidth` pixels wide (aspect kept), exposes it so
// the mean luminance lands at middle grey, applies Reinhard's x/(1+x) and the sRGB curve,
// and encodes an 8-bit RGB PNG into *png.
Status makePreviewPng(const RgbImage& image, int maxWidth, std::string* png);

}  // namespace prt::serve
