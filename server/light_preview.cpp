#include "light_preview.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace prt::serve {
namespace {

float srgbEncode(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

Status makePreviewPng(const RgbImage& image, int maxWidth, std::string* png) {
  if (image.width < 1 || image.height < 1) return Status::error(StatusCode::kInvalidArgument, "empty image");
  const int w = std::min(image.width, maxWidth);
  const int h = std::max(1, static_cast<int>(std::lround(static_cast<double>(image.height) * w / image.width)));
  std::vector<double> sum(static_cast<std::size_t>(w) * h * 3, 0.0);
  std::vector<int> count(static_cast<std::size_t>(w) * h, 0);
  double luminance = 0.0;
  for (int y = 0; y < image.height; ++y) {
    const int ty = static_cast<int>(static_cast<long long>(y) * h / image.height);
    for (int x = 0; x < image.width; ++x) {
      const int tx = static_cast<int>(static_cast<long long>(x) * w / image.width);
      const Rgb p = image.at(x, y);
      const std::size_t t = static_cast<std::size_t>(ty) * w + tx;
      sum[t * 3] += p.r;
      sum[t * 3 + 1] += p.g;
      sum[t * 3 + 2] += p.b;
      ++count[t];
      luminance += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    }
  }
  luminance /= static_cast<double>(image.width) * image.height;
  const double exposure = luminance > 1e-12 ? 0.18 / luminance : 1.0;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t t = 0; t < count.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const double v = count[t] ? std::max(0.0, sum[t * 3 + c] / count[t] * exposure) : 0.0;
      pixels[t * 3 + c] = static_cast<std::uint8_t>(std::lround(255.0 * srgbEncode(static_cast<float>(v / (1.0 + v)))));
    }
  }
  png->clear();
  if (!stbi_write_png_to_func(appendBytes, png, w, h, 3, pixels.data(), w * 3)) {
    // stb fails only when it cannot allocate the compressed image.
    return Status::error(StatusCode::kResourceExhausted, "PNG encoding failed (out of memory)");
  }
  return Status::ok();
}

}  // namespace prt::serve
