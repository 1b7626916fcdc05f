// IEEE-754 binary16 ("half") conversion for the client's RGBA16F transfer textures
// (texel_texture.h). GL-free. The codec has its own converter, but it is private to the codec
// (tests/codec_private_check.cmake), and the client needs only these two directions.
#pragma once

#include <cstdint>

namespace prt::web {

// The half nearest `value`, ties to even (what a GPU's float-to-half conversion does); values
// of magnitude >= 65520 give +-infinity, NaN stays NaN. Subnormal halves are produced exactly.
std::uint16_t floatToHalf(float value);

// The exact float value of half `bits` (every half is representable as a float).
float halfToFloat(std::uint16_t bits);

}  // namespace prt::web
