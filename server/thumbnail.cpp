#include "thumbnail.h"

#include <stb_image_write.h>

#include <algorithm>

#include "mesh_raster.h"
#include "prt/exit_radiance.h"
#include "thumbnail_view.h"

namespace prt::serve {
namespace {

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

int thumbnailPass(const AssetSummary& summary) {
  for (const TransferKind kind : {TransferKind::kInterreflected, TransferKind::kShadowed, TransferKind::kUnshadowed}) {
    for (std::size_t i = 0; i < summary.passes.size(); ++i) {
      const AssetPassInfo& p = summary.passes[i];
      if (p.kind == kind && p.form == TransferForm::kVector && p.domain == TransferDomain::kVertex) return static_cast<int>(i);
    }
  }
  return -1;
}

Status renderThumbnail(std::span<const std::uint8_t> file, const AssetSummary& summary, ThumbnailImage* out) {
  const int passIndex = thumbnailPass(summary);
  if (passIndex < 0) {
    return Status::error(StatusCode::kInvalidArgument, "no per-vertex diffuse transfer to draw a thumbnail from");
  }
  BakedAsset asset;
  PRT_RETURN_IF_ERROR(decodeAssetGeometry(file, &asset));
  TransferPass pass;
  int bands = 0;
  PRT_RETURN_IF_ERROR(decodeAssetPass(file, passIndex, 0, &pass, &bands));
  const std::size_t vertices = asset.positions.size();
  const std::size_t stride = static_cast<std::size_t>(bands) * bands;
  if (bands < 1 || pass.coeffs.size() != vertices * pass.channels * stride) {
    return Status::error(StatusCode::kCorrupt, "thumbnail: the transfer does not match the geometry");
  }
  const std::vector<Rgb> light = thumbnailLighting(bands);
  std::vector<float> radiance(vertices * 3);
  PRT_RETURN_IF_ERROR(exitRadiance(pass.coeffs, pass.channels, stride, asset.albedo, light, radiance));

  const int s = kThumbnailSupersample;
  RasterTarget target(kThumbnailWidth * s, kThumbnailHeight * s);
  const ThumbnailCamera camera = frameThumbnail(asset.positions, target.width, target.height);
  std::vector<RasterVertex> projected(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    projected[v] = camera.project(asset.positions[v], {radiance[v * 3], radiance[v * 3 + 1], radiance[v * 3 + 2]});
  }
  for (std::size_t t = 0; t + 2 < asset.indices.size(); t += 3) {
    const std::uint32_t a = asset.indices[t], b = asset.indices[t + 1], c = asset.indices[t + 2];
    if (a >= vertices || b >= vertices || c >= vertices) continue;  // the reader checked; cheap to be sure
    drawTriangle(target, projected[a], projected[b], projected[c]);
  }

  out->width = kThumbnailWidth;
  out->height = kThumbnailHeight;
  out->rgba.assign(static_cast<std::size_t>(kThumbnailWidth) * kThumbnailHeight * 4, 0);
  for (int y = 0; y < kThumbnailHeight; ++y) {
    for (int x = 0; x < kThumbnailWidth; ++x) {
      double r = 0, g = 0, b = 0;
      int hits = 0;
      for (int sy = 0; sy < s; ++sy) {
        for (int sx = 0; sx < s; ++sx) {
          const std::size_t i = static_cast<std::size_t>(y * s + sy) * target.width + (x * s + sx);
          if (!target.covered[i]) continue;
          r += target.colour[i].r, g += target.colour[i].g, b += target.colour[i].b;
          ++hits;
        }
      }
      if (hits == 0) continue;
      // Straight alpha: the colour is the mesh's own (the mean over the samples that hit
      // it), the alpha how much of the pixel it covers, so edges blend over any backdrop.
      std::uint8_t* p = &out->rgba[(static_cast<std::size_t>(y) * kThumbnailWidth + x) * 4];
      p[0] = toneMap8(static_cast<float>(r / hits));
      p[1] = toneMap8(static_cast<float>(g / hits));
      p[2] = toneMap8(static_cast<float>(b / hits));
      p[3] = static_cast<std::uint8_t>((255 * hits + s * s / 2) / (s * s));
    }
  }
  return Status::ok();
}

Status makeThumbnailPng(std::span<const std::uint8_t> file, const AssetSummary& summary, std::string* png) {
  ThumbnailImage image;
  PRT_RETURN_IF_ERROR(renderThumbnail(file, summary, &image));
  png->clear();
  if (!stbi_write_png_to_func(appendBytes, png, image.width, image.height, 4, image.rgba.data(), image.width * 4)) {
    // stb fails only when it cannot allocate the compressed image.
    return Status::error(StatusCode::kResourceExhausted, "PNG encoding failed (out of memory)");
  }
  return Status::ok();
}

}  // namespace prt::serve
