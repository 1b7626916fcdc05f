#include "os_error.h"

#include <cerrno>
#include <cstring>

#include "native/file_io.h"

namespace prt::serve {

Status errnoStatus(int error, const std::string& message) {
  return Status::error(statusCodeForErrno(error), message + ": " + std::strerror(error));
}

}  // namespace prt::serve
