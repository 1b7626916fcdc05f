#include "asset_stream.h"

#include <string>

namespace prt::web {

std::uint8_t* AssetStream::reserve(std::size_t bytes) {
  release();
  try {
    file_.assign(bytes, 0);
  } catch (...) {
    return nullptr;
  }
  return file_.data();
}

void AssetStream::release() {
  file_.clear();
  file_.shrink_to_fit();
  summary_ = {};
  headerRead_ = false;
}

Status AssetStream::decodeGeometry(BakedAsset* out) {
  AssetSummary s;
  if (Status st = peekAssetHeader(file_, &s); !st.isOk()) return st;
  if (s.fileSize != file_.size()) {
    return Status::error(StatusCode::kCorrupt, "the asset's header declares " + std::to_string(s.fileSize) +
                                                   " bytes but the catalogue said " + std::to_string(file_.size()));
  }
  BakedAsset decoded;
  if (Status st = decodeAssetGeometry(file_, &decoded); !st.isOk()) return st;
  // Empty for an asset without texel passes; else the sections must be here (checksummed).
  if (Status st = decodeAssetAtlases(file_, &decoded); !st.isOk()) return st;
  // Empty without an RTT; else tangents, patch uv and the RTT must be here (checksummed).
  if (Status st = decodeAssetBiScale(file_, &decoded); !st.isOk()) return st;
  *out = std::move(decoded);
  summary_ = std::move(s);
  headerRead_ = true;
  return Status::ok();
}

int AssetStream::passIndex(int kind, TransferForm form, TransferDomain domain) const {
  for (std::size_t i = 0; i < summary_.passes.size(); ++i) {
    const AssetPassInfo& p = summary_.passes[i];
    if (static_cast<int>(p.kind) == kind && p.form == form && p.domain == domain) return static_cast<int>(i);
  }
  return -1;
}

bool AssetStream::hasKind(int kind) const { return passIndex(kind) >= 0; }
bool AssetStream::hasMatrixKind(int kind) const { return passIndex(kind, TransferForm::kMatrix) >= 0; }
bool AssetStream::hasTexelKind(int kind) const { return passIndex(kind, TransferForm::kVector, TransferDomain::kTexel) >= 0; }

bool AssetStream::hasVisibility() const { return visibilityIndex() >= 0; }

int AssetStream::visibilityIndex() const {
  for (std::size_t i = 0; i < summary_.passes.size(); ++i) {
    if (summary_.passes[i].form == TransferForm::kVisibility) return static_cast<int>(i);
  }
  return -1;
}

Status AssetStream::decodeVisibilityPass(int bands, TransferPass* out, int* order) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = visibilityIndex();
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no texel visibility pass");
  return decodeAssetPass(file_, i, bands, out, order);
}

Status AssetStream::decodeTexelPass(int kind, int bands, TransferPass* out, int* order) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = passIndex(kind, TransferForm::kVector, TransferDomain::kTexel);
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no texel pass of kind " + std::to_string(kind));
  return decodeAssetPass(file_, i, bands, out, order);
}

Status AssetStream::decodeMatrixPassCpca(int kind, int bands, CpcaMatrixTransfer* out, TransferPass* info) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = passIndex(kind, TransferForm::kMatrix);
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no matrix pass of kind " + std::to_string(kind));
  return decodeAssetPassCpcaMatrix(file_, i, bands, out, info);
}

Status AssetStream::decodeSpecular(std::vector<SpecularMaterial>* out) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  return decodeAssetSpecular(file_, out);
}

bool AssetStream::isCpca(int kind) const { return isCpcaAt(passIndex(kind)); }
bool AssetStream::isMatrixCpca(int kind) const { return isCpcaAt(passIndex(kind, TransferForm::kMatrix)); }

Status AssetStream::decodeMatrixPass(int kind, int bands, TransferPass* out, int* order) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = passIndex(kind, TransferForm::kMatrix);
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no matrix pass of kind " + std::to_string(kind));
  return decodeAssetPass(file_, i, bands, out, order);
}

bool AssetStream::isCpcaAt(int i) const {
  if (!headerRead_ || i < 0 || !summary_.passes[static_cast<std::size_t>(i)].encoded) return false;
  const AssetSectionInfo& section = summary_.sections[summary_.passes[static_cast<std::size_t>(i)].section];
  // Offsets were checked against the file size by peekAssetHeader.
  const auto blob = std::span<const std::uint8_t>(file_).subspan(static_cast<std::size_t>(section.offset),
                                                                 static_cast<std::size_t>(section.size));
  TransferBlobInfo info;
  return readTransferBlobInfo(blob, &info).isOk() && info.encoding == TransferEncoding::kCpca;
}

Status AssetStream::decodePass(int kind, int bands, TransferPass* out, int* order) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = passIndex(kind);
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no transfer pass of kind " + std::to_string(kind));
  return decodeAssetPass(file_, i, bands, out, order);
}

Status AssetStream::decodePassCpca(int kind, int bands, CpcaTransfer* out, TransferPass* info) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  const int i = passIndex(kind);
  if (i < 0) return Status::error(StatusCode::kInvalidArgument, "the asset has no transfer pass of kind " + std::to_string(kind));
  return decodeAssetPassCpca(file_, i, bands, out, info);
}

}  // namespace prt::web
