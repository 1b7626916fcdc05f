// The server's life: check the directories, bind, scan, serve on a thread pool until
// SIGINT/SIGTERM, then stop gracefully.
#pragma once

#include "options.h"
#include "prt/status.h"

namespace prt::serve {

// Runs prt-serve with `options` until SIGINT/SIGTERM; ok after a graceful stop. Prints
// "prt-serve: listening on http://ADDR:PORT/" on stdout once requests can be made. Errors
// are returned, not printed, coded for the exit status (native/exit_status.h): kNotFound or
// kIoError for --root/--web, kUnavailable for a port or address that cannot be bound,
// kResourceExhausted for memory, kInternal for a bug. Never throws.
Status runServer(const ServeOptions& options) noexcept;

}  // namespace prt::serve
