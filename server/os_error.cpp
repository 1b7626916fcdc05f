#include "os_error.h"

#include <cerrno>
#include <cstring>

namespace prt::serve {

StatusCode codeForErrno(int error) {
  switch (error) {
    case ENOENT:
    case ENOTDIR: return StatusCode::kNotFound;  // ENOTDIR: a path component is a file
    case ENOSPC:
    case EDQUOT:
    case EFBIG:
    case ENOMEM:
    case EMFILE:
    case ENFILE: return StatusCode::kResourceExhausted;
    default: return StatusCode::kIoError;
  }
}

Status errnoStatus(int error, const std::string& message) {
  return Status::error(codeForErrno(error), message + ": " + std::strerror(error));
}

}  // namespace prt::serve
