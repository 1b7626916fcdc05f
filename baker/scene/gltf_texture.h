// glTF base-colour textures: decoding (as tinygltf's image callback), sRGB linearisation
// and bilinear sampling with glTF's wrap modes.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace tinygltf {
class Model;
struct Image;
}  // namespace tinygltf

namespace prt::bake {

// Largest texture side decoded; larger images are skipped (with a warning) rather than
// risking gigabytes for a per-vertex albedo.
inline constexpr int kMaxTextureSide = 16384;

enum class WrapMode { kRepeat, kClampToEdge, kMirroredRepeat };

// Maps a glTF sampler wrap value (10497, 33071, 33648) to a WrapMode; false (and kRepeat,
// glTF's default) for anything else.
bool wrapModeFromGltf(int value, WrapMode* out);

// A texture in linear RGB, row 0 at the top: glTF's uv (0, 0) is the image's top-left corner.
struct LinearTexture {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;  // width × height × 3
};

// The sRGB transfer function (IEC 61966-2-1): encoded value in [0, 1] to linear.
float srgbToLinear(float encoded);

// Linearises 8-bit sRGB pixels with `components` channels (1 grey, 2 grey+alpha, 3 RGB,
// 4 RGBA; alpha is dropped). Errors if the sizes disagree.
Status linearTextureFromSrgb8(int width, int height, int components, std::span<const unsigned char> pixels,
                              LinearTexture* out);

// The same for data textures (normal maps): each 8-bit value / 255, no transfer function.
Status textureFromUnorm8(int width, int height, int components, std::span<const unsigned char> pixels,
                         LinearTexture* out);

// Bilinear sample at (u, v), texel centres at ((i + ½)/width, (j + ½)/height), each axis
// wrapped by its mode. Filtering happens on linear values, as GPUs do for sRGB textures.
// Non-finite coordinates read as 0; an empty texture samples as black.
Rgb sampleBilinear(const LinearTexture& texture, float u, float v, WrapMode wrapS, WrapMode wrapT);

// State shared with decodeGltfImage through tinygltf's user pointer.
struct ImageDecodeLog {
  const tinygltf::Model* model = nullptr;  // the model being parsed, to bounds-check bufferView images
  std::map<int, std::string> failures;     // image index → why it was left undecoded
};

// tinygltf image callback (TinyGLTF::SetImageLoader, user pointer: an ImageDecodeLog).
// Decodes PNG/JPEG/... with stb_image into 8-bit RGBA. An image that cannot be decoded is
// left empty and logged, so that one bad texture does not fail the whole file; an image
// whose bufferView lies outside its buffer fails the load (tinygltf does not check it).
bool decodeGltfImage(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn, int requiredWidth,
                     int requiredHeight, const unsigned char* bytes, int size, void* userData);

}  // namespace prt::bake
