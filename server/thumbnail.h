// A scene thumbnail: a small picture of a verified asset under the default light, drawn on
// the CPU (the server has no GPU) from the asset's own diffuse transfer, for the page's
// scene picker. thumbnail_view.h says how it looks; thumbnail_store.h how it is served.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/status.h"

namespace prt::serve {

// The pass a thumbnail shows: the index into summary.passes of the per-vertex vector pass
// the page's default transfer would pick, interreflected before shadowed before
// unshadowed; -1 when the asset has none (only texel or matrix passes).
int thumbnailPass(const AssetSummary& summary);

// Straight-alpha RGBA, kThumbnailWidth x kThumbnailHeight, rows top first.
struct ThumbnailImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

// Draws the asset `file` (whose summary is `summary`; the caller has verified it, but every
// section read is checked again, so any bytes are safe): the geometry and the
// thumbnailPass transfer decoded with the shared reader, per-vertex exit radiance
// (prt/exit_radiance.h) under thumbnailLighting, rasterised from frameThumbnail's camera at
// kThumbnailSupersample^2 samples a pixel, each pixel the mean radiance of the samples that
// hit the mesh, tone-mapped (toneMap8), and alpha the fraction that hit (0 where only
// background shows). kInvalidArgument when the asset has no vertex transfer to show; the
// reader's errors otherwise.
Status renderThumbnail(std::span<const std::uint8_t> file, const AssetSummary& summary, ThumbnailImage* out);

// renderThumbnail encoded as an 8-bit RGBA PNG (stb_image_write) into *png.
Status makeThumbnailPng(std::span<const std::uint8_t> file, const AssetSummary& summary, std::string* png);

}  // namespace prt::serve
