// Embind bindings of the GL-free shared code (asset decoding, SH evaluation, projection and
// rotation). Compiled into both the browser module and the Node module the tests load.
#include <emscripten/bind.h>
#include <emscripten/emscripten.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "client_limits.h"
#include "cpca_texture.h"
#include "cube_faces.h"
#include "analytic_lights.h"
#include "emitters.h"
#include "glossy_synthetic.h"
#include "glossy_fused.h"
#include "glossy_texture.h"
#include "prt/asset.h"
#include "prt/cube_sh_weights.h"
#include "prt/cubemap.h"
#include "prt/exit_radiance.h"
#include "prt/glossy_radiance.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "prt/sh_rotation.h"
#include "prt/sh_zonal.h"
#include "prt/transfer_codec.h"
#include "transfer_texture.h"

using emscripten::val;

namespace {

std::vector<std::uint8_t> bytesFrom(const val& array) {
  return emscripten::convertJSArrayToNumberVector<std::uint8_t>(array);
}

// {ok, error, order, vertices, triangles, name, passes:[{kind, domain, channels, bounces}]}, or with
// ok false the reader's named error.
val inspectAsset(const val& bytes) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::BakedAsset asset;
  val out = val::object();
  const prt::Status s = prt::decodeAsset(data, &asset);
  out.set("ok", s.isOk());
  out.set("error", s.isOk() ? std::string() : s.toString());
  if (!s.isOk()) return out;
  out.set("order", asset.shOrder);
  out.set("vertices", static_cast<double>(asset.positions.size()));
  out.set("triangles", static_cast<double>(asset.indices.size() / 3));
  out.set("name", asset.name);
  val passes = val::array();
  for (const prt::TransferPass& p : asset.passes) {
    val pass = val::object();
    pass.set("kind", std::string(prt::transferKindName(p.kind)));
    pass.set("domain", std::string(prt::transferDomainName(p.domain)));
    pass.set("channels", p.channels);
    pass.set("bounces", p.bounces);
    passes.call<void>("push", pass);
  }
  out.set("passes", passes);
  return out;
}

// Exit radiance of every vertex under constant unit radiance for `kind`, flat RGB: the same
// numbers `prt-bake shade --light constant` prints natively.
val shadeConstant(const val& bytes, const std::string& kind) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::BakedAsset asset;
  if (!prt::decodeAsset(data, &asset).isOk()) return val::null();
  for (const prt::TransferPass& p : asset.passes) {
    if (kind != prt::transferKindName(p.kind) || p.domain != prt::TransferDomain::kVertex) continue;
    const std::size_t n2 = static_cast<std::size_t>(prt::shCoeffCount(asset.shOrder));
    const float l0 = static_cast<float>(2.0 * std::sqrt(prt::kPi));  // radiance 1 everywhere
    const prt::Rgb lighting[] = {{l0, l0, l0}};
    std::vector<float> out(asset.positions.size() * 3);
    if (!prt::exitRadiance(p.coeffs, p.channels, n2, asset.albedo, lighting, out).isOk()) return val::null();
    return val::array(out);
  }
  return val::null();
}

// CPCA rendering on the CPU (cpca_texture.h's arithmetic of the two shaders) against the
// plain dot product with the expanded transfer, for pass `kind` of an asset whose pass is
// CPCA-encoded: {packed, expanded} exit radiance (flat RGB per vertex) under `lighting`
// (packLighting layout, kPackedLightingFloats floats, cut to displayOrder), or a string naming the error.
val cpcaRadianceCheck(const val& bytes, const std::string& kind, const val& lighting, int displayOrder) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  const std::vector<float> light = emscripten::convertJSArrayToNumberVector<float>(lighting);
  if (light.size() != static_cast<std::size_t>(prt::web::kPackedLightingFloats)) {
    return val("lighting must hold " + std::to_string(prt::web::kPackedLightingFloats) + " floats");
  }
  prt::BakedAsset asset;
  if (prt::Status s = prt::decodeAsset(data, &asset); !s.isOk()) return val(s.toString());
  for (const prt::TransferPass& p : asset.passes) {
    if (kind != prt::transferKindName(p.kind) || p.domain != prt::TransferDomain::kVertex) continue;
    if (p.encoded.empty()) return val(kind + " pass is float32, not CPCA");
    prt::CpcaTransfer cpca;
    if (prt::Status s = prt::decodeCpcaTransfer(p.encoded, asset.shOrder, &cpca); !s.isOk()) return val(s.toString());
    prt::web::CpcaTextures packed;
    if (prt::Status s = prt::web::packCpca(cpca, 16384, &packed); !s.isOk()) return val(s.toString());
    std::vector<float> albedo;
    for (const prt::Rgb& a : asset.albedo) albedo.insert(albedo.end(), {a.r, a.g, a.b});
    const std::vector<float> viaClusters = prt::web::cpcaRadiance(packed, light.data(), displayOrder, albedo);
    const std::size_t n2 = static_cast<std::size_t>(asset.shOrder * asset.shOrder);
    const std::size_t active = static_cast<std::size_t>(std::clamp(displayOrder, 1, asset.shOrder));
    std::vector<prt::Rgb> rgbLight(active * active);
    for (std::size_t i = 0; i < rgbLight.size(); ++i) rgbLight[i] = {light[i], light[prt::web::kMaxClientCoeffs + i], light[2 * prt::web::kMaxClientCoeffs + i]};
    std::vector<double> reference(asset.positions.size() * 3);
    if (prt::Status s = prt::exitRadianceDouble(p.coeffs, p.channels, n2, asset.albedo, rgbLight, reference); !s.isOk()) {
      return val(s.toString());
    }
    const std::vector<float> expanded(reference.begin(), reference.end());
    val out = val::object();
    out.set("packed", val::array(viaClusters));
    out.set("expanded", val::array(expanded));
    out.set("clusters", packed.clusters);
    out.set("weights", packed.weightCount);
    return out;
  }
  return val(std::string("the asset has no ") + kind + " pass");
}

// Benchmark: decodes a transfer-codec blob `repeats` times, each way the client can:
// {expand: seconds per decodeTransfer to floats, cpca: seconds per decodeCpcaTransfer +
// packCpca (direct rendering; null for other encodings), bytes, vertices}, or the error.
val timeTransferDecode(const val& bytes, int repeats) {
  const std::vector<std::uint8_t> blob = bytesFrom(bytes);
  prt::TransferBlobInfo info;
  if (prt::Status s = prt::readTransferBlobInfo(blob, &info); !s.isOk()) return val(s.toString());
  std::vector<float> floats;
  const double t0 = emscripten_get_now();
  for (int r = 0; r < repeats; ++r) {
    if (prt::Status s = prt::decodeTransfer(blob, info.order, &floats); !s.isOk()) return val(s.toString());
  }
  const double t1 = emscripten_get_now();
  val out = val::object();
  out.set("expand", (t1 - t0) / 1000.0 / repeats);
  out.set("cpca", val::null());
  if (info.encoding == prt::TransferEncoding::kCpca) {
    prt::CpcaTransfer cpca;
    prt::web::CpcaTextures packed;
    const double t2 = emscripten_get_now();
    for (int r = 0; r < repeats; ++r) {
      if (prt::Status s = prt::decodeCpcaTransfer(blob, info.order, &cpca); !s.isOk()) return val(s.toString());
      if (prt::Status s = prt::web::packCpca(cpca, 16384, &packed); !s.isOk()) return val(s.toString());
    }
    out.set("cpca", (emscripten_get_now() - t2) / 1000.0 / repeats);
  }
  out.set("bytes", static_cast<double>(blob.size()));
  out.set("vertices", static_cast<double>(info.vertexCount));
  return out;
}

// Glossy rendering on the CPU (glossy_texture.h's emulation of glossy_table.vert,
// glossy_transfer.vert and glossy.vert from the packed textures) against prt::glossyExitRadiance on the expanded
// matrices (float and double accumulation), for a synthetic CPCA matrix pass (glossy_synthetic.h)
// on `vertices` random points and normals: spec {bands, channels, packing ("full" |
// "symmetric"), clusters, vectors, weightBits, seed}, eye [x, y, z], lighting (packLighting
// layout, kPackedLightingFloats floats), `activeBands` displayed. Returns {emulated, reference,
// referenceDouble, basisExact} (flat RGB per vertex) or a string naming the error.
val glossySyntheticCheck(const val& spec, int vertices, const val& eye, const val& lighting, int activeBands, bool fresnel) {
  prt::web::SyntheticGlossySpec s;
  s.bands = spec["bands"].as<int>();
  s.channels = spec["channels"].as<int>();
  s.packing = spec["packing"].as<std::string>() == "symmetric" ? prt::MatrixPacking::kSymmetric : prt::MatrixPacking::kFull;
  s.clusters = spec["clusters"].as<int>();
  s.vectors = spec["vectors"].as<int>();
  s.weightBits = spec["weightBits"].as<int>();
  s.seed = static_cast<std::uint64_t>(spec["seed"].as<double>());
  const std::vector<float> light = emscripten::convertJSArrayToNumberVector<float>(lighting);
  const std::vector<float> e = emscripten::convertJSArrayToNumberVector<float>(eye);
  if (light.size() != static_cast<std::size_t>(prt::web::kPackedLightingFloats) || e.size() != 3 || vertices < 1) {
    return val(std::string("lighting must hold kPackedLightingFloats floats, eye 3, vertices >= 1"));
  }
  if (activeBands < 1 || activeBands > s.bands) return val(std::string("activeBands must be 1 .. bands"));
  prt::CpcaMatrixTransfer cpca;
  if (prt::Status st = prt::web::makeSyntheticCpcaMatrix(s, static_cast<std::uint32_t>(vertices), &cpca); !st.isOk()) return val(st.toString());
  // Geometry and materials from the same seed: points in a unit box, unit normals, f0 and
  // exponents over the range materials use (dielectric to metal, s from 0 to 200).
  std::uint64_t state = s.seed * 7919u + 17u;
  auto next = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>(state >> 40) / static_cast<float>(1u << 24);
  };
  std::vector<prt::Vec3> positions(static_cast<std::size_t>(vertices)), normals(positions.size());
  std::vector<prt::SpecularMaterial> specular(positions.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    positions[v] = {2 * next() - 1, 2 * next() - 1, 2 * next() - 1};
    prt::Vec3 n{2 * next() - 1, 2 * next() - 1, 2 * next() - 1};
    if (prt::length(n) < 1e-3f) n = {0, 0, 1};
    normals[v] = n * (1.0f / prt::length(n));
    specular[v] = {{0.04f + 0.96f * next(), 0.04f + 0.96f * next(), 0.04f + 0.96f * next()}, 200.0f * next() * next()};
  }
  prt::web::GlossyTextures packed;
  if (prt::Status st = prt::web::packGlossy(cpca, specular, 16384, &packed); !st.isOk()) return val(st.toString());
  const prt::Vec3 eyePoint{e[0], e[1], e[2]};
  const std::vector<float> table = prt::web::glossyTableCpu(packed, light.data(), activeBands);
  const std::vector<float> transfer = prt::web::glossyTransferCpu(packed, table, activeBands);
  const std::vector<float> emulated = prt::web::glossyRadianceCpu(packed, transfer, activeBands, positions, normals, eyePoint, fresnel);
  // The fused step (glossy_fused.h) at group sizes 1, 3 and 8: the same radiance from the table.
  val fused = val::object();
  for (int size : {1, 3, prt::web::kMaxGlossyGroup}) {
    prt::web::GlossyGroups groups;
    if (prt::Status st = prt::web::groupGlossyVertices(packed.clusterOf, packed.clusters, size, &groups); !st.isOk()) return val(st.toString());
    fused.set(std::to_string(size),
              val::array(prt::web::glossyFusedCpu(packed, groups, table, activeBands, positions, normals, eyePoint, fresnel)));
  }
  std::vector<float> expanded(static_cast<std::size_t>(vertices) * static_cast<std::size_t>(s.channels) * prt::matrixEntryCount(s.bands, s.packing));
  if (prt::Status st = prt::cpcaMatrixReconstruct(cpca, expanded); !st.isOk()) return val(st.toString());
  std::vector<float> local;
  if (prt::Status st = prt::web::expandCpcaMatrix(cpca, &local); !st.isOk()) return val(st.toString());
  std::vector<prt::Rgb> rgb(static_cast<std::size_t>(activeBands * activeBands));
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    rgb[i] = {light[i], light[prt::web::kMaxClientCoeffs + i], light[2 * prt::web::kMaxClientCoeffs + i]};
  }
  const prt::GlossyView view{eyePoint, fresnel};
  std::vector<float> reference(3 * positions.size());
  std::vector<double> referenceDouble(3 * positions.size());
  if (prt::Status st = prt::glossyExitRadiance(expanded, s.bands, s.packing, s.channels, positions, normals, specular, view, rgb, reference);
      !st.isOk()) {
    return val(st.toString());
  }
  if (prt::Status st = prt::glossyExitRadianceDouble(expanded, s.bands, s.packing, s.channels, positions, normals, specular, view, rgb,
                                                     referenceDouble);
      !st.isOk()) {
    return val(st.toString());
  }
  // The shader's SH evaluation against the shared one, bit for bit, at every reflected direction.
  bool basisExact = true;
  for (std::size_t v = 0; v < positions.size() && basisExact; ++v) {
    float a[64], b[64];
    prt::web::glossyShBasis(s.bands, normals[v], a);
    prt::evalShBasisUnchecked(s.bands, normals[v], b);
    for (int i = 0; i < s.bands * s.bands; ++i) basisExact = basisExact && a[i] == b[i];
  }
  val out = val::object();
  out.set("emulated", val::array(emulated));
  out.set("fused", fused);
  out.set("reference", val::array(reference));
  out.set("referenceDouble", val::array(std::vector<float>(referenceDouble.begin(), referenceDouble.end())));
  out.set("basisExact", basisExact);
  out.set("expansionsAgree", local == expanded);  // glossy_synthetic's expansion is the codec's, bit for bit
  out.set("tableTexels", packed.tableTexels);
  return out;
}

// groupGlossyVertices (glossy_fused.h) on cluster ids `clusterOf`: {size, cluster, members,
// slot} as arrays and {groupSize}, glossyGroupSize for these ids at `vectors` and `rowTexels`;
// or a string naming the error. Safe on any ids.
val glossyGroups(const val& clusterOf, int clusters, int size, int vectors, int rowTexels) {
  const std::vector<double> raw = emscripten::convertJSArrayToNumberVector<double>(clusterOf);
  std::vector<std::uint16_t> ids(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!(raw[i] >= 0 && raw[i] <= 65535)) return val(std::string("cluster ids must be 0 .. 65535"));
    ids[i] = static_cast<std::uint16_t>(raw[i]);
  }
  prt::web::GlossyGroups g;
  if (prt::Status s = prt::web::groupGlossyVertices(ids, clusters, size, &g); !s.isOk()) return val(s.toString());
  val out = val::object();
  out.set("size", g.size);
  out.set("cluster", val::array(g.cluster));
  out.set("members", val::array(g.members));
  out.set("slot", val::array(g.slot));
  out.set("groupSize", prt::web::glossyGroupSize(ids.size(), static_cast<std::size_t>(std::max(clusters, 1)), vectors, rowTexels));
  return out;
}

// Glossy exit radiance of an asset's matrix pass `kind` toward eye [x, y, z] under `lighting`
// (flat RGB per coefficient, bands^2 rows, bands <= the baked order): {reference} from
// prt::glossyExitRadiance on the pass's full decode (decodeAsset), and for a CPCA pass
// {emulated} from the client's packed textures (glossy_texture.h, the shaders' arithmetic) and
// {reconstructed} from glossyExitRadiance on cpcaMatrixReconstruct; flat RGB per vertex, or a
// string naming the error.
val glossyAssetCheck(const val& bytes, const std::string& kind, const val& lighting, const val& eye, bool fresnel) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  const std::vector<float> flat = emscripten::convertJSArrayToNumberVector<float>(lighting);
  const std::vector<float> e = emscripten::convertJSArrayToNumberVector<float>(eye);
  if (e.size() != 3 || flat.empty() || flat.size() % 3 != 0) return val(std::string("eye must hold 3 numbers, lighting RGB rows"));
  prt::BakedAsset asset;
  if (prt::Status s = prt::decodeAsset(data, &asset); !s.isOk()) return val(s.toString());
  const prt::TransferPass* p = nullptr;
  for (const prt::TransferPass& q : asset.passes)
    if (q.form == prt::TransferForm::kMatrix && kind == prt::transferKindName(q.kind)) p = &q;
  if (!p) return val("the asset has no " + kind + " matrix pass");
  std::vector<prt::Rgb> rgb(flat.size() / 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  const int bands = static_cast<int>(std::lround(std::sqrt(static_cast<double>(rgb.size()))));
  const prt::MatrixPacking packing = prt::matrixPackingFor(p->kind, asset.lighting.model);
  const prt::GlossyView view{{e[0], e[1], e[2]}, fresnel};
  std::vector<float> reference(3 * asset.positions.size());
  if (prt::Status s = prt::glossyExitRadiance(p->coeffs, asset.shOrder, packing, p->channels, asset.positions, asset.normals, asset.specular,
                                              view, rgb, reference);
      !s.isOk()) {
    return val(s.toString());
  }
  val out = val::object();
  out.set("reference", val::array(reference));
  prt::TransferBlobInfo info;
  if (!p->encoded.empty() && prt::readTransferBlobInfo(p->encoded, &info).isOk() && info.encoding == prt::TransferEncoding::kCpca) {
    prt::CpcaMatrixTransfer cpca;
    if (prt::Status s = prt::decodeCpcaMatrixTransfer(p->encoded, bands, &cpca); !s.isOk()) return val(s.toString());
    prt::web::GlossyTextures packed;
    if (prt::Status s = prt::web::packGlossy(cpca, asset.specular, 16384, &packed); !s.isOk()) return val(s.toString());
    float light[prt::web::kPackedLightingFloats] = {};
    for (std::size_t i = 0; i < rgb.size(); ++i) {
      light[i] = rgb[i].r;
      light[prt::web::kMaxClientCoeffs + i] = rgb[i].g;
      light[2 * prt::web::kMaxClientCoeffs + i] = rgb[i].b;
    }
    const std::vector<float> table = prt::web::glossyTableCpu(packed, light, bands);
    const std::vector<float> transfer = prt::web::glossyTransferCpu(packed, table, bands);
    out.set("emulated", val::array(prt::web::glossyRadianceCpu(packed, transfer, bands, asset.positions, asset.normals, view.eye, fresnel)));
    std::vector<float> expanded(asset.positions.size() * static_cast<std::size_t>(cpca.channels) * prt::matrixEntryCount(bands, packing));
    if (prt::Status s = prt::cpcaMatrixReconstruct(cpca, expanded); !s.isOk()) return val(s.toString());
    std::vector<float> local;
    if (prt::Status s = prt::web::expandCpcaMatrix(cpca, &local); !s.isOk()) return val(s.toString());
    out.set("expansionsAgree", local == expanded);
    std::vector<float> reconstructed(3 * asset.positions.size());
    if (prt::Status s = prt::glossyExitRadiance(expanded, bands, packing, cpca.channels, asset.positions, asset.normals, asset.specular, view,
                                                rgb, reconstructed);
        !s.isOk()) {
      return val(s.toString());
    }
    out.set("reconstructed", val::array(reconstructed));
    out.set("clusters", static_cast<int>(cpca.clusterCount));
    out.set("vectors", cpca.vectors);
  }
  return out;
}

val evalBasis(int order, float x, float y, float z) {
  std::vector<float> out(static_cast<std::size_t>(prt::shCoeffCount(std::max(1, std::min(order, prt::kMaxShOrder)))));
  const prt::Status s = prt::evalShBasis(order, {x, y, z}, out);
  if (!s.isOk()) return val(s.toString());
  return val::array(out);
}

// Rotates flat coefficients (one channel) by a row-major 3x3 matrix.
val rotateCoefficients(int order, const val& coeffs, const val& matrix) {
  const std::vector<float> in = emscripten::convertJSArrayToNumberVector<float>(coeffs);
  const std::vector<float> m = emscripten::convertJSArrayToNumberVector<float>(matrix);
  if (m.size() != 9) return val(std::string("matrix must hold 9 values"));
  prt::Mat3 r;
  for (int i = 0; i < 9; ++i) r.m[i / 3][i % 3] = m[static_cast<std::size_t>(i)];
  prt::ShRotation rot;
  if (prt::Status s = prt::ShRotation::make(order, r, &rot); !s.isOk()) return val(s.toString());
  std::vector<float> out(in.size());
  if (prt::Status s = rot.apply(in, out); !s.isOk()) return val(s.toString());
  return val::array(out);
}

// Projects a cube map given as 6 faces of size*size*3 floats (GL order), returns flat RGB.
val projectCube(int order, int size, const val& faces) {
  prt::CubeMap cube;
  cube.size = size;
  for (int f = 0; f < 6; ++f) cube.faces[static_cast<std::size_t>(f)] = emscripten::convertJSArrayToNumberVector<float>(faces[f]);
  std::vector<prt::Rgb> c;
  if (prt::Status s = prt::projectCubeMap(order, cube, &c); !s.isOk()) return val(s.toString());
  std::vector<float> flat;
  for (const prt::Rgb& v : c) flat.insert(flat.end(), {v.r, v.g, v.b});
  return val::array(flat);
}

// Radiance SH of a uniform circular light: radiance `radiance` inside the cap of half-angle
// zeta (radians) about axis (x, y, z): zonalCircularLight placed on the axis. Flat, one
// channel, order^2 values; or the error. The analytic reference for a sphere light seen
// from outside (zeta = asin(radius / distance)).
val circularLightSH(int order, float zeta, float radiance, float x, float y, float z) {
  if (prt::Status s = prt::checkShOrder(order); !s.isOk()) return val(s.toString());
  std::vector<float> zonal(static_cast<std::size_t>(order));
  std::vector<float> out(static_cast<std::size_t>(prt::shCoeffCount(order)));
  if (prt::Status s = prt::zonalCircularLight(order, zeta, radiance, zonal); !s.isOk()) return val(s.toString());
  if (prt::Status s = prt::placeZonal(order, zonal, {x, y, z}, out); !s.isOk()) return val(s.toString());
  return val::array(out);
}

// parseEmitters on a flat array: {error, count, emitters: [{shape, position, radiance,
// normal, u, v, bounds}]} (the frame and bounds the renderer uses).
val parseLights(const val& flat, int meshCount) {
  const std::vector<float> data = emscripten::convertJSArrayToNumberVector<float>(flat);
  std::vector<prt::web::Emitter> emitters;
  val out = val::object();
  const std::string error = prt::web::parseEmitters(data, meshCount, &emitters);
  out.set("error", error);
  out.set("count", static_cast<int>(emitters.size()));
  val list = val::array();
  auto vec = [](prt::Vec3 v) { return val::array(std::vector<float>{v.x, v.y, v.z}); };
  for (const prt::web::Emitter& e : emitters) {
    val item = val::object();
    item.set("shape", static_cast<int>(e.shape));
    item.set("position", vec(e.position));
    item.set("normal", vec(e.normal));
    item.set("radiance", val::array(std::vector<float>{e.radiance.r, e.radiance.g, e.radiance.b}));
    const prt::web::EmitterFrame f = prt::web::emitterFrame(e.normal);
    item.set("u", vec(f.u));
    item.set("v", vec(f.v));
    const prt::web::BoundingSphere b = prt::web::emitterBounds(e, {});
    item.set("boundsRadius", b.radius);
    list.call<void>("push", item);
  }
  out.set("emitters", list);
  return out;
}

// The analytic path's SH of lights `flat` (16 floats each, no meshes) seen from c at `order`,
// summed with their radiance: flat [r,g,b] per coefficient, or an error string.
val analyticLightSH(const val& flat, const val& c, int order) {
  const std::vector<float> data = emscripten::convertJSArrayToNumberVector<float>(flat);
  const std::vector<float> cv = emscripten::convertJSArrayToNumberVector<float>(c);
  if (cv.size() != 3) return val(std::string("c must hold 3 numbers"));
  std::vector<prt::web::Emitter> emitters;
  if (std::string e = prt::web::parseEmitters(data, 0, &emitters); !e.empty()) return val(e);
  prt::web::AnalyticLights lights;
  if (prt::Status s = lights.setView({cv[0], cv[1], cv[2]}, order); !s.isOk()) return val(s.toString());
  lights.setEmitters(emitters, data);
  std::vector<float> packed(prt::web::kPackedLightingFloats);
  lights.update(packed.data());
  std::vector<float> out;
  for (int i = 0; i < order * order; ++i)
    for (int ch = 0; ch < 3; ++ch) out.push_back(packed[static_cast<std::size_t>(ch * prt::web::kMaxClientCoeffs + i)]);
  return val::array(out);
}

// Where world point p lands on light-cube face `face` seen from c: [s, t, depth] (NDC).
val cubeFaceProject(int face, const val& c, const val& p) {
  if (face < 0 || face > 5) return val(std::string("face must be 0..5"));
  const std::vector<float> cv = emscripten::convertJSArrayToNumberVector<float>(c);
  const std::vector<float> pv = emscripten::convertJSArrayToNumberVector<float>(p);
  if (cv.size() != 3 || pv.size() != 3) return val(std::string("c and p must hold 3 numbers"));
  const glm::mat4 m = prt::web::cubeFaceViewProjection(face, {cv[0], cv[1], cv[2]}, 0.01f);
  const glm::vec4 clip = m * glm::vec4(pv[0], pv[1], pv[2], 1.0f);
  return val::array(std::vector<float>{clip.x / clip.w, clip.y / clip.w, clip.z / clip.w});
}

bool sphereTouchesCubeFace(int face, const val& c, const val& center, float radius) {
  const std::vector<float> cv = emscripten::convertJSArrayToNumberVector<float>(c);
  const std::vector<float> sv = emscripten::convertJSArrayToNumberVector<float>(center);
  if (face < 0 || face > 5 || cv.size() != 3 || sv.size() != 3) return true;
  return prt::web::sphereTouchesCubeFace(face, {cv[0], cv[1], cv[2]}, {{sv[0], sv[1], sv[2]}, radius});
}

// sphereFaceRect: [x0, y0, x1, y1] inclusive (empty: x1 < x0).
val sphereFaceRect(int face, const val& c, const val& center, float radius, int size) {
  const std::vector<float> cv = emscripten::convertJSArrayToNumberVector<float>(c);
  const std::vector<float> sv = emscripten::convertJSArrayToNumberVector<float>(center);
  if (face < 0 || face > 5 || cv.size() != 3 || sv.size() != 3 || size < 1) return val(std::string("bad arguments"));
  const prt::web::FaceRect r = prt::web::sphereFaceRect(face, {cv[0], cv[1], cv[2]}, {{sv[0], sv[1], sv[2]}, radius}, size);
  return val::array(std::vector<int>{r.x0, r.y0, r.x1, r.y1});
}

// The six faces decoded from an RGBE8 atlas (3 size x 2 size RGBA bytes), flat per face.
val decodeRgbeAtlas(int size, const val& bytes) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::CubeMap cube;
  if (prt::Status s = prt::web::cubeMapFromRgbeAtlas(size, data, &cube); !s.isOk()) return val(s.toString());
  val faces = val::array();
  for (const auto& f : cube.faces) faces.call<void>("push", val::array(f));
  return faces;
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_core) {
  // The client's order limit and the packLighting layout's size (client_limits.h).
  emscripten::constant("kMaxClientOrder", prt::web::kMaxClientOrder);
  emscripten::constant("kPackedLightingFloats", prt::web::kPackedLightingFloats);
  emscripten::function("circularLightSH", &circularLightSH);
  emscripten::function("parseLights", &parseLights);
  emscripten::function("analyticLightSH", &analyticLightSH);
  emscripten::function("cubeFaceProject", &cubeFaceProject);
  emscripten::function("sphereTouchesCubeFace", &sphereTouchesCubeFace);
  emscripten::function("decodeRgbeAtlas", &decodeRgbeAtlas);
  emscripten::function("sphereFaceRect", &sphereFaceRect);
  emscripten::function("inspectAsset", &inspectAsset);
  emscripten::function("shadeConstant", &shadeConstant);
  emscripten::function("cpcaRadianceCheck", &cpcaRadianceCheck);
  emscripten::function("timeTransferDecode", &timeTransferDecode);
  emscripten::function("glossySyntheticCheck", &glossySyntheticCheck);
  emscripten::function("glossyAssetCheck", &glossyAssetCheck);
  emscripten::function("glossyGroups", &glossyGroups);
  emscripten::constant("kMaxGlossyOrder", prt::web::kMaxGlossyOrder);
  emscripten::function("evalBasis", &evalBasis);
  emscripten::function("rotateCoefficients", &rotateCoefficients);
  emscripten::function("projectCube", &projectCube);
}
