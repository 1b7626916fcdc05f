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

// `image` box-filtered to at most `maxWidth` pixels wide (aspect kept), and its mean
// luminance (of the full image).
RgbImage boxDownsample(const RgbImage& image, int maxWidth, double* meanLuminance) {
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
  *meanLuminance = luminance / (static_cast<double>(image.width) * image.height);
  RgbImage out;
  out.width = w;
  out.height = h;
  out.rgb.resize(count.size() * 3);
  for (std::size_t t = 0; t < count.size(); ++t) {
    const double n = count[t] ? count[t] : 1;
    for (int c = 0; c < 3; ++c) out.rgb[t * 3 + c] = static_cast<float>(sum[t * 3 + c] / n);
  }
  return out;
}

}  // namespace

Status makePreviewPng(const RgbImage& image, int maxWidth, std::string* png) {
  if (image.width < 1 || image.height < 1) return Status::error(StatusCode::kInvalidArgument, "empty image");
  double luminance = 0.0;
  const RgbImage small = boxDownsample(image, maxWidth, &luminance);
  const int w = small.width, h = small.height;
  const double exposure = luminance > 1e-12 ? 0.18 / luminance : 1.0;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t t = 0; t < small.rgb.size() / 3; ++t) {
    for (int c = 0; c < 3; ++c) {
      const double v = std::max(0.0, small.rgb[t * 3 + c] * exposure);
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

std::uint32_t packRgb9e5(Rgb linear) {
  constexpr int kMantissaBits = 9, kBias = 15, kMaxExponent = 31;
  const double largestValue = 511.0 / 512.0 * 65536.0;  // (2^9 - 1) / 2^9 * 2^(31 - 15)
  const auto clampChannel = [&](float v) { return v > 0.0f ? std::min(static_cast<double>(v), largestValue) : 0.0; };  // NaN -> 0
  const double r = clampChannel(linear.r), g = clampChannel(linear.g), b = clampChannel(linear.b);
  const double largest = std::max({r, g, b});
  // The spec's exp_shared: floor(log2(largest)) + 1 + bias, at least 0 (frexp gives
  // largest = m 2^e with m in [0.5, 1), so floor(log2(largest)) = e - 1).
  int e = 0;
  if (largest > 0.0) std::frexp(largest, &e);
  const int floorLog2 = largest > 0.0 ? e - 1 : -kBias - 1;  // log2(0) = -inf: the smallest exponent
  int shared = std::max(-kBias - 1, floorLog2) + 1 + kBias;
  // Rounding the largest channel can carry into a tenth bit: then one exponent step more.
  if (std::floor(largest / std::ldexp(1.0, shared - kBias - kMantissaBits) + 0.5) >= 512.0) ++shared;
  shared = std::min(shared, kMaxExponent);
  const double scale = std::ldexp(1.0, shared - kBias - kMantissaBits);
  const auto mantissa = [&](double v) { return std::min<std::uint32_t>(511, static_cast<std::uint32_t>(std::floor(v / scale + 0.5))); };
  return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (static_cast<std::uint32_t>(shared) << 27);
}

Status makeBackgroundRgb9e5(const RgbImage& image, int maxWidth, std::string* bytes, int* width, int* height) {
  if (image.width < 1 || image.height < 1) return Status::error(StatusCode::kInvalidArgument, "empty image");
  double luminance = 0.0;
  const RgbImage small = boxDownsample(image, maxWidth, &luminance);
  const std::size_t texels = small.rgb.size() / 3;
  bytes->resize(texels * 4);
  for (std::size_t t = 0; t < texels; ++t) {
    const std::uint32_t v = packRgb9e5({small.rgb[t * 3], small.rgb[t * 3 + 1], small.rgb[t * 3 + 2]});
    for (int k = 0; k < 4; ++k) (*bytes)[t * 4 + k] = static_cast<char>((v >> (8 * k)) & 0xffu);  // little-endian, as WebGL reads it
  }
  *width = small.width;
  *height = small.height;
  return Status::ok();
}

}  // namespace prt::serve
