#include "native/exit_status.h"

namespace prt {

int exitStatusFor(StatusCode code) {
  switch (code) {
    case StatusCode::kOk: return kExitOk;
    case StatusCode::kUsage: return kExitUsage;
    case StatusCode::kNotFound:
    case StatusCode::kIoError: return kExitNotFound;
    case StatusCode::kInvalidArgument:
    case StatusCode::kSizeMismatch:
    case StatusCode::kNotFinite:
    case StatusCode::kTruncated:
    case StatusCode::kBadMagic:
    case StatusCode::kBadVersion:
    case StatusCode::kChecksumMismatch:
    case StatusCode::kCorrupt: return kExitInvalidInput;
    case StatusCode::kResourceExhausted: return kExitResourceExhausted;
    case StatusCode::kUnavailable: return kExitUnavailable;
    case StatusCode::kInternal: return kExitInternal;
  }
  return kExitInternal;  // a code added without a row here is a bug
}

const char* exitStatusHelp() {
  return "Exit status:\n"
         "  0  success\n"
         "  2  usage: the command line does not parse\n"
         "  3  a file is missing, unreadable or cannot be written\n"
         "  4  invalid input: a file's contents or an option's value\n"
         "  5  internal error (a bug; please report it)\n"
         "  6  out of memory, disk space or a configured limit\n"
         "  7  unavailable: a service is not there now (e.g. the port is in use)\n"
         "  128+N  killed by signal N (an interrupted write leaves the old output intact)\n";
}

}  // namespace prt
