// The bi-scale sections' value rules (tangents, patch uv, RTT; docs/asset-format.md
// "Bi-scale"), shared by the asset writer (checkAsset) and reader so both refuse the same
// files with the same words. Private to the asset code.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::asset_bi_scale {

// Ok when `tangent` is within kTangentTolerance of unit length and of orthogonal to `normal`
// (unit); else kInvalidArgument (kNotFinite for NaN or infinity) naming `vertex`.
Status checkTangent(Vec3 tangent, Vec3 normal, std::size_t vertex);

// Ok when patch coordinate `value` (float `index` of the patch uv) is finite and within
// kMaxPatchCoordinate; else kNotFinite or kInvalidArgument naming the vertex and axis.
Status checkPatchCoordinate(float value, std::size_t index);

// Ok when the 9 floats of placement `index` (origin, axisU, axisV) are finite; else kNotFinite
// naming it.
Status checkPlacement(const std::array<float, 9>& values, std::size_t index);

// Ok when id map texel `texel` holds a placement index below `placements` or kNoPlacement;
// else kInvalidArgument naming it.
Status checkIdMapEntry(std::uint16_t value, std::size_t placements, std::size_t texel);

// Ok when `bytes` is an RTT file decodeRtt accepts, of order <= `assetOrder`; else its
// error (or kInvalidArgument for the order), prefixed with "RTT: ". Safe on untrusted bytes.
Status checkRttBytes(std::span<const std::uint8_t> bytes, int assetOrder);

}  // namespace prt::asset_bi_scale
