#include "transfer_texture.h"

#include <algorithm>
#include <string>

#include "prt/sh_basis.h"

namespace prt::web {

Status packTransfer(const TransferPass& pass, int order, std::size_t vertexCount, int maxHeight, TransferTexture* out) {
  if (pass.channels != 1 && pass.channels != 3) {
    return Status::error(StatusCode::kInvalidArgument, "transfer pass has " + std::to_string(pass.channels) + " channels");
  }
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order));
  if (pass.coeffs.size() != vertexCount * n2 * static_cast<std::size_t>(pass.channels)) {
    return Status::error(StatusCode::kSizeMismatch, "transfer pass size does not match the vertex count");
  }
  const int perChannel = texelsForOrder(order);
  const std::size_t texelCount = vertexCount * static_cast<std::size_t>(perChannel * pass.channels);
  const std::size_t maxTexels = static_cast<std::size_t>(kTransferTextureWidth) * static_cast<std::size_t>(std::max(1, maxHeight));
  if (texelCount > maxTexels) {
    return Status::error(StatusCode::kInvalidArgument,
                         "transfer needs " + std::to_string(texelCount) + " texels; one texture on this device holds at most " +
                             std::to_string(maxTexels) + " (MAX_TEXTURE_SIZE " + std::to_string(maxHeight) + ")");
  }
  out->width = kTransferTextureWidth;
  out->height = static_cast<int>(std::max<std::size_t>(1, (texelCount + kTransferTextureWidth - 1) / kTransferTextureWidth));
  out->channels = pass.channels;
  out->texelsPerChannel = perChannel;
  out->texels.assign(static_cast<std::size_t>(out->width) * out->height * 4, 0.0f);
  const std::size_t padded = static_cast<std::size_t>(perChannel) * 4;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    for (int c = 0; c < pass.channels; ++c) {
      const float* src = &pass.coeffs[(v * pass.channels + c) * n2];
      float* dst = &out->texels[(v * pass.channels + c) * padded];
      std::copy(src, src + n2, dst);
    }
  }
  return Status::ok();
}

void packLighting(const std::vector<Rgb>& coeffs, int displayOrder, float* out) {
  std::fill(out, out + kPackedLightingFloats, 0.0f);
  const std::size_t n = std::min(coeffs.size(), static_cast<std::size_t>(shCoeffCount(std::min(displayOrder, kMaxClientOrder))));
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = coeffs[i].r;
    out[kMaxClientCoeffs + i] = coeffs[i].g;
    out[2 * kMaxClientCoeffs + i] = coeffs[i].b;
  }
}

Status textureRowsFor(std::size_t texels, int maxHeight, const std::string& what, int* rows) {
  const std::size_t width = static_cast<std::size_t>(kTransferTextureWidth);
  const std::size_t need = std::max<std::size_t>(1, (texels + width - 1) / width);
  if (need > static_cast<std::size_t>(std::max(1, maxHeight))) {
    return Status::error(StatusCode::kInvalidArgument,
                         what + " needs " + std::to_string(texels) + " texels; one texture on this device holds " +
                             std::to_string(width * static_cast<std::size_t>(std::max(1, maxHeight))) +
                             " (MAX_TEXTURE_SIZE " + std::to_string(maxHeight) + ")");
  }
  *rows = static_cast<int>(need);
  return Status::ok();
}

}  // namespace prt::web
