#include "prt/asset_bi_scale.h"

#include <cmath>

#include "prt/asset.h"
#include "prt/rtt.h"

namespace prt::asset_bi_scale {

Status checkTangent(Vec3 tangent, Vec3 normal, std::size_t vertex) {
  const std::string label = "tangent of vertex " + std::to_string(vertex);
  if (!std::isfinite(tangent.x) || !std::isfinite(tangent.y) || !std::isfinite(tangent.z)) {
    return Status::error(StatusCode::kNotFinite, label + " is not finite");
  }
  const float length = std::sqrt(dot(tangent, tangent));
  if (!(std::fabs(length - 1.0f) <= kTangentTolerance)) {
    return Status::error(StatusCode::kInvalidArgument, label + " has length " + std::to_string(length) + "; unit expected");
  }
  const float cosine = dot(tangent, normal);
  if (!(std::fabs(cosine) <= kTangentTolerance)) {
    return Status::error(StatusCode::kInvalidArgument,
                         label + " is not orthogonal to its normal (dot product " + std::to_string(cosine) + ")");
  }
  return Status::ok();
}

Status checkPatchCoordinate(float value, std::size_t index) {
  const std::string label = "patch uv of vertex " + std::to_string(index / 2) + (index % 2 ? " v" : " u");
  if (!std::isfinite(value)) return Status::error(StatusCode::kNotFinite, label + " is not finite");
  if (!(std::fabs(value) <= kMaxPatchCoordinate)) {
    return Status::error(StatusCode::kInvalidArgument, label + " is " + std::to_string(value) + "; at most " +
                                                           std::to_string(static_cast<int>(kMaxPatchCoordinate)) +
                                                           " in magnitude (float precision of the patch position)");
  }
  return Status::ok();
}

Status checkPlacement(const std::array<float, 9>& values, std::size_t index) {
  for (float x : values) {
    if (!std::isfinite(x)) return Status::error(StatusCode::kNotFinite, "patch placement " + std::to_string(index) + " is not finite");
  }
  return Status::ok();
}

Status checkIdMapEntry(std::uint16_t value, std::size_t placements, std::size_t texel) {
  if (value == kNoPlacement || value < placements) return Status::ok();
  return Status::error(StatusCode::kInvalidArgument, "id map texel " + std::to_string(texel) + " names placement " +
                                                         std::to_string(value) + " of " + std::to_string(placements));
}

Status checkRttBytes(std::span<const std::uint8_t> bytes, int assetOrder) {
  Rtt rtt;
  if (Status s = decodeRtt(bytes, &rtt); !s.isOk()) return Status::error(s.code(), "RTT: " + s.message());
  if (rtt.order > assetOrder) {
    return Status::error(StatusCode::kInvalidArgument, "RTT: order " + std::to_string(rtt.order) +
                                                           " exceeds the asset's order " + std::to_string(assetOrder));
  }
  return Status::ok();
}

}  // namespace prt::asset_bi_scale
