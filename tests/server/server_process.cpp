#include "server_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

namespace prt::serve::test {
namespace {

std::string readWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Waits for `pid` up to `timeout`; its exit status, or -1 (signalled or still running).
int waitFor(pid_t pid, std::chrono::milliseconds timeout, bool* exited) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  *exited = false;
  for (;;) {
    int status = 0;
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      *exited = true;
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    if (r < 0 || std::chrono::steady_clock::now() >= deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

pid_t spawnServe(const std::vector<std::string>& args, int stdoutFd, int stderrFd) {
  std::vector<std::string> argv{serveExecutable()};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, stdoutFd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, stderrFd, STDERR_FILENO);
  pid_t pid = -1;
  if (::posix_spawn(&pid, cargv[0], &actions, nullptr, cargv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

}  // namespace

const char* serveExecutable() { return PRT_SERVE_EXE; }

ExitResult runServe(const std::vector<std::string>& args, std::chrono::milliseconds timeout) {
  char outPath[] = "/tmp/prt-serve-test-out-XXXXXX";
  char errPath[] = "/tmp/prt-serve-test-err-XXXXXX";
  const int outFd = ::mkstemp(outPath), errFd = ::mkstemp(errPath);
  ExitResult result;
  const pid_t pid = spawnServe(args, outFd, errFd);
  ::close(outFd);
  ::close(errFd);
  if (pid > 0) {
    bool exited = false;
    result.exitCode = waitFor(pid, timeout, &exited);
    if (!exited) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  result.out = readWhole(outPath);
  result.err = readWhole(errPath);
  ::unlink(outPath);
  ::unlink(errPath);
  return result;
}

std::unique_ptr<ServerProcess> ServerProcess::start(const std::vector<std::string>& args, const std::string& logPath,
                                                    std::string* error) {
  std::vector<std::string> all = args;
  bool hasPort = false;
  for (const std::string& a : args) hasPort = hasPort || a == "--port" || a.starts_with("--port=");
  if (!hasPort) {
    all.push_back("--port");
    all.push_back("0");
  }
  int pipeFds[2];
  if (::pipe2(pipeFds, O_CLOEXEC) != 0) {
    *error = "pipe failed";
    return nullptr;
  }
  const int logFd = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  std::unique_ptr<ServerProcess> p(new ServerProcess);
  p->logPath_ = logPath;
  p->pid_ = spawnServe(all, pipeFds[1], logFd);
  ::close(pipeFds[1]);
  ::close(logFd);
  p->stdoutFd_ = pipeFds[0];
  if (p->pid_ <= 0) {
    *error = "cannot start prt-serve";
    return nullptr;
  }
  // Wait for "prt-serve: listening on http://127.0.0.1:PORT/". Generous: a scan under
  // ASan compresses every asset.
  std::string out;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (out.find('\n') == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    pollfd pfd{p->stdoutFd_, POLLIN, 0};
    if (::poll(&pfd, 1, 100) <= 0) continue;
    char buf[256];
    const ssize_t n = ::read(p->stdoutFd_, buf, sizeof buf);
    if (n <= 0) break;  // the server exited
    out.append(buf, static_cast<std::size_t>(n));
  }
  const std::size_t at = out.find("listening on http://");
  const std::size_t colon = at == std::string::npos ? std::string::npos : out.find(':', at + 20);
  if (colon == std::string::npos) {
    *error = "prt-serve did not start; stdout: " + out + "; stderr: " + p->log();
    return nullptr;
  }
  p->port_ = std::atoi(out.c_str() + colon + 1);
  return p;
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0 && running()) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
  if (stdoutFd_ >= 0) ::close(stdoutFd_);
}

bool ServerProcess::running() {
  if (pid_ <= 0) return false;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == pid_) {
    pid_ = -1;
    return false;
  }
  return true;
}

int ServerProcess::stop(int signal, std::chrono::milliseconds timeout) {
  if (pid_ <= 0) return -1;
  if (signal != 0) ::kill(pid_, signal);
  bool exited = false;
  const int code = waitFor(pid_, timeout, &exited);
  if (exited) pid_ = -1;
  return code;
}

std::string ServerProcess::log() const { return readWhole(logPath_); }

}  // namespace prt::serve::test
