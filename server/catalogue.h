// The catalogue of baked assets under --root: which .prt files exist, whether each one is
// valid (verifyAsset, every checksum and value), its content hash and URL, and the JSON
// document /api/scenes serves. It follows the directory: a request after the recheck
// interval walks the tree (stat only) and re-examines just the files whose stamp changed.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "dir_scan.h"
#include "part_store.h"
#include "prt/asset.h"
#include "resource.h"
#include "root_dir.h"
#include "thumbnail_store.h"

namespace prt::serve {

struct CatalogueEntry {
  std::string file;  // path under the root
  std::string name;  // the asset's own name (metadata), else the file name without .prt
  std::uint64_t bytes = 0;
  FileStamp stamp;   // of the version that was verified
  bool usable = false;
  std::string error;  // why not, when !usable
  AssetSummary summary;
  std::string hash;  // 16 hex digits of XXH64 over the file, when usable
  std::string url;   // /assets/<hash>/<file name, percent-encoded>
  // Every representation is the server's own copy of the verified bytes (identity and
  // variants in anonymous temporary files, parts in memory): nothing done to the file
  // under the root can change what goes out under the content-addressed URL.
  std::shared_ptr<const Resource> resource;
  FileRef source;  // the file as verified; its stamp tells an in-place rewrite
  std::vector<ServedPart> parts;  // the file cut into parts, in file order; empty: served whole only
  // Its picture for the scene picker (thumbnail.h); null for unusable entries and url empty
  // when none could be made (the entry is listed all the same, without "thumbnail").
  std::shared_ptr<const ServedThumbnail> thumbnail;
};

struct CatalogueSnapshot {
  std::vector<ScannedFile> listing;  // the walk this snapshot was built from
  std::vector<std::shared_ptr<const CatalogueEntry>> entries;  // sorted by file
  // Decoded URL path ("/assets/<hash>/<name>") to its usable entry.
  std::map<std::string, std::shared_ptr<const CatalogueEntry>, std::less<>> byPath;
  PartMap parts;  // every part of every usable entry, by URL path (shared parts once)
  ThumbnailMap thumbnailsByHash;  // by asset content hash: what the next refresh reuses
  std::map<std::string, std::shared_ptr<const Resource>, std::less<>> thumbnails;  // by URL path
  std::shared_ptr<const Resource> json;  // the /api/scenes document
  bool retry = false;  // some file changed while it was read: look again next time
  int usableCount = 0;
};

struct CatalogueOptions {
  std::chrono::milliseconds recheck{1000};  // how stale a listing may get
  std::uint64_t maxAssetBytes = std::uint64_t{1} << 30;  // larger files are listed unusable
  bool compress = true;  // make br/zstd/gzip variants...
  // ...for assets up to this size: ~0.1 s per MB of scan time for the three, which would
  // hold the catalogue of a 250 MB asset for half a minute. Larger ones go out as they are.
  std::uint64_t maxCompressBytes = std::uint64_t{64} << 20;
  // Assets up to this size are also cut into parts (/parts/<hash>), which are held in
  // memory with their br/zstd/gzip variants: about 3x the asset's size. 0: no parts at all.
  std::uint64_t maxPartsBytes = std::uint64_t{64} << 20;
  // Assets up to this size get a thumbnail (a decode and a small CPU render at scan time:
  // about 12 ms for the 20k-vertex demo room). 0: no thumbnails.
  std::uint64_t maxThumbnailBytes = std::uint64_t{64} << 20;
};

class Catalogue {
 public:
  // Scans `root` once, so the first request finds a listing.
  Catalogue(RootDir root, CatalogueOptions options);

  // The current snapshot, re-examining the root first when the last look is older than the
  // recheck interval (one thread looks; the others keep using the previous snapshot).
  std::shared_ptr<const CatalogueSnapshot> current();

  // The usable entry at decoded URL `path`, provided its file still is the verified version
  // (an in-place rewrite is noticed here, and triggers a rescan); null otherwise. Responses
  // already under way keep sending the private copy, so they stay byte-exact.
  std::shared_ptr<const CatalogueEntry> findAsset(std::string_view path);

  // The part at decoded URL path ("/parts/<hash>") in the current snapshot; null otherwise.
  // Parts are copies of verified bytes, so a later change to the file cannot reach them.
  std::shared_ptr<const Resource> findPart(std::string_view path);

  // The thumbnail PNG at decoded URL path ("/api/scenes/thumbnail/<hash>.png") in the current
  // snapshot; null otherwise.
  std::shared_ptr<const Resource> findThumbnail(std::string_view path);

 private:
  void refresh();

  RootDir root_;
  CatalogueOptions options_;
  std::mutex scanMutex_;  // one scan at a time
  mutable std::mutex snapshotMutex_;
  std::shared_ptr<const CatalogueSnapshot> snapshot_;
  std::atomic<std::int64_t> nextCheck_{0};  // steady-clock nanoseconds
};

}  // namespace prt::serve
