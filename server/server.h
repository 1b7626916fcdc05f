// The server's life: check the directories, bind, scan, serve on a thread pool until
// SIGINT/SIGTERM, then stop gracefully.
#pragma once

#include "options.h"

namespace prt::serve {

// Runs prt-serve with `options` and returns the process exit status. Prints
// "prt-serve: listening on http://ADDR:PORT/" on stdout once requests can be made, and
// errors ("prt-serve: error: ...") on stderr. Never throws.
int runServer(const ServeOptions& options) noexcept;

}  // namespace prt::serve
