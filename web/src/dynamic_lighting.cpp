#include "dynamic_lighting.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "client_limits.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "transfer_texture.h"

namespace prt::web {

Status DynamicLighting::init(bool floatTargets) {
  floatTargets_ = floatTargets;
  if (Status s = renderer_.init(); !s.isOk()) return s;
  if (Status s = reduction_.init(); !s.isOk()) return s;
  if (Status s = block_.init(floatTargets); !s.isOk()) return s;
  if (!block_.cubeShFramebuffer()) floatTargets_ = false;
  if (!floatTargets_ && path_ == ProjectionPath::kGpu) path_ = ProjectionPath::kCpu;
  cpuCubeSh_.assign(kPackedLightingFloats, 0.0f);
  return Status::ok();
}

std::string DynamicLighting::setLights(std::span<const float> flat) {
  std::vector<Emitter> parsed;
  if (std::string e = parseEmitters(flat, static_cast<int>(meshes_.size()), &parsed); !e.empty()) return e;
  emitters_ = std::move(parsed);
  flat_.assign(flat.begin(), flat.end());
  bounds_.clear();
  for (const Emitter& e : emitters_) bounds_.push_back(prt::web::emitterBounds(e, meshes_));
  analytic_.setEmitters(emitters_, flat_);
  selectCubeEmitters();
  return "";
}

void DynamicLighting::selectCubeEmitters() {
  std::vector<Emitter> emitters;
  std::vector<BoundingSphere> bounds;
  std::vector<float> flat;
  for (std::size_t k = 0; k < emitters_.size(); ++k) {
    if (analyticPath() && AnalyticLights::handles(emitters_[k].shape)) continue;
    emitters.push_back(emitters_[k]);
    bounds.push_back(bounds_[k]);
    flat.insert(flat.end(), flat_.begin() + static_cast<std::ptrdiff_t>(k * kFloatsPerEmitter),
                flat_.begin() + static_cast<std::ptrdiff_t>((k + 1) * kFloatsPerEmitter));
  }
  // Moving an analytic light must not re-render the cube: only a change of its own emitters does.
  if (flat != cubeFlat_ || emitters.empty() != cubeEmitters_.empty()) dirty_ = true;
  cubeEmitters_ = std::move(emitters);
  cubeBounds_ = std::move(bounds);
  cubeFlat_ = std::move(flat);
}

int DynamicLighting::addLightMesh(std::vector<float> positions, std::vector<std::uint32_t> indices) {
  LightMesh mesh;
  if (!makeLightMesh(std::move(positions), std::move(indices), &mesh).empty()) return -1;
  renderer_.addMesh(mesh);
  mesh.positions.clear();  // on the GPU now; the bounds are what the CPU needs
  mesh.positions.shrink_to_fit();
  mesh.indices.clear();
  mesh.indices.shrink_to_fit();
  meshes_.push_back(std::move(mesh));
  return static_cast<int>(meshes_.size()) - 1;
}

std::string DynamicLighting::setProjection(int mode) {
  if (mode < 0 || mode > 2) return "projection mode must be 0 (GPU), 1 (CPU) or 2 (analytic)";
  const ProjectionPath before = path_;
  std::string error;
  if (mode == 0 && !gpuProjectionSupported()) {
    path_ = ProjectionPath::kCpu;
    error = "GPU projection needs float render targets (EXT_color_buffer_float), which this device lacks; using the CPU path";
  } else {
    path_ = static_cast<ProjectionPath>(mode);
  }
  if (path_ != before) {
    dirty_ = true;
    analytic_.invalidate(-1);
    std::fill(std::begin(analyticSh_), std::end(analyticSh_), 0.0f);
    selectCubeEmitters();
  }
  return error;
}

std::string DynamicLighting::setCubeSize(int size) {
  if (size < kMinCubeSize || size > kMaxCubeSize) {
    return "cube size " + std::to_string(size) + " is outside [" + std::to_string(kMinCubeSize) + ", " + std::to_string(kMaxCubeSize) + "]";
  }
  if (size != cubeSize_) dirty_ = true;
  cubeSize_ = size;
  return "";
}

void DynamicLighting::simulateNoFloatTargets(bool on) {
  if (on == simulateNoFloat_) return;
  simulateNoFloat_ = on;
  if (!gpuProjectionSupported() && path_ == ProjectionPath::kGpu) path_ = ProjectionPath::kCpu;
  dirty_ = true;
}

void DynamicLighting::setView(Vec3 center, float sceneRadius, int order) {
  const float nearZ = std::max(1e-6f, sceneRadius * 1e-4f);
  order = std::clamp(order, 1, kMaxClientOrder);
  if (center.x != center_.x || center.y != center_.y || center.z != center_.z || nearZ != nearZ_ || order != order_) dirty_ = true;
  center_ = center;
  nearZ_ = nearZ;
  order_ = order;
  (void)analytic_.setView(center, order);  // order is within 1..kMaxClientOrder = kMaxPolygonShOrder
}

void DynamicLighting::project() {
  dirty_ = false;
  ++cubeVersion_;
  cubeEmpty_ = cubeEmitters_.empty();
  lastOnGpu_ = false;
  if (cubeEmpty_) {
    std::fill(cpuCubeSh_.begin(), cpuCubeSh_.end(), 0.0f);
    block_.uploadCubeSh(cpuCubeSh_.data());
    return;
  }
  projectionError_.clear();
  if (cubeOnGpu()) {
    const Status s = projectOnGpu();
    if (s.isOk()) {
      lastOnGpu_ = true;
      return;
    }
    projectionError_ = s.message() + "; projected on the CPU instead";  // this time only
  }
  const Status s = projectOnCpu();
  if (!s.isOk()) {
    projectionError_ = s.message();
    // Nothing sensible to light with: no emitter contribution rather than stale numbers.
    std::fill(cpuCubeSh_.begin(), cpuCubeSh_.end(), 0.0f);
    block_.uploadCubeSh(cpuCubeSh_.data());
  }
}

Status DynamicLighting::projectOnGpu() {
  if (Status s = cube_.resize(cubeSize_, true); !s.isOk()) return s;
  if (Status s = reduction_.prepare(cubeSize_, order_); !s.isOk()) return s;
  cube_.render(renderer_, cubeEmitters_, cubeBounds_, center_, nearZ_);
  // Where emitters can be: a sphere's pixels lie inside the sphere itself (its impostor
  // cube only bounds the ray casting), everything else inside its bounds.
  FaceRect rects[6];
  for (std::size_t k = 0; k < cubeEmitters_.size(); ++k) {
    const Emitter& e = cubeEmitters_[k];
    const BoundingSphere reach = e.shape == EmitterShape::kSphere ? BoundingSphere{e.position, e.sizeX} : cubeBounds_[k];
    for (int f = 0; f < 6; ++f) rects[f] = unite(rects[f], sphereFaceRect(f, center_, reach, cubeSize_));
  }
  reduction_.run(cube_.texture(), block_.cubeShFramebuffer(), rects);
  return Status::ok();
}

Status DynamicLighting::projectOnCpu() {
  if (Status s = cube_.resize(cubeSize_, gpuProjectionSupported()); !s.isOk()) return s;
  cube_.render(renderer_, cubeEmitters_, cubeBounds_, center_, nearZ_);
  CubeMap cube;
  if (Status s = cube_.read(&cube); !s.isOk()) return s;
  std::vector<Rgb> coeffs;
  if (Status s = projectCubeMap(order_, cube, &coeffs); !s.isOk()) return s;
  packLighting(coeffs, order_, cpuCubeSh_.data());
  block_.uploadCubeSh(cpuCubeSh_.data());
  return Status::ok();
}

void DynamicLighting::update(const float* environment, int displayOrder) {
  if (dirty_) project();
  if (analyticPath() && analytic_.dirty()) analytic_.update(analyticSh_);
  combine(environment, displayOrder, false);
}

void DynamicLighting::combine(const float* environment, int displayOrder, bool force) {
  if (environment != environment_) std::memcpy(environment_, environment, sizeof environment_);
  displayOrder = std::clamp(displayOrder, 1, kMaxClientOrder);
  // The block adds the cube SH to this input, so the analytic lights ride with the environment.
  const int cut = shCoeffCount(displayOrder);
  float input[kPackedLightingFloats];
  for (int i = 0; i < kPackedLightingFloats; ++i) input[i] = environment[i] + (i % kMaxClientCoeffs < cut ? analyticSh_[i] : 0.0f);
  if (force || combinedVersion_ != cubeVersion_ || combinedOrder_ != displayOrder ||
      std::memcmp(combinedEnvironment_, input, sizeof combinedEnvironment_) != 0) {
    block_.combine(input, displayOrder);
    ++blockVersion_;
    combinedVersion_ = cubeVersion_;
    combinedOrder_ = displayOrder;
    std::memcpy(combinedEnvironment_, input, sizeof combinedEnvironment_);
  } else {
    block_.bind();
  }
}

void DynamicLighting::projectNow(int onlyLight) {
  if (!analyticPath()) {
    dirty_ = true;
    project();
    return;
  }
  if (!cubeEmitters_.empty()) {
    dirty_ = true;
    project();
  }
  analytic_.invalidate(onlyLight);
  analytic_.update(analyticSh_);
  combine(environment_, std::max(1, combinedOrder_ == 0 ? order_ : combinedOrder_), true);
}

void DynamicLighting::finishGpu() {
  glFinish();
  block_.readFirstTexel();
}

void DynamicLighting::drawEmitters(const glm::mat4& viewProjection, Vec3 eye, float exposure) {
  if (emitters_.empty()) return;
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  EmitterView view;
  view.viewProjection = viewProjection;
  view.eye = eye;
  view.output = EmitterOutput::kDisplay;
  view.exposure = exposure;
  renderer_.begin(view);
  for (const Emitter& e : emitters_) renderer_.draw(e);
  renderer_.end();
}

namespace {
// packLighting layout -> flat [r,g,b] per coefficient, `count` coefficients.
std::vector<float> unpack(const float* packed, int count) {
  std::vector<float> out(static_cast<std::size_t>(3 * count));
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(3 * i + c)] = packed[kMaxClientCoeffs * c + i];
  return out;
}
}  // namespace

std::vector<float> DynamicLighting::lightSH() const {
  float packed[kPackedLightingFloats];
  block_.read(packed);
  return unpack(packed, shCoeffCount(std::max(1, combinedOrder_)));
}

std::vector<float> DynamicLighting::cubeSH() {
  if (dirty_) project();
  float packed[kPackedLightingFloats];
  if (!lastOnGpu_ || !block_.readCubeSh(packed).isOk()) std::memcpy(packed, cpuCubeSh_.data(), sizeof packed);
  if (analyticPath()) {
    if (analytic_.dirty()) analytic_.update(analyticSh_);
    for (int i = 0; i < kPackedLightingFloats; ++i) packed[i] += analyticSh_[i];
  }
  return unpack(packed, shCoeffCount(order_));
}

}  // namespace prt::web
