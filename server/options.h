// prt-serve's command line.
#pragma once

#include <algorithm>
#include <span>
#include <string>

#include "prt/status.h"

namespace prt::serve {

struct ServeOptions {
  std::string root;                 // --root: baked assets and environment maps
  std::string web;                  // --web: the client's static files ("" = none)
  std::string bind = "127.0.0.1";  // --bind
  int port = 8080;                  // --port; 0 picks a free port (printed at start)
  int threads = 0;                  // --threads; 0 = one per hardware thread
  int maxConnections = 1024;        // --max-connections
  int maxConnectionsPerClient = 0;  // --max-connections-per-client; 0: a quarter of maxConnections
  double readTimeoutSeconds = 15;   // --read-timeout: to receive a request head
  double writeTimeoutSeconds = 30;  // --write-timeout: without progress while sending
  int maxPartsMiB = 64;             // --max-parts-mib: larger assets are served whole only
  bool quiet = false;               // --quiet: no access log
  bool help = false;
  bool version = false;

  // Connections one client address may hold: the option, else a quarter of the cap (at least 1).
  int perClientLimit() const {
    return maxConnectionsPerClient > 0 ? maxConnectionsPerClient : std::max(1, maxConnections / 4);
  }
};

// The text --help prints, before native/exit_status.h's table of exit statuses.
const char* serveHelpText();

// Parses `args` (without the program name) into *out with the shared strict parser
// (native/cli_args.h). Errors (kUsage) name the flag: unknown flags, missing values, a flag
// given twice, values out of range, a --bind that is no IP address, stray arguments, a
// missing --root. --help or -h anywhere wins over every error; --version is ok without
// --root.
Status parseServeOptions(std::span<const std::string> args, ServeOptions* out);

}  // namespace prt::serve
