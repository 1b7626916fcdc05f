#include "baker/biscale/placement_gutters.h"

#include <climits>
#include <string>
#include <vector>

#include "baker/texture/texel_dilate.h"

namespace prt::bake {

Status fillPlacementGutters(std::span<const TextureAtlas> atlases, std::span<const std::uint64_t> firstTexel,
                            std::span<const std::uint8_t> sampled, int passes,
                            std::span<std::uint16_t> placementOfTexel) {
  if (passes < 0 || passes > kMaxDilationPasses) {
    return Status::error(StatusCode::kInvalidArgument, "gutterTexels " + std::to_string(passes) + " is outside 0 … " +
                                                           std::to_string(kMaxDilationPasses));
  }
  if (firstTexel.size() != atlases.size() + 1) {
    return Status::error(StatusCode::kSizeMismatch, "firstTexel holds " + std::to_string(firstTexel.size()) +
                                                        " entries for " + std::to_string(atlases.size()) + " atlases");
  }
  std::uint64_t total = 0;
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    if (firstTexel[a] != total) {
      return Status::error(StatusCode::kSizeMismatch, "atlas " + std::to_string(a) + " starts at texel " +
                                                          std::to_string(firstTexel[a]) + ", expected " +
                                                          std::to_string(total));
    }
    total += std::uint64_t{atlases[a].width} * atlases[a].height;
  }
  if (firstTexel.back() != total || sampled.size() != total || placementOfTexel.size() != total) {
    return Status::error(StatusCode::kSizeMismatch, "the atlases hold " + std::to_string(total) + " texels; sampled has " +
                                                        std::to_string(sampled.size()) + ", placementOfTexel " +
                                                        std::to_string(placementOfTexel.size()));
  }
  std::vector<std::int64_t> source;  // per texel of one atlas: the sampled texel it copies, -1 none
  std::vector<int> filledIn;         // the pass that filled it: 0 sampled, INT_MAX not yet
  for (std::size_t a = 0; a < atlases.size(); ++a) {
    const std::int64_t w = atlases[a].width, h = atlases[a].height;
    const std::uint64_t first = firstTexel[a];
    source.assign(static_cast<std::size_t>(w * h), -1);
    filledIn.assign(static_cast<std::size_t>(w * h), INT_MAX);
    for (std::int64_t i = 0; i < w * h; ++i) {
      if (sampled[first + static_cast<std::uint64_t>(i)]) {
        source[static_cast<std::size_t>(i)] = i;
        filledIn[static_cast<std::size_t>(i)] = 0;
      }
    }
    for (int pass = 1; pass <= passes; ++pass) {
      bool any = false;
      for (std::int64_t y = 0; y < h; ++y)
        for (std::int64_t x = 0; x < w; ++x) {
          const auto i = static_cast<std::size_t>(y * w + x);
          if (filledIn[i] != INT_MAX) continue;
          std::int64_t best = -1, bestD2 = 0;
          for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dx = -1; dx <= 1; ++dx) {
              const std::int64_t nx = x + dx, ny = y + dy;
              if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
              const auto n = static_cast<std::size_t>(ny * w + nx);
              // Only texels filled before this pass: the result must not depend on scan order.
              if (filledIn[n] >= pass) continue;
              const std::int64_t s = source[n], sx = s % w - x, sy = s / w - y, d2 = sx * sx + sy * sy;
              if (best < 0 || d2 < bestD2 || (d2 == bestD2 && s < best)) {
                best = s;
                bestD2 = d2;
              }
            }
          if (best < 0) continue;
          source[i] = best;
          filledIn[i] = pass;
          placementOfTexel[first + i] = placementOfTexel[first + static_cast<std::uint64_t>(best)];
          any = true;
        }
      if (!any) break;
    }
  }
  return Status::ok();
}

}  // namespace prt::bake
