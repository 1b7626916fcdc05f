// A directory the server serves from, and the one place that opens files under it.
#pragma once

#include <sys/stat.h>

#include <string>
#include <string_view>

#include "open_file.h"
#include "prt/status.h"

namespace prt::serve {

enum class OpenOutcome {
  kFile,       // a regular file inside the root; *file and *st are set
  kDirectory,  // a directory inside the root
  kMissing,    // nothing there, or not a regular file or directory
  kOutside,    // it exists but resolves (through a symlink) outside the root
};

class RootDir {
 public:
  RootDir() = default;

  // Resolves `path` to its canonical absolute form; fails (naming `flag` and the path)
  // unless it is an existing, readable directory.
  static Status open(const std::string& path, std::string_view flag, RootDir* out);

  // The canonical path, without a trailing slash ("/" only for the file-system root).
  const std::string& path() const { return path_; }

  // True when the canonical absolute path `real` is the root or lies under it.
  bool contains(std::string_view real) const;

  // Opens `relative` ('/'-separated segments already validated by parseTarget, no leading
  // slash; empty means the root itself). The check runs on the descriptor actually opened
  // (its /proc/self/fd link), so a symlink swapped in between check and use cannot lead
  // out. Symlinks whose targets stay inside the root are followed.
  OpenOutcome openRelative(std::string_view relative, FileRef* file, struct stat* st) const;

 private:
  std::string path_;
};

}  // namespace prt::serve
