#include "baker/rtt/height_patch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace prt::bake {

const char* const kProceduralPatchNames = "flat, weave, holes, stucco";

namespace {

constexpr int kMinSize = 8, kMaxSize = 2048;

// Top of a cylinder of radius r whose axis is at height `centre`, at distance d from the
// axis in the plane across it; -infinity outside it.
double cylinderTop(double d, double r, double centre) { return std::fabs(d) < r ? centre + std::sqrt(r * r - d * d) : -1e30; }

// Distance from t to the nearest of the periodic centres (k + 0.5) / n, signed.
double periodicOffset(double t, int n) {
  const double cell = t * n;
  return (cell - std::floor(cell) - 0.5) / n;
}

// A plain weave: n warp threads along x and n weft threads along y, each a cylinder whose
// axis rises and falls as cos, warp j in phase (-1)^j, weft opposite, so each passes over
// and under the other family alternately. Base plane under both.
double weave(double x, double y) {
  constexpr int n = 4;
  const double r = 0.45 / n, amplitude = 0.35 * r;
  const int warp = static_cast<int>(std::floor(y * n)) % n, weft = static_cast<int>(std::floor(x * n)) % n;
  const double warpAxis = amplitude * std::cos(kPi * n * x) * ((warp % 2) ? -1.0 : 1.0);
  const double weftAxis = -amplitude * std::cos(kPi * n * y) * ((weft % 2) ? -1.0 : 1.0);
  const double top = std::max(cylinderTop(periodicOffset(y, n), r, warpAxis), cylinderTop(periodicOffset(x, n), r, weftAxis));
  return std::max(top, -r - amplitude);
}

// A plate (height 0) with 2 x 2 round pits of radius 0.16 and depth 0.12.
double holes(double x, double y) {
  const double dx = periodicOffset(x, 2), dy = periodicOffset(y, 2);
  return dx * dx + dy * dy < 0.16 * 0.16 ? -0.12 : 0.0;
}

// Smooth bumps: a fixed sum of periodic cosines of low integer frequencies.
double stucco(double x, double y) {
  double h = 0.0;
  std::uint32_t state = 12345u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  };
  for (int k = 0; k < 24; ++k) {
    const int fx = 1 + static_cast<int>(next() * 6.0), fy = static_cast<int>(next() * 6.0) - 2;
    const double phase = 2.0 * kPi * next(), amplitude = 0.012 / std::sqrt(static_cast<double>(fx * fx + fy * fy));
    h += amplitude * std::cos(2.0 * kPi * (fx * x + fy * y) + phase);
  }
  return h;
}

Status checkSize(int size) {
  if (size < kMinSize || size > kMaxSize) {
    return Status::error(StatusCode::kInvalidArgument,
                         "patch size " + std::to_string(size) + " outside " + std::to_string(kMinSize) + " .. " + std::to_string(kMaxSize));
  }
  return Status::ok();
}

}  // namespace

Status makeProceduralPatch(std::string_view name, int size, float albedo, HeightPatch* out) {
  if (Status s = checkSize(size); !s.isOk()) return s;
  if (!(albedo >= 0.0f && albedo <= 1.0f)) return Status::error(StatusCode::kInvalidArgument, "albedo outside [0, 1]");
  double (*fn)(double, double) = nullptr;
  if (name == "weave") fn = weave;
  else if (name == "holes") fn = holes;
  else if (name == "stucco") fn = stucco;
  else if (name != "flat") {
    return Status::error(StatusCode::kInvalidArgument, "unknown patch '" + std::string(name) + "' (built in: " + kProceduralPatchNames + ")");
  }
  HeightPatch p;
  p.size = size;
  p.height.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      const double x = static_cast<double>(i) / size, y = static_cast<double>(j) / size;
      p.height[static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)] =
          fn ? static_cast<float>(fn(x, y)) : 0.0f;
    }
  }
  p.albedo.assign(p.height.size(), Rgb{albedo, albedo, albedo});
  *out = std::move(p);
  return Status::ok();
}

Status makeImagePatch(const RgbImage& height, float heightScale, const RgbImage* albedoImage, float albedo, HeightPatch* out) {
  if (height.width != height.height) {
    return Status::error(StatusCode::kInvalidArgument, "height map is " + std::to_string(height.width) + "x" + std::to_string(height.height) +
                                                           ": a patch must be square");
  }
  if (Status s = checkSize(height.width); !s.isOk()) return s;
  if (!std::isfinite(heightScale)) return Status::error(StatusCode::kInvalidArgument, "height scale is not finite");
  if (!(albedo >= 0.0f && albedo <= 1.0f)) return Status::error(StatusCode::kInvalidArgument, "albedo outside [0, 1]");
  if (albedoImage && (albedoImage->width != height.width || albedoImage->height != height.height)) {
    return Status::error(StatusCode::kInvalidArgument, "albedo map is " + std::to_string(albedoImage->width) + "x" +
                                                           std::to_string(albedoImage->height) + ", the height map " +
                                                           std::to_string(height.width) + "x" + std::to_string(height.height));
  }
  HeightPatch p;
  p.size = height.width;
  const std::size_t n = static_cast<std::size_t>(p.size) * static_cast<std::size_t>(p.size);
  p.height.resize(n);
  p.albedo.assign(n, Rgb{albedo, albedo, albedo});
  for (int j = 0; j < p.size; ++j) {
    for (int i = 0; i < p.size; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(p.size) + static_cast<std::size_t>(i);
      // Image row j is patch row y = j / size: v runs down the image, as glTF's UVs do.
      const float h = height.at(i, j).r * heightScale;
      if (!std::isfinite(h)) return Status::error(StatusCode::kInvalidArgument, "height map texel (" + std::to_string(i) + ", " + std::to_string(j) + ") is not finite");
      p.height[k] = h;
      if (albedoImage) {
        const Rgb a = albedoImage->at(i, j);
        if (!(a.r >= 0.0f && a.r <= 1.0f && a.g >= 0.0f && a.g <= 1.0f && a.b >= 0.0f && a.b <= 1.0f)) {
          return Status::error(StatusCode::kInvalidArgument,
                               "albedo map texel (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside [0, 1]");
        }
        p.albedo[k] = a;
        p.coloured = p.coloured || a.r != a.g || a.g != a.b;
      }
    }
  }
  *out = std::move(p);
  return Status::ok();
}

}  // namespace prt::bake
