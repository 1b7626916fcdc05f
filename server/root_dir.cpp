#include "root_dir.h"

#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <memory>

#include "os_error.h"

namespace prt::serve {
namespace {

// The real path of an open descriptor; empty when it cannot be read (no /proc) or the file
// was deleted after opening (the link then ends in " (deleted)", which no root contains).
std::string realPathOf(int fd) {
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  char buf[PATH_MAX + 1];
  const ssize_t n = ::readlink(link, buf, PATH_MAX);
  if (n <= 0) return {};
  return std::string(buf, static_cast<std::size_t>(n));
}

}  // namespace

Status RootDir::open(const std::string& path, std::string_view flag, RootDir* out) {
  const std::string what = std::string(flag) + " '" + path + "'";
  // The option parser turns "--root ''" away; an empty path here is a caller's mistake.
  if (path.empty()) return Status::error(StatusCode::kInvalidArgument, std::string(flag) + " is empty");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errnoStatus(errno, what + " is not a directory");
  // Not found rather than invalid: the directory the option names is not there (a file
  // is in its place), as ENOTDIR reads for a path through a file.
  if (!S_ISDIR(st.st_mode)) return Status::error(StatusCode::kNotFound, what + " is not a directory");
  if (::access(path.c_str(), R_OK | X_OK) != 0) return errnoStatus(errno, what + " is not readable");
  std::unique_ptr<char, decltype(&::free)> real(::realpath(path.c_str(), nullptr), &::free);
  if (!real) return errnoStatus(errno, what + " cannot be resolved");
  out->path_ = real.get();
  return Status::ok();
}

bool RootDir::contains(std::string_view real) const {
  if (path_ == "/") return !real.empty() && real[0] == '/';
  if (real.size() < path_.size() || real.substr(0, path_.size()) != path_) return false;
  return real.size() == path_.size() || real[path_.size()] == '/';
}

OpenOutcome RootDir::openRelative(std::string_view relative, FileRef* file, struct stat* st) const {
  std::string full = path_;
  if (!relative.empty()) {
    if (full != "/") full += '/';
    full += relative;
  }
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
  const int fd = ::open(full.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return OpenOutcome::kMissing;
  auto owned = std::make_shared<const OpenFile>(fd);
  if (::fstat(fd, st) != 0) return OpenOutcome::kMissing;
  if (!contains(realPathOf(fd))) return OpenOutcome::kOutside;
  if (S_ISDIR(st->st_mode)) return OpenOutcome::kDirectory;
  if (!S_ISREG(st->st_mode)) return OpenOutcome::kMissing;
  *file = std::move(owned);
  return OpenOutcome::kFile;
}

}  // namespace prt::serve
