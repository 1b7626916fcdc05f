#include "baker/texture/texel_filter.h"

#include <algorithm>
#include <cmath>

namespace prt::bake {

int bilinearTaps(Uv uv, const TextureAtlas& atlas, std::uint64_t firstTexel, std::span<const std::uint8_t> filled,
                 TexelTap taps[4]) {
  const int w = static_cast<int>(atlas.width), h = static_cast<int>(atlas.height);
  // Clamped first, so a UV far outside (extrapolated by the caller) cannot overflow an int.
  const double px = std::clamp(static_cast<double>(uv.u), -1.0, 2.0) * w - 0.5;
  const double py = std::clamp(static_cast<double>(uv.v), -1.0, 2.0) * h - 0.5;
  const double fx0 = std::floor(px), fy0 = std::floor(py);
  const double fx = px - fx0, fy = py - fy0;
  const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
  int count = 0;
  double total = 0.0;
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const int x = std::clamp(x0 + dx, 0, w - 1), y = std::clamp(y0 + dy, 0, h - 1);
      const double weight = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
      const std::uint64_t texel = firstTexel + static_cast<std::uint64_t>(y) * atlas.width + static_cast<std::uint64_t>(x);
      if (weight <= 0.0 || !filled[texel]) continue;
      taps[count++] = {texel, static_cast<float>(weight)};
      total += weight;
    }
  }
  for (int t = 0; t < count; ++t) taps[t].weight = static_cast<float>(taps[t].weight / total);
  return count;
}

}  // namespace prt::bake
