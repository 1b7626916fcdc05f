// Status codes for failed system calls, so that a missing directory, a full disk and a
// refused read reach the exit status (native/exit_status.h) and the logs as what they are.
#pragma once

#include <string>

#include "prt/status.h"

namespace prt::serve {

// Status::error(statusCodeForErrno(error), message + ": " + strerror(error)), the code
// chosen by native/file_io.h's table (kNotFound, kResourceExhausted or kIoError).
Status errnoStatus(int error, const std::string& message);

}  // namespace prt::serve
