#include "prt/image.h"

#include <cmath>
#include <string>

namespace prt {

Status checkImage(const RgbImage& image, const char* what) {
  if (image.width < 1 || image.height < 1 || image.width > kMaxImageSide || image.height > kMaxImageSide) {
    return Status::error(StatusCode::kInvalidArgument,
                         std::string(what) + " is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + "; each side must be in [1, " +
                             std::to_string(kMaxImageSide) + "]");
  }
  if (static_cast<long long>(image.width) * image.height > kMaxImagePixels) {
    return Status::error(StatusCode::kInvalidArgument,
                         std::string(what) + " is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + "; at most " + std::to_string(kMaxImagePixels) +
                             " pixels are supported");
  }
  const std::size_t expected = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3;
  if (image.rgb.size() != expected) {
    return Status::error(StatusCode::kSizeMismatch, std::string(what) + " has " + std::to_string(image.rgb.size()) +
                                                        " floats, " + std::to_string(expected) + " expected");
  }
  for (std::size_t i = 0; i < expected; ++i) {
    if (!std::isfinite(image.rgb[i])) {
      const std::size_t pixel = i / 3;
      return Status::error(StatusCode::kNotFinite,
                           std::string(what) + " has a non-finite value at pixel (" +
                               std::to_string(pixel % static_cast<std::size_t>(image.width)) + ", " +
                               std::to_string(pixel / static_cast<std::size_t>(image.width)) + ")");
    }
  }
  return Status::ok();
}

}  // namespace prt
