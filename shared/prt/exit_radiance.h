// Exit radiance of per-vertex SH transfer under SH lighting: the one reference every
// consumer uses (prt-bake shade and compress-report, the wasm core, the CPU emulation of
// the CPCA shaders), so float and double results differ only by their accumulation.
//
// For vertex v and colour channel c, over the first `lighting.size()` coefficients i:
//   scalar transfer (channels 1):  L_vc = albedo_vc * sum_i T_vi  L_ci
//   RGB transfer    (channels 3):  L_vc =            sum_i T_vci L_ci   (albedo folded in)
// (docs/sh-conventions.md: transfer carries rho/pi; lighting is radiance coefficients.)
// `transfer` is [vertex][channel][coefficient] with `stride` floats per channel (the stored
// order squared, or more for padded layouts); products are summed in coefficient order.
#pragma once

#include <span>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Writes [vertex][rgb] exit radiance to `out` (3 per vertex, float accumulation, as the GPU
// shaders do). channels 1 or 3; lighting.size() <= stride; `albedo` one per vertex for
// scalar transfer, or empty for albedo 1 (RGB transfer ignores it); sizes must agree:
// transfer.size() == vertices * channels * stride, out.size() == 3 * vertices.
Status exitRadiance(std::span<const float> transfer, int channels, std::size_t stride, std::span<const Rgb> albedo,
                    std::span<const Rgb> lighting, std::span<float> out);

// The same with double accumulation (products of float inputs summed in double), the
// reference that codec errors are measured against.
Status exitRadianceDouble(std::span<const float> transfer, int channels, std::size_t stride, std::span<const Rgb> albedo,
                          std::span<const Rgb> lighting, std::span<double> out);

}  // namespace prt
