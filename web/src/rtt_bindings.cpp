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
#include "bi_scale_texture.h"
#include "prt/sh_rotation.h"
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

// The bi-scale rotation step on the CPU (packBiScaleRotations + biScaleRotateCpu, which the
// GPU's rotation step is checked against in the page) against prt::ShRotation::apply of the
// frame's rotation, for `count` seeded frames (some with tangents off by up to 1e-3, as the
// asset allows) and transferred radiance vectors of `bands` bands in rows of `rowTexels`:
// {worst, peak, zeroTail (the largest |value| beyond bands^2, which must be 0)}, or an error.
val biScaleRotateCheck(int bands, int rowTexels, int count, int seed) {
  std::uint32_t state = static_cast<std::uint32_t>(seed) * 2654435761u + 1u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / static_cast<float>(1u << 24) * 2.0f - 1.0f;
  };
  std::vector<prt::Vec3> normals(static_cast<std::size_t>(count)), tangents(normals.size());
  for (std::size_t v = 0; v < normals.size(); ++v) {
    prt::Vec3 n{next(), next(), next()};
    n = n * (1.0f / prt::length(n));
    prt::Vec3 t = prt::cross(n, prt::Vec3{next(), next(), next()});
    t = t * (1.0f / prt::length(t));
    if (v % 2) t = t + n * 1e-3f;  // as far off as the asset allows
    normals[v] = n;
    tangents[v] = t;
  }
  prt::web::BiScaleRotations rotations;
  if (prt::Status s = prt::web::packBiScaleRotations(normals, tangents, bands, &rotations); !s.isOk()) return val(s.toString());
  const std::size_t stride = static_cast<std::size_t>(rowTexels) * 4, n2 = static_cast<std::size_t>(bands * bands);
  std::vector<float> transfer(3 * normals.size() * stride, 0.0f), rotated(transfer.size());
  for (std::size_t r = 0; r < 3 * normals.size(); ++r)
    for (std::size_t i = 0; i < n2; ++i) transfer[r * stride + i] = next();
  prt::web::biScaleRotateCpu(rotations, transfer, count, rowTexels, rotated);
  double worst = 0.0, peak = 0.0, tail = 0.0;
  std::vector<float> expected(n2);
  for (int c = 0; c < 3; ++c)
    for (std::size_t v = 0; v < normals.size(); ++v) {
      const prt::Vec3 n = normals[v];
      prt::Vec3 t = tangents[v] - n * prt::dot(tangents[v], n);
      t = t * (1.0f / prt::length(t));
      const prt::Vec3 rows[3] = {t, prt::cross(n, t), n};
      prt::Mat3 m;
      for (int i = 0; i < 3; ++i) m.m[i][0] = rows[i].x, m.m[i][1] = rows[i].y, m.m[i][2] = rows[i].z;
      prt::ShRotation rotation;
      if (prt::Status s = prt::ShRotation::make(bands, m, &rotation); !s.isOk()) return val(s.toString());
      const std::size_t row = (static_cast<std::size_t>(c) * normals.size() + v) * stride;
      if (prt::Status s = rotation.apply(std::span<const float>(&transfer[row], n2), expected); !s.isOk()) return val(s.toString());
      for (std::size_t i = 0; i < n2; ++i) {
        worst = std::max(worst, static_cast<double>(std::fabs(expected[i] - rotated[row + i])));
        peak = std::max(peak, static_cast<double>(std::fabs(expected[i])));
      }
      for (std::size_t i = n2; i < stride; ++i) tail = std::max(tail, static_cast<double>(std::fabs(rotated[row + i])));
    }
  val out = val::object();
  out.set("worst", worst);
  out.set("peak", peak);
  out.set("zeroTail", tail);
  out.set("mainLength", static_cast<int>(prt::web::biScaleRotateMain(bands, rowTexels).size()));
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_rtt_core) {
  emscripten::function("biScaleRotateCheck", &biScaleRotateCheck);
  emscripten::function("rttTextureCheck", &rttTextureCheck);
  emscripten::function("syntheticRtt", &syntheticRtt);
}
