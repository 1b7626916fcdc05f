// A whole file mapped read-only into memory, for large inputs read once in place (a sharded
// bake's hit records: docs/scale-out.md) instead of copied into zero-filled buffers.
//
// A mapping sees the file as it is on disk while mapped: whoever truncates it meanwhile
// makes reads fault (SIGBUS). Map only files that are replaced by rename, never rewritten in
// place (every output of native/file_io.h's writeFileAtomically is).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "prt/status.h"

namespace prt {

class MappedFile {
 public:
  MappedFile() = default;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  ~MappedFile();

  // Maps all of `path`; fails as readFileBytes does (naming the path: missing, not a regular
  // file, unreadable, larger than maxBytes) or when the mapping fails. An empty file maps to
  // an empty span.
  static Status open(const std::string& path, std::uint64_t maxBytes, MappedFile* out);

  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }

 private:
  void unmap() noexcept;

  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace prt
