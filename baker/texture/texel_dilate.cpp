#include "baker/texture/texel_dilate.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <new>
#include <string>

#include "baker/scene/uv_atlas_check.h"

namespace prt::bake {
namespace {

enum : std::uint8_t { kEmpty = 0, kFilled = 1, kQueued = 2 };

Status fail(StatusCode code, const std::string& message) { return Status::error(code, "gutter dilation: " + message); }

class Dilator {
 public:
  Dilator(std::span<float> texels, int width, int height, int channels)
      : texels_(texels), w_(width), h_(height), c_(static_cast<std::size_t>(channels)) {}

  // Marks the used texels filled and puts those bordering an empty texel in the frontier.
  void start(std::span<const std::uint8_t> coverage);
  void pass();
  bool done() const { return frontier_.empty(); }
  const std::vector<std::uint8_t>& state() const { return state_; }

 private:
  // Calls f(neighbour index) for each in-atlas 8-neighbour of texel i, in a fixed order.
  template <typename F>
  void forNeighbours(std::size_t i, F&& f) const {
    const int x = static_cast<int>(i % static_cast<std::size_t>(w_)),
              y = static_cast<int>(i / static_cast<std::size_t>(w_));
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w_ || ny >= h_) continue;
        f(static_cast<std::size_t>(ny) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(nx));
      }
    }
  }

  std::span<float> texels_;
  int w_, h_;
  std::size_t c_;
  std::vector<std::uint8_t> state_;
  std::vector<std::size_t> frontier_;  // texels filled last pass (or used, before the first)
  std::vector<std::size_t> queued_;
  std::vector<float> values_;
  std::vector<double> sum_;
};

void Dilator::start(std::span<const std::uint8_t> coverage) {
  state_.resize(coverage.size());
  for (std::size_t i = 0; i < coverage.size(); ++i) state_[i] = coverage[i] ? kFilled : kEmpty;
  // Interior texels of a chart can never neighbour an empty one, so they stay out of the frontier.
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_[i] != kFilled) continue;
    bool border = false;
    forNeighbours(i, [&](std::size_t j) { border = border || state_[j] == kEmpty; });
    if (border) frontier_.push_back(i);
  }
}

void Dilator::pass() {
  queued_.clear();
  for (const std::size_t f : frontier_) {
    forNeighbours(f, [&](std::size_t j) {
      if (state_[j] != kEmpty) return;
      state_[j] = kQueued;
      queued_.push_back(j);
    });
  }
  // Every value of this pass is computed before any is written, so each depends only on the
  // state before the pass and the visiting order does not matter.
  values_.resize(queued_.size() * c_);
  sum_.resize(c_);
  for (std::size_t q = 0; q < queued_.size(); ++q) {
    std::fill(sum_.begin(), sum_.end(), 0.0);
    int count = 0;
    forNeighbours(queued_[q], [&](std::size_t j) {
      if (state_[j] != kFilled) return;
      ++count;
      for (std::size_t c = 0; c < c_; ++c) sum_[c] += texels_[j * c_ + c];
    });
    // count >= 1: a queued texel neighbours a frontier texel. k equal floats sum exactly in
    // double (k <= 8), so the mean of a constant is that constant, bit for bit.
    for (std::size_t c = 0; c < c_; ++c) values_[q * c_ + c] = static_cast<float>(sum_[c] / count);
  }
  for (std::size_t q = 0; q < queued_.size(); ++q) {
    std::copy_n(values_.begin() + static_cast<std::ptrdiff_t>(q * c_), c_,
                texels_.begin() + static_cast<std::ptrdiff_t>(queued_[q] * c_));
    state_[queued_[q]] = kFilled;
  }
  frontier_.swap(queued_);
}

}  // namespace

Status dilateGutters(std::span<float> texels, int width, int height, int channels,
                     std::span<const std::uint8_t> coverage, int passes, std::vector<std::uint8_t>* filled) {
  if (width < 1 || width > kMaxAtlasSize || height < 1 || height > kMaxAtlasSize)
    return fail(StatusCode::kInvalidArgument, "texture size " + std::to_string(width) + "x" + std::to_string(height) +
                                                  " is outside 1 … " + std::to_string(kMaxAtlasSize));
  if (channels < 1 || channels > kMaxDilationChannels)
    return fail(StatusCode::kInvalidArgument,
                std::to_string(channels) + " channels is outside 1 … " + std::to_string(kMaxDilationChannels));
  if (passes < 0 || passes > kMaxDilationPasses)
    return fail(StatusCode::kInvalidArgument,
                std::to_string(passes) + " passes is outside 0 … " + std::to_string(kMaxDilationPasses));
  // At most 2^28 texels × 4096 channels: no overflow in size_t.
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t c = static_cast<std::size_t>(channels);
  if (coverage.size() != n)
    return fail(StatusCode::kSizeMismatch,
                std::to_string(coverage.size()) + " coverage flags for " + std::to_string(n) + " texels");
  if (texels.size() != n * c)
    return fail(StatusCode::kSizeMismatch, std::to_string(texels.size()) + " floats for " + std::to_string(n) +
                                               " texels of " + std::to_string(channels) + " channels");
  for (std::size_t i = 0; i < n; ++i) {
    if (!coverage[i]) continue;
    for (std::size_t k = 0; k < c; ++k)
      if (!std::isfinite(texels[i * c + k]))
        return fail(StatusCode::kNotFinite,
                    "used texel " + std::to_string(i) + " channel " + std::to_string(k) + " is not finite");
  }
  try {
    Dilator d(texels, width, height, channels);
    d.start(coverage);
    for (int p = 0; p < passes && !d.done(); ++p) d.pass();
    if (filled != nullptr) {
      filled->resize(n);
      for (std::size_t i = 0; i < n; ++i) (*filled)[i] = d.state()[i] == kFilled ? 1 : 0;
    }
  } catch (const std::bad_alloc&) {
    return fail(StatusCode::kResourceExhausted, "out of memory at " + std::to_string(width) + "x" +
                                                    std::to_string(height) + ", " + std::to_string(channels) +
                                                    " channels");
  }
  return Status::ok();
}

}  // namespace prt::bake
