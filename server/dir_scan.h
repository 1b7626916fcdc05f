// Listing the files of one kind under a root, cheaply enough to repeat every second: the
// catalogue and the light library compare consecutive listings to notice changes.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "open_file.h"
#include "root_dir.h"

namespace prt::serve {

struct ScannedFile {
  std::string relPath;  // under the root, '/'-separated
  std::string absPath;  // root + relPath (may be a symlink that stays inside the root)
  FileStamp stamp;      // of the file the path leads to; zero when `problem` is set
  std::string problem;  // non-empty: why it cannot be used (a symlink out of the root, ...)
  bool operator==(const ScannedFile&) const = default;
};

struct ScanLimits {
  int maxDepth = 16;              // directories below the root
  std::size_t maxFiles = 10000;   // matching files listed; the rest are ignored
};

// Regular files under `root` whose names end in one of `extensions` (lower case, with the
// dot; matched case-insensitively), sorted by relPath. Hidden entries (a leading '.') and
// anything that is not a regular file or directory are skipped. Symlinks are followed only
// when their target is inside the root; a matching symlink that leads out is listed with a
// problem, so the operator sees why it is not served. Never follows a directory loop.
std::vector<ScannedFile> scanDirectory(const RootDir& root, std::span<const std::string_view> extensions,
                                       const ScanLimits& limits = {});

}  // namespace prt::serve
