#include "prt/sh_window.h"

#include <cmath>
#include <string>

#include "prt/sh_basis.h"

namespace prt {

Status parseShWindow(std::string_view name, ShWindow* out) {
  if (name == "none") { *out = ShWindow::kNone; return Status::ok(); }
  if (name == "hanning") { *out = ShWindow::kHanning; return Status::ok(); }
  if (name == "lanczos") { *out = ShWindow::kLanczos; return Status::ok(); }
  return Status::error(StatusCode::kInvalidArgument,
                       "unknown window '" + std::string(name) + "' (expected none, hanning or lanczos)");
}

const char* shWindowName(ShWindow window) {
  switch (window) {
    case ShWindow::kNone: return "none";
    case ShWindow::kHanning: return "hanning";
    case ShWindow::kLanczos: return "lanczos";
  }
  return "unknown";
}

Status shWindowWeights(ShWindow window, int order, float width, std::span<float> out) {
  if (Status s = checkShOrder(order); !s.isOk()) return s;
  if (out.size() < static_cast<std::size_t>(order)) {
    return Status::error(StatusCode::kSizeMismatch, "window weights need " + std::to_string(order) + " values");
  }
  if (!std::isfinite(width)) return Status::error(StatusCode::kNotFinite, "window width is not finite");
  const double w = width > 0.0f ? width : static_cast<double>(order);
  for (int l = 0; l < order; ++l) {
    const double x = l / w;
    double weight = 1.0;
    if (window == ShWindow::kHanning) {
      weight = x < 1.0 ? 0.5 * (1.0 + std::cos(kPi * x)) : 0.0;
    } else if (window == ShWindow::kLanczos) {
      weight = l == 0 ? 1.0 : (x < 1.0 ? std::sin(kPi * x) / (kPi * x) : 0.0);
    }
    out[l] = static_cast<float>(weight);
  }
  return Status::ok();
}

Status applyShWindow(ShWindow window, int order, float width, std::span<Rgb> coeffs) {
  float w[kMaxShOrder];
  if (Status s = shWindowWeights(window, order, width, std::span<float>(w, kMaxShOrder)); !s.isOk()) return s;
  if (coeffs.size() < static_cast<std::size_t>(shCoeffCount(order))) {
    return Status::error(StatusCode::kSizeMismatch, "coefficients must hold order*order values");
  }
  for (int i = 0; i < shCoeffCount(order); ++i) coeffs[i] = coeffs[i] * w[shBandOf(i)];
  return Status::ok();
}

}  // namespace prt
