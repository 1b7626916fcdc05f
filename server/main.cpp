// prt-serve: the HTTP server of the PRT project (see docs/server.md).
#include <cstdio>
#include <string>
#include <vector>

#include "native/exit_status.h"
#include "options.h"
#include "server.h"

#ifndef PRT_VERSION
#define PRT_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  prt::serve::ServeOptions options;
  prt::Status status = prt::serve::parseServeOptions(args, &options);
  if (status.isOk() && options.help) {
    std::fputs(prt::serve::serveHelpText(), stdout);
    std::fputs("\n", stdout);
    std::fputs(prt::exitStatusHelp(), stdout);
    return prt::kExitOk;
  }
  if (status.isOk() && options.version) {
    std::printf("prt-serve %s\n", PRT_VERSION);
    return prt::kExitOk;
  }
  if (status.isOk()) status = prt::serve::runServer(options);
  if (status.isOk()) return prt::kExitOk;
  // Every failure, from the command line to a busy port, leaves through here: one line on
  // stderr and the exit status of its code, from the table prt-bake shares.
  std::fprintf(stderr, "prt-serve: error: %s\n", status.message().c_str());
  if (status.code() == prt::StatusCode::kUsage) std::fputs("Try 'prt-serve --help'.\n", stderr);
  return prt::exitStatusFor(status.code());
}
