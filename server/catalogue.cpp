#include "catalogue.h"

#include <sys/stat.h>

#include "content_hash.h"
#include "encoded_variants.h"
#include "native/json_text.h"
#include "public_error.h"
#include "request_target.h"
#include "temp_file.h"

namespace prt::serve {
namespace {

constexpr std::string_view kExtensions[] = {".prt"};

std::int64_t steadyNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::string baseName(const std::string& rel) {
  const std::size_t slash = rel.rfind('/');
  return slash == std::string::npos ? rel : rel.substr(slash + 1);
}

std::string stem(const std::string& fileName) {
  const std::size_t dot = fileName.rfind('.');
  return dot == std::string::npos ? fileName : fileName.substr(0, dot);
}

bool urlSafeName(std::string_view name) {
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f || c == '\\') return false;
  }
  return true;
}

// Examines one listed file: open, read, verify, hash, make the variants, the parts and the
// thumbnail.
std::shared_ptr<const CatalogueEntry> examine(const RootDir& root, const ScannedFile& scanned,
                                              const CatalogueOptions& options, PartPool* pool,
                                              ThumbnailPool* thumbnails, bool* unstable) {
  auto e = std::make_shared<CatalogueEntry>();
  e->file = scanned.relPath;
  const std::string fileName = baseName(scanned.relPath);
  e->name = stem(fileName);
  e->bytes = scanned.stamp.size;
  if (!scanned.problem.empty()) {
    e->error = scanned.problem;
    return e;
  }
  FileRef file;
  struct stat st {};
  switch (root.openRelative(scanned.relPath, &file, &st)) {
    case OpenOutcome::kFile: break;
    case OpenOutcome::kOutside: e->error = "resolves outside the root"; return e;
    default: e->error = "cannot be opened"; *unstable = true; return e;
  }
  e->stamp = stampOf(st);
  e->bytes = e->stamp.size;
  if (e->bytes > options.maxAssetBytes) {
    e->error = "larger than the server's limit of " + std::to_string(options.maxAssetBytes) + " bytes";
    return e;
  }
  if (!urlSafeName(fileName)) {
    e->error = "file name holds control characters or a backslash";
    return e;
  }
  std::vector<std::uint8_t> bytes;
  if (Status s = readAllAt(file->fd(), e->bytes, &bytes); !s.isOk()) {
    e->error = s.message();
    *unstable = true;
    return e;
  }
  struct stat after {};
  if (::fstat(file->fd(), &after) != 0 || !(stampOf(after) == e->stamp)) {
    // Being written right now; what was read may be half old, half new.
    e->error = "changed while being read; it will be examined again";
    e->stamp = {};
    *unstable = true;
    return e;
  }
  if (Status s = verifyAsset(bytes, &e->summary); !s.isOk()) {
    e->error = s.toString();
    return e;
  }
  if (!e->summary.name.empty()) e->name = e->summary.name;
  e->hash = hashHex(xxh64(bytes));
  e->url = "/assets/" + e->hash + "/" + encodePathSegment(fileName);

  auto resource = std::make_shared<Resource>();
  resource->contentType = "application/octet-stream";
  // The URL changes whenever the content does, so any cache may keep it for good.
  resource->cacheControl = "public, max-age=31536000, immutable";
  Variant identity;
  // Sent from a private copy written from the very bytes just verified and hashed, not
  // from the file: sendfile reads the page cache at send time (and TCP keeps referring to
  // those pages until they are acknowledged), so an in-place write during a download
  // would otherwise go out under the old hash, immutable, for a year of caching.
  const std::string_view verified(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (Status s = writeTempFile(verified, &identity.body.file); !s.isOk()) {
    logDetail("asset '" + scanned.relPath + "'", s.message());
    e->error = "the server could not store its private copy (temporary directory full or unwritable; see its log)";
    return e;
  }
  e->source = std::move(file);
  identity.body.size = e->bytes;
  identity.etag = etagFor(e->hash, Encoding::kIdentity);
  resource->variants.push_back(std::move(identity));
  if (options.compress && e->bytes <= options.maxCompressBytes) {
    for (Variant& v : makeEncodedVariants(bytes, e->hash, VariantStorage::kTempFile, nullptr)) {
      resource->variants.push_back(std::move(v));
    }
  }
  e->resource = std::move(resource);
  if (e->bytes <= options.maxPartsBytes) {
    // On failure (never for a verified file, short of an XXH64 collision) the entry has
    // no parts and clients fetch the whole asset.
    pool->makeParts(bytes, e->summary, options.compress && e->bytes <= options.maxCompressBytes, &e->parts);
  }
  if (e->bytes <= options.maxThumbnailBytes) {
    // Never fails the entry: without a thumbnail it is listed and served the same.
    e->thumbnail = thumbnails->thumbnailFor(e->hash, bytes, e->summary, scanned.relPath);
  }
  e->usable = true;
  return e;
}

// The catalogue is public: an error that would show where the server keeps its files is
// replaced (and logged in full). The reader's messages name no paths; this is the wall in
// case one ever does.
std::shared_ptr<const CatalogueEntry> withPublicError(std::shared_ptr<const CatalogueEntry> entry,
                                                      const ScannedFile& scanned, const RootDir& root) {
  const std::string safe = publicMessage(entry->error, scanned.absPath, scanned.relPath, root.path(),
                                         "cannot be used (the server's log has the details)");
  if (safe == entry->error) return entry;
  logDetail("asset '" + scanned.relPath + "'", entry->error);
  auto copy = std::make_shared<CatalogueEntry>(*entry);
  copy->error = safe;
  return copy;
}

// {"offset":O,"size":S,"url":"/parts/<hash>","kind":K[,"section":i][,"pass":P[,"form":"matrix"|"visibility"],"domain":D][,"band":l]};
// the atlas sections' parts carry "domain":"texel" without a pass.
std::string partJson(const ServedPart& p) {
  const AssetPart& r = p.range;
  std::string j = "{\"offset\":" + std::to_string(r.offset) + ",\"size\":" + std::to_string(r.size) +
                  ",\"url\":" + jsonString(p.url) + ",\"kind\":\"" + assetPartKindName(r.kind) + "\"";
  if (r.section >= 0) j += ",\"section\":" + std::to_string(r.section);
  if (r.hasPass) j += ",\"pass\":" + jsonString(transferKindName(r.pass));
  if (r.matrix) j += ",\"form\":\"matrix\"";
  if (r.visibility) j += ",\"form\":\"visibility\"";
  // The client needs the domain to leave texel data alone until it renders transfer textures.
  if (r.hasPass || r.domain == TransferDomain::kTexel) j += ",\"domain\":" + jsonString(transferDomainName(r.domain));
  if (r.band >= 0) j += ",\"band\":" + std::to_string(r.band);
  return j + "}";
}

std::string entryJson(const CatalogueEntry& e) {
  std::string j = "{\"name\":" + jsonString(e.name) + ",\"file\":" + jsonString(e.file) +
                  ",\"usable\":" + (e.usable ? "true" : "false") + ",\"bytes\":" + std::to_string(e.bytes);
  if (!e.usable) return j + ",\"error\":" + jsonString(e.error) + "}";
  const AssetSummary& s = e.summary;
  j += ",\"url\":" + jsonString(e.url) + ",\"hash\":" + jsonString(e.hash);
  j += ",\"version\":\"" + std::to_string(s.versionMajor) + "." + std::to_string(s.versionMinor) + "\"";
  j += ",\"vertices\":" + std::to_string(s.vertexCount) + ",\"triangles\":" + std::to_string(s.triangleCount);
  j += ",\"shOrder\":" + std::to_string(s.shOrder) + ",\"passes\":[";
  for (std::size_t i = 0; i < s.passes.size(); ++i) {
    const AssetPassInfo& p = s.passes[i];
    // Glossy matrix passes say so; vector passes keep the listing they always had. Every pass
    // says where its transfer lives: per vertex, or per texel of the atlases.
    j += std::string(i ? "," : "") + "{\"kind\":" + jsonString(transferKindName(p.kind)) +
         (p.form != TransferForm::kVector ? ",\"form\":" + jsonString(transferFormName(p.form)) : "") +
         (p.form == TransferForm::kVisibility ? ",\"order\":" + std::to_string(p.order) : "") +
         ",\"domain\":" + jsonString(transferDomainName(p.domain)) +
         ",\"channels\":" + std::to_string(p.channels) + ",\"bounces\":" + std::to_string(p.bounces) + "}";
  }
  j += "],\"texels\":" + std::to_string(s.texelCount) + ",\"samples\":" + std::to_string(s.samples) + ",\"sampling\":" + jsonString(s.sampling);
  // The client needs the lighting model to light the transfer correctly, and for the local
  // models where to render its light cube map from (docs/spatially-varying.md).
  j += ",\"lighting\":" + jsonString(lightingModelName(s.lighting.model));
  if (isLocalLighting(s.lighting.model)) {
    const Vec3 c = s.lighting.center;
    j += ",\"lightCenter\":[" + jsonNumber(c.x) + "," + jsonNumber(c.y) + "," + jsonNumber(c.z) +
         "],\"lightRadius\":" + jsonNumber(s.lighting.radius);
  }
  j += ",\"encodings\":[";
  for (std::size_t i = 1; i < e.resource->variants.size(); ++i) {
    j += std::string(i > 1 ? "," : "") + "\"" + encodingToken(e.resource->variants[i].encoding) + "\"";
  }
  j += "]";
  if (e.thumbnail && !e.thumbnail->url.empty()) j += ",\"thumbnail\":" + jsonString(e.thumbnail->url);
  if (!e.parts.empty()) {
    j += ",\"parts\":[";
    for (std::size_t i = 0; i < e.parts.size(); ++i) {
      if (i > 0) j += ",";
      j += partJson(e.parts[i]);
    }
    j += "]";
  }
  return j + "}";
}

// The /api/scenes document as a resource: revalidated on every use (no-cache), with an
// ETag from its content, so an unchanged catalogue costs a client one 304.
std::shared_ptr<const Resource> documentResource(const std::string& text) {
  auto r = std::make_shared<Resource>();
  r->contentType = "application/json";
  r->cacheControl = "no-cache";
  const std::string tag = hashHex(xxh64({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}));
  Variant identity;
  identity.body = memoryBody(text);
  identity.etag = etagFor(tag, Encoding::kIdentity);
  r->variants.push_back(std::move(identity));
  for (Variant& v : makeEncodedVariants({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, tag,
                                        VariantStorage::kMemory, nullptr)) {
    r->variants.push_back(std::move(v));
  }
  return r;
}

}  // namespace

Catalogue::Catalogue(RootDir root, CatalogueOptions options) : root_(std::move(root)), options_(options) {
  std::lock_guard lock(scanMutex_);
  refresh();
  nextCheck_.store(steadyNs() + std::chrono::nanoseconds(options_.recheck).count());
}

std::shared_ptr<const CatalogueSnapshot> Catalogue::current() {
  if (steadyNs() >= nextCheck_.load(std::memory_order_relaxed)) {
    std::unique_lock lock(scanMutex_, std::try_to_lock);
    if (lock.owns_lock() && steadyNs() >= nextCheck_.load()) {
      refresh();
      nextCheck_.store(steadyNs() + std::chrono::nanoseconds(options_.recheck).count());
    }
  }
  std::lock_guard lock(snapshotMutex_);
  return snapshot_;
}

std::shared_ptr<const CatalogueEntry> Catalogue::findAsset(std::string_view path) {
  const std::shared_ptr<const CatalogueSnapshot> snap = current();
  const auto it = snap->byPath.find(path);
  if (it == snap->byPath.end()) return nullptr;
  const CatalogueEntry& e = *it->second;
  struct stat st {};
  if (::fstat(e.source->fd(), &st) != 0 || !(stampOf(st) == e.stamp)) {
    nextCheck_.store(0);  // rewritten in place: the next request rescans
    return nullptr;
  }
  return it->second;
}

std::shared_ptr<const Resource> Catalogue::findThumbnail(std::string_view path) {
  const std::shared_ptr<const CatalogueSnapshot> snap = current();
  const auto it = snap->thumbnails.find(path);
  return it == snap->thumbnails.end() ? nullptr : it->second;
}

std::shared_ptr<const Resource> Catalogue::findPart(std::string_view path) {
  const std::shared_ptr<const CatalogueSnapshot> snap = current();
  const auto it = snap->parts.find(path);
  return it == snap->parts.end() ? nullptr : it->second;
}

void Catalogue::refresh() {
  std::vector<ScannedFile> listing = scanDirectory(root_, kExtensions);
  std::shared_ptr<const CatalogueSnapshot> old;
  {
    std::lock_guard lock(snapshotMutex_);
    old = snapshot_;
  }
  if (old && !old->retry && old->listing == listing) return;

  std::map<std::string, std::shared_ptr<const CatalogueEntry>, std::less<>> previous;
  if (old) {
    for (const auto& e : old->entries) previous.emplace(e->file, e);
  }
  auto snap = std::make_shared<CatalogueSnapshot>();
  PartPool pool(old ? old->parts : PartMap{});
  ThumbnailPool thumbnails(old ? old->thumbnailsByHash : ThumbnailMap{});
  for (const ScannedFile& f : listing) {
    const auto it = previous.find(f.relPath);
    const bool same = it != previous.end() && f.problem.empty() && !(it->second->stamp == FileStamp{}) &&
                      it->second->stamp == f.stamp;
    std::shared_ptr<const CatalogueEntry> entry = same ? it->second : examine(root_, f, options_, &pool, &thumbnails, &snap->retry);
    if (!same && !entry->usable) entry = withPublicError(entry, f, root_);
    if (entry->usable) {
      ++snap->usableCount;
      snap->byPath.emplace("/assets/" + entry->hash + "/" + baseName(entry->file), entry);
      for (const ServedPart& p : entry->parts) snap->parts.emplace(p.url, p.resource);
      // Only the hashes still listed are kept, so a deleted asset's thumbnail goes with it.
      if (entry->thumbnail) {
        snap->thumbnailsByHash.emplace(entry->hash, entry->thumbnail);
        if (entry->thumbnail->resource) snap->thumbnails.emplace(entry->thumbnail->url, entry->thumbnail->resource);
      }
    }
    snap->entries.push_back(std::move(entry));
  }
  std::string json = "{\"scenes\":[";
  for (std::size_t i = 0; i < snap->entries.size(); ++i) json += (i ? ",\n" : "\n") + entryJson(*snap->entries[i]);
  json += "\n],\"usable\":" + std::to_string(snap->usableCount) +
          ",\"unusable\":" + std::to_string(snap->entries.size() - static_cast<std::size_t>(snap->usableCount)) + "}\n";
  snap->json = documentResource(json);
  snap->listing = std::move(listing);
  std::lock_guard lock(snapshotMutex_);
  snapshot_ = std::move(snap);
}

}  // namespace prt::serve
