// Runs the real prt-serve binary for the tests: on a free loopback port the kernel picks
// (--port 0; the server prints it), with stderr (the access log) captured in a file.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace prt::serve::test {

// Path of the prt-serve binary under test.
const char* serveExecutable();

struct ExitResult {
  int exitCode = -1;  // -1: killed by a signal or did not exit in time
  std::string out;
  std::string err;
};

// Runs prt-serve with `args` to completion (--help, usage errors, startup failures).
ExitResult runServe(const std::vector<std::string>& args, std::chrono::milliseconds timeout);

class ServerProcess {
 public:
  // Starts prt-serve with `args` plus "--port 0" (unless args name a port) and waits for
  // its "listening on" line; null with *error set when it exits or stays silent instead.
  static std::unique_ptr<ServerProcess> start(const std::vector<std::string>& args, const std::string& logPath,
                                              std::string* error);
  ~ServerProcess();  // SIGKILL if still running
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  // Sends `signal` (0: none) and waits up to `timeout` for the exit; the exit status, or -1.
  int stop(int signal, std::chrono::milliseconds timeout);
  // Everything the server wrote to stderr so far.
  std::string log() const;
  bool running();

 private:
  ServerProcess() = default;
  pid_t pid_ = -1;
  int port_ = 0;
  int stdoutFd_ = -1;
  std::string logPath_;
};

}  // namespace prt::serve::test
