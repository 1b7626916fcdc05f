// 8-bit basis entries of matrix CPCA (transfer_codec_basis8.h).
#include "transfer_codec_basis8.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace prt::transfer_codec {

float basisScale(std::span<const float> entries) {
  double maxAbs = 0.0;
  for (float x : entries) maxAbs = std::max(maxAbs, std::fabs(static_cast<double>(x)));
  if (maxAbs == 0.0) return 0.0f;
  // Nearest float to max/Q, raised ulp by ulp until Q levels cover max (as the weight steps).
  float scale = std::max(static_cast<float>(maxAbs / kBasisLevels), std::numeric_limits<float>::min());
  while (static_cast<double>(scale) * kBasisLevels < maxAbs) scale = std::nextafter(scale, 2.0f * scale + 1.0f);
  return scale;
}

std::int8_t basisLevel(float x, float scale) {
  if (scale <= 0.0f) return 0;
  const double q = std::nearbyint(static_cast<double>(x) / static_cast<double>(scale));
  return static_cast<std::int8_t>(std::clamp(q, -static_cast<double>(kBasisLevels), static_cast<double>(kBasisLevels)));
}

}  // namespace prt::transfer_codec
