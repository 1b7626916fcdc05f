// The served form of the scene thumbnails (thumbnail.h): one immutable PNG resource per
// asset content hash, at /api/scenes/thumbnail/<XXH64 of the PNG>.png, made once and shared
// by every catalogue snapshot while some listed file still has that hash.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "prt/asset.h"
#include "resource.h"

namespace prt::serve {

inline constexpr std::string_view kThumbnailPrefix = "/api/scenes/thumbnail/";

// A thumbnail, or the record that one could not be made (url empty, resource null), so
// the same content is not tried again.
struct ServedThumbnail {
  std::string url;  // /api/scenes/thumbnail/<hash>.png
  std::shared_ptr<const Resource> resource;
};

// Asset content hash (16 hex digits) to its thumbnail.
using ThumbnailMap = std::map<std::string, std::shared_ptr<const ServedThumbnail>, std::less<>>;

// Makes thumbnails during one catalogue refresh, reusing those already made for the same
// content (the previous snapshot's and this refresh's). Not thread-safe (the catalogue
// refreshes on one thread at a time).
class ThumbnailPool {
 public:
  explicit ThumbnailPool(ThumbnailMap known) : known_(std::move(known)) {}

  // The thumbnail of the verified asset `file` whose content hash is `assetHash`: the one
  // already made for that hash, else a new one (makeThumbnailPng). Never null; url empty
  // when none could be made, the reason logged with `relPath` (the asset stays listed and
  // served). Catches every exception: a thumbnail never takes a scene or the server down.
  std::shared_ptr<const ServedThumbnail> thumbnailFor(const std::string& assetHash, std::span<const std::uint8_t> file,
                                                      const AssetSummary& summary, const std::string& relPath);

 private:
  ThumbnailMap known_;
};

}  // namespace prt::serve
