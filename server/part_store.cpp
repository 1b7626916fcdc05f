#include "part_store.h"

#include <algorithm>

#include "content_hash.h"
#include "encoded_variants.h"

namespace prt::serve {
namespace {

std::shared_ptr<const Resource> partResource(std::span<const std::uint8_t> bytes, const std::string& hash,
                                             bool compress) {
  auto r = std::make_shared<Resource>();
  r->contentType = "application/octet-stream";
  // Named by its content: any cache may keep it for good.
  r->cacheControl = "public, max-age=31536000, immutable";
  Variant identity;
  identity.body = memoryBody(std::string(bytes.begin(), bytes.end()));
  identity.etag = etagFor(hash, Encoding::kIdentity);
  r->variants.push_back(std::move(identity));
  if (compress) {
    for (Variant& v : makeEncodedVariants(bytes, hash, VariantStorage::kMemory, nullptr)) r->variants.push_back(std::move(v));
  }
  return r;
}

bool sameBytes(const Resource& held, std::span<const std::uint8_t> bytes) {
  const std::string& h = *held.variants.front().body.memory;
  return h.size() == bytes.size() && std::equal(bytes.begin(), bytes.end(), h.begin(),
                                                [](std::uint8_t a, char b) { return a == static_cast<std::uint8_t>(b); });
}

}  // namespace

bool PartPool::makeParts(std::span<const std::uint8_t> file, const AssetSummary& summary, bool compress,
                         std::vector<ServedPart>* out) {
  out->clear();
  std::vector<ServedPart> served;
  for (const AssetPart& range : cutAssetParts(file, summary)) {
    const std::span<const std::uint8_t> bytes = file.subspan(range.offset, range.size);
    const std::string hash = hashHex(xxh64(bytes));
    ServedPart p{range, std::string(kPartPrefix) + hash, nullptr};
    if (const auto it = parts_.find(p.url); it != parts_.end()) {
      if (!sameBytes(*it->second, bytes)) return false;
      p.resource = it->second;
    } else {
      p.resource = partResource(bytes, hash, compress);
      parts_.emplace(p.url, p.resource);
    }
    served.push_back(std::move(p));
  }
  if (served.empty()) return false;
  *out = std::move(served);
  return true;
}

}  // namespace prt::serve
