// The lighting model an asset's transfer was baked for (docs/spatially-varying.md) and its
// validation, shared by the encoder, the decoder and the baker's option checks.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "prt/asset.h"

namespace prt {
namespace {

// +0.0 only: -0.0 compares equal to 0 but is a second encoding of "nothing".
bool isPositiveZero(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u == 0;
}

}  // namespace

const char* lightingModelName(LightingModel model) {
  switch (model) {
    case LightingModel::kDistant: return "distant";
    case LightingModel::kLocalSphere: return "local-sphere";
    case LightingModel::kLocalSpherePaper: return "local-sphere-paper";
  }
  return "unknown";
}

MatrixPacking matrixPackingFor(TransferKind kind, LightingModel model) {
  const bool symmetricKind = kind == TransferKind::kUnshadowed || kind == TransferKind::kShadowed;
  return symmetricKind && model == LightingModel::kDistant ? MatrixPacking::kSymmetric : MatrixPacking::kFull;
}

bool isLocalLighting(LightingModel model) {
  return model == LightingModel::kLocalSphere || model == LightingModel::kLocalSpherePaper;
}

Status checkLightingInfo(const LightingInfo& l) {
  const auto model = static_cast<std::uint32_t>(l.model);
  if (model > static_cast<std::uint32_t>(LightingModel::kLocalSpherePaper)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "lighting model " + std::to_string(model) + " is unknown (0 distant, 1 local-sphere, 2 local-sphere-paper)");
  }
  if (!isLocalLighting(l.model)) {
    if (!isPositiveZero(l.center.x) || !isPositiveZero(l.center.y) || !isPositiveZero(l.center.z) ||
        !isPositiveZero(l.radius)) {
      return Status::error(StatusCode::kInvalidArgument,
                           "lighting model distant has no centre or radius; they must be 0");
    }
    return Status::ok();
  }
  const std::string name = lightingModelName(l.model);
  if (!isFinite(l.center)) {
    return Status::error(StatusCode::kNotFinite, "lighting " + name + " centre is not finite");
  }
  if (!std::isfinite(l.radius)) {
    return Status::error(StatusCode::kNotFinite, "lighting " + name + " radius is not finite");
  }
  if (!(l.radius > 0.0f)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "lighting " + name + " radius " + std::to_string(l.radius) + " is not positive");
  }
  return Status::ok();
}

}  // namespace prt
