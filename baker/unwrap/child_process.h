// Runs an external program (Blender, for the atlas generator) without a shell: an argv
// spawned with posix_spawnp, stdin from /dev/null, stdout and stderr together into a log
// file, killed when it runs past a time limit.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "prt/status.h"

namespace prt::bake {

struct ChildResult {
  bool timedOut = false;  // killed (SIGKILL) at the time limit
  int exitStatus = -1;    // when it exited by itself: its status (0 = success)
  int signal = 0;         // when a signal ended it (the time limit's SIGKILL included)
  double seconds = 0.0;   // wall time from spawn to exit
};

// Runs argv[0] (looked up on PATH unless it contains a '/') with argv, its output in `logPath`
// (created or truncated, mode 0600), and waits at most `limit`. `started` (when set) gets the
// child's pid as soon as it exists, `finished` after it has been reaped, so a signal handler can
// kill it meanwhile. kNotFound when the program does not exist, kIoError when it cannot be run
// (permissions, not executable) or the log cannot be created; the child's own failure is in
// *out, not the status.
Status runChild(const std::vector<std::string>& argv, const std::string& logPath, std::chrono::milliseconds limit,
                ChildResult* out, const std::function<void(pid_t)>& started = {},
                const std::function<void()>& finished = {});

// The last `maxLines` non-empty lines of a log (at most its last 64 KiB), joined by " | ":
// what an error message quotes from a failed child.
std::string logTail(const std::string& logPath, int maxLines);

}  // namespace prt::bake
