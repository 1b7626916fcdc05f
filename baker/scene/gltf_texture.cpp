#include "baker/scene/gltf_texture.h"

#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>

namespace prt::bake {
namespace {

// 256-entry table: every decoded texel goes through it, and pow() per texel is slow.
const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

// Folds a coordinate into a range where the texel arithmetic below cannot overflow int,
// without changing which texels it selects under `mode`.
double foldCoordinate(double t, WrapMode mode) {
  if (!std::isfinite(t)) return 0.0;
  switch (mode) {
    case WrapMode::kRepeat: return t - std::floor(t);
    case WrapMode::kMirroredRepeat: return t - 2.0 * std::floor(t / 2.0);
    case WrapMode::kClampToEdge: return std::clamp(t, -1.0, 2.0);
  }
  return 0.0;
}

int wrapTexel(int i, int size, WrapMode mode) {
  switch (mode) {
    case WrapMode::kRepeat: {
      const int m = i % size;
      return m < 0 ? m + size : m;
    }
    case WrapMode::kMirroredRepeat: {
      int m = i % (2 * size);
      if (m < 0) m += 2 * size;
      return m < size ? m : 2 * size - 1 - m;
    }
    case WrapMode::kClampToEdge: return std::clamp(i, 0, size - 1);
  }
  return 0;
}

Rgb texel(const LinearTexture& t, int x, int y) {
  const std::size_t i =
      (static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(x)) * 3;
  return {t.rgb[i], t.rgb[i + 1], t.rgb[i + 2]};
}

struct StbFree {
  void operator()(unsigned char* p) const { stbi_image_free(p); }
};

std::string imageLabel(const tinygltf::Image& image, int index) {
  std::string s = "image " + std::to_string(index);
  if (!image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
    s += " ('" + image.uri + "')";
  } else if (!image.name.empty()) {
    s += " ('" + image.name + "')";
  }
  return s;
}

}  // namespace

bool wrapModeFromGltf(int value, WrapMode* out) {
  switch (value) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: *out = WrapMode::kRepeat; return true;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: *out = WrapMode::kClampToEdge; return true;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: *out = WrapMode::kMirroredRepeat; return true;
    default: *out = WrapMode::kRepeat; return false;
  }
}

float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

namespace {

// The 8-bit decode shared by colour and data textures: each byte through `lut`.
Status textureFrom8Bit(int width, int height, int components, std::span<const unsigned char> pixels,
                       const std::array<float, 256>& lut, LinearTexture* out) {
  *out = LinearTexture();
  if (width < 1 || height < 1 || width > kMaxTextureSide || height > kMaxTextureSide || components < 1 ||
      components > 4) {
    return Status::error(StatusCode::kInvalidArgument, "texture of " + std::to_string(width) + "x" +
                                                           std::to_string(height) + " with " +
                                                           std::to_string(components) + " channels is not supported");
  }
  const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (pixels.size() != texels * static_cast<std::size_t>(components)) {
    return Status::error(StatusCode::kSizeMismatch, "texture of " + std::to_string(width) + "x" +
                                                        std::to_string(height) + "x" + std::to_string(components) +
                                                        " has " + std::to_string(pixels.size()) + " bytes");
  }
  out->width = width;
  out->height = height;
  out->rgb.resize(texels * 3);
  const auto c = static_cast<std::size_t>(components);
  for (std::size_t i = 0; i < texels; ++i) {
    const unsigned char* p = pixels.data() + i * c;
    // Grey (+alpha) images replicate their one colour channel.
    const bool grey = components < 3;
    out->rgb[3 * i] = lut[p[0]];
    out->rgb[3 * i + 1] = lut[grey ? p[0] : p[1]];
    out->rgb[3 * i + 2] = lut[grey ? p[0] : p[2]];
  }
  return Status::ok();
}

}  // namespace

Status linearTextureFromSrgb8(int width, int height, int components, std::span<const unsigned char> pixels,
                              LinearTexture* out) {
  return textureFrom8Bit(width, height, components, pixels, srgbTable(), out);
}

Status textureFromUnorm8(int width, int height, int components, std::span<const unsigned char> pixels,
                         LinearTexture* out) {
  static const std::array<float, 256> unorm = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<std::size_t>(i)] = static_cast<float>(i) / 255.0f;
    return t;
  }();
  return textureFrom8Bit(width, height, components, pixels, unorm, out);
}

Rgb sampleBilinear(const LinearTexture& texture, float u, float v, WrapMode wrapS, WrapMode wrapT) {
  if (texture.width < 1 || texture.height < 1 ||
      texture.rgb.size() < static_cast<std::size_t>(texture.width) * texture.height * 3) {
    return {0, 0, 0};
  }
  const double x = foldCoordinate(u, wrapS) * texture.width - 0.5;
  const double y = foldCoordinate(v, wrapT) * texture.height - 0.5;
  const double fx0 = std::floor(x);
  const double fy0 = std::floor(y);
  const auto wx = static_cast<float>(x - fx0);
  const auto wy = static_cast<float>(y - fy0);
  const int x0 = static_cast<int>(fx0);
  const int y0 = static_cast<int>(fy0);
  const int xa = wrapTexel(x0, texture.width, wrapS), xb = wrapTexel(x0 + 1, texture.width, wrapS);
  const int ya = wrapTexel(y0, texture.height, wrapT), yb = wrapTexel(y0 + 1, texture.height, wrapT);
  const Rgb top = texel(texture, xa, ya) * (1.0f - wx) + texel(texture, xb, ya) * wx;
  const Rgb bottom = texel(texture, xa, yb) * (1.0f - wx) + texel(texture, xb, yb) * wx;
  return top * (1.0f - wy) + bottom * wy;
}

bool decodeGltfImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int /*requiredWidth*/,
                     int /*requiredHeight*/, const unsigned char* bytes, int size, void* userData) {
  auto* log = static_cast<ImageDecodeLog*>(userData);
  const std::string label = imageLabel(*image, imageIndex);
  try {
    // tinygltf hands over &buffer.data[bufferView.byteOffset] and byteLength without
    // checking them against the buffer: check before touching a byte.
    if (image->bufferView >= 0 && log != nullptr && log->model != nullptr) {
      const tinygltf::Model& model = *log->model;
      const auto view = static_cast<std::size_t>(image->bufferView);
      const tinygltf::BufferView& bv = model.bufferViews.at(view);
      const std::size_t bufferSize = model.buffers.at(static_cast<std::size_t>(bv.buffer)).data.size();
      if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset || bv.byteLength > 0x7fffffffu) {
        if (err) {
          *err += label + ": bufferView " + std::to_string(image->bufferView) + " (byteOffset " +
                  std::to_string(bv.byteOffset) + ", byteLength " + std::to_string(bv.byteLength) +
                  ") reaches past the end of buffer " + std::to_string(bv.buffer) + ", which holds " +
                  std::to_string(bufferSize) + " bytes\n";
        }
        return false;
      }
    }
    auto skip = [&](const std::string& why) {
      if (log != nullptr) log->failures[imageIndex] = why;
      if (warn) *warn += label + ": " + why + "\n";
      return true;  // keep loading: the texture is dropped, the geometry is still good
    };
    if (bytes == nullptr || size <= 0) return skip("no image data");
    int w = 0, h = 0, comp = 0;
    // glTF images are PNG or JPEG. Refuse anything else before stb_image sees it: its HDR
    // decoder loops forever on some corrupt run lengths.
    const bool png = size >= 8 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G';
    const bool jpeg = size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
    if (!png && !jpeg) return skip("not a PNG or JPEG image");
    if (stbi_info_from_memory(bytes, size, &w, &h, &comp) == 0) {
      return skip(std::string("cannot decode (") + stbi_failure_reason() + ")");
    }
    if (w < 1 || h < 1 || w > kMaxTextureSide || h > kMaxTextureSide) {
      return skip(std::to_string(w) + "x" + std::to_string(h) + " is larger than " + std::to_string(kMaxTextureSide) +
                  " on a side");
    }
    std::unique_ptr<unsigned char, StbFree> pixels(stbi_load_from_memory(bytes, size, &w, &h, &comp, 4));
    if (!pixels) return skip(std::string("cannot decode (") + stbi_failure_reason() + ")");
    image->width = w;
    image->height = h;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    return true;
  } catch (const std::exception& e) {
    if (err) *err += label + ": " + e.what() + "\n";
    return false;
  }
}

}  // namespace prt::bake
