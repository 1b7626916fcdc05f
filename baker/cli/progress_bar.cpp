#include "baker/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace prt::bake {

double estimateRemainingSeconds(double elapsedSeconds, std::size_t done, std::size_t total) {
  if (done == 0 || total == 0) return -1.0;
  if (done >= total) return 0.0;
  // The pass's average rate, not a recent window: the workers take small blocks of vertices
  // from a shared counter (parallel_for.h), so the rate settles after the first blocks, and
  // an average does not swing with one slow (heavily occluded) block as a window would.
  return elapsedSeconds * static_cast<double>(total - done) / static_cast<double>(done);
}

std::string formatDuration(double seconds) {
  if (seconds < 0 || !std::isfinite(seconds)) return "--:--";
  if (seconds >= 100.0 * 3600.0) return ">99h";  // an estimate this long is news enough
  const auto total = static_cast<long long>(std::llround(seconds));
  char s[32];
  if (total < 3600) std::snprintf(s, sizeof s, "%lld:%02lld", total / 60, total % 60);
  else std::snprintf(s, sizeof s, "%lld:%02lld:%02lld", total / 3600, total / 60 % 60, total % 60);
  return s;
}

std::string formatProgressLine(const BakeProgress& p, double elapsedSeconds) {
  const double fraction = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
  // 10 cells and fixed-width fields keep the line at 79 columns (a wider one wraps on an
  // 80-column terminal, and '\r' then redraws only its last row) and as long as the last
  // one, so a redraw leaves nothing of it behind.
  const int width = 10, filled = static_cast<int>(fraction * width);
  std::string bar(static_cast<std::size_t>(std::clamp(filled, 0, width)), '#');
  bar.resize(width, '.');
  char rate[32] = "   (no rays)   ";  // bounce passes gather cached hits and cast nothing
  if (p.rays > 0) {
    std::snprintf(rate, sizeof rate, "%7.2f Mrays/s", elapsedSeconds > 0 ? static_cast<double>(p.rays) / elapsedSeconds * 1e-6 : 0.0);
  }
  char line[160];
  std::snprintf(line, sizeof line, "%-9s [%s] %5.1f%% %s  %8s elapsed  %8s left ", p.pass, bar.c_str(), 100.0 * fraction, rate,
                formatDuration(elapsedSeconds).c_str(), formatDuration(estimateRemainingSeconds(elapsedSeconds, p.done, p.total)).c_str());
  return line;
}

ProgressBar::ProgressBar(std::FILE* stream, bool enabled)
    : stream_(stream), enabled_(enabled), tty_(::isatty(::fileno(stream)) == 1) {}

void ProgressBar::update(const BakeProgress& p) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (pass_ != p.pass) {
    finish();
    pass_ = p.pass;
    passStart_ = now;
    lastDraw_ = now - std::chrono::seconds(1);
  }
  const bool done = p.done >= p.total;
  // Texel passes (transfer textures) count texels; every other pass counts vertices.
  const char* unit = pass_.rfind("texel", 0) == 0 ? "texels" : "vertices";
  if (!tty_) {
    if (done) {
      const double s = std::chrono::duration<double>(now - passStart_).count();
      if (p.rays > 0) {
        std::fprintf(stream_, "prt-bake: %s: %zu %s, %.2f s, %.2f Mrays/s\n", p.pass, p.total, unit, s,
                     s > 0 ? static_cast<double>(p.rays) / s * 1e-6 : 0.0);
      } else {
        std::fprintf(stream_, "prt-bake: %s: %zu %s, %.2f s\n", p.pass, p.total, unit, s);
      }
    }
    return;
  }
  if (!done && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  std::fprintf(stream_, "\r%s", formatProgressLine(p, std::chrono::duration<double>(now - passStart_).count()).c_str());
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fputc('\n', stream_);
  drawn_ = false;
}

}  // namespace prt::bake
