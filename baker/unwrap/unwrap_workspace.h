// The atlas generator's private scratch directory (mkdtemp under $TMPDIR, else /tmp, mode
// 0700) with its fixed set of files. It is removed when the workspace goes away, and also when
// SIGINT, SIGTERM or SIGHUP ends the process meanwhile: the handler kills the running child,
// removes the files and re-raises, so the exit status still names the signal.
#pragma once

#include <sys/types.h>

#include <string>

#include "prt/status.h"

namespace prt::bake {

class UnwrapWorkspace {
 public:
  // The files the generator uses, each inside the directory.
  enum File { kScript, kMesh, kAtlas, kLog, kFileCount };

  UnwrapWorkspace() = default;
  ~UnwrapWorkspace();
  UnwrapWorkspace(const UnwrapWorkspace&) = delete;
  UnwrapWorkspace& operator=(const UnwrapWorkspace&) = delete;

  // Creates the directory and installs the signal cleanup; one workspace per process at a time
  // (the handler tracks one), kInternal for a second.
  Status create();
  const std::string& dir() const { return dir_; }
  std::string path(File f) const;
  // The child the signal handler kills (0: none running).
  void setChild(pid_t pid);

 private:
  void remove();
  std::string dir_;
};

}  // namespace prt::bake
