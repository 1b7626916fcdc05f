// How a scene thumbnail looks (thumbnail.h draws it): the fixed 3/4 camera framing the
// asset, the default light it is lit by, and the page's tone mapping. Pure computation.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh_raster.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt::serve {

// The PNG's size in pixels (4:3, a picker tile) and the samples per pixel on each axis.
inline constexpr int kThumbnailWidth = 160;
inline constexpr int kThumbnailHeight = 120;
inline constexpr int kThumbnailSupersample = 3;

// The view direction: the eye lies at this yaw about +y from +z (the page's frame() has
// yaw 0) and this pitch above the horizon, so two sides and the top show.
inline constexpr float kThumbnailYaw = 0.6f;    // radians
inline constexpr float kThumbnailPitch = 0.45f;  // radians
// The empty border around the framed geometry, as a fraction of the image's width/height.
inline constexpr float kThumbnailMargin = 0.06f;

// A pinhole camera looking at the asset, projecting onto a width x height image.
struct ThumbnailCamera {
  Vec3 eye, right, up, forward;  // orthonormal; forward points into the scene
  double scale = 1.0;            // pixels per unit of (lateral offset / depth)
  double centreU = 0.0, centreV = 0.0;  // the (u, v) = lateral / depth that lands at the image centre
  int width = 0, height = 0;

  // World point p as a raster vertex (x right, y down, in pixels; depth along forward),
  // with colour `colour`. Depth <= 0 (behind the eye) gives a vertex drawTriangle ignores.
  RasterVertex project(Vec3 p, Rgb colour = {}) const;
};

// The camera at kThumbnailYaw / kThumbnailPitch, outside the bounding sphere of `positions`
// (so every point is in front of it), scaled and centred so the projected points fill a
// width x height image up to kThumbnailMargin on the binding side. `positions` non-empty and
// finite (a verified asset's), width and height >= 1; a degenerate (single-point) set is
// framed as a tiny sphere.
ThumbnailCamera frameThumbnail(std::span<const Vec3> positions, int width, int height);

// The default light as SH radiance coefficients of order `order` (order^2 RGB values, the
// basis of docs/sh-conventions.md): a constant sky of radiance 0.35 plus a soft key light, a
// cap of 30 degrees half-angle and radiance 3 about kThumbnailKeyDirection, warm white.
// Bright enough that albedo 0.8 facing the key comes out near 0.9 (exposure 0 EV).
inline constexpr Vec3 kThumbnailKeyDirection = {-0.1f, 0.86f, 0.5f};  // unnormalised; above, left of the eye
std::vector<Rgb> thumbnailLighting(int order);

// The page's tone mapping at 0 EV (web/shaders/shade.frag): Narkowicz's ACES fit of the
// linear value (negatives as 0), then the sRGB curve, rounded to 8 bits.
std::uint8_t toneMap8(float linear);

}  // namespace prt::serve
