#include "file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace prt {
namespace {

Status ioError(const std::string& path, const std::string& what) {
  return Status::error(StatusCode::kInvalidArgument, "'" + path + "': " + what);
}

std::string errnoText() { return std::strerror(errno); }

}  // namespace

Status readFileBytes(const std::string& path, std::uint64_t maxBytes, std::vector<std::uint8_t>* out) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return ioError(path, errno == ENOENT ? "no such file" : "cannot open: " + errnoText());
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return ioError(path, "not a regular file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > maxBytes) {
    ::close(fd);
    return ioError(path, "file is " + std::to_string(st.st_size) + " bytes; at most " + std::to_string(maxBytes) +
                             " are accepted");
  }
  out->resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < out->size()) {
    const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      return ioError(path, n == 0 ? "file shrank while being read" : "read failed: " + errnoText());
    }
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return Status::ok();
}

Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes) {
  const std::string temp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return ioError(path, "cannot create '" + temp + "': " + errnoText());
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = errnoText();
      ::close(fd);
      ::unlink(temp.c_str());
      return ioError(path, "write failed: " + why);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string why = errnoText();
    ::unlink(temp.c_str());
    return ioError(path, "flush failed: " + why);
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string why = errnoText();
    ::unlink(temp.c_str());
    return ioError(path, "rename failed: " + why);
  }
  return Status::ok();
}

}  // namespace prt
