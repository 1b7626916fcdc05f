#include "baker/scene/glossy_materials.h"

#include <cmath>
#include <string>

namespace prt::bake {
namespace {

bool unit(float x) { return x >= 0.0f && x <= 1.0f; }

}  // namespace

Status applyGlossyMaterials(const GlossyMaterialOptions& o, Scene* scene) {
  const std::size_t n = scene->positions.size();
  if (o.exponent && !(std::isfinite(*o.exponent) && *o.exponent >= 0.0)) {
    return Status::error(StatusCode::kInvalidArgument, "specular exponent must be finite and >= 0");
  }
  if (!(std::isfinite(o.maxExponent) && o.maxExponent >= 0.0)) {
    return Status::error(StatusCode::kInvalidArgument, "maximum specular exponent must be finite and >= 0");
  }
  if (!scene->pbr.empty() && scene->pbr.size() != n) {
    return Status::error(StatusCode::kInvalidArgument, "scene has " + std::to_string(scene->pbr.size()) +
                                                           " materials for " + std::to_string(n) + " vertices");
  }
  if (scene->albedo.size() != n) return Status::error(StatusCode::kInvalidArgument, "scene albedo does not match its positions");
  scene->specular.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const PbrVertex m = scene->pbr.empty() ? PbrVertex{} : scene->pbr[v];
    if (!unit(m.metallic) || !unit(m.roughness) || !unit(m.dielectricF0.r) || !unit(m.dielectricF0.g) ||
        !unit(m.dielectricF0.b)) {
      return Status::error(StatusCode::kInvalidArgument,
                           "vertex " + std::to_string(v) + ": metallic, roughness or specular outside [0, 1]");
    }
    const Rgb base = scene->albedo[v];
    const float d = 1.0f - m.metallic;
    scene->albedo[v] = {d * base.r, d * base.g, d * base.b};
    SpecularMaterial& s = scene->specular[v];
    s.f0 = {d * m.dielectricF0.r + m.metallic * base.r, d * m.dielectricF0.g + m.metallic * base.g,
            d * m.dielectricF0.b + m.metallic * base.b};
    double exponent = 0.0;
    if (o.exponent) {
      exponent = *o.exponent;
    } else if (Status st = specularExponentFromRoughness(m.roughness, o.maxExponent, &exponent); !st.isOk()) {
      return st;
    }
    s.exponent = static_cast<float>(exponent);
  }
  return Status::ok();
}

}  // namespace prt::bake
