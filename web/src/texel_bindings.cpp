// Embind bindings of the GL-free transfer-texture code (texel_texture.h, prt/half_float.h) and a
// test helper that makes texel-only assets; compiled into both the browser module and the Node
// module the tests load (tests/web/texel_core_node_test.mjs, browser_texel_test.mjs).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <string>
#include <vector>

#include "prt/half_float.h"
#include "prt/asset.h"
#include "texel_texture.h"

using emscripten::val;

namespace {

std::vector<std::uint8_t> bytesFrom(const val& array) { return emscripten::convertJSArrayToNumberVector<std::uint8_t>(array); }

// A JS copy of `data` (a typed array of its element type): the vector dies with the call.
template <typename T>
val copyOut(const std::vector<T>& data) {
  return val(emscripten::typed_memory_view(data.size(), data.data())).call<val>("slice");
}

// Texel pass `kind` (by name) of the asset in `bytes`, decoded from its first `bands` bands (0:
// all) as the streaming client decodes it, and packed by packTexelTransfer against the given
// device limits: {order, channels, layersPerChannel, floats: the decoded pass (Float32Array),
// atlases: [{width, height, layers, halves: Uint16Array}]}, or a string naming the error.
val texelPackCheck(const val& bytes, const std::string& kind, int bands, int maxSize, int maxLayers) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::AssetSummary summary;
  if (prt::Status s = prt::peekAssetHeader(data, &summary); !s.isOk()) return val(s.toString());
  int index = -1;
  for (std::size_t i = 0; i < summary.passes.size(); ++i) {
    const prt::AssetPassInfo& p = summary.passes[i];
    if (p.domain == prt::TransferDomain::kTexel && kind == prt::transferKindName(p.kind)) index = static_cast<int>(i);
  }
  if (index < 0) return val("the asset has no texel pass '" + kind + "'");
  prt::BakedAsset atlases;
  if (prt::Status s = prt::decodeAssetAtlases(data, &atlases); !s.isOk()) return val(s.toString());
  prt::TransferPass pass;
  int order = 0;
  if (prt::Status s = prt::decodeAssetPass(data, index, bands, &pass, &order); !s.isOk()) return val(s.toString());
  prt::web::TexelTextures packed;
  if (prt::Status s = prt::web::packTexelTransfer(pass, order, atlases.atlases, maxSize, maxLayers, &packed); !s.isOk()) {
    return val(s.toString());
  }
  val out = val::object();
  out.set("order", packed.order);
  out.set("channels", packed.channels);
  out.set("layersPerChannel", packed.layersPerChannel);
  out.set("floats", copyOut(pass.coeffs));
  val list = val::array();
  for (const prt::web::TexelAtlasTexture& t : packed.atlases) {
    val a = val::object();
    a.set("width", t.width);
    a.set("height", t.height);
    a.set("layers", t.layers);
    a.set("halves", copyOut(t.halves));
    list.call<void>("push", a);
  }
  out.set("atlases", list);
  return out;
}

// floatToHalf over a list of numbers (read as float32): a Uint16Array.
val floatsToHalves(const val& values) {
  const std::vector<float> in = emscripten::convertJSArrayToNumberVector<float>(values);
  std::vector<std::uint16_t> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = prt::floatToHalf(in[i]);
  return copyOut(out);
}

// halfToFloat over a list of half bit patterns: a Float32Array.
val halvesToFloats(const val& halves) {
  const std::vector<std::uint16_t> in = emscripten::convertJSArrayToNumberVector<std::uint16_t>(halves);
  std::vector<float> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = prt::halfToFloat(in[i]);
  return copyOut(out);
}

// Tests: the asset in `bytes` with every vertex pass (and the specular materials only they use)
// removed, named `name` ("" keeps its name), re-encoded: a file whose only transfer is per
// texel (Uint8Array), or a string naming the error (no texel pass, a decode or encode failure).
val texelOnlyAsset(const val& bytes, const std::string& name) {
  prt::BakedAsset asset;
  if (prt::Status s = prt::decodeAsset(bytesFrom(bytes), &asset); !s.isOk()) return val(s.toString());
  if (!name.empty()) asset.name = name;
  std::erase_if(asset.passes, [](const prt::TransferPass& p) { return p.domain != prt::TransferDomain::kTexel; });
  if (asset.passes.empty()) return val(std::string("the asset has no texel pass"));
  // Specular materials stay only for a pass that shades with them (a TPFL visibility pass).
  const bool glossy = std::any_of(asset.passes.begin(), asset.passes.end(),
                                  [](const prt::TransferPass& p) { return p.form != prt::TransferForm::kVector; });
  if (!glossy) asset.specular.clear();
  std::vector<std::uint8_t> out;
  if (prt::Status s = prt::encodeAsset(asset, &out); !s.isOk()) return val(s.toString());
  return copyOut(out);
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_texel_core) {
  emscripten::function("texelPackCheck", &texelPackCheck);
  emscripten::function("floatsToHalves", &floatsToHalves);
  emscripten::function("halvesToFloats", &halvesToFloats);
  emscripten::function("texelOnlyAsset", &texelOnlyAsset);
}
