#include "baker/cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>

namespace prt::bake {

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
  const double s = std::chrono::duration<double>(now - passStart_).count();
  const double fraction = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
  const double eta = fraction > 0 ? s * (1.0 - fraction) / fraction : 0.0;
  const int width = 30, filled = static_cast<int>(fraction * width);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  char rate[32] = "  (no rays)   ";  // bounce passes gather cached hits and cast nothing
  if (p.rays > 0) std::snprintf(rate, sizeof rate, "%7.2f Mrays/s", s > 0 ? static_cast<double>(p.rays) / s * 1e-6 : 0.0);
  std::fprintf(stream_, "\r%-9s [%s] %5.1f%%  %s  ETA %5.0fs ", p.pass, bar.c_str(), 100.0 * fraction, rate,
               std::max(0.0, eta));
  std::fflush(stream_);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) std::fputc('\n', stream_);
  drawn_ = false;
}

}  // namespace prt::bake
