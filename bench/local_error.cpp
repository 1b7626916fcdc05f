// prt-bench-local-error: how well spatially-varying ("local sphere") transfer reproduces
// direct lighting from an emitter on the lighting sphere, next to the distant bake of the
// same lighting (docs/spatially-varying.md). The built-in room, order 5, shadowed transfer
// only (interreflection off, so both sides are direct light), the lighting sphere the CLI's
// default (bounds centre, half the diagonal), and a 15-degree cap of it as the emitter. The
// reference is the brute-force area integral over the cap with Embree visibility
// (baker/transfer/direct_reference.h). Also times the local bake against the distant one in the same
// run. Prints a table; --json / --md write the results.
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "baker/scene/default_scene.h"
#include "baker/transfer/direct_reference.h"
#include "native/file_io.h"
#include "baker/transfer/local_sphere.h"
#include "prt/sh_basis.h"
#include "baker/transfer/transfer_bake.h"

using namespace prt;

namespace {

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string num(double v, const char* format = "%.6g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

Status writeText(const std::string& path, const std::string& text) {
  return writeFileAtomically(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

// Per-vertex error statistics over the lit vertices, relative to the true (cap reference)
// irradiance `scale` in every row, so that the rows compare.
struct ErrorStats {
  double mean = 0, median = 0, p95 = 0, max = 0;  // of |a - b| / scale
  double rmsOverMean = 0;                         // sqrt(mean (a - b)^2) / mean scale
  double meanSigned = 0;                          // mean (a - b) / mean scale: overall bias
};

ErrorStats errorStats(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& scale,
                      const std::vector<std::size_t>& lit) {
  std::vector<double> rel;
  double sq = 0.0, sumRef = 0.0, signedSum = 0.0;
  for (std::size_t v : lit) {
    rel.push_back(std::fabs(a[v] - b[v]) / scale[v]);
    sq += (a[v] - b[v]) * (a[v] - b[v]);
    signedSum += a[v] - b[v];
    sumRef += scale[v];
  }
  std::sort(rel.begin(), rel.end());
  ErrorStats s;
  const double n = static_cast<double>(rel.size());
  for (double r : rel) s.mean += r / n;
  s.median = rel[rel.size() / 2];
  s.p95 = rel[static_cast<std::size_t>(0.95 * (n - 1))];
  s.max = rel.back();
  s.rmsOverMean = std::sqrt(sq / n) / (sumRef / n);
  s.meanSigned = signedSum / sumRef;
  return s;
}

// E_prt(v) = pi sum_i S_i(v) L_i: the transfer's irradiance, comparable with the reference's E.
std::vector<double> prtIrradiance(const bake::BakeResult& r, const std::vector<float>& lighting) {
  const std::size_t n2 = lighting.size(), vertices = r.shadowed.size() / n2;
  std::vector<double> e(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    double acc = 0.0;
    for (std::size_t i = 0; i < n2; ++i) acc += static_cast<double>(r.shadowed[v * n2 + i]) * lighting[i];
    e[v] = kPi * acc;
  }
  return e;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string jsonPath, mdPath;
  std::size_t referenceSamples = 4096;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json" && i + 1 < argc) jsonPath = argv[++i];
    else if (a == "--md" && i + 1 < argc) mdPath = argv[++i];
    else if (a == "--reference-samples" && i + 1 < argc) referenceSamples = std::stoul(argv[++i]);
    else {
      std::fprintf(stderr, "usage: prt-bench-local-error [--reference-samples N] [--json PATH] [--md PATH]\n");
      return 2;
    }
  }
  const bake::Scene scene = bake::makeDefaultScene();
  const LightingInfo sphere = bake::defaultLightingSphere(scene, LightingModel::kLocalSphere);
  bake::CapEmitter cap;
  cap.center = sphere.center;
  cap.radius = sphere.radius;
  cap.axis = Vec3{-0.4f, 0.75f, 0.55f} * (1.0f / length(Vec3{-0.4f, 0.75f, 0.55f}));  // above the open front-left
  cap.halfAngle = static_cast<float>(15.0 * kPi / 180.0);
  cap.radiance = 10.0f;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());

  bake::BakeOptions o;
  o.order = 5;
  o.samples = 1024;
  o.interreflection = false;
  o.threads = threads;
  std::vector<float> lighting;
  if (Status s = bake::capLightingSh(cap, o.order, &lighting); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-local-error: %s\n", s.message().c_str());
    return 1;
  }

  // Bakes, alternating so that a busy machine slows both alike; the faster of two runs each.
  bake::BakeResult distant, local;
  double distantSeconds = INFINITY, localSeconds = INFINITY;
  for (int round = 0; round < 3; ++round) {
    for (bool isLocal : {false, true}) {
      o.lighting = isLocal ? sphere : LightingInfo{};
      bake::BakeResult r;
      const auto t0 = std::chrono::steady_clock::now();
      if (Status s = bake::bakeTransfer(scene, o, &r); !s.isOk()) {
        std::fprintf(stderr, "prt-bench-local-error: bake: %s\n", s.message().c_str());
        return 1;
      }
      const double t = seconds(t0);
      (isLocal ? localSeconds : distantSeconds) = std::min(isLocal ? localSeconds : distantSeconds, t);
      (isLocal ? local : distant) = std::move(r);
    }
  }
  // Order 8 too, to show how much of the local error is SH truncation of the small cap, and
  // what the per-ray basis evaluation costs when it is heavier.
  std::vector<float> lighting8;
  (void)bake::capLightingSh(cap, 8, &lighting8);
  bake::BakeResult local8;
  double distant8Seconds = INFINITY, local8Seconds = INFINITY;
  o.order = 8;
  for (int round = 0; round < 2; ++round) {
    for (bool isLocal : {false, true}) {
      o.lighting = isLocal ? sphere : LightingInfo{};
      bake::BakeResult r;
      const auto t0 = std::chrono::steady_clock::now();
      if (Status s = bake::bakeTransfer(scene, o, &r); !s.isOk()) {
        std::fprintf(stderr, "prt-bench-local-error: bake: %s\n", s.message().c_str());
        return 1;
      }
      double& best = isLocal ? local8Seconds : distant8Seconds;
      best = std::min(best, seconds(t0));
      if (isLocal) local8 = std::move(r);
    }
  }

  const auto tr = std::chrono::steady_clock::now();
  bake::DirectReferenceOptions ro;
  ro.samples = referenceSamples;
  ro.threads = threads;
  std::vector<double> reference, reference2;
  if (Status s = bake::directIrradianceFromCap(scene, cap, ro, &reference); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-local-error: reference: %s\n", s.message().c_str());
    return 1;
  }
  const double referenceSeconds = seconds(tr);
  ro.seed = 7;  // an independently shifted point set: the reference's own noise
  if (Status s = bake::directIrradianceFromCap(scene, cap, ro, &reference2); !s.isOk()) return 1;

  // The same area integral over the whole sphere with its radiance replaced by the order-5
  // SH the transfer is multiplied with: PRT against this is the formulation's error alone
  // (plus Monte Carlo), the gap between this and the cap's reference the SH truncation.
  bake::CapEmitter truncated{cap.center, cap.radius, {0, 1, 0}, static_cast<float>(kPi), 1.0f, [&lighting](Vec3 w) {
    std::vector<float> y(lighting.size());
    evalShBasisUnchecked(5, w, y.data());
    float acc = 0.0f;
    for (std::size_t i = 0; i < y.size(); ++i) acc += lighting[i] * y[i];
    return acc;
  }};
  bake::DirectReferenceOptions to = ro;
  to.seed = 0;
  to.samples = 4 * referenceSamples;
  std::vector<double> truncatedReference;
  if (Status s = bake::directIrradianceFromCap(scene, truncated, to, &truncatedReference); !s.isOk()) return 1;

  const std::size_t vertexCount = scene.positions.size();
  double meanAll = 0.0;
  for (double e : reference) meanAll += e / static_cast<double>(vertexCount);
  std::vector<std::size_t> lit;
  for (std::size_t v = 0; v < vertexCount; ++v)
    if (reference[v] >= 0.05 * meanAll) lit.push_back(v);
  const std::vector<double>& ref = reference;
  const ErrorStats localErr = errorStats(prtIrradiance(local, lighting), ref, ref, lit);
  const ErrorStats local8Err = errorStats(prtIrradiance(local8, lighting8), ref, ref, lit);
  const ErrorStats distantErr = errorStats(prtIrradiance(distant, lighting), ref, ref, lit);
  const ErrorStats noise = errorStats(reference2, ref, ref, lit);
  const ErrorStats formulation = errorStats(prtIrradiance(local, lighting), truncatedReference, ref, lit);
  const ErrorStats truncation = errorStats(truncatedReference, ref, ref, lit);

  struct Row {
    const char* name;
    const ErrorStats* s;
  };
  const Row rows[] = {{"local sphere, order 5", &localErr},
                      {"distant, order 5", &distantErr},
                      {"local sphere, order 8", &local8Err},
                      {"reference vs itself (2 point sets)", &noise},
                      {"local sphere, order 5, vs reference lit by the same order-5 SH", &formulation},
                      {"reference lit by the order-5 SH vs reference (truncation alone)", &truncation}};
  std::string table =
      "| bake vs reference | mean rel. error | median | 95th pct | max | RMS / mean | bias (mean signed / mean) |\n"
      "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    table += std::string("| ") + r.name + " | " + num(100 * r.s->mean, "%.2f%%") + " | " + num(100 * r.s->median, "%.2f%%") +
             " | " + num(100 * r.s->p95, "%.2f%%") + " | " + num(100 * r.s->max, "%.1f%%") + " | " +
             num(100 * r.s->rmsOverMean, "%.2f%%") + " | " + num(100 * r.s->meanSigned, "%+.2f%%") + " |\n";
  }
  std::string timing = "| bake (1024 samples, shadowed only, " + std::to_string(threads) +
                       " threads; best of alternating runs) | order 5: s | order 8: s |\n|---|---:|---:|\n";
  timing += "| distant | " + num(distantSeconds, "%.3f") + " | " + num(distant8Seconds, "%.3f") + " |\n";
  timing += "| local sphere | " + num(localSeconds, "%.3f") + " | " + num(local8Seconds, "%.3f") + " |\n";
  timing += "| ratio local / distant | " + num(localSeconds / distantSeconds, "%.2f") + " | " +
            num(local8Seconds / distant8Seconds, "%.2f") + " |\n";

  utsname u{};
  uname(&u);
  const std::string setup =
      "Default room (" + std::to_string(vertexCount) + " vertices), lighting sphere centre (" + num(sphere.center.x) + ", " +
      num(sphere.center.y) + ", " + num(sphere.center.z) + "), radius " + num(sphere.radius) +
      "; emitter: a 15-degree cap of the sphere about (-0.4, 0.75, 0.55), radiance 10; reference: " +
      std::to_string(referenceSamples) + " area samples per vertex on the cap (" + num(referenceSeconds, "%.1f") + " s), " +
      std::to_string(4 * referenceSamples) + " on the whole sphere for the truncated-SH reference; " +
      std::to_string(lit.size()) + " lit vertices (reference irradiance >= 5% of its mean over all vertices).";
  std::printf("%s\n\n%s\n%s", setup.c_str(), table.c_str(), timing.c_str());

  if (!mdPath.empty()) {
    std::string md = "# Spatially-varying lighting: error against brute force, and bake cost\n\n";
    md += "`scripts/bench-local.sh` (bench/local_error.cpp), " + utcNow() + ", " + cpuModel() + ", " + u.sysname + " " +
          u.release + ". See docs/spatially-varying.md.\n\n" + setup + "\n\n";
    md += "Per-vertex error of the exit radiance (albedo cancels: irradiance pi sum_i S_i L_i against the reference E) "
          "over the lit vertices:\n\n" + table + "\n" + timing;
    if (Status s = writeText(mdPath, md); !s.isOk()) {
      std::fprintf(stderr, "prt-bench-local-error: %s\n", s.message().c_str());
      return 1;
    }
  }
  if (!jsonPath.empty()) {
    auto stats = [](const ErrorStats& s) {
      return "{\"mean\": " + num(s.mean) + ", \"median\": " + num(s.median) + ", \"p95\": " + num(s.p95) +
             ", \"max\": " + num(s.max) + ", \"rms_over_mean\": " + num(s.rmsOverMean) + ", \"bias\": " + num(s.meanSigned) + "}";
    };
    std::string j = "{\n  \"benchmark\": \"local-lighting-error\",\n  \"date\": \"" + utcNow() + "\",\n  \"cpu\": \"" + cpuModel() +
                    "\",\n  \"threads\": " + std::to_string(threads) + ",\n";
    j += "  \"scene\": {\"name\": \"default-room\", \"vertices\": " + std::to_string(vertexCount) + "},\n";
    j += "  \"sphere\": {\"center\": [" + num(sphere.center.x) + ", " + num(sphere.center.y) + ", " + num(sphere.center.z) +
         "], \"radius\": " + num(sphere.radius) + "},\n";
    j += "  \"emitter\": {\"axis\": [" + num(cap.axis.x) + ", " + num(cap.axis.y) + ", " + num(cap.axis.z) +
         "], \"half_angle_degrees\": 15, \"radiance\": " + num(cap.radiance) + "},\n";
    j += "  \"bake\": {\"order\": 5, \"samples\": 1024, \"pass\": \"shadowed\"},\n";
    j += "  \"reference\": {\"samples\": " + std::to_string(referenceSamples) + ", \"seconds\": " + num(referenceSeconds) + "},\n";
    j += "  \"lit_vertices\": " + std::to_string(lit.size()) + ",\n";
    j += "  \"relative_error\": {\n    \"local_order5\": " + stats(localErr) + ",\n    \"distant_order5\": " + stats(distantErr) +
         ",\n    \"local_order8\": " + stats(local8Err) + ",\n    \"reference_noise\": " + stats(noise) +
         ",\n    \"local_order5_vs_truncated_reference\": " + stats(formulation) +
         ",\n    \"truncated_reference_vs_reference\": " + stats(truncation) + "\n  },\n";
    j += "  \"bake_seconds\": {\"order5\": {\"distant\": " + num(distantSeconds) + ", \"local\": " + num(localSeconds) +
         ", \"ratio\": " + num(localSeconds / distantSeconds) + "}, \"order8\": {\"distant\": " + num(distant8Seconds) +
         ", \"local\": " + num(local8Seconds) + ", \"ratio\": " + num(local8Seconds / distant8Seconds) + "}}\n}\n";
    if (Status s = writeText(jsonPath, j); !s.isOk()) {
      std::fprintf(stderr, "prt-bench-local-error: %s\n", s.message().c_str());
      return 1;
    }
  }
  return 0;
}
