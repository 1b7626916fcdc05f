// The environment maps (OpenEXR, Radiance .hdr) under --root, projected onto SH radiance
// coefficients by the shared library (baker/environment_map.h: the layout follows the
// aspect ratio as `prt-bake probe` guesses it), for GET /api/lights?order=N. Each file
// version is loaded only when an order is first asked for, and each (version, order)
// projected once; the documents and previews are cached until the files change.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "dir_scan.h"
#include "environment_map.h"
#include "prt/vec3.h"
#include "resource.h"
#include "root_dir.h"

namespace prt::serve {

class LightLibrary {
 public:
  // Lists the maps (nothing is loaded yet).
  LightLibrary(RootDir root, std::chrono::milliseconds recheck);

  // The /api/lights document for `order` (the caller checks 1..kMaxShOrder): every map,
  // usable ones with their coefficients and preview URL, the others with the error.
  // Serialised: a first request per order may load and project every map.
  std::shared_ptr<const Resource> document(int order);

  // The preview PNG at decoded URL path `path` ("/api/lights/preview/<hash>.png"), or null.
  std::shared_ptr<const Resource> preview(std::string_view path);

  // How many maps the root holds, usable or not.
  std::size_t count();

 private:
  struct Light {
    ScannedFile scanned;
    bool loaded = false;  // the image was read once (format, size, layout, preview known)
    std::string error;    // non-empty: unusable
    std::string format;
    int width = 0, height = 0;
    EnvLayout layout = EnvLayout::kEquirect;
    std::map<int, std::vector<Rgb>> coefficients;  // by order
    std::string previewPath;
    std::shared_ptr<const Resource> previewResource;
  };

  // The message a response may carry for `detail` (no server paths); the detail is logged.
  std::string publicError(const ScannedFile& file, const std::string& detail) const;
  void refreshLocked();
  void ensureProjected(Light& light, int order);

  RootDir root_;
  std::chrono::milliseconds recheck_;
  std::mutex mutex_;
  std::vector<ScannedFile> listing_;
  std::vector<std::shared_ptr<Light>> lights_;
  std::map<int, std::shared_ptr<const Resource>> documents_;
  std::map<std::string, std::shared_ptr<const Resource>, std::less<>> previews_;
  std::chrono::steady_clock::time_point nextCheck_{};
};

}  // namespace prt::serve
