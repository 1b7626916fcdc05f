// Status codes for failed system calls, so that a missing directory, a full disk and a
// refused read reach the exit status (native/exit_status.h) and the logs as what they are.
#pragma once

#include <string>

#include "prt/status.h"

namespace prt::serve {

// The code for a call that failed with `error` (an errno value): kNotFound for ENOENT and
// ENOTDIR, kResourceExhausted for ENOSPC, EDQUOT, EFBIG, ENOMEM, EMFILE and ENFILE,
// kIoError for everything else (EACCES, EIO, EROFS, ...).
StatusCode codeForErrno(int error);

// Status::error(codeForErrno(error), message + ": " + strerror(error)).
Status errnoStatus(int error, const std::string& message);

}  // namespace prt::serve
