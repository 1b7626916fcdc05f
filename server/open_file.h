// Read-only file descriptors shared by the catalogue and in-flight responses, and the
// identity of one version of a file.
#pragma once

#include <sys/stat.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "prt/status.h"

namespace prt::serve {

// What tells two versions of a file apart without reading it: a rewrite, a rename over it
// or a touch changes at least one field.
struct FileStamp {
  std::uint64_t device = 0;
  std::uint64_t inode = 0;
  std::uint64_t size = 0;
  std::int64_t mtimeNs = 0;
  std::int64_t ctimeNs = 0;
  bool operator==(const FileStamp&) const = default;
};

// The stamp of a stat() result.
FileStamp stampOf(const struct stat& st);

// Owns one descriptor; closed when the last response sending from it finishes, so a
// rescan can drop a file version while a slow client is still downloading it.
class OpenFile {
 public:
  // Takes ownership of `fd`.
  explicit OpenFile(int fd) noexcept : fd_(fd) {}
  ~OpenFile();
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;

  int fd() const noexcept { return fd_; }

 private:
  int fd_;
};

using FileRef = std::shared_ptr<const OpenFile>;

// Reads bytes [0, size) of the open file `fd` into *out (pread, so the descriptor's offset
// is left alone and responses may share it). By descriptor, not by path as
// native/file_io.h's readFileBytes does: the bytes must come from the very file
// RootDir::openRelative checked, which a path reopened later need not name. Errors:
// errno's code (os_error.h) for a failed read, kTruncated when the file shrank below `size`.
Status readAllAt(int fd, std::uint64_t size, std::vector<std::uint8_t>* out);

}  // namespace prt::serve
