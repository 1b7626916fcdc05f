#include "native/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "native/file_io.h"

namespace prt {
namespace {

Status fileError(StatusCode code, const std::string& path, const std::string& what) {
  return Status::error(code, "'" + path + "': " + what);
}

}  // namespace

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), size_(std::exchange(other.size_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    unmap();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

MappedFile::~MappedFile() { unmap(); }

void MappedFile::unmap() noexcept {
  if (data_ != nullptr) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  data_ = nullptr;
  size_ = 0;
}

Status MappedFile::open(const std::string& path, std::uint64_t maxBytes, MappedFile* out) {
  *out = MappedFile();
  int fd = -1;
  std::uint64_t fileSize = 0;
  if (Status s = openFileForReading(path, maxBytes, &fd, &fileSize); !s.isOk()) return s;
  const std::size_t size = static_cast<std::size_t>(fileSize);
  if (size == 0) {
    ::close(fd);
    return Status::ok();
  }
  // MAP_POPULATE: the whole file is about to be checksummed, so fault it in at once rather
  // than a page at a time.
  void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  const int e = errno;
  ::close(fd);  // the mapping keeps the file
  if (p == MAP_FAILED) return fileError(statusCodeForErrno(e), path, std::string("cannot map: ") + std::strerror(e));
  out->data_ = static_cast<const std::uint8_t*>(p);
  out->size_ = size;
  return Status::ok();
}

}  // namespace prt
