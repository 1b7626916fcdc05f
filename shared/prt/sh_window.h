// Per-band windowing of SH expansions against ringing (Gibbs oscillation).
// Off by default everywhere: a window trades sharpness for fewer negative lobes.
#pragma once

#include <span>
#include <string_view>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

enum class ShWindow {
  kNone,     // w_l = 1
  kHanning,  // w_l = (1 + cos(pi l / W)) / 2 for l < W, else 0
  kLanczos,  // w_l = sinc(l / W) = sin(pi l / W) / (pi l / W) for l < W, else 0
};

// Parses "none" | "hanning" | "lanczos"; an error lists the valid names otherwise.
Status parseShWindow(std::string_view name, ShWindow* out);
const char* shWindowName(ShWindow window);

// Band weights w_0..w_{order-1} for window width W (in bands). W <= 0 means W = order,
// which keeps every band of the expansion non-zero. out.size() >= order.
Status shWindowWeights(ShWindow window, int order, float width, std::span<float> out);

// Multiplies each band of `coeffs` (order*order RGB values) by its weight.
Status applyShWindow(ShWindow window, int order, float width, std::span<Rgb> coeffs);

}  // namespace prt
