#include "temp_file.h"

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <string>

#include "os_error.h"

namespace prt::serve {

Status writeTempFile(std::string_view bytes, FileRef* out) {
  const char* env = std::getenv("TMPDIR");
  const std::string dir = env && *env ? env : "/tmp";
  int fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd < 0) {
    std::string pattern = dir + "/prt-serve-XXXXXX";
    fd = ::mkostemp(pattern.data(), O_CLOEXEC);
    if (fd >= 0) ::unlink(pattern.c_str());
  }
  if (fd < 0) return errnoStatus(errno, "cannot create a temporary file in '" + dir + "'");
  auto file = std::make_shared<const OpenFile>(fd);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    // A write that stores nothing yet reports no error is taken as an I/O error.
    if (n <= 0) return errnoStatus(n < 0 ? errno : EIO, "cannot write a temporary file in '" + dir + "'");
    done += static_cast<std::size_t>(n);
  }
  *out = std::move(file);
  return Status::ok();
}

}  // namespace prt::serve
