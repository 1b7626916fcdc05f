// The environment maps (OpenEXR, Radiance .hdr) under --root, projected onto SH radiance
// coefficients by the shared library (native/environment_map.h: the layout follows the
// aspect ratio as `prt-bake probe` guesses it), for GET /api/lights?order=N. Each file
// version is loaded only when an order is first asked for, and each (version, order)
// projected once, on the library's own worker thread: a projection takes a large fraction
// of a second per map, and on an I/O thread it would stall every connection that thread
// serves. The documents and previews are cached until the files change.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "dir_scan.h"
#include "native/environment_map.h"
#include "prt/vec3.h"
#include "resource.h"
#include "root_dir.h"

namespace prt::serve {

class LightLibrary {
 public:
  // Called with the document once it is made; null when making it failed (out of memory).
  using DocumentCallback = std::function<void(std::shared_ptr<const Resource>)>;

  // Lists the maps (nothing is loaded yet) and starts the worker thread.
  LightLibrary(RootDir root, std::chrono::milliseconds recheck);
  ~LightLibrary();  // stop()
  LightLibrary(const LightLibrary&) = delete;
  LightLibrary& operator=(const LightLibrary&) = delete;

  // The /api/lights document for `order` (the caller checks 1..kMaxShOrder) if it is
  // cached, else null (then documentLater). Re-lists the maps first when the listing is
  // older than the recheck interval. Cheap: never loads or projects a map.
  std::shared_ptr<const Resource> cachedDocument(int order);

  // Makes the document for `order` on the worker thread and calls `done` there with it:
  // every map, usable ones with their coefficients and preview URL, the others with the
  // error. Requests for one order share one computation; `done` runs at once, on the
  // calling thread, when the document is already cached. Never blocks on a projection.
  void documentLater(int order, DocumentCallback done);

  // Stops the worker (after the projection it is in, if any) and destroys the callbacks
  // still waiting, unrun. Call before the I/O context their sessions belong to is gone.
  void stop();

  // The derived image at decoded URL path `path`: a preview PNG ("/api/lights/preview/<hash>.png")
  // or a background texture ("/api/lights/background/<hash>.rgb9e5"); null when none is.
  std::shared_ptr<const Resource> preview(std::string_view path);

  // How many maps the root holds, usable or not.
  std::size_t count();

 private:
  // Written by the worker only, except the preview fields, which it sets under mutex_
  // (refreshLocked reads them from I/O threads).
  struct Light {
    ScannedFile scanned;  // immutable
    bool loaded = false;  // the image was read once (format, size, layout, preview known)
    std::string error;    // non-empty: unusable
    std::string format;
    int width = 0, height = 0;
    EnvLayout layout = EnvLayout::kEquirect;
    std::map<int, std::vector<Rgb>> coefficients;  // by order
    std::string previewPath;
    std::shared_ptr<const Resource> previewResource;
    // The background texture (equirect maps only: the page samples it as one).
    std::string backgroundPath;
    std::shared_ptr<const Resource> backgroundResource;
    int backgroundWidth = 0, backgroundHeight = 0;
  };

  // The message a response may carry for `detail` (no server paths); the detail is logged.
  std::string publicError(const ScannedFile& file, const std::string& detail) const;
  void refreshLocked();
  void work();
  std::shared_ptr<const Resource> makeDocument(int order, const std::vector<std::shared_ptr<Light>>& lights);
  void ensureProjected(Light& light, int order);

  RootDir root_;
  std::chrono::milliseconds recheck_;
  std::mutex mutex_;
  std::vector<ScannedFile> listing_;
  std::vector<std::shared_ptr<Light>> lights_;
  std::uint64_t generation_ = 0;  // counts listing changes: a document made from an older one is not cached
  std::map<int, std::shared_ptr<const Resource>> documents_;
  std::map<std::string, std::shared_ptr<const Resource>, std::less<>> previews_;  // and backgrounds
  std::chrono::steady_clock::time_point nextCheck_{};
  std::deque<int> queue_;                           // orders to make, oldest request first
  std::map<int, std::vector<DocumentCallback>> waiting_;  // by order
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace prt::serve
