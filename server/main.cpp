// prt-serve: the HTTP server of the PRT project (see docs/server.md).
#include <cstdio>
#include <string>
#include <vector>

#include "options.h"
#include "server.h"

#ifndef PRT_VERSION
#define PRT_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  prt::serve::ServeOptions options;
  if (prt::Status s = prt::serve::parseServeOptions(args, &options); !s.isOk()) {
    std::fprintf(stderr, "prt-serve: error: %s\nTry 'prt-serve --help'.\n", s.message().c_str());
    return prt::serve::kExitUsageError;
  }
  if (options.help) {
    std::fputs(prt::serve::serveHelpText(), stdout);
    return prt::serve::kExitOk;
  }
  if (options.version) {
    std::printf("prt-serve %s\n", PRT_VERSION);
    return prt::serve::kExitOk;
  }
  return prt::serve::runServer(options);
}
