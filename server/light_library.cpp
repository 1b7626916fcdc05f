#include "light_library.h"

#include <cstdio>

#include "content_hash.h"
#include "encoded_variants.h"
#include "native/image_io.h"
#include "native/json_text.h"
#include "light_preview.h"
#include "public_error.h"

namespace prt::serve {
namespace {

constexpr std::string_view kExtensions[] = {".exr", ".hdr"};
constexpr int kPreviewWidth = 256;
// The background texture's width (2:1, so 1024 x 512, 2 MiB as RGB9E5): about 0.35 degrees a
// texel, a few screen pixels at the page's 0.8 rad field of view on a laptop screen;
// 2048 would be 8 MiB for a sharper sky on large screens, after the scene.
constexpr int kBackgroundWidth = 1024;

// A derived image (immutable, cached for a year): `bytes` at a URL under `prefix` named by
// their hash, so a changed map gets a new URL; sets *path to that URL.
std::shared_ptr<Resource> derivedImage(std::string bytes, const char* contentType, const std::string& prefix, const char* suffix,
                                       std::string* path) {
  auto r = std::make_shared<Resource>();
  r->contentType = contentType;
  r->cacheControl = "public, max-age=31536000, immutable";
  const std::string tag = hashHex(xxh64({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}));
  Variant v;
  v.body = memoryBody(std::move(bytes));
  v.etag = etagFor(tag, Encoding::kIdentity);
  r->variants.push_back(std::move(v));
  *path = prefix + tag + suffix;
  return r;
}

std::string stemOf(const std::string& rel) {
  std::string name = rel.substr(rel.rfind('/') == std::string::npos ? 0 : rel.rfind('/') + 1);
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

ImageFormat sniffFormat(const std::string& path) {
  unsigned char head[16] = {};
  std::size_t got = 0;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    got = std::fread(head, 1, sizeof head, f);
    std::fclose(f);
  }
  return detectImageFormat(head, got);
}

std::shared_ptr<const Resource> jsonResource(const std::string& text) {
  auto r = std::make_shared<Resource>();
  r->contentType = "application/json";
  r->cacheControl = "no-cache";
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  const std::string tag = hashHex(xxh64(bytes));
  Variant identity;
  identity.body = memoryBody(text);
  identity.etag = etagFor(tag, Encoding::kIdentity);
  r->variants.push_back(std::move(identity));
  for (Variant& v : makeEncodedVariants(bytes, tag, VariantStorage::kMemory, nullptr)) r->variants.push_back(std::move(v));
  return r;
}

}  // namespace

std::string LightLibrary::publicError(const ScannedFile& file, const std::string& detail) const {
  // The loader names the file by its absolute path, and OpenEXR's messages repeat it.
  logDetail("environment map '" + file.relPath + "'", detail);
  return publicMessage(detail, file.absPath, file.relPath, root_.path(),
                       "cannot be read as an image (the server's log has the details)");
}

LightLibrary::LightLibrary(RootDir root, std::chrono::milliseconds recheck) : root_(std::move(root)), recheck_(recheck) {
  {
    std::lock_guard lock(mutex_);
    refreshLocked();
    nextCheck_ = std::chrono::steady_clock::now() + recheck_;
  }
  worker_ = std::thread([this] { work(); });
}

LightLibrary::~LightLibrary() { stop(); }

void LightLibrary::stop() {
  std::map<int, std::vector<DocumentCallback>> dropped;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    queue_.clear();
    dropped.swap(waiting_);
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
  // `dropped` goes here, outside the lock: the callbacks hold sessions.
}

std::size_t LightLibrary::count() {
  std::lock_guard lock(mutex_);
  return lights_.size();
}

void LightLibrary::refreshLocked() {
  std::vector<ScannedFile> listing = scanDirectory(root_, kExtensions);
  if (listing == listing_) return;
  std::map<std::string, std::shared_ptr<Light>, std::less<>> previous;
  for (const auto& l : lights_) previous.emplace(l->scanned.relPath, l);
  std::vector<std::shared_ptr<Light>> lights;
  for (const ScannedFile& f : listing) {
    const auto it = previous.find(f.relPath);
    if (it != previous.end() && it->second->scanned == f) {
      lights.push_back(it->second);
      continue;
    }
    auto l = std::make_shared<Light>();
    l->scanned = f;
    if (!f.problem.empty()) {
      l->error = f.problem;
      l->loaded = true;
    }
    lights.push_back(std::move(l));
  }
  lights_ = std::move(lights);
  listing_ = std::move(listing);
  ++generation_;
  documents_.clear();
  previews_.clear();
  for (const auto& l : lights_) {
    if (l->previewResource) previews_.emplace(l->previewPath, l->previewResource);
    if (l->backgroundResource) previews_.emplace(l->backgroundPath, l->backgroundResource);
  }
}

void LightLibrary::ensureProjected(Light& light, int order) {
  if (!light.error.empty() || light.coefficients.count(order)) return;
  RgbImage image;
  if (Status s = loadImage(light.scanned.absPath, &image); !s.isOk()) {
    light.error = publicError(light.scanned, s.message());
    light.loaded = true;
    return;
  }
  if (!light.loaded) {
    light.loaded = true;
    light.format = imageFormatName(sniffFormat(light.scanned.absPath));
    light.width = image.width;
    light.height = image.height;
    const char* aspect = nullptr;
    const std::optional<EnvLayout> layout = guessLayout(image.width, image.height, &aspect);
    if (!layout) {
      light.error = "its size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " matches no layout (2:1 equirect, 1:1 angular map, 4:3 or 3:4 cross)";
      return;
    }
    light.layout = *layout;
    std::string png;
    if (makePreviewPng(image, kPreviewWidth, &png).isOk()) {
      std::string path;
      auto r = derivedImage(std::move(png), "image/png", "/api/lights/preview/", ".png", &path);
      std::lock_guard lock(mutex_);
      light.previewPath = path;
      light.previewResource = r;
      previews_.emplace(light.previewPath, r);
    }
    std::string texture;
    int tw = 0, th = 0;
    if (light.layout == EnvLayout::kEquirect && makeBackgroundRgb9e5(image, kBackgroundWidth, &texture, &tw, &th).isOk()) {
      std::string path;
      auto r = derivedImage(std::move(texture), "application/octet-stream", "/api/lights/background/", ".rgb9e5", &path);
      std::lock_guard lock(mutex_);
      light.backgroundPath = path;
      light.backgroundResource = r;
      light.backgroundWidth = tw;
      light.backgroundHeight = th;
      previews_.emplace(light.backgroundPath, r);
    }
  }
  std::vector<Rgb> coeffs;
  if (Status s = projectLayout(light.layout, order, image, &coeffs); !s.isOk()) {
    light.error = publicError(light.scanned, s.message());
    return;
  }
  light.coefficients.emplace(order, std::move(coeffs));
}

std::shared_ptr<const Resource> LightLibrary::cachedDocument(int order) {
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (now >= nextCheck_) {
    refreshLocked();
    nextCheck_ = now + recheck_;
  }
  const auto it = documents_.find(order);
  return it == documents_.end() ? nullptr : it->second;
}

void LightLibrary::documentLater(int order, DocumentCallback done) {
  std::shared_ptr<const Resource> ready;
  {
    std::lock_guard lock(mutex_);
    if (const auto it = documents_.find(order); it != documents_.end()) {
      ready = it->second;
    } else {
      std::vector<DocumentCallback>& waiters = waiting_[order];
      if (waiters.empty()) queue_.push_back(order);
      waiters.push_back(std::move(done));
    }
  }
  if (ready) return done(std::move(ready));
  wake_.notify_one();
}

void LightLibrary::work() {
  for (;;) {
    int order = 0;
    std::vector<std::shared_ptr<Light>> lights;
    std::uint64_t generation = 0;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      order = queue_.front();
      queue_.pop_front();
      lights = lights_;
      generation = generation_;
    }
    std::shared_ptr<const Resource> doc;
    try {
      doc = makeDocument(order, lights);
    } catch (const std::exception& e) {
      logDetail("making the lights document for order " + std::to_string(order) + " failed", e.what());
    }
    std::vector<DocumentCallback> waiters;
    {
      std::lock_guard lock(mutex_);
      // Made from the listing of its time: served to those who asked meanwhile, but not
      // kept once the maps have changed.
      if (doc && generation == generation_) documents_.emplace(order, doc);
      if (const auto it = waiting_.find(order); it != waiting_.end()) {
        waiters = std::move(it->second);
        waiting_.erase(it);
      }
    }
    for (DocumentCallback& w : waiters) w(doc);
  }
}

std::shared_ptr<const Resource> LightLibrary::makeDocument(int order, const std::vector<std::shared_ptr<Light>>& lights) {
  std::string j = "{\"order\":" + std::to_string(order) + ",\"lights\":[";
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Light& l = *lights[i];
    ensureProjected(l, order);
    j += std::string(i ? "," : "") + "\n{\"name\":" + jsonString(stemOf(l.scanned.relPath)) +
         ",\"file\":" + jsonString(l.scanned.relPath) + ",\"usable\":" + (l.error.empty() ? "true" : "false");
    if (!l.error.empty()) {
      j += ",\"error\":" + jsonString(l.error) + "}";
      continue;
    }
    j += ",\"format\":" + jsonString(l.format) + ",\"width\":" + std::to_string(l.width) +
         ",\"height\":" + std::to_string(l.height) + ",\"layout\":" + jsonString(layoutName(l.layout));
    if (!l.previewPath.empty()) j += ",\"preview\":" + jsonString(l.previewPath);
    if (!l.backgroundPath.empty()) {
      j += ",\"background\":{\"url\":" + jsonString(l.backgroundPath) + ",\"format\":\"rgb9e5\",\"width\":" +
           std::to_string(l.backgroundWidth) + ",\"height\":" + std::to_string(l.backgroundHeight) + "}";
    }
    j += ",\"coefficients\":[";
    const std::vector<Rgb>& c = l.coefficients.at(order);
    for (std::size_t k = 0; k < c.size(); ++k) {
      j += std::string(k ? "," : "") + "[" + jsonNumber(c[k].r) + "," + jsonNumber(c[k].g) + "," + jsonNumber(c[k].b) + "]";
    }
    j += "]}";
  }
  j += "\n]}\n";
  return jsonResource(j);
}

std::shared_ptr<const Resource> LightLibrary::preview(std::string_view path) {
  std::lock_guard lock(mutex_);
  const auto it = previews_.find(path);
  return it == previews_.end() ? nullptr : it->second;
}

}  // namespace prt::serve
