#include "analytic_lights.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "client_limits.h"
#include "prt/sh_basis.h"
#include "prt/sh_planar_light.h"
#include "prt/sh_zonal.h"

namespace prt::web {

Status AnalyticLights::setView(Vec3 center, int order) {
  if (order != order_) {
    PRT_RETURN_IF_ERROR(PolygonShProjector::make(order, &projector_));
    order_ = order;
    invalidate(-1);
  }
  if (center.x != center_.x || center.y != center_.y || center.z != center_.z) {
    center_ = center;
    invalidate(-1);
  }
  return Status::ok();
}

void AnalyticLights::setEmitters(std::span<const Emitter> emitters, std::span<const float> flat) {
  lights_.resize(emitters.size());
  analyticCount_ = 0;
  for (std::size_t k = 0; k < emitters.size(); ++k) {
    Light& l = lights_[k];
    const float* f = &flat[k * kFloatsPerEmitter];
    if (std::memcmp(l.key, f, sizeof l.key) != 0) {
      std::memcpy(l.key, f, sizeof l.key);
      l.dirty = true;
      anyDirty_ = true;
    }
    l.emitter = emitters[k];
    l.analytic = handles(emitters[k].shape);
    analyticCount_ += l.analytic ? 1 : 0;
  }
  anyDirty_ = true;  // the sum changes when lights go away, even if none is dirty
}

void AnalyticLights::invalidate(int index) {
  anyDirty_ = true;
  if (index < 0) {
    for (Light& l : lights_) l.dirty = true;
  } else if (static_cast<std::size_t>(index) < lights_.size()) {
    lights_[static_cast<std::size_t>(index)].dirty = true;
  }
}

Status AnalyticLights::projectEmitter(const PolygonShProjector& projector, const Emitter& e, Vec3 c, double* out) {
  const int order = projector.order();
  const std::span<double> o(out, static_cast<std::size_t>(order * order));
  switch (e.shape) {
    case EmitterShape::kSphere: {
      const Vec3 axis = e.position - c;
      const float d = length(axis);
      if (!(d > e.sizeX)) return Status::ok();  // inside: the cube sees its black inside
      float zonal[kMaxPolygonShOrder], placed[kMaxPolygonShOrder * kMaxPolygonShOrder];
      PRT_RETURN_IF_ERROR(zonalCircularLight(order, std::asin(std::min(1.0f, e.sizeX / d)), 1.0f, zonal));
      PRT_RETURN_IF_ERROR(placeZonal(order, std::span<const float>(zonal, order), axis, placed));
      for (int i = 0; i < order * order; ++i) out[i] += placed[i];
      return Status::ok();
    }
    case EmitterShape::kDisc:
    case EmitterShape::kRect: {
      // One-sided: from behind or within rounding of the plane the cube records black (or nothing).
      const float size = e.shape == EmitterShape::kDisc ? e.sizeX : 0.5f * std::max(e.sizeX, e.sizeY);
      if (!(dot(e.normal, c - e.position) > 1e-5f * size)) return Status::ok();
      if (e.shape == EmitterShape::kDisc) return accumulateDisc(projector, e.position, e.normal, e.sizeX, c, kDefaultDiscEdges, 1.0, o);
      const EmitterFrame fr = emitterFrame(e.normal);
      const Vec3 hu = fr.u * (0.5f * e.sizeX), hv = fr.v * (0.5f * e.sizeY);
      // Counter-clockwise seen from the front (u x v = n), as the drawn square's front face.
      const Vec3 quad[4] = {e.position - hu - hv, e.position + hu - hv, e.position + hu + hv, e.position - hu + hv};
      return accumulatePlanarPolygon(projector, quad, c, 1.0, o);
    }
    case EmitterShape::kMesh:
      break;
  }
  return Status::error(StatusCode::kInvalidArgument, "mesh emitters have no analytic projection; they use the light cube");
}

void AnalyticLights::update(float* packed) {
  const int n2 = order_ * order_;
  for (Light& l : lights_) {
    if (!l.analytic || !l.dirty) continue;
    l.sh.assign(static_cast<std::size_t>(n2), 0.0);
    // Inputs were validated by parseEmitters; a failure here (a degenerate case the checks
    // below float precision catch) leaves this light dark rather than wrong.
    if (!projectEmitter(projector_, l.emitter, center_, l.sh.data()).isOk()) std::fill(l.sh.begin(), l.sh.end(), 0.0);
    l.dirty = false;
  }
  double sum[3][kMaxClientCoeffs] = {};
  for (const Light& l : lights_) {
    if (!l.analytic) continue;
    const double rgb[3] = {l.emitter.radiance.r, l.emitter.radiance.g, l.emitter.radiance.b};
    for (int c = 0; c < 3; ++c) {
      if (rgb[c] == 0.0) continue;
      for (int i = 0; i < n2; ++i) sum[c][i] += rgb[c] * l.sh[static_cast<std::size_t>(i)];
    }
  }
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kMaxClientCoeffs; ++i) packed[c * kMaxClientCoeffs + i] = static_cast<float>(sum[c][i]);
  anyDirty_ = false;
}

}  // namespace prt::web
