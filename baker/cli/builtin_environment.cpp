#include "baker/cli/builtin_environment.h"

#include <cmath>
#include <string>

namespace prt {
namespace {

constexpr double kDegree = kPi / 180.0;

Rgb mix(Rgb a, Rgb b, float t) { return a * (1.0f - t) + b * t; }

// Radiance of the sky in unit direction `d`.
Rgb skyRadiance(Vec3 d, Vec3 sun, float cosSunRadius) {
  if (dot(d, sun) >= cosSunRadius) return Rgb{1.0f, 0.95f, 0.85f} * kBuiltinSkySunRadiance;
  if (d.y < 0.0f) return {0.12f, 0.08f, 0.05f};  // dark-brown ground
  const Rgb horizon{0.75f, 0.85f, 1.0f}, zenith{0.15f, 0.35f, 0.85f};
  return mix(horizon, zenith, std::sqrt(d.y));  // sqrt: the blue deepens quickly off the horizon
}

}  // namespace

bool isBuiltinEnvironment(std::string_view name) { return name == "sky"; }

Vec3 builtinSkySunDirection() {
  const double el = kBuiltinSkySunElevationDeg * kDegree, az = kBuiltinSkySunAzimuthDeg * kDegree;
  return {static_cast<float>(std::cos(el) * std::cos(az)), static_cast<float>(std::sin(el)),
          static_cast<float>(std::cos(el) * std::sin(az))};
}

Status makeBuiltinEnvironment(std::string_view name, RgbImage* out) {
  if (!isBuiltinEnvironment(name)) {
    return Status::error(StatusCode::kInvalidArgument, "unknown built-in environment '" + std::string(name) +
                                                           "' (known: " + kBuiltinEnvironmentNames + ")");
  }
  const int w = kBuiltinSkyWidth, h = kBuiltinSkyHeight;
  const Vec3 sun = builtinSkySunDirection();
  const float cosSunRadius = static_cast<float>(std::cos(kBuiltinSkySunRadiusDeg * kDegree));
  out->width = w;
  out->height = h;
  out->rgb.assign(static_cast<std::size_t>(w) * h * 3, 0.0f);
  // 4x4 supersampling anti-aliases the horizon and the sun, whose disc is only a few
  // pixels wide: its centroid, and so the band-1 direction, then lands where it should.
  constexpr int kSub = 4;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      Rgb sum;
      for (int sj = 0; sj < kSub; ++sj) {
        for (int si = 0; si < kSub; ++si) {
          // The mapping of prt::projectEquirect, evaluated at sub-pixel centres.
          const double u = (i + (si + 0.5) / kSub) / w, v = (j + (sj + 0.5) / kSub) / h;
          const double phi = 2.0 * kPi * (u - 0.5), lat = 0.5 * kPi - kPi * v;
          const Vec3 d{static_cast<float>(std::cos(lat) * std::cos(phi)), static_cast<float>(std::sin(lat)),
                       static_cast<float>(std::cos(lat) * std::sin(phi))};
          sum = sum + skyRadiance(d, sun, cosSunRadius);
        }
      }
      float* p = &out->rgb[(static_cast<std::size_t>(j) * w + i) * 3];
      p[0] = sum.r / (kSub * kSub);
      p[1] = sum.g / (kSub * kSub);
      p[2] = sum.b / (kSub * kSub);
    }
  }
  return Status::ok();
}

}  // namespace prt
