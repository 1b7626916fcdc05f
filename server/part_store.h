// The served form of an asset's parts (asset_parts.h): one immutable, content-addressed
// resource per distinct part, at /parts/<XXH64 of its bytes>, held in memory with its
// precompressed variants and shared by every asset (and every snapshot) that holds the
// same bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "asset_parts.h"
#include "resource.h"

namespace prt::serve {

inline constexpr std::string_view kPartPrefix = "/parts/";

// Part URL path ("/parts/<16 hex digits>") to its resource.
using PartMap = std::map<std::string, std::shared_ptr<const Resource>, std::less<>>;

struct ServedPart {
  AssetPart range;   // where it lies in the asset and what it holds
  std::string url;   // /parts/<hash>
  std::shared_ptr<const Resource> resource;
};

// Makes part resources during one catalogue refresh, reusing those already held: the
// previous snapshot's and the ones made earlier in this refresh. Not thread-safe (the
// catalogue refreshes on one thread at a time).
class PartPool {
 public:
  // Starts from `known` (the previous snapshot's parts).
  explicit PartPool(PartMap known) : parts_(std::move(known)) {}

  // The served parts of the verified asset `file` (cutAssetParts of `summary`), in file
  // order, with br/zstd/gzip variants when `compress`. False (and *out empty) when the
  // file cannot be cut or a part's hash is already held for different bytes (an XXH64
  // collision): the asset is then served whole only.
  bool makeParts(std::span<const std::uint8_t> file, const AssetSummary& summary, bool compress,
                 std::vector<ServedPart>* out);

 private:
  PartMap parts_;
};

}  // namespace prt::serve
