// Bake progress on stderr: a redrawn bar on a terminal (percent, rays/s, elapsed time and
// the estimated time left in the pass), one line per finished pass otherwise, nothing with
// --quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "baker/transfer/transfer_bake.h"

namespace prt::bake {

// Seconds left in a pass that has done `done` of `total` units in `elapsedSeconds`, by its
// average rate since the pass began: elapsed x (total - done) / done. Negative (unknown)
// before the first unit is done. docs/baker.md, "Progress".
double estimateRemainingSeconds(double elapsedSeconds, std::size_t done, std::size_t total);

// "m:ss" below an hour, "h:mm:ss" from an hour on (seconds rounded to the nearest), ">99h"
// from 100 hours on, "--:--" for a negative (unknown) duration.
std::string formatDuration(double seconds);

// The bar's text for `p` after `elapsedSeconds` of its pass, without the leading '\r':
// pass, bar, percent, ray rate, elapsed and estimated remaining time.
std::string formatProgressLine(const BakeProgress& p, double elapsedSeconds);

class ProgressBar {
 public:
  // `enabled` false silences everything (--quiet).
  ProgressBar(std::FILE* stream, bool enabled);

  // Called (serialised) from the bake's worker threads.
  void update(const BakeProgress& p);
  // Ends the current bar line, if one is drawn.
  void finish();

 private:
  std::FILE* stream_;
  bool enabled_;
  bool tty_;
  std::string pass_;
  std::chrono::steady_clock::time_point passStart_, lastDraw_;
  bool drawn_ = false;
};

}  // namespace prt::bake
