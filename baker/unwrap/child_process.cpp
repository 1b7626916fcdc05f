#include "baker/unwrap/child_process.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <thread>

#include "native/file_io.h"

extern char** environ;

namespace prt::bake {
namespace {

// posix_spawn's file actions, freed on every path out.
class SpawnActions {
 public:
  SpawnActions() { ok_ = posix_spawn_file_actions_init(&actions_) == 0; }
  ~SpawnActions() {
    if (ok_) posix_spawn_file_actions_destroy(&actions_);
  }
  SpawnActions(const SpawnActions&) = delete;
  SpawnActions& operator=(const SpawnActions&) = delete;
  bool ok() const { return ok_; }
  posix_spawn_file_actions_t* get() { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_{};
  bool ok_ = false;
};

}  // namespace

Status runChild(const std::vector<std::string>& argv, const std::string& logPath, std::chrono::milliseconds limit,
                ChildResult* out, const std::function<void(pid_t)>& started, const std::function<void()>& finished) {
  *out = ChildResult{};
  if (argv.empty() || argv[0].empty()) return Status::error(StatusCode::kInvalidArgument, "runChild: no program");
  // Opened here, not by a file action, so that a log that cannot be created is our error and
  // not the child's; the child gets it as stdout and stderr, and the parent's copy is closed.
  const int log = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (log < 0) {
    return Status::error(statusCodeForErrno(errno), "cannot create '" + logPath + "': " + std::strerror(errno));
  }
  SpawnActions actions;
  bool ready = actions.ok() &&
               posix_spawn_file_actions_addopen(actions.get(), 0, "/dev/null", O_RDONLY, 0) == 0 &&
               posix_spawn_file_actions_adddup2(actions.get(), log, 1) == 0 &&
               posix_spawn_file_actions_adddup2(actions.get(), log, 2) == 0;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // SIGINT, SIGTERM and SIGHUP stay blocked from before the spawn until `started` has
  // published the pid, so a cleanup handler never misses a child that exists; the child
  // itself starts with the mask we had.
  sigset_t cleanup, old;
  sigemptyset(&cleanup);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&cleanup, sig);
  ::pthread_sigmask(SIG_BLOCK, &cleanup, &old);
  posix_spawnattr_t attr;
  const bool attrOk = posix_spawnattr_init(&attr) == 0;
  ready = ready && attrOk && posix_spawnattr_setsigmask(&attr, &old) == 0 &&
          posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK) == 0;
  pid_t pid = -1;
  const auto t0 = std::chrono::steady_clock::now();
  const int spawned = ready ? posix_spawnp(&pid, args[0], actions.get(), &attr, args.data(), environ) : ENOMEM;
  if (attrOk) posix_spawnattr_destroy(&attr);
  ::close(log);
  if (spawned == 0 && started) started(pid);
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (spawned != 0) {
    const StatusCode code = spawned == ENOENT ? StatusCode::kNotFound : statusCodeForErrno(spawned);
    return Status::error(code, "cannot run '" + argv[0] + "': " + std::strerror(spawned));
  }
  // Polled rather than waited on with a timer signal: a signal handler of our own would have
  // to be process-wide, and 10 ms is nothing against Blender's seconds of start-up.
  const auto deadline = t0 + limit;
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) {
      const int e = errno;
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      if (finished) finished();
      return Status::error(StatusCode::kInternal, "cannot wait for '" + argv[0] + "': " + std::strerror(e));
    }
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      out->timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (finished) finished();
  out->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (WIFEXITED(status)) out->exitStatus = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) out->signal = WTERMSIG(status);
  return Status::ok();
}

std::string logTail(const std::string& logPath, int maxLines) {
  std::FILE* f = std::fopen(logPath.c_str(), "rb");
  if (f == nullptr) return {};
  constexpr long kTail = 64 * 1024;
  std::string text;
  if (std::fseek(f, 0, SEEK_END) == 0) {
    const long size = std::ftell(f);
    std::fseek(f, size > kTail ? size - kTail : 0, SEEK_SET);
    text.resize(static_cast<std::size_t>(size > kTail ? kTail : (size > 0 ? size : 0)));
    text.resize(std::fread(text.data(), 1, text.size(), f));
  }
  std::fclose(f);
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.push_back(std::move(line));
    start = end + 1;
  }
  std::string joined;
  const std::size_t first = lines.size() > static_cast<std::size_t>(maxLines) ? lines.size() - maxLines : 0;
  for (std::size_t i = first; i < lines.size(); ++i) joined += (joined.empty() ? "" : " | ") + lines[i];
  return joined;
}

}  // namespace prt::bake
