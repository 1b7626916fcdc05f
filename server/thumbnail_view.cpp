#include "thumbnail_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "prt/sh_zonal.h"

namespace prt::serve {
namespace {

constexpr float kAmbientRadiance = 0.35f;
constexpr Rgb kAmbientColour = {0.92f, 0.96f, 1.0f};  // a slightly cool sky
constexpr float kKeyHalfAngle = static_cast<float>(30.0 * kPi / 180.0);
constexpr float kKeyRadiance = 3.0f;
constexpr Rgb kKeyColour = {1.0f, 0.96f, 0.9f};  // a slightly warm sun
// The page's vertical field of view (web/src/orbit_camera.h): the thumbnail's perspective
// looks like the page's.
constexpr double kFovY = 0.8;

Vec3 normalised(Vec3 v) { return v * (1.0f / length(v)); }

}  // namespace

RasterVertex ThumbnailCamera::project(Vec3 p, Rgb colour) const {
  const Vec3 q = p - eye;
  RasterVertex v;
  v.depth = dot(q, forward);
  v.colour = colour;
  if (!(v.depth > 0.0f)) {
    v.depth = -1.0f;
    return v;
  }
  const double u = dot(q, right) / static_cast<double>(v.depth), w = dot(q, up) / static_cast<double>(v.depth);
  v.x = static_cast<float>(0.5 * width + scale * (u - centreU));
  v.y = static_cast<float>(0.5 * height - scale * (w - centreV));
  return v;
}

ThumbnailCamera frameThumbnail(std::span<const Vec3> positions, int width, int height) {
  Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  Vec3 hi = lo * -1.0f;
  for (const Vec3& p : positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  if (positions.empty()) lo = hi = Vec3{};
  const Vec3 centre = (lo + hi) * 0.5f;
  // The sphere about the box (as the page frames it); a point set gets a small one so the
  // eye still stands apart from it.
  const float radius = std::max(0.5f * length(hi - lo), 1e-3f * std::max({1.0f, std::fabs(centre.x), std::fabs(centre.y), std::fabs(centre.z)}));
  const Vec3 toEye{std::sin(kThumbnailYaw) * std::cos(kThumbnailPitch), std::sin(kThumbnailPitch),
                   std::cos(kThumbnailYaw) * std::cos(kThumbnailPitch)};
  ThumbnailCamera cam;
  cam.width = width;
  cam.height = height;
  // Where the sphere just fits the vertical field of view: every point has depth >= distance - radius > 0.
  const float distance = radius / static_cast<float>(std::sin(0.5 * kFovY));
  cam.eye = centre + toEye * distance;
  cam.forward = toEye * -1.0f;
  cam.right = normalised(cross(cam.forward, Vec3{0.0f, 1.0f, 0.0f}));
  cam.up = cross(cam.right, cam.forward);
  // Fit the points' projected extent, not the sphere's: a long, low object fills the tile.
  double minU = std::numeric_limits<double>::max(), maxU = -minU, minV = minU, maxV = -minU;
  for (const Vec3& p : positions) {
    const Vec3 q = p - cam.eye;
    const double z = dot(q, cam.forward);
    if (!(z > 0.0)) continue;
    const double u = dot(q, cam.right) / z, v = dot(q, cam.up) / z;
    minU = std::min(minU, u), maxU = std::max(maxU, u), minV = std::min(minV, v), maxV = std::max(maxV, v);
  }
  if (!(minU <= maxU)) minU = maxU = minV = maxV = 0.0;
  const double tiny = 1e-6;
  const double spanU = std::max(maxU - minU, tiny), spanV = std::max(maxV - minV, tiny);
  const double usable = 1.0 - 2.0 * kThumbnailMargin;
  cam.scale = std::min(width * usable / spanU, height * usable / spanV);
  cam.centreU = 0.5 * (minU + maxU);
  cam.centreV = 0.5 * (minV + maxV);
  return cam;
}

std::vector<Rgb> thumbnailLighting(int order) {
  const std::size_t n = static_cast<std::size_t>(order) * order;
  std::vector<Rgb> light(n);
  if (order < 1) return light;
  std::vector<float> zonal(static_cast<std::size_t>(order)), placed(n);
  // Valid arguments (order >= 1, 0 < zeta <= pi, a non-zero axis): these cannot fail.
  (void)zonalCircularLight(order, kKeyHalfAngle, kKeyRadiance, zonal);
  (void)placeZonal(order, zonal, normalised(kThumbnailKeyDirection), placed);
  for (std::size_t i = 0; i < n; ++i) light[i] = Rgb{kKeyColour.r * placed[i], kKeyColour.g * placed[i], kKeyColour.b * placed[i]};
  // A constant radiance L projects to L sqrt(4 pi) on y00 alone.
  light[0] = light[0] + kAmbientColour * static_cast<float>(kAmbientRadiance * std::sqrt(4.0 * kPi));
  return light;
}

std::uint8_t toneMap8(float linear) {
  // NaN as black, +infinity as white (the fit tends to 1.03 and is clamped).
  const double x = std::isnan(linear) ? 0.0 : std::clamp(static_cast<double>(linear), 0.0, 1e6);
  const double aces = std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  const double srgb = aces <= 0.0031308 ? 12.92 * aces : 1.055 * std::pow(aces, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(srgb, 0.0, 1.0)));
}

}  // namespace prt::serve
