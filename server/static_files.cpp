#include "static_files.h"

#include <cstdio>

#include "encoded_variants.h"
#include "mime_types.h"
#include "page_policy.h"

namespace prt::serve {
namespace {

constexpr std::uint64_t kMinCompressBytes = 256;        // below this, headers dominate
constexpr std::uint64_t kMaxCompressBytes = 32u << 20;  // a larger file is sent as it is
constexpr std::uint64_t kCacheBytes = 64u << 20;        // total size of cached variants
constexpr std::size_t kCacheEntries = 512;

bool hasHiddenSegment(std::string_view path) {
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (path[i] == '/' && path[i + 1] == '.') return true;
  }
  return false;
}

std::string hex(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

StaticFiles::StaticFiles(RootDir web) : web_(std::move(web)) {}

std::vector<Variant> StaticFiles::variantsFor(const FileRef& file, const FileStamp& stamp, const std::string& baseTag) {
  {
    std::lock_guard lock(mutex_);
    for (auto it = cache_.begin(); it != cache_.end(); ++it) {
      if (it->stamp == stamp) {
        cache_.splice(cache_.begin(), cache_, it);
        return it->variants;
      }
    }
  }
  // Compressed outside the lock: two first requests may both compress, which costs time
  // once but never blocks requests for other files.
  Cached c;
  c.stamp = stamp;
  std::vector<std::uint8_t> bytes;
  // Unreadable now: served as it is, uncompressed, from the descriptor.
  if (!readAllAt(file->fd(), stamp.size, &bytes).isOk()) return {};
  // Rewritten while being read: the bytes may be half old, half new, and must not be
  // cached under the old version's stamp.
  struct stat after {};
  if (::fstat(file->fd(), &after) != 0 || !(stampOf(after) == stamp)) return {};
  c.variants = makeEncodedVariants(bytes, baseTag, VariantStorage::kMemory, nullptr);
  for (const Variant& v : c.variants) c.bytes += v.body.size;
  std::lock_guard lock(mutex_);
  cache_.push_front(c);
  cachedBytes_ += c.bytes;
  while ((cachedBytes_ > kCacheBytes || cache_.size() > kCacheEntries) && cache_.size() > 1) {
    cachedBytes_ -= cache_.back().bytes;
    cache_.pop_back();
  }
  return c.variants;
}

Reply StaticFiles::serve(const RequestHead& request, std::string_view path, std::string_view rawPath) {
  const unsigned version = request.version();
  if (hasHiddenSegment(path)) return errorReply(version, http::status::not_found, "not found", false);
  std::string relative(path.substr(1));
  if (relative.empty() || relative.back() == '/') relative += "index.html";
  FileRef file;
  struct stat st {};
  switch (web_.openRelative(relative, &file, &st)) {
    case OpenOutcome::kFile: break;
    case OpenOutcome::kDirectory: {
      Reply r = errorReply(version, http::status::moved_permanently, "this is a directory", false);
      r.head.set(http::field::location, std::string(rawPath) + "/");
      return r;
    }
    case OpenOutcome::kMissing:
    case OpenOutcome::kOutside: return errorReply(version, http::status::not_found, "not found", false);
  }
  const FileStamp stamp = stampOf(st);
  Resource resource;
  resource.contentType = std::string(contentTypeFor(relative));
  // The client's files change with each build, under the same names: caches must ask
  // (cheaply, If-None-Match) before reusing them.
  resource.cacheControl = "no-cache";
  // Strong validator from the stamp (inode, size, modification time), as nginx does: a
  // content hash would mean reading every file once per version.
  const std::string tag = hex(stamp.inode) + "-" + hex(stamp.size) + "-" + hex(static_cast<std::uint64_t>(stamp.mtimeNs));
  Variant identity;
  identity.body.file = file;
  identity.body.size = stamp.size;
  identity.etag = etagFor(tag, Encoding::kIdentity);
  resource.variants.push_back(std::move(identity));
  if (isCompressibleType(resource.contentType) && stamp.size >= kMinCompressBytes && stamp.size <= kMaxCompressBytes) {
    for (Variant& v : variantsFor(file, stamp, tag)) resource.variants.push_back(std::move(v));
  }
  Reply reply = respond(request, resource);
  addDocumentPolicy(resource.contentType, reply.head);
  return reply;
}

}  // namespace prt::serve
