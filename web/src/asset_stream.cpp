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
  if (Status st = decodeAssetGeometry(file_, out); !st.isOk()) return st;
  summary_ = std::move(s);
  headerRead_ = true;
  return Status::ok();
}

bool AssetStream::hasKind(int kind) const {
  for (const AssetPassInfo& p : summary_.passes)
    if (static_cast<int>(p.kind) == kind) return true;
  return false;
}

Status AssetStream::decodePass(int kind, int bands, TransferPass* out, int* order) {
  if (!headerRead_) return Status::error(StatusCode::kInvalidArgument, "the asset's geometry has not been decoded yet");
  for (std::size_t i = 0; i < summary_.passes.size(); ++i) {
    if (static_cast<int>(summary_.passes[i].kind) != kind) continue;
    return decodeAssetPass(file_, static_cast<int>(i), bands, out, order);
  }
  return Status::error(StatusCode::kInvalidArgument, "the asset has no transfer pass of kind " + std::to_string(kind));
}

}  // namespace prt::web
