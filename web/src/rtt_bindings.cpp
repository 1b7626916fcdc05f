// Embind bindings of the radiance transfer texture code (prt/rtt.h, prt/bi_scale.h,
// rtt_texture.h) for the tests (tests/web/rtt_core_node_test.mjs): an RTT file read by the
// wasm core, its packed textures' lookup against the shared reference.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <cmath>
#include <string>
#include <vector>

#include "prt/bi_scale.h"
#include "prt/rtt.h"
#include "rtt_texture.h"

using emscripten::val;

namespace {

// Reads RTT file `bytes` (a Uint8Array) and compares the packed textures' lookup
// (rttTextureLookupCpu) with prt::rttLookup at `count` seeded positions and views, view
// dependence on and off: {order, channels, spatial, views, layers, size, worst (largest
// difference over the largest |coefficient|), peak, first (the first coefficients at
// position (0.5, 0.5), view +z)}, or a string naming the error (the reader's, or packing's).
val rttTextureCheck(const val& bytes, int count, int seed) {
  const std::vector<std::uint8_t> data = emscripten::convertJSArrayToNumberVector<std::uint8_t>(bytes);
  prt::Rtt rtt;
  if (prt::Status s = prt::decodeRtt(data, &rtt); !s.isOk()) return val(s.toString());
  prt::web::RttTextures t;
  if (prt::Status s = prt::web::packRtt(rtt, 2048, 256, &t); !s.isOk()) return val(s.toString());
  const std::size_t per = static_cast<std::size_t>(rtt.channels * rtt.order * rtt.order);
  std::vector<float> a(per), b(per);
  std::uint32_t state = static_cast<std::uint32_t>(seed) * 2654435761u + 1u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  };
  double worst = 0.0, peak = 0.0;
  for (int k = 0; k < count; ++k) {
    const float u = 3.0f * next() - 1.0f, v = 3.0f * next() - 1.0f;
    const float z = next(), phi = 6.2831853f * next(), r = std::sqrt(1.0f - z * z);
    const prt::Vec3 w{r * std::cos(phi), r * std::sin(phi), z};
    for (bool viewDependent : {true, false}) {
      prt::rttLookup(rtt, u, v, w, viewDependent, a.data());
      prt::web::rttTextureLookupCpu(t, u, v, w, viewDependent, b.data());
      for (std::size_t q = 0; q < per; ++q) {
        worst = std::max(worst, static_cast<double>(std::fabs(a[q] - b[q])));
        peak = std::max(peak, static_cast<double>(std::fabs(a[q])));
      }
    }
  }
  prt::rttLookup(rtt, 0.5f, 0.5f, {0, 0, 1}, true, a.data());
  val out = val::object();
  out.set("order", rtt.order);
  out.set("channels", rtt.channels);
  out.set("spatial", rtt.spatial);
  out.set("views", rtt.views);
  out.set("layers", rtt.channels * t.layersPerChannel);
  out.set("size", t.size);
  out.set("worst", peak > 0.0 ? worst / peak : worst);
  out.set("peak", peak);
  out.set("first", val::array(std::vector<float>(a.begin(), a.begin() + static_cast<long>(std::min<std::size_t>(per, 4)))));
  return out;
}

// An RTT of the given shape with seeded values (for packing limits), as file bytes.
val syntheticRtt(int order, int channels, int spatial, int views, float scale) {
  prt::Rtt r;
  r.order = order;
  r.channels = channels;
  r.spatial = spatial;
  r.views = views;
  // Up to 64 M coefficients (256 MB): the test module's heap is not unlimited.
  if (r.coeffCount() == 0 || r.coeffCount() > (std::size_t{1} << 26)) return val(std::string("bad or too large RTT shape"));
  r.coeffs.resize(r.coeffCount());
  for (std::size_t i = 0; i < r.coeffs.size(); ++i) r.coeffs[i] = scale * std::sin(0.37f * static_cast<float>(i));
  std::vector<std::uint8_t> bytes;
  if (prt::Status s = prt::encodeRtt(r, &bytes); !s.isOk()) return val(s.toString());
  return val(emscripten::typed_memory_view(bytes.size(), bytes.data())).call<val>("slice");
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_rtt_core) {
  emscripten::function("rttTextureCheck", &rttTextureCheck);
  emscripten::function("syntheticRtt", &syntheticRtt);
}
