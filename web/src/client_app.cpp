#include "client_app.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bi_scale_texture.h"
#include "glossy_synthetic.h"
#include "glossy_texture.h"
#include "prt/glossy_radiance.h"
#include "prt/sh_basis.h"
#include "prt/sh_rotation.h"
#include "transfer_texture.h"

namespace prt::web {

ClientApp::ClientApp(const GlContextOptions& options) {
  if (std::string e = context_.create(options); !e.empty()) {
    error_ = std::move(e);
    return;
  }
  if (Status s = renderer_.init(); !s.isOk()) {
    error_ = s.message();
    return;
  }
  // Float render targets (the light cube, the GPU projection); without them the cube is
  // RGBE8 and projected on the CPU.
  const bool floatTargets = context_.enableExtension("EXT_color_buffer_float");
  if (Status s = lights_.init(floatTargets); !s.isOk()) error_ = s.message();
  setWhiteFurnace(1.0f);
}

void ClientApp::makeCurrent() const { context_.makeCurrent(); }

std::uint8_t* ClientApp::reserveAsset(std::size_t bytes) {
  pending_.clear();
  pending_.shrink_to_fit();
  try {
    pending_.resize(bytes);
  } catch (...) {
    return nullptr;
  }
  return pending_.data();
}

std::string ClientApp::loadAsset() {
  if (!ok()) return error_;
  stream_.release();  // a scene still streaming is abandoned (its loader sees the buffer gone)
  BakedAsset decoded;
  const Status s = decodeAsset(pending_, &decoded);
  pending_.clear();
  pending_.shrink_to_fit();
  if (!s.isOk()) return s.toString();
  // CPCA passes go up in their compressed form (when cpcaDirect_), the others expanded;
  // glossy matrix passes always as CPCA (a float32 one as one cluster per vertex); texel
  // passes expanded, into transfer textures.
  std::vector<std::pair<TransferKind, CpcaTransfer>> cpca;
  std::vector<std::pair<TransferKind, CpcaMatrixTransfer>> glossy;
  std::vector<TransferPass> expanded, texel;
  std::optional<TransferPass> visibility;  // the TPFL glossy term of the texel passes
  const int glossyBands = std::min(decoded.shOrder, kMaxGlossyOrder);
  for (TransferPass& p : decoded.passes) {
    if (p.domain == TransferDomain::kTexel) {
      p.encoded = {};
      if (p.form == TransferForm::kVisibility) {
        if (!visibility) visibility = std::move(p);
        continue;
      }
      texel.push_back(std::move(p));
      continue;
    }
    if (p.form == TransferForm::kMatrix) {
      CpcaMatrixTransfer m;
      if (!p.encoded.empty()) {
        TransferBlobInfo info;
        if (Status st = readTransferBlobInfo(p.encoded, &info); !st.isOk()) return st.toString();
        if (info.encoding == TransferEncoding::kCpca) {
          if (Status st = decodeCpcaMatrixTransfer(p.encoded, glossyBands, &m); !st.isOk()) return st.toString();
          glossy.emplace_back(p.kind, std::move(m));
          continue;
        }
      }
      // Expanded matrices (float32, or another encoding's full decode): their leading block.
      const MatrixPacking packing = matrixPackingFor(p.kind, decoded.lighting.model);
      const std::size_t full = matrixEntryCount(decoded.shOrder, packing), lead = matrixEntryCount(glossyBands, packing);
      const std::size_t rows = decoded.positions.size() * static_cast<std::size_t>(p.channels);
      if (p.coeffs.size() != rows * full) return "glossy pass: matrix count disagrees with the vertex count";
      std::vector<float> block(rows * lead);
      for (std::size_t r = 0; r < rows; ++r) std::copy_n(&p.coeffs[r * full], lead, &block[r * lead]);
      if (Status st = cpcaFromPlainMatrices(block, glossyBands, packing, p.channels, static_cast<std::uint32_t>(decoded.positions.size()), &m);
          !st.isOk()) {
        return st.message();
      }
      glossy.emplace_back(p.kind, std::move(m));
      continue;
    }
    CpcaTransfer c;
    if (cpcaDirect_ && !p.encoded.empty() && decodeCpcaTransfer(p.encoded, decoded.shOrder, &c).isOk()) {
      cpca.emplace_back(p.kind, std::move(c));
    } else {
      expanded.push_back(std::move(p));
    }
  }
  decoded.passes = std::move(expanded);
  if (Status u = renderer_.upload(decoded); !u.isOk()) return u.message();
  if (Status u = renderer_.uploadBiScale(decoded); !u.isOk()) return u.message();
  for (const auto& [kind, c] : cpca) {
    if (Status u = renderer_.uploadCpcaPass(kind, c); !u.isOk()) return u.message();
  }
  for (const TransferPass& t : texel) {
    if (Status u = renderer_.uploadTexelPass(t, decoded.shOrder); !u.isOk()) return u.message();
  }
  texel = {};
  if (visibility) {
    if (Status u = renderer_.uploadTexelVisibility(*visibility, visibility->order, decoded.specular); !u.isOk()) return u.message();
    visibility.reset();
  }
  adoptGeometry(std::move(decoded));
  for (auto& [kind, m] : glossy) {
    if (std::string e = uploadGlossy(kind, std::move(m)); !e.empty()) return e;
  }
  resolveSource();
  return "";
}

bool ClientApp::hasAnyPass(ShadingMode mode) const {
  if (!ok()) return false;
  if (!isPassKind(mode)) return renderer_.hasPass(mode);  // Lambert: the geometry
  if (source_ == TransferDomain::kTexel) return renderer_.texelOrder(mode) > 0;
  return renderer_.hasPass(mode) || renderer_.glossyOrder(mode) > 0;
}

bool ClientApp::offers(ShadingMode mode, TransferDomain d) const {
  if (!isPassKind(mode)) return false;
  const int kind = static_cast<int>(mode);
  if (d == TransferDomain::kTexel) return renderer_.texelOrder(mode) > 0 || stream_.hasTexelKind(kind);
  return renderer_.hasPass(mode) || renderer_.glossyOrder(mode) > 0 || stream_.hasKind(kind) || stream_.hasMatrixKind(kind);
}

bool ClientApp::hasSource(TransferDomain d) const {
  return offers(ShadingMode::kUnshadowed, d) || offers(ShadingMode::kShadowed, d) || offers(ShadingMode::kInterreflected, d);
}

void ClientApp::resolveSource() {
  const TransferDomain other = wantedSource_ == TransferDomain::kTexel ? TransferDomain::kVertex : TransferDomain::kTexel;
  source_ = !hasSource(wantedSource_) && hasSource(other) ? other : wantedSource_;
  if (mode_ == ShadingMode::kLambert || offers(mode_, source_)) return;
  for (ShadingMode m : {ShadingMode::kInterreflected, ShadingMode::kShadowed, ShadingMode::kUnshadowed}) {
    if (offers(m, source_)) {
      mode_ = m;
      return;
    }
  }
}

void ClientApp::setSource(TransferDomain d) {
  if (d != TransferDomain::kVertex && d != TransferDomain::kTexel) return;
  const TransferDomain before = source_;
  wantedSource_ = d;
  resolveSource();
  if (source_ != before) pendingMode_.reset();  // a mode waiting for its pass waited in the other domain
}

std::string ClientApp::streamTexelPass(ShadingMode mode, int bands) {
  if (!ok()) return error_;
  if (!isPassKind(mode)) return "streamTexelPass: kind must be a pass kind (unshadowed, shadowed or interreflected)";
  TransferPass pass;
  int order = 0;
  if (Status s = stream_.decodeTexelPass(static_cast<int>(mode), bands, &pass, &order); !s.isOk()) return s.toString();
  makeCurrent();
  if (Status u = renderer_.uploadTexelPass(pass, order); !u.isOk()) return u.message();
  if (pendingMode_ == mode && source_ == TransferDomain::kTexel) {
    mode_ = mode;
    pendingMode_.reset();
  }
  return "";
}

std::string ClientApp::streamVisibilityPass(int bands) {
  if (!ok()) return error_;
  TransferPass pass;
  int order = 0;
  if (Status s = stream_.decodeVisibilityPass(bands, &pass, &order); !s.isOk()) return s.toString();
  makeCurrent();
  if (Status u = renderer_.uploadTexelVisibility(pass, order, asset_.specular); !u.isOk()) return u.message();
  productVersion_.reset();  // remade for the new visibility order at the next frame
  return "";
}

bool ClientApp::hasTexelGlossy() const { return ok() && (renderer_.texelVisibilityOrder() > 0 || stream_.hasVisibility()); }

std::string ClientApp::updateTexelProduct() {
  if (renderer_.texelVisibilityOrder() == 0) return "";
  // The product's bands: the displayed lighting's, at most the lobe's kMaxGlossyOrder.
  const int bands = std::clamp(std::min(displayOrder_, kMaxGlossyOrder), 1, kMaxGlossyOrder);
  const std::uint64_t version = (static_cast<std::uint64_t>(lights_.lightingVersion()) << 8) | static_cast<std::uint64_t>(bands);
  if (productVersion_ == version) return "";
  // The lighting block is built on the GPU (environment plus light cube): read back, as
  // lightSH does, only when it changed. A synchronous read, a few hundred bytes.
  const std::vector<float> flat = lights_.lightSH();
  std::vector<Rgb> lighting(static_cast<std::size_t>(bands * bands));
  for (std::size_t i = 0; i < lighting.size(); ++i) {
    if (3 * i + 2 < flat.size()) lighting[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  }
  if (Status s = renderer_.setTexelProduct(lighting, bands); !s.isOk()) return s.message();
  productVersion_ = version;
  return "";
}

TexelShading ClientApp::texelShading() const {
  TexelShading t;
  t.displayOrder = displayOrder_;
  t.exposure = exposure_;
  const GlossyMix mix = glossyMix(mode_);
  t.diffuse = mix != GlossyMix::kGlossy;
  t.glossy = mix != GlossyMix::kDiffuse;
  t.eye = camera_.eye();
  t.fresnel = fresnel_;
  return t;
}

std::vector<int> ClientApp::atlasSizes() const {
  std::vector<int> out;
  for (const TextureAtlas& a : renderer_.atlases()) out.insert(out.end(), {static_cast<int>(a.width), static_cast<int>(a.height)});
  return out;
}

std::string ClientApp::texelAtlasRadiance(ShadingMode kind, int atlas, std::vector<float>* out, bool positions) {
  if (!ok()) return error_;
  makeCurrent();
  prepareLighting();
  if (std::string e = updateTexelProduct(); !e.empty()) return e;
  TexelShading shading = texelShading();
  const GlossyMix mix = glossyMix(kind);
  shading.diffuse = mix != GlossyMix::kGlossy;
  shading.glossy = mix != GlossyMix::kDiffuse;
  shading.positions = positions;
  if (Status s = renderer_.readTexelAtlas(kind, atlas, shading, out); !s.isOk()) return s.message();
  return "";
}

std::string ClientApp::uploadGlossy(TransferKind kind, CpcaMatrixTransfer cpca) {
  const auto k = static_cast<std::size_t>(kind);
  if (k > 2) return "glossy pass of an unknown kind";
  if (asset_.specular.size() != asset_.positions.size()) return "the asset has a glossy pass but no specular material per vertex";
  makeCurrent();
  if (Status u = renderer_.uploadGlossyPass(kind, cpca, asset_.specular, asset_.positions, asset_.normals); !u.isOk()) return u.message();
  glossyCpu_[k] = std::move(cpca);
  return "";
}

void ClientApp::setGlossyMix(ShadingMode kind, GlossyMix mix) {
  if (!isPassKind(kind)) return;
  if (mix != GlossyMix::kDiffuse && mix != GlossyMix::kGlossy && mix != GlossyMix::kBoth) return;
  glossyMix_[static_cast<std::size_t>(kind)] = mix;
}

GlossyMix ClientApp::glossyMix(ShadingMode kind) const {
  return isPassKind(kind) ? glossyMix_[static_cast<std::size_t>(kind)] : GlossyMix::kDiffuse;
}

bool ClientApp::hasGlossy(ShadingMode kind) const {
  if (!isPassKind(kind)) return false;
  return renderer_.glossyOrder(kind) > 0 || stream_.hasMatrixKind(static_cast<int>(kind));
}

std::string ClientApp::streamGlossyPass(ShadingMode mode, int bands) {
  if (!ok()) return error_;
  if (!isPassKind(mode)) return "streamGlossyPass: kind must be a pass kind (unshadowed, shadowed or interreflected)";
  const int kind = static_cast<int>(mode);
  CpcaMatrixTransfer cpca;
  if (stream_.isMatrixCpca(kind)) {
    TransferPass info;
    if (Status s = stream_.decodeMatrixPassCpca(kind, bands, &cpca, &info); !s.isOk()) return s.toString();
    if (cpca.bands > kMaxGlossyOrder) {
      // The client draws at most kMaxGlossyOrder bands: decode that prefix (the leading block).
      if (Status s = stream_.decodeMatrixPassCpca(kind, kMaxGlossyOrder, &cpca, &info); !s.isOk()) return s.toString();
    }
  } else {
    // Float32 (or another encoding): expanded, then one cluster per vertex.
    TransferPass pass;
    int order = 0;
    if (Status s = stream_.decodeMatrixPass(kind, bands, &pass, &order); !s.isOk()) return s.toString();
    const int lead = std::min(order, kMaxGlossyOrder);
    const MatrixPacking packing = matrixPackingFor(static_cast<TransferKind>(kind), asset_.lighting.model);
    const std::size_t full = matrixEntryCount(order, packing), part = matrixEntryCount(lead, packing);
    const std::size_t rows = asset_.positions.size() * static_cast<std::size_t>(pass.channels);
    if (pass.coeffs.size() != rows * full) return "glossy pass: matrix count disagrees with the vertex count";
    std::vector<float> block(rows * part);
    for (std::size_t r = 0; r < rows; ++r) std::copy_n(&pass.coeffs[r * full], part, &block[r * part]);
    if (Status s = cpcaFromPlainMatrices(block, lead, packing, pass.channels, static_cast<std::uint32_t>(asset_.positions.size()), &cpca);
        !s.isOk()) {
      return s.message();
    }
  }
  if (std::string e = uploadGlossy(static_cast<TransferKind>(kind), std::move(cpca)); !e.empty()) return e;
  if (pendingMode_ == mode && source_ == TransferDomain::kVertex) {
    mode_ = mode;
    pendingMode_.reset();
  }
  return "";
}

std::vector<float> ClientApp::vertexGlossy() const {
  if (!ok()) return {};
  makeCurrent();
  return renderer_.readGlossy(asset_.positions.size());
}

std::vector<float> ClientApp::glossyReference(ShadingMode kind) {
  if (!ok() || !isPassKind(kind)) return {};
  const CpcaMatrixTransfer& cpca = glossyCpu_[static_cast<std::size_t>(kind)];
  if (cpca.bands == 0 || renderer_.glossyOrder(kind) == 0) return {};
  std::vector<float> expanded(asset_.positions.size() * static_cast<std::size_t>(cpca.channels) * matrixEntryCount(cpca.bands, cpca.packing));
  if (!cpcaMatrixReconstruct(cpca, expanded).isOk()) return {};
  // The lighting the GPU drew with: the block (light cube + environment) at the display order.
  const int bands = std::clamp(displayOrder_, 1, cpca.bands);
  const std::vector<float> flat = lights_.lightSH();
  std::vector<Rgb> lighting(static_cast<std::size_t>(bands * bands));
  for (std::size_t i = 0; i < lighting.size() && 3 * i + 2 < flat.size(); ++i) lighting[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  std::vector<float> out(3 * asset_.positions.size());
  const GlossyView view{toVec3(lastEye_), fresnel_};
  if (!glossyExitRadiance(expanded, cpca.bands, cpca.packing, cpca.channels, asset_.positions, asset_.normals, asset_.specular, view,
                          lighting, out)
           .isOk()) {
    return {};
  }
  return out;
}

std::vector<float> ClientApp::biScaleRotated() const {
  if (!ok() || !renderer_.drewBiScale()) return {};
  makeCurrent();
  return renderer_.readBiScaleRotated();
}

std::vector<float> ClientApp::biScaleRotatedReference() {
  if (!ok() || !renderer_.drewBiScale() || !isPassKind(mode_)) return {};
  const CpcaMatrixTransfer& cpca = glossyCpu_[static_cast<std::size_t>(mode_)];
  if (cpca.bands == 0 || asset_.tangents.size() != asset_.positions.size()) return {};
  std::vector<float> expanded(asset_.positions.size() * static_cast<std::size_t>(cpca.channels) * matrixEntryCount(cpca.bands, cpca.packing));
  if (!cpcaMatrixReconstruct(cpca, expanded).isOk()) return {};
  const int bands = std::clamp(std::min({displayOrder_, renderer_.glossyOrder(mode_), renderer_.biScaleOrder()}), 1, 8);
  const int rowTexels = renderer_.biScaleRowTexels();
  const std::size_t nb = static_cast<std::size_t>(bands * bands), stride = static_cast<std::size_t>(rowTexels) * 4;
  const std::vector<float> flat = lights_.lightSH();  // the lighting the GPU drew with
  const std::size_t V = asset_.positions.size(), entries = matrixEntryCount(cpca.bands, cpca.packing);
  std::vector<float> world(3 * V * stride, 0.0f), light(nb);
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < nb; ++i) light[i] = 3 * i + static_cast<std::size_t>(c) < flat.size() ? flat[3 * i + static_cast<std::size_t>(c)] : 0.0f;
    for (std::size_t v = 0; v < V; ++v) {
      const float* m = &expanded[(v * static_cast<std::size_t>(cpca.channels) + (cpca.channels == 3 ? static_cast<std::size_t>(c) : 0)) * entries];
      applyPackedMatrixUnchecked(m, cpca.packing, nb, light.data(), &world[(static_cast<std::size_t>(c) * V + v) * stride]);
    }
  }
  BiScaleRotations rotations;
  if (!packBiScaleRotations(asset_.normals, asset_.tangents, bands, &rotations).isOk()) return {};
  std::vector<float> out(world.size());
  biScaleRotateCpu(rotations, world, static_cast<int>(V), rowTexels, out);
  return out;
}

std::string ClientApp::useSyntheticGlossy(ShadingMode kind, int bands, int channels, int clusters, int vectors, int seed, float f0,
                                          float exponent, float minGreen) {
  if (!ok()) return error_;
  if (!isPassKind(kind) || asset_.positions.empty()) return "useSyntheticGlossy: needs a scene and a pass kind";
  if (!(f0 >= 0.0f && f0 <= 1.0f) || !(exponent >= 0.0f) || !std::isfinite(exponent)) return "useSyntheticGlossy: f0 in [0, 1], exponent >= 0";
  SyntheticGlossySpec spec;
  spec.bands = bands;
  spec.channels = channels;
  spec.clusters = clusters;
  spec.vectors = vectors;
  spec.seed = static_cast<std::uint64_t>(seed);
  spec.packing = kind == ShadingMode::kShadowed ? MatrixPacking::kSymmetric : MatrixPacking::kFull;
  std::vector<std::uint8_t> glossy(asset_.positions.size());
  asset_.specular.assign(asset_.positions.size(), SpecularMaterial{{0.0f, 0.0f, 0.0f}, 0.0f, 0.0f});  // no specular part
  for (std::size_t v = 0; v < asset_.positions.size(); ++v) {
    glossy[v] = asset_.albedo[v].g >= minGreen ? 1 : 0;
    if (glossy[v]) asset_.specular[v] = {{f0, f0, f0}, exponent};
  }
  CpcaMatrixTransfer cpca;
  if (Status s = makeSyntheticCpcaMatrix(spec, static_cast<std::uint32_t>(asset_.positions.size()), &cpca, glossy); !s.isOk()) {
    return s.toString();
  }
  return uploadGlossy(static_cast<TransferKind>(kind), std::move(cpca));
}

void ClientApp::adoptGeometry(BakedAsset decoded) {
  productVersion_.reset();  // a new scene: its product matrix is made at the next frame
  productError_.clear();
  asset_ = std::move(decoded);
  glossyCpu_ = {};
  asset_.passes.clear();  // on the GPU now; the CPU copy is not used again
  asset_.passes.shrink_to_fit();
  boundsMin_ = boundsMax_ = asset_.positions.front();
  for (const Vec3& p : asset_.positions) {
    boundsMin_ = {std::min(boundsMin_.x, p.x), std::min(boundsMin_.y, p.y), std::min(boundsMin_.z, p.z)};
    boundsMax_ = {std::max(boundsMax_.x, p.x), std::max(boundsMax_.y, p.y), std::max(boundsMax_.z, p.z)};
  }
  displayOrder_ = std::min(asset_.shOrder, kMaxClientOrder);
  pendingMode_.reset();
  frameScene();
}

std::uint8_t* ClientApp::reserveStream(std::size_t bytes) { return stream_.reserve(bytes); }

std::string ClientApp::streamGeometry() {
  if (!ok()) return error_;
  BakedAsset decoded;
  if (Status s = stream_.decodeGeometry(&decoded); !s.isOk()) return s.toString();
  makeCurrent();
  if (Status u = renderer_.uploadGeometry(decoded); !u.isOk()) return u.message();
  if (Status u = renderer_.uploadBiScale(decoded); !u.isOk()) return u.message();
  const bool anyGlossy = stream_.hasMatrixKind(0) || stream_.hasMatrixKind(1) || stream_.hasMatrixKind(2) || stream_.hasVisibility();
  if (anyGlossy && decoded.specular.size() != decoded.positions.size()) {
    if (Status s = stream_.decodeSpecular(&decoded.specular); !s.isOk()) return s.toString();
  }
  adoptGeometry(std::move(decoded));
  // The drawn domain and pass, chosen as loadAsset chooses among the passes the file holds.
  resolveSource();
  return "";
}

std::string ClientApp::streamPass(ShadingMode mode, int bands) {
  if (!ok()) return error_;
  if (!isPassKind(mode)) return "streamPass: kind must be a pass kind (unshadowed, shadowed or interreflected)";
  const int kind = static_cast<int>(mode);
  TransferPass pass;
  if (cpcaDirect_ && stream_.isCpca(kind)) {
    CpcaTransfer cpca;
    if (Status s = stream_.decodePassCpca(kind, bands, &cpca, &pass); !s.isOk()) return s.toString();
    makeCurrent();
    if (Status u = renderer_.uploadCpcaPass(pass.kind, cpca); !u.isOk()) return u.message();
  } else {
    int order = 0;
    if (Status s = stream_.decodePass(kind, bands, &pass, &order); !s.isOk()) return s.toString();
    makeCurrent();
    if (Status u = renderer_.uploadPass(pass, order); !u.isOk()) return u.message();
  }
  if (pendingMode_ == mode && source_ == TransferDomain::kVertex) {
    mode_ = mode;
    pendingMode_.reset();
  }
  return "";
}

std::string ClientApp::setEnvironment(const std::vector<float>& flatRgb, int order) {
  if (order < 1 || order > kMaxShOrder || flatRgb.size() != static_cast<std::size_t>(3 * shCoeffCount(order))) {
    return "environment SH must hold order^2 RGB coefficients, order 1.." + std::to_string(kMaxShOrder);
  }
  for (float v : flatRgb)
    if (!std::isfinite(v)) return "environment SH holds a non-finite value";
  environmentOrder_ = std::min(order, kMaxClientOrder);
  environment_.assign(static_cast<std::size_t>(shCoeffCount(environmentOrder_)), Rgb{});
  for (std::size_t i = 0; i < environment_.size(); ++i) environment_[i] = {flatRgb[3 * i], flatRgb[3 * i + 1], flatRgb[3 * i + 2]};
  (void)setBackgroundImage(0, 0, {});  // the previous map's image; the page uploads this one's
  updateLighting();
  return "";
}

void ClientApp::setWhiteFurnace(float intensity) {
  (void)setBackgroundImage(0, 0, {});
  environmentOrder_ = 1;
  environment_.assign(1, Rgb{1, 1, 1} * (intensity * static_cast<float>(2.0 * std::sqrt(kPi))));
  updateLighting();
}

void ClientApp::setEnvRotation(float yaw, float pitch) {
  yaw_ = yaw;
  pitch_ = std::clamp(pitch, -1.5f, 1.5f);
}
void ClientApp::setLightColor(float r, float g, float b) { color_ = {r, g, b}; }
void ClientApp::setMode(ShadingMode m) {
  if (!isPassKind(m) && m != ShadingMode::kLambert) return;
  if (hasAnyPass(m) || asset_.positions.empty()) {
    mode_ = m;
    pendingMode_.reset();
  } else if (offers(m, source_)) {
    pendingMode_ = m;  // still streaming: switch when its first band arrives
  }
}
void ClientApp::setDisplayOrder(int order) { displayOrder_ = std::clamp(order, 1, std::max(1, std::min(asset_.shOrder, kMaxClientOrder))); }
void ClientApp::setExposure(float ev) { exposure_ = std::exp2(std::clamp(ev, -20.0f, 20.0f)); }

std::string ClientApp::setBackgroundImage(int width, int height, std::span<const std::uint32_t> texels) {
  if (!ok()) return error_;
  makeCurrent();
  const Status s = renderer_.setBackgroundImage(width, height, texels);
  return s.isOk() ? "" : s.message();
}

std::vector<float> ClientApp::cameraPose() const {
  const OrbitCamera::Pose p = camera_.pose();
  return {p.target.x, p.target.y, p.target.z, p.yaw, p.pitch, p.distance};
}

bool ClientApp::setCameraPose(const std::vector<float>& pose) {
  if (pose.size() != 6) return false;
  return camera_.setPose({glm::vec3(pose[0], pose[1], pose[2]), pose[3], pose[4], pose[5]});
}

void ClientApp::frameScene() {
  camera_.frame(toGlm((boundsMin_ + boundsMax_) * 0.5f), 0.5f * length(boundsMax_ - boundsMin_), camera_.aspect());
}

void ClientApp::updateLighting() {
  Mat3 r = rotationAxisAngle({0, 1, 0}, yaw_) * rotationAxisAngle({1, 0, 0}, pitch_);
  lighting_ = environment_;
  if (environmentOrder_ > 1) {
    ShRotation rot;
    if (ShRotation::make(environmentOrder_, r, &rot).isOk()) (void)rot.apply(environment_, lighting_);
  }
  for (Rgb& c : lighting_) c = {c.r * color_.r, c.g * color_.g, c.b * color_.b};
  // glm is column-major: column j of environmentRotation_ is column j of r.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) environmentRotation_[j][i] = r.m[i][j];
  packLighting(lighting_, displayOrder_, packed_);
}

Vec3 ClientApp::lightCenter() const {
  if (isLocalLighting(asset_.lighting.model)) return asset_.lighting.center;
  return (boundsMin_ + boundsMax_) * 0.5f;
}

void ClientApp::syncLightView() {
  // The cube is projected at the baked order (the lighting holds at most kMaxClientOrder
  // bands); before a scene is loaded, at 5.
  const int order = asset_.shOrder > 0 ? std::min(asset_.shOrder, kMaxClientOrder) : 5;
  lights_.setView(lightCenter(), 0.5f * length(boundsMax_ - boundsMin_), order);
}

void ClientApp::render(int width, int height) {
  if (!ok() || width <= 0 || height <= 0) return;
  makeCurrent();
  prepareLighting();
  camera_.setAspect(static_cast<float>(width) / height);
  const Vec3 eye = toVec3(camera_.eyePosition());
  const glm::vec2 depth = camera_.sceneDepthRange();
  float nearZ = depth.x, farZ = depth.y;
  for (const BoundingSphere& b : lights_.emitterBounds()) {  // keep the emitters inside the depth range
    const float d = length(b.center - eye);
    farZ = std::max(farZ, d + b.radius);
    nearZ = std::min(nearZ, d - b.radius);
  }
  nearZ = std::max(nearZ, farZ * 1e-4f);
  camera_.update(nearZ, farZ);
  // Only a texel frame that shows the glossy term needs P(L) (and the lighting's read-back).
  if (source_ == TransferDomain::kTexel && isPassKind(mode_) && glossyMix(mode_) != GlossyMix::kDiffuse) {
    productError_ = updateTexelProduct();  // on failure the frame draws without the glossy term
  }
  FrameParams p;
  p.viewProjection = camera_.viewProjection();
  p.mode = mode_;
  p.displayOrder = displayOrder_;
  p.exposure = exposure_;
  p.background = backgroundMode_ == BackgroundMode::kColour || environmentEnabled_ ? backgroundMode_ : BackgroundMode::kNone;
  p.backgroundColour = backgroundColour_;
  p.environmentRotation = environmentRotation_;
  p.environmentTint = {color_.r, color_.g, color_.b};
  p.environment = packed_;
  p.mix = glossyMix(mode_);
  p.eye = camera_.eye();
  p.fresnel = fresnel_;
  p.lightingVersion = lights_.lightingVersion();
  p.domain = source_;
  p.biScale = biScale_;
  p.viewDependent = viewDependent_;
  lastEye_ = p.eye;
  renderer_.draw(width, height, p);
  lights_.drawEmitters(camera_.viewProjection(), toVec3(camera_.eye()), exposure_);
}

void ClientApp::finishShading() const {
  if (!ok()) return;
  makeCurrent();
  (void)renderer_.readRadiance(1);
}

void ClientApp::prepareLighting() {
  updateLighting();  // the shared SH rotation, every frame
  static const float kNoEnvironment[kPackedLightingFloats] = {};
  syncLightView();
  // Re-projects the light cube only when dirty; leaves the lighting block bound.
  lights_.update(environmentEnabled_ ? packed_ : kNoEnvironment, displayOrder_);
}

bool ClientApp::shadeGlossyVertices(int work) {
  if (!ok() || work < 0 || work > 4) return false;
  makeCurrent();
  prepareLighting();
  return renderer_.shadeGlossy(mode_, displayOrder_, camera_.eye(), lights_.lightingVersion(), fresnel_, static_cast<GlossyWork>(work));
}

bool ClientApp::shadeVertices() {
  if (!ok()) return false;
  makeCurrent();
  prepareLighting();
  return renderer_.shade(mode_, displayOrder_);
}

std::string ClientApp::setLights(const std::vector<float>& flat) {
  if (!ok()) return error_;
  return lights_.setLights(flat);
}

int ClientApp::addLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices) {
  if (!ok()) return -1;
  makeCurrent();
  return lights_.addLightMesh(std::move(positions), std::move(indices));
}

std::string ClientApp::setProjection(int mode) {
  if (!ok()) return error_;
  return lights_.setProjection(mode);
}

std::string ClientApp::setCubeSize(int size) {
  if (!ok()) return error_;
  return lights_.setCubeSize(size);
}

std::vector<float> ClientApp::cubeSH() {
  if (!ok()) return {};
  makeCurrent();
  syncLightView();
  return lights_.cubeSH();
}

void ClientApp::projectLightsNow(int onlyLight) {
  if (!ok()) return;
  makeCurrent();
  syncLightView();
  lights_.projectNow(onlyLight);
}

void ClientApp::finishGpu() {
  if (!ok()) return;
  makeCurrent();
  lights_.finishGpu();
}

std::vector<float> ClientApp::rayFromScreen(float ndcX, float ndcY) const {
  const glm::vec3 e = camera_.eye(), d = camera_.rayDirection(ndcX, ndcY);
  return {e.x, e.y, e.z, d.x, d.y, d.z};
}

std::vector<float> ClientApp::project(float x, float y, float z) const {
  const glm::vec3 p = camera_.project({x, y, z});
  return {p.x, p.y, p.z};
}

std::vector<float> ClientApp::viewProjection() const {
  const float* m = glm::value_ptr(camera_.viewProjection());
  return std::vector<float>(m, m + 16);
}

std::vector<float> ClientApp::vertexRadiance() const {
  if (!ok()) return {};
  makeCurrent();
  return renderer_.readRadiance(asset_.positions.size());
}

std::vector<float> ClientApp::lightSH() {
  if (!ok()) return {};
  makeCurrent();
  return lights_.lightSH();
}

}  // namespace prt::web
