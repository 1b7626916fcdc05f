#include "native/file_io.h"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>

namespace prt {
namespace {

Status fileError(StatusCode code, const std::string& path, const std::string& what) {
  return Status::error(code, "'" + path + "': " + what);
}

// For a failed call that just set errno: the code errno stands for.
Status errnoError(const std::string& path, const std::string& what) {
  return fileError(statusCodeForErrno(errno), path, what);
}

std::string errnoText() { return std::strerror(errno); }

const char* fileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// ---- removing the temporary on SIGINT/SIGTERM/SIGHUP ------------------------------------
// The handler may only use async-signal-safe calls: it unlinks the one temporary the
// process is writing (a fixed buffer, published by a flag), restores the default action and
// re-raises, so the exit status still says which signal ended the process.

constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};
char gTempPath[PATH_MAX + 32];
volatile sig_atomic_t gTempActive = 0;

extern "C" void removeTempAndReraise(int sig) {
  if (gTempActive) ::unlink(gTempPath);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void installCleanupHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : kCleanupSignals) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // keep what the parent asked for (nohup)
      struct sigaction sa {};
      sa.sa_handler = removeTempAndReraise;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

// Blocks the cleanup signals for its lifetime, so the handler never sees a half-set path.
class CleanupSignalsBlocked {
 public:
  CleanupSignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int sig : kCleanupSignals) sigaddset(&set, sig);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~CleanupSignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  CleanupSignalsBlocked(const CleanupSignalsBlocked&) = delete;
  CleanupSignalsBlocked& operator=(const CleanupSignalsBlocked&) = delete;

 private:
  sigset_t old_;
};

void forgetTemp() {
  CleanupSignalsBlocked blocked;
  gTempActive = 0;
}

// Test hook (docs/baker.md): PRT_TEST_STALL_BEFORE_RENAME_MS=N makes a write announce itself
// on stderr and wait N ms with its temporary complete, so tests can signal it in that window.
void stallForTests(const std::string& temp) {
  const char* ms = std::getenv("PRT_TEST_STALL_BEFORE_RENAME_MS");
  if (ms == nullptr || *ms == '\0') return;
  std::fprintf(stderr, "prt: test hook: stalling before renaming '%s'\n", temp.c_str());
  std::fflush(stderr);
  std::this_thread::sleep_for(std::chrono::milliseconds(std::strtol(ms, nullptr, 10)));
}

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// Resolves `output` to the path that must be replaced: itself, or for a symbolic link the
// file it points to. Fails, naming `output`, for anything but a missing or regular file.
Status resolveOutput(const std::string& output, std::span<const std::string> inputs, std::string* target) {
  if (output.empty()) return Status::error(StatusCode::kInvalidArgument, "the output path is empty");
  struct stat st {};
  if (::lstat(output.c_str(), &st) != 0) {
    if (errno == ENOENT) {
      *target = output;
      return Status::ok();
    }
    return errnoError(output, "cannot check the output path: " + errnoText());
  }
  std::string resolved = output;
  if (S_ISLNK(st.st_mode)) {
    char buf[PATH_MAX];
    if (::realpath(output.c_str(), buf) == nullptr || ::stat(buf, &st) != 0) {
      return fileError(StatusCode::kInvalidArgument, output, "is a symbolic link to a missing or unreachable file (" + errnoText() +
                                 "); refusing to replace the link");
    }
    resolved = buf;
  }
  if (!S_ISREG(st.st_mode)) {
    return fileError(StatusCode::kInvalidArgument, output, std::string("exists and is ") + fileTypeName(st.st_mode) +
                               "; refusing to replace it (give the path of a new or regular file)");
  }
  for (const std::string& input : inputs) {
    struct stat in {};
    if (::stat(input.c_str(), &in) == 0 && in.st_dev == st.st_dev && in.st_ino == st.st_ino) {
      return fileError(StatusCode::kInvalidArgument, output, "is the input '" + input + "'; refusing to overwrite it (choose another output path)");
    }
  }
  *target = resolved;
  return Status::ok();
}

}  // namespace

StatusCode statusCodeForErrno(int errorNumber) {
  switch (errorNumber) {
    case ENOENT:
    case ENOTDIR: return StatusCode::kNotFound;
    case ENOSPC:
    case EDQUOT:
    case ENOMEM:
    case EMFILE:
    case ENFILE:
    case EFBIG: return StatusCode::kResourceExhausted;
    default: return StatusCode::kIoError;
  }
}

Status openFileForReading(const std::string& path, std::uint64_t maxBytes, int* fd, std::uint64_t* size) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer (it is then refused as not a
  // regular file); reads of regular files ignore the flag.
  const int f = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (f < 0) return errnoError(path, errno == ENOENT ? "no such file" : "cannot open: " + errnoText());
  struct stat st {};
  if (::fstat(f, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(f);
    return fileError(StatusCode::kInvalidArgument, path, "not a regular file");
  }
  if (static_cast<std::uint64_t>(st.st_size) > maxBytes) {
    ::close(f);
    return fileError(StatusCode::kInvalidArgument, path, "file is " + std::to_string(st.st_size) + " bytes; at most " + std::to_string(maxBytes) +
                             " are accepted");
  }
  *fd = f;
  *size = static_cast<std::uint64_t>(st.st_size);
  return Status::ok();
}

Status readFileBytes(const std::string& path, std::uint64_t maxBytes, std::vector<std::uint8_t>* out) {
  int fd = -1;
  std::uint64_t size = 0;
  if (Status s = openFileForReading(path, maxBytes, &fd, &size); !s.isOk()) return s;
  out->resize(static_cast<std::size_t>(size));
  std::size_t done = 0;
  while (done < out->size()) {
    const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      return fileError(n == 0 ? StatusCode::kIoError : statusCodeForErrno(errno), path,
                       n == 0 ? "file shrank while being read" : "read failed: " + errnoText());
    }
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return Status::ok();
}

Status checkOutputPath(const std::string& output, std::span<const std::string> inputs) {
  std::string target;
  return resolveOutput(output, inputs, &target);
}

Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes,
                           std::span<const std::string> inputs) {
  const std::span<const std::uint8_t> whole[] = {bytes};
  return writePartsAtomically(path, whole, inputs);
}

Status writePartsAtomically(const std::string& path, std::span<const std::span<const std::uint8_t>> parts,
                            std::span<const std::string> inputs) {
  std::string target;
  if (Status s = resolveOutput(path, inputs, &target); !s.isOk()) return s;
  const std::string pattern = target + ".prt-partial-XXXXXX";
  if (pattern.size() >= sizeof gTempPath) return fileError(StatusCode::kInvalidArgument, path, "the path is too long");
  installCleanupHandlers();

  int fd = -1;
  {
    CleanupSignalsBlocked blocked;
    std::memcpy(gTempPath, pattern.c_str(), pattern.size() + 1);
    fd = ::mkostemp(gTempPath, O_CLOEXEC);  // O_EXCL: never opens what someone else put there
    if (fd >= 0) gTempActive = 1;
  }
  if (fd < 0) return errnoError(path, "cannot create a temporary file beside it: " + errnoText());
  const std::string temp = gTempPath;
  auto abandon = [&](const std::string& what) {
    const int savedErrno = errno;
    const std::string why = errnoText();
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
    forgetTemp();
    return fileError(statusCodeForErrno(savedErrno), path, what + ": " + why);
  };

  if (::fchmod(fd, 0644) != 0) return abandon("cannot set the temporary file's mode");
  for (const std::span<const std::uint8_t> bytes : parts) {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return abandon("write failed");
      done += static_cast<std::size_t>(n);
    }
  }
  if (::fsync(fd) != 0) return abandon("flush failed");
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) return abandon("flush failed");
  stallForTests(temp);

  // Checked again just before the rename: the path may have changed during a long bake.
  std::string now;
  if (Status s = resolveOutput(path, inputs, &now); !s.isOk()) {
    ::unlink(temp.c_str());
    forgetTemp();
    return s;
  }
  if (::rename(temp.c_str(), target.c_str()) != 0) return abandon("rename failed");
  forgetTemp();

  // The rename lives in the directory: flush it too, or a crash could bring the old file back.
  const int dir = ::open(directoryOf(target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir < 0) return errnoError(path, "written, but its directory cannot be opened to flush it: " + errnoText());
  const int synced = ::fsync(dir);
  const int syncErrno = errno;
  ::close(dir);
  if (synced != 0 && syncErrno != EINVAL) {  // EINVAL: the file system cannot sync directories
    errno = syncErrno;
    return errnoError(path, "written, but flushing its directory failed: " + errnoText());
  }
  return Status::ok();
}

}  // namespace prt
