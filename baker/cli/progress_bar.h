// Bake progress on stderr: a redrawn bar on a terminal (percent, rays/s, ETA), one line
// per finished pass otherwise, nothing with --quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

#include "baker/transfer/transfer_bake.h"

namespace prt::bake {

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
