// The web client's files under --web: Content-Type by extension, ETags from the file's
// stamp, and br/zstd/gzip variants made on a file version's first request and kept in a
// bounded cache, so a rebuilt client is picked up without a restart.
#pragma once

#include <cstdint>
#include <list>
#include <map>
#include <mutex>
#include <string_view>
#include <vector>

#include "reply.h"
#include "respond.h"
#include "root_dir.h"

namespace prt::serve {

class StaticFiles {
 public:
  explicit StaticFiles(RootDir web);

  // The reply to GET/HEAD for decoded path `path` (validated by parseTarget); `rawPath` is
  // the path as the client sent it, for a redirect from a directory to "dir/". "/" and
  // "dir/" serve index.html; hidden files (a segment starting with '.') and anything that
  // resolves outside the web directory are 404.
  Reply serve(const RequestHead& request, std::string_view path, std::string_view rawPath);

 private:
  struct Cached {
    FileStamp stamp;
    std::vector<Variant> variants;
    std::uint64_t bytes = 0;
  };
  // The encoded variants of one file version, made on first use; empty for files not
  // worth compressing.
  std::vector<Variant> variantsFor(const FileRef& file, const FileStamp& stamp, const std::string& baseTag);

  RootDir web_;
  std::mutex mutex_;
  std::list<Cached> cache_;  // most recently used first
  std::uint64_t cachedBytes_ = 0;
};

}  // namespace prt::serve
