#include "baker/rtt/rtt_bake.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "baker/rtt/periodic_tracer.h"
#include "baker/transfer/parallel_for.h"
#include "prt/sh_basis.h"

namespace prt::bake {
namespace {

struct LightDirection {
  Vec3 dir;
  float weight;  // solid angle, sr
};

// Gauss-Legendre nodes and weights of [-1, 1] by Newton's method on P_n.
void legendreNodes(int n, std::vector<double>* x, std::vector<double>* w) {
  x->resize(static_cast<std::size_t>(n));
  w->resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double t = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 1.0;
    for (int iteration = 0; iteration < 64; ++iteration) {
      double previous = 1.0, current = t;
      for (int k = 2; k <= n; ++k) {
        const double next = ((2.0 * k - 1.0) * t * current - (k - 1.0) * previous) / k;
        previous = current;
        current = next;
      }
      if (n == 1) previous = 1.0;
      derivative = n * (t * current - previous) / (t * t - 1.0);
      const double step = current / derivative;
      t -= step;
      if (std::fabs(step) < 1e-15) break;
    }
    (*x)[static_cast<std::size_t>(i)] = t;
    (*w)[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - t * t) * derivative * derivative);
  }
}

// The upper hemisphere's product rule: cos(theta) at the Gauss-Legendre nodes of [0, 1],
// phi at `azimuths` uniform cell centres; weights sum to 2 pi. Exact for polynomials in
// cos(theta) of degree < 2 polar times trigonometric ones of order < azimuths.
std::vector<LightDirection> hemisphereDirections(int polar, int azimuths) {
  std::vector<double> x, w;
  legendreNodes(polar, &x, &w);
  std::vector<LightDirection> out;
  for (int i = 0; i < polar; ++i) {
    const double c = 0.5 * (x[static_cast<std::size_t>(i)] + 1.0), s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double weight = 0.5 * w[static_cast<std::size_t>(i)] * 2.0 * kPi / azimuths;
    for (int j = 0; j < azimuths; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / azimuths;
      out.push_back({{static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)), static_cast<float>(c)},
                     static_cast<float>(weight)});
    }
  }
  return out;
}

// Unit normal at grid point (i, j) by central differences with wrap.
Vec3 gridNormal(const HeightPatch& p, int i, int j) {
  const int n = p.size;
  auto h = [&](int a, int b) {
    return p.height[static_cast<std::size_t>((b + n) % n) * static_cast<std::size_t>(n) + static_cast<std::size_t>((a + n) % n)];
  };
  const float spacing = 1.0f / static_cast<float>(n);
  const float dx = (h(i + 1, j) - h(i - 1, j)) / (2.0f * spacing), dy = (h(i, j + 1) - h(i, j - 1)) / (2.0f * spacing);
  const Vec3 g{-dx, -dy, 1.0f};
  return g * (1.0f / length(g));
}

Status checkSettings(const HeightPatch& patch, const RttSettings& s) {
  auto bad = [](const std::string& m) { return Status::error(StatusCode::kInvalidArgument, m); };
  if (patch.size < 2 || patch.height.size() != static_cast<std::size_t>(patch.size) * static_cast<std::size_t>(patch.size) ||
      patch.albedo.size() != patch.height.size()) {
    return bad("RTT patch arrays disagree with its size");
  }
  if (s.order < 1 || s.order > kMaxRttOrder) return bad("RTT order " + std::to_string(s.order) + " outside 1 .. " + std::to_string(kMaxRttOrder));
  if (s.spatial < 1 || s.spatial > kMaxRttSpatial) return bad("RTT spatial size outside 1 .. " + std::to_string(kMaxRttSpatial));
  if (s.views < 1 || s.views > kMaxRttViews) return bad("RTT view size outside 1 .. " + std::to_string(kMaxRttViews));
  if (s.supersample < 1 || s.supersample > 16) return bad("RTT supersampling outside 1 .. 16");
  if (s.lightPolar < 1 || s.lightPolar > 256 || s.lightAzimuth < 1 || s.lightAzimuth > 512) return bad("RTT light directions out of range");
  if (s.bounces < 0 || s.bounces > 16) return bad("RTT bounces outside 0 .. 16");
  return Status::ok();
}

}  // namespace

Status bakeRtt(const HeightPatch& patch, const RttSettings& settings, const RttProgress& progress, Rtt* out) {
  if (Status s = checkSettings(patch, settings); !s.isOk()) return s;
  PeriodicTracer tracer;
  if (Status s = PeriodicTracer::build(patch, &tracer); !s.isOk()) return s;
  const unsigned threads = settings.threads ? settings.threads : defaultThreadCount();
  const int n2 = settings.order * settings.order;
  const std::size_t nn = static_cast<std::size_t>(n2);
  const int channels = patch.coloured ? 3 : 1;
  const std::size_t points = patch.height.size();
  const std::vector<LightDirection> lights = hemisphereDirections(settings.lightPolar, settings.lightAzimuth);
  const std::size_t L = lights.size();
  std::vector<float> basis(L * nn);
  // Rays leave a surface point this far along its normal, in grid spacings.
  constexpr float kRayOffset = 1e-3f;
  for (std::size_t k = 0; k < L; ++k) evalShBasisUnchecked(settings.order, lights[k].dir, &basis[k * nn]);

  // 1. Per grid point: the direct (shadowed) transfer over the light directions the patch
  //    does not block. 2. Bounces: each gathers the previous bounce's transfer from the
  //    points the blocked directions hit (interpolated over the hit triangle), times rho / pi
  //    and the cosine. The rays are cast again each pass rather than stored: a 2048^2 patch
  //    with 128 directions would need 8 GB of hits.
  const float spacing = 1.0f / static_cast<float>(patch.size);
  const std::size_t rows = static_cast<std::size_t>(patch.size), perPoint = static_cast<std::size_t>(channels) * nn;
  std::vector<float> transfer(points * perPoint, 0.0f), previous, next;
  for (int pass = 0; pass <= settings.bounces; ++pass) {
    next.assign(points * perPoint, 0.0f);
    std::atomic<std::size_t> rowsDone{0};
    if (progress) progress(pass == 0 ? "direct" : "bounce", 0, rows);
    parallelFor(rows, threads, [&](std::size_t j, unsigned thread) {
      std::vector<float> gathered(perPoint);
      for (int i = 0; i < patch.size; ++i) {
        const std::size_t p = j * rows + static_cast<std::size_t>(i);
        const Vec3 n = gridNormal(patch, i, static_cast<int>(j));
        const Vec3 x{static_cast<float>(i) * spacing, static_cast<float>(j) * spacing, patch.height[p]};
        const Rgb a = patch.albedo[p];
        const float rho[3] = {a.r, a.g, a.b};
        float* t = &next[p * perPoint];
        for (std::size_t k = 0; k < L; ++k) {
          const float cosine = dot(n, lights[k].dir);
          if (cosine <= 0.0f) continue;  // below the meso tangent plane
          const PeriodicHit h = tracer.firstHit(x + n * (kRayOffset * spacing), lights[k].dir);
          const float f = lights[k].weight * cosine / static_cast<float>(kPi);
          if (pass == 0 && !h.hit) {
            for (int c = 0; c < channels; ++c)
              for (std::size_t q = 0; q < nn; ++q) t[static_cast<std::size_t>(c) * nn + q] += rho[c] * f * basis[k * nn + q];
          } else if (pass > 0 && h.hit) {
            tracer.interpolate(h, previous, perPoint, gathered.data());
            for (int c = 0; c < channels; ++c)
              for (std::size_t q = 0; q < nn; ++q) t[static_cast<std::size_t>(c) * nn + q] += rho[c] * f * gathered[static_cast<std::size_t>(c) * nn + q];
          }
        }
      }
      const std::size_t done = ++rowsDone;
      if (progress && thread == 0) progress(pass == 0 ? "direct" : "bounce", done, rows);
    });
    for (std::size_t q = 0; q < transfer.size(); ++q) transfer[q] += next[q];
    previous.swap(next);
  }

  // 3. The views: per spatial sample and view direction, the transfer of the first point the
  //    view rays through the sample's supersamples (on the mid-depth plane) meet.
  Rtt r;
  r.order = settings.order;
  r.channels = channels;
  r.spatial = settings.spatial;
  r.views = settings.views;
  r.coeffs.assign(r.coeffCount(), 0.0f);
  const std::size_t S = static_cast<std::size_t>(settings.spatial), V = static_cast<std::size_t>(settings.views);
  const int ss = settings.supersample;
  const float midDepth = 0.5f * (tracer.minHeight() + tracer.maxHeight());
  std::atomic<std::size_t> viewRowsDone{0};
  if (progress) progress("views", 0, S);
  parallelFor(S, threads, [&](std::size_t y, unsigned thread) {
    std::vector<float> value(perPoint);
    for (std::size_t x = 0; x < S; ++x) {
      for (std::size_t b = 0; b < V; ++b) {
        for (std::size_t a = 0; a < V; ++a) {
          const Vec3 w = rttViewDirection(static_cast<int>(a), static_cast<int>(b), static_cast<int>(V));
          float* dst = &r.coeffs[(((y * S + x) * V + b) * V + a) * perPoint];
          for (int sy = 0; sy < ss; ++sy) {
            for (int sx = 0; sx < ss; ++sx) {
              const float u = (static_cast<float>(x) + (static_cast<float>(sx) + 0.5f) / static_cast<float>(ss)) / static_cast<float>(S);
              const float v = (static_cast<float>(y) + (static_cast<float>(sy) + 0.5f) / static_cast<float>(ss)) / static_cast<float>(S);
              const PeriodicHit h = tracer.viewHit({u, v, midDepth}, w);
              if (!h.hit) continue;  // cannot happen on a height field: kept 0 rather than guessed
              tracer.interpolate(h, transfer, perPoint, value.data());
              for (std::size_t q = 0; q < perPoint; ++q) dst[q] += value[q];
            }
          }
          const float scale = 1.0f / static_cast<float>(ss * ss);
          for (std::size_t q = 0; q < perPoint; ++q) dst[q] *= scale;
        }
      }
    }
    const std::size_t done = ++viewRowsDone;
    if (progress && thread == 0) progress("views", done, S);
  });
  *out = std::move(r);
  return Status::ok();
}

}  // namespace prt::bake
