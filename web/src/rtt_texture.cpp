#include "rtt_texture.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "prt/half_float.h"

namespace prt::web {

Status packRtt(const Rtt& rtt, int maxTextureSize, int maxLayers, RttTextures* out) {
  if (rtt.coeffCount() == 0 || rtt.coeffs.size() != rtt.coeffCount()) return Status::error(StatusCode::kInvalidArgument, "RTT shape");
  const int n2 = rtt.order * rtt.order, T = (n2 + 3) / 4;
  const int size = rtt.spatial * rtt.views, layers = rtt.channels * T;
  if (size > maxTextureSize) {
    return Status::error(StatusCode::kInvalidArgument, "RTT of " + std::to_string(rtt.spatial) + "^2 positions x " + std::to_string(rtt.views) +
                                                           "^2 views needs " + std::to_string(size) + "^2 texels a layer; this device holds " +
                                                           std::to_string(maxTextureSize));
  }
  if (layers > maxLayers) {
    return Status::error(StatusCode::kInvalidArgument,
                         "RTT needs " + std::to_string(layers) + " texture layers; this device holds " + std::to_string(maxLayers));
  }
  RttTextures t;
  t.order = rtt.order;
  t.channels = rtt.channels;
  t.spatial = rtt.spatial;
  t.views = rtt.views;
  t.layersPerChannel = T;
  t.size = size;
  const std::size_t S = static_cast<std::size_t>(rtt.spatial), V = static_cast<std::size_t>(rtt.views), W = static_cast<std::size_t>(size);
  const std::size_t C = static_cast<std::size_t>(rtt.channels), N = static_cast<std::size_t>(n2);
  t.halves.assign(static_cast<std::size_t>(layers) * W * W * 4, 0);
  for (std::size_t y = 0; y < S; ++y)
    for (std::size_t x = 0; x < S; ++x)
      for (std::size_t b = 0; b < V; ++b)
        for (std::size_t a = 0; a < V; ++a)
          for (std::size_t c = 0; c < C; ++c) {
            const float* src = &rtt.coeffs[((((y * S + x) * V + b) * V + a) * C + c) * N];
            for (std::size_t i = 0; i < N; ++i) {
              const std::uint16_t h = floatToHalf(src[i]);
              if (!isFiniteHalf(h)) {
                return Status::error(StatusCode::kNotFinite, "RTT coefficient " + std::to_string(src[i]) + " is beyond binary16's range");
              }
              const std::size_t layer = c * static_cast<std::size_t>(T) + i / 4;
              const std::size_t texel = (y * V + b) * W + (x * V + a);
              t.halves[(layer * W * W + texel) * 4 + i % 4] = h;
            }
          }
  *out = std::move(t);
  return Status::ok();
}

void rttTextureLookupCpu(const RttTextures& t, float u, float v, Vec3 view, bool viewDependent, float* out) {
  const int S = t.spatial, V = t.views, W = t.size, n2 = t.order * t.order;
  const float fu = u - std::floor(u), fv = v - std::floor(v);
  const int x = std::min(S - 1, static_cast<int>(fu * static_cast<float>(S)));
  const int y = std::min(S - 1, static_cast<int>(fv * static_cast<float>(S)));
  float a = 0.5f * static_cast<float>(V), b = a;
  if (viewDependent) rttViewCoordinates(view, V, &a, &b);
  // The texel-space coordinate the shader samples at: inside the block, clamped to its outer
  // sample centres; GL's LINEAR filter then weights texels floor(c - 0.5) and the next.
  const float maxCentre = static_cast<float>(V) - 0.5f;
  const float cx = static_cast<float>(x * V) + std::clamp(a, 0.5f, maxCentre);
  const float cy = static_cast<float>(y * V) + std::clamp(b, 0.5f, maxCentre);
  const int x0 = static_cast<int>(std::floor(cx - 0.5f)), y0 = static_cast<int>(std::floor(cy - 0.5f));
  const float tx = cx - 0.5f - static_cast<float>(x0), ty = cy - 0.5f - static_cast<float>(y0);
  const int x1 = std::min(x0 + 1, W - 1), y1 = std::min(y0 + 1, W - 1);
  const std::size_t plane = static_cast<std::size_t>(W) * static_cast<std::size_t>(W);
  auto texel = [&](std::size_t layer, int px, int py, int k) {
    return halfToFloat(t.halves[(layer * plane + static_cast<std::size_t>(py) * static_cast<std::size_t>(W) + static_cast<std::size_t>(px)) * 4 +
                                static_cast<std::size_t>(k)]);
  };
  for (int c = 0; c < t.channels; ++c)
    for (int i = 0; i < n2; ++i) {
      const std::size_t layer = static_cast<std::size_t>(c * t.layersPerChannel + i / 4);
      const int k = i % 4;
      out[c * n2 + i] = (1.0f - ty) * ((1.0f - tx) * texel(layer, x0, y0, k) + tx * texel(layer, x1, y0, k)) +
                        ty * ((1.0f - tx) * texel(layer, x0, y1, k) + tx * texel(layer, x1, y1, k));
    }
}

}  // namespace prt::web
