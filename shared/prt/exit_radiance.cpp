#include "prt/exit_radiance.h"

#include <string>

namespace prt {
namespace {

template <typename Acc>
Status exitRadianceImpl(std::span<const float> transfer, int channels, std::size_t stride, std::span<const Rgb> albedo,
                        std::span<const Rgb> lighting, std::span<Acc> out) {
  if (channels != 1 && channels != 3) {
    return Status::error(StatusCode::kInvalidArgument, "exit radiance: channels " + std::to_string(channels) + " is not 1 or 3");
  }
  if (stride == 0 || lighting.size() > stride) {
    return Status::error(StatusCode::kInvalidArgument, "exit radiance: " + std::to_string(lighting.size()) +
                                                           " lighting coefficients for a stride of " + std::to_string(stride));
  }
  const std::size_t perVertex = static_cast<std::size_t>(channels) * stride;
  const std::size_t vertices = out.size() / 3;
  if (out.size() % 3 != 0 || transfer.size() != vertices * perVertex ||
      (channels == 1 && !albedo.empty() && albedo.size() != vertices)) {
    return Status::error(StatusCode::kSizeMismatch, "exit radiance: transfer, albedo and output sizes disagree");
  }
  const std::size_t used = lighting.size();
  for (std::size_t v = 0; v < vertices; ++v) {
    const float* t = &transfer[v * perVertex];
    // Channel c reads its own transfer row for RGB passes and the one shared row otherwise.
    const float* row[3] = {t, channels == 3 ? t + stride : t, channels == 3 ? t + 2 * stride : t};
    Acc r = 0, g = 0, b = 0;
    for (std::size_t i = 0; i < used; ++i) {
      r += static_cast<Acc>(row[0][i]) * static_cast<Acc>(lighting[i].r);
      g += static_cast<Acc>(row[1][i]) * static_cast<Acc>(lighting[i].g);
      b += static_cast<Acc>(row[2][i]) * static_cast<Acc>(lighting[i].b);
    }
    if (channels == 1 && !albedo.empty()) {
      r *= static_cast<Acc>(albedo[v].r);
      g *= static_cast<Acc>(albedo[v].g);
      b *= static_cast<Acc>(albedo[v].b);
    }
    out[3 * v] = r;
    out[3 * v + 1] = g;
    out[3 * v + 2] = b;
  }
  return Status::ok();
}

}  // namespace

Status exitRadiance(std::span<const float> transfer, int channels, std::size_t stride, std::span<const Rgb> albedo,
                    std::span<const Rgb> lighting, std::span<float> out) {
  return exitRadianceImpl<float>(transfer, channels, stride, albedo, lighting, out);
}

Status exitRadianceDouble(std::span<const float> transfer, int channels, std::size_t stride, std::span<const Rgb> albedo,
                          std::span<const Rgb> lighting, std::span<double> out) {
  return exitRadianceImpl<double>(transfer, channels, stride, albedo, lighting, out);
}

}  // namespace prt
