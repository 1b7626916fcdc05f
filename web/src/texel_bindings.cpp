// Embind bindings of the GL-free transfer-texture code (texel_texture.h, prt/half_float.h) and a
// test helper that makes texel-only assets; compiled into both the browser module and the Node
// module the tests load (tests/web/texel_core_node_test.mjs, browser_texel_test.mjs).
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/glossy_radiance.h"
#include "prt/half_float.h"
#include "texel_glossy.h"
#include "texel_texture.h"
#include "transfer_texture.h"

using emscripten::val;

namespace {

std::vector<std::uint8_t> bytesFrom(const val& array) { return emscripten::convertJSArrayToNumberVector<std::uint8_t>(array); }

// A JS copy of `data` (a typed array of its element type): the vector dies with the call.
template <typename T>
val copyOut(const std::vector<T>& data) {
  return val(emscripten::typed_memory_view(data.size(), data.data())).call<val>("slice");
}

// Packed atlas textures as JS: [{width, height, layers, halves: Uint16Array}].
val atlasTextures(const std::vector<prt::web::TexelAtlasTexture>& textures) {
  val list = val::array();
  for (const prt::web::TexelAtlasTexture& t : textures) {
    val a = val::object();
    a.set("width", t.width);
    a.set("height", t.height);
    a.set("layers", t.layers);
    a.set("halves", copyOut(t.halves));
    list.call<void>("push", a);
  }
  return list;
}

// Texel pass `kind` (by name; "visibility": the TPFL visibility pass) of the asset in `bytes`, decoded from its first `bands` bands (0:
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
    const bool visibility = p.form == prt::TransferForm::kVisibility;
    if (p.domain == prt::TransferDomain::kTexel && (visibility ? kind == "visibility" : kind == prt::transferKindName(p.kind))) {
      index = static_cast<int>(i);
    }
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
  out.set("atlases", atlasTextures(packed.atlases));
  return out;
}

// The asset's texel normals as the client uploads them (packTexelNormals), with what they came
// from: {codes: Int16Array (2 per texel), coverage: Uint8Array, atlases: [{width, height, layers (1),
// halves: Uint16Array (RGBA per texel)}]}, or a string naming the error. `maxSize` as the
// device's MAX_TEXTURE_SIZE; `dropCodes` > 0 removes that many codes first (a refusal test).
val texelNormalsPackCheck(const val& bytes, int maxSize, int dropCodes) {
  prt::BakedAsset atlases;
  if (prt::Status s = prt::decodeAssetAtlases(bytesFrom(bytes), &atlases); !s.isOk()) return val(s.toString());
  if (atlases.texelNormals.empty()) return val(std::string("the asset has no texel normals"));
  std::vector<std::int16_t> codes = atlases.texelNormals;
  codes.resize(codes.size() - std::min(codes.size(), static_cast<std::size_t>(std::max(dropCodes, 0))));
  std::vector<prt::web::TexelAtlasTexture> packed;
  if (prt::Status s = prt::web::packTexelNormals(codes, atlases.texelCoverage, atlases.atlases, maxSize, &packed); !s.isOk()) {
    return val(s.toString());
  }
  val out = val::object();
  out.set("codes", copyOut(atlases.texelNormals));
  out.set("coverage", copyOut(atlases.texelCoverage));
  out.set("atlases", atlasTextures(packed));
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

// The TPFL glossy term at given texels of the asset in `bytes` two ways: texel_prt.frag's
// arithmetic on the packed textures (tpflGlossyCpu on the RGBA16F visibility layers read at the
// texel, exactly its centre, and packTpflProduct's texture) and prt::tpflGlossyExitRadiance on
// the decoded float visibility. `texels`: 9 numbers per texel (atlas, x, y, position xyz,
// normal xyz), `eye` xyz, `lighting` bands^2 RGB. A texel's material is that of the vertex
// nearest its position (exact where materials are constant per object, as in the default
// room); among the vertices whose normal is within 45 degrees of the texel's, so a sphere's texel
// touching the floor does not take the floor's material. Returns {gpu: Float32Array, reference: Float32Array (3 per texel), visibilityOrder,
// transferOrder, rowTexels, layers}, or a string naming the error.
val tpflTexelCheck(const val& bytes, const val& texelsIn, const val& eyeIn, const val& lightingIn, int bands) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  const std::vector<float> texels = emscripten::convertJSArrayToNumberVector<float>(texelsIn);
  const std::vector<float> eyeXyz = emscripten::convertJSArrayToNumberVector<float>(eyeIn);
  const std::vector<float> flat = emscripten::convertJSArrayToNumberVector<float>(lightingIn);
  if (texels.size() % 9 != 0 || eyeXyz.size() != 3 || flat.size() != static_cast<std::size_t>(3 * bands * bands)) {
    return val(std::string("tpflTexelCheck: 9 numbers per texel, an eye, bands^2 RGB lighting"));
  }
  prt::BakedAsset asset;
  if (prt::Status s = prt::decodeAsset(data, &asset); !s.isOk()) return val(s.toString());
  const prt::TransferPass* visibility = nullptr;
  for (const prt::TransferPass& p : asset.passes) {
    if (p.form == prt::TransferForm::kVisibility) visibility = &p;
  }
  if (!visibility) return val(std::string("the asset has no visibility pass"));
  if (asset.specular.size() != asset.positions.size()) return val(std::string("the asset has no specular materials"));
  prt::web::TexelTextures packed;
  if (prt::Status s = prt::web::packTexelTransfer(*visibility, visibility->order, asset.atlases, 16384, 2048, &packed); !s.isOk()) {
    return val(s.toString());
  }
  const int m = visibility->order, t = prt::web::tpflTransferOrder(bands, m);
  prt::ShTripleProduct product;
  if (prt::Status s = prt::ShTripleProduct::make(bands, t, &product); !s.isOk()) return val(s.toString());
  std::vector<prt::Rgb> lighting(static_cast<std::size_t>(bands * bands));
  for (std::size_t i = 0; i < lighting.size(); ++i) lighting[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  prt::web::TpflProductTexture texture;
  if (prt::Status s = prt::web::packTpflProduct(product, lighting, &texture); !s.isOk()) return val(s.toString());
  const std::size_t count = texels.size() / 9, m2 = static_cast<std::size_t>(m) * m, t2 = static_cast<std::size_t>(t) * t;
  const int layers = prt::web::texelsForOrder(std::min(m, t));
  std::vector<float> gpu(3 * count), reference(3 * count), cut(count * t2, 0.0f);
  std::vector<prt::Vec3> positions(count), normals(count);
  std::vector<prt::SpecularMaterial> materials(count);
  const prt::Vec3 eye{eyeXyz[0], eyeXyz[1], eyeXyz[2]};
  for (std::size_t k = 0; k < count; ++k) {
    const float* in = &texels[9 * k];
    const auto atlas = static_cast<std::size_t>(in[0]);
    const auto x = static_cast<std::size_t>(in[1]), y = static_cast<std::size_t>(in[2]);
    if (atlas >= packed.atlases.size()) return val(std::string("tpflTexelCheck: atlas out of range"));
    const prt::web::TexelAtlasTexture& a = packed.atlases[atlas];
    const std::size_t w = static_cast<std::size_t>(a.width), h = static_cast<std::size_t>(a.height);
    if (x >= w || y >= h) return val(std::string("tpflTexelCheck: texel out of range"));
    std::size_t first = 0;
    for (std::size_t b = 0; b < atlas; ++b) first += static_cast<std::size_t>(packed.atlases[b].width) * packed.atlases[b].height;
    positions[k] = {in[3], in[4], in[5]};
    normals[k] = {in[6], in[7], in[8]};
    std::size_t nearest = 0;
    float best = INFINITY;
    for (std::size_t v = 0; v < asset.positions.size(); ++v) {
      const prt::Vec3 d = asset.positions[v] - positions[k];
      const float d2 = prt::dot(d, d);
      if (d2 < best && prt::dot(asset.normals[v], normals[k]) > 0.7071f) best = d2, nearest = v;
    }
    materials[k] = asset.specular[nearest];
    // The shader's view of the texel: its RGBA16F layers at the texel centre (no filtering).
    std::vector<float> v(4 * static_cast<std::size_t>(layers));
    for (int l = 0; l < layers; ++l) {
      for (int q = 0; q < 4; ++q) {
        v[4 * static_cast<std::size_t>(l) + q] = prt::halfToFloat(a.halves[((static_cast<std::size_t>(l) * h + y) * w + x) * 4 + q]);
      }
    }
    const prt::SpecularMaterial& mat = materials[k];
    const float spec[5] = {mat.f0.r, mat.f0.g, mat.f0.b, mat.exponent, mat.f90};
    prt::web::tpflGlossyCpu(texture, v.data(), layers, positions[k], normals[k], spec, eye, true, &gpu[3 * k]);
    std::copy_n(&visibility->coeffs[(first + y * w + x) * m2], std::min(m2, t2), &cut[k * t2]);
  }
  if (prt::Status s = prt::tpflGlossyExitRadiance(product, cut, positions, normals, materials, prt::GlossyView{eye, true}, lighting,
                                                  reference);
      !s.isOk()) {
    return val(s.toString());
  }
  val out = val::object();
  out.set("gpu", copyOut(gpu));
  out.set("reference", copyOut(reference));
  out.set("visibilityOrder", m);
  out.set("transferOrder", t);
  out.set("rowTexels", texture.rowTexels);
  out.set("layers", layers);
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_texel_core) {
  emscripten::function("texelPackCheck", &texelPackCheck);
  emscripten::function("floatsToHalves", &floatsToHalves);
  emscripten::function("halvesToFloats", &halvesToFloats);
  emscripten::function("texelOnlyAsset", &texelOnlyAsset);
  emscripten::function("tpflTexelCheck", &tpflTexelCheck);
  emscripten::function("texelNormalsPackCheck", &texelNormalsPackCheck);
}
