// In-memory float RGB images: the common currency between image loaders (baker/) and the
// SH projections (shared/). No I/O here.
#pragma once

#include <cstddef>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

inline constexpr int kMaxImageSide = 1 << 15;  // 32768 pixels on a side
// A total cap too, so a corrupt header cannot ask for a 12 GiB allocation: 8192 x 8192.
inline constexpr long long kMaxImagePixels = 1LL << 26;

// Linear RGB, row-major, row 0 at the top, 3 floats per pixel.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;

  Rgb at(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Ok when 1 <= width, height <= kMaxImageSide, width*height <= kMaxImagePixels, rgb.size() == width*height*3 and every value
// is finite. The message names `what` and the first offending size or pixel.
Status checkImage(const RgbImage& image, const char* what);

}  // namespace prt
