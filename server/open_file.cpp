#include "open_file.h"

#include <unistd.h>

#include <cerrno>

#include "os_error.h"

namespace prt::serve {

FileStamp stampOf(const struct stat& st) {
  FileStamp s;
  s.device = static_cast<std::uint64_t>(st.st_dev);
  s.inode = static_cast<std::uint64_t>(st.st_ino);
  s.size = static_cast<std::uint64_t>(st.st_size);
  s.mtimeNs = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  s.ctimeNs = static_cast<std::int64_t>(st.st_ctim.tv_sec) * 1000000000 + st.st_ctim.tv_nsec;
  return s;
}

OpenFile::~OpenFile() {
  if (fd_ >= 0) ::close(fd_);
}

Status readAllAt(int fd, std::uint64_t size, std::vector<std::uint8_t>* out) {
  out->resize(static_cast<std::size_t>(size));
  std::size_t done = 0;
  while (done < out->size()) {
    const ssize_t n = ::pread(fd, out->data() + done, out->size() - done, static_cast<off_t>(done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errnoStatus(errno, "read failed");
    if (n == 0) return Status::error(StatusCode::kTruncated, "file shrank while being read");
    done += static_cast<std::size_t>(n);
  }
  return Status::ok();
}

}  // namespace prt::serve
