#include "baker/unwrap/unwrap_workspace.h"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "native/file_io.h"

namespace prt::bake {
namespace {

constexpr const char* kNames[UnwrapWorkspace::kFileCount] = {"smart_uv_project.py", "mesh.prtm", "atlas.prtm",
                                                             "blender.log"};
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};

// What the handler needs, in fixed buffers (only async-signal-safe calls may use them), set
// while the cleanup signals are blocked so the handler never sees them half-written.
char gDir[PATH_MAX];
char gFiles[UnwrapWorkspace::kFileCount][PATH_MAX + 32];
volatile sig_atomic_t gActive = 0;
volatile sig_atomic_t gChild = 0;
struct sigaction gPrevious[3];
bool gInstalled[3] = {};

extern "C" void cleanUpAndReraise(int sig) {
  if (gChild > 0) ::kill(static_cast<pid_t>(gChild), SIGKILL);
  if (gActive) {
    for (const char* f : gFiles) ::unlink(f);
    ::rmdir(gDir);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int sig : kCleanupSignals) sigaddset(&set, sig);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_;
};

}  // namespace

Status UnwrapWorkspace::create() {
  if (!dir_.empty()) return Status::error(StatusCode::kInternal, "UnwrapWorkspace::create called twice");
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/prt-unwrap-XXXXXX";
  if (pattern.size() + 32 >= PATH_MAX) return Status::error(StatusCode::kInvalidArgument, "TMPDIR is too long");
  SignalsBlocked blocked;
  if (gActive) return Status::error(StatusCode::kInternal, "one unwrap workspace at a time");
  if (::mkdtemp(pattern.data()) == nullptr) {
    return Status::error(statusCodeForErrno(errno),
                         "cannot create a scratch directory '" + pattern + "': " + std::strerror(errno));
  }
  dir_ = pattern;
  std::strcpy(gDir, dir_.c_str());
  for (int f = 0; f < kFileCount; ++f) std::strcpy(gFiles[f], path(static_cast<File>(f)).c_str());
  gChild = 0;
  gActive = 1;
  for (int i = 0; i < 3; ++i) {
    ::sigaction(kCleanupSignals[i], nullptr, &gPrevious[i]);
    gInstalled[i] = gPrevious[i].sa_handler != SIG_IGN;  // keep what the parent asked for (nohup)
    if (!gInstalled[i]) continue;
    struct sigaction sa {};
    sa.sa_handler = cleanUpAndReraise;
    sigemptyset(&sa.sa_mask);
    ::sigaction(kCleanupSignals[i], &sa, nullptr);
  }
  return Status::ok();
}

std::string UnwrapWorkspace::path(File f) const { return dir_ + "/" + kNames[f]; }

void UnwrapWorkspace::setChild(pid_t pid) {
  SignalsBlocked blocked;
  gChild = pid;
}

void UnwrapWorkspace::remove() {
  SignalsBlocked blocked;
  // Whatever else appeared in it goes too: the directory is ours alone.
  std::error_code ignored;
  std::filesystem::remove_all(dir_, ignored);
  gActive = 0;
  gChild = 0;
  for (int i = 0; i < 3; ++i) {
    if (gInstalled[i]) ::sigaction(kCleanupSignals[i], &gPrevious[i], nullptr);
    gInstalled[i] = false;
  }
}

UnwrapWorkspace::~UnwrapWorkspace() {
  if (!dir_.empty()) remove();
}

}  // namespace prt::bake
