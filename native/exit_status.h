// Process exit statuses of the project's command-line tools (prt-bake, prt-serve), chosen
// from a Status code in this one place so every tool and every error path agrees. The
// table is documented in docs/baker.md and docs/server.md and printed by --help.
#pragma once

#include "prt/status.h"

namespace prt {

inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;              // the command line does not parse
inline constexpr int kExitNotFound = 3;           // a file is missing, unreadable or unwritable
inline constexpr int kExitInvalidInput = 4;       // an input's contents or a value is invalid
inline constexpr int kExitInternal = 5;           // a bug: please report it
inline constexpr int kExitResourceExhausted = 6;  // out of memory, disk space or a limit
inline constexpr int kExitUnavailable = 7;        // a service is not there now (port in use)

// The exit status for a failure with `code` (kExitOk for StatusCode::kOk).
int exitStatusFor(StatusCode code);

// The --help paragraph listing these statuses, ending in a newline.
const char* exitStatusHelp();

}  // namespace prt
