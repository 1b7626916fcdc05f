#include "thumbnail_store.h"

#include <exception>

#include "content_hash.h"
#include "encoded_variants.h"
#include "public_error.h"
#include "thumbnail.h"

namespace prt::serve {

std::shared_ptr<const ServedThumbnail> ThumbnailPool::thumbnailFor(const std::string& assetHash,
                                                                   std::span<const std::uint8_t> file,
                                                                   const AssetSummary& summary,
                                                                   const std::string& relPath) {
  if (const auto it = known_.find(assetHash); it != known_.end()) return it->second;
  auto made = std::make_shared<ServedThumbnail>();
  std::string png;
  Status status = Status::ok();
  try {
    status = makeThumbnailPng(file, summary, &png);
  } catch (const std::exception& e) {  // out of memory, most likely
    status = Status::error(StatusCode::kResourceExhausted, e.what());
  }
  if (status.isOk()) {
    const std::string tag = hashHex(xxh64({reinterpret_cast<const std::uint8_t*>(png.data()), png.size()}));
    auto r = std::make_shared<Resource>();
    r->contentType = "image/png";
    // Named by its bytes: any cache may keep it for good. PNG is compressed already: no variants.
    r->cacheControl = "public, max-age=31536000, immutable";
    Variant identity;
    identity.body = memoryBody(std::move(png));
    identity.etag = etagFor(tag, Encoding::kIdentity);
    r->variants.push_back(std::move(identity));
    made->url = std::string(kThumbnailPrefix) + tag + ".png";
    made->resource = std::move(r);
  } else {
    logDetail("thumbnail of asset '" + relPath + "'", status.toString());
  }
  known_.emplace(assetHash, made);
  return made;
}

}  // namespace prt::serve
