// Unit normals in 2 x 16 bits: the octahedral map (Meyer et al. 2010; Cigolle et al. 2014,
// "A Survey of Efficient Representations for Independent Unit Vectors") stored as snorm16,
// as the asset's texel normals section keeps the normal-mapped shading normal per texel
// (docs/asset-format.md, type 19). snorm rather than unorm: 0 is a code, so the axes (a flat,
// unperturbed texel's +z in its octahedron, and the fold's corners) decode exactly.
#pragma once

#include <array>
#include <cstdint>

#include "prt/vec3.h"

namespace prt {

// The one snorm16 code the octahedral normals never use: -32768 would decode like -32767
// (GL's snorm rule clamps it), so refusing it gives every normal a single encoding.
inline constexpr std::int16_t kOctahedralInvalidCode = -32768;

// The measured worst case of encodeOctahedralNormal then decodeOctahedralNormal over the
// sphere, in degrees (tests/shared/octahedral_normal_test.cpp pins it with a dense sweep).
inline constexpr double kOctahedralMaxErrorDegrees = 0.0026;

// The code pair of unit-ish vector n (normalised first; zero or non-finite gives +z's code
// (0, 0)): of the four roundings of its octahedral coordinates, the one whose decoding is
// closest in angle to n (Cigolle et al.'s "precise" encoder). Never returns -32768.
std::array<std::int16_t, 2> encodeOctahedralNormal(Vec3 n);

// The unit normal of a code pair; -32768 reads as -32767 (GL's snorm16 rule). Total.
Vec3 decodeOctahedralNormal(std::int16_t x, std::int16_t y);

}  // namespace prt
