// prt-bench-glossy: times the baker's glossy passes (shadowed matrices in the direct pass,
// glossy bounces) on a glTF scene or a built-in one, and reports the shadowed matrix's
// rank-k update (ssyrk; sgemm for local lighting) in GFLOP/s against this machine's peak.
// Writes one JSON object to stdout; progress goes to stderr.
//
// Peak, two estimates (both reported):
//   measured: a single-threaded 1024^3 sgemm through the same OpenBLAS, in GFLOP/s per
//             core (the rate the kernel reaches on shapes it is built for);
//   nominal:  cpu MHz (from /proc/cpuinfo, the clock at the time of reading) x FLOPs per
//             cycle per core from the flags: avx512f 64 (2 FMA ports x 16 lanes x 2),
//             avx2+fma 32, else 8 (SSE: 4 lanes x (mul + add)).
// The rank-k rate is flops / thread-seconds (per core), compared with both per-core peaks.
#include <cblas.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "baker/scene/default_scene.h"
#include "baker/scene/gltf_loader.h"
#include "baker/transfer/transfer_bake.h"

extern "C" void openblas_set_num_threads(int num_threads);

using namespace prt;

namespace {

struct CpuInfo {
  std::string model = "unknown";
  double mhz = 0.0;
  int flopsPerCycle = 8;
  std::string simd = "sse";
};

CpuInfo readCpuInfo() {
  CpuInfo c;
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  bool haveFlags = false;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string value = line.substr(colon + 1 + (colon + 1 < line.size() ? 1 : 0));
    if (line.rfind("model name", 0) == 0 && c.model == "unknown") c.model = value;
    if (line.rfind("cpu MHz", 0) == 0 && c.mhz == 0.0) c.mhz = std::atof(value.c_str());
    if (line.rfind("flags", 0) == 0 && !haveFlags) {
      haveFlags = true;
      const std::string f = " " + value + " ";
      if (f.find(" avx512f ") != std::string::npos) {
        c.flopsPerCycle = 64;
        c.simd = "avx512f";
      } else if (f.find(" avx2 ") != std::string::npos && f.find(" fma ") != std::string::npos) {
        c.flopsPerCycle = 32;
        c.simd = "avx2+fma";
      }
    }
  }
  return c;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Single-threaded sgemm rate, GFLOP/s (best of 3).
double measuredSgemmPeak() {
  const int n = 1024;
  std::vector<float> a(static_cast<std::size_t>(n) * n, 0.5f), b(a.size(), 0.25f), c(a.size(), 0.0f);
  double best = 0.0;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasNoTrans, n, n, n, 1.0f, a.data(), n, b.data(), n, 0.0f, c.data(), n);
    best = std::max(best, 2.0 * n * n * n / seconds(t0) * 1e-9);
  }
  return best;
}

double peakMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

std::string jsonString(const std::string& s) {
  std::string o = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') o += '\\';
    if (static_cast<unsigned char>(ch) < 0x20) continue;
    o += ch;
  }
  return o + "\"";
}

int usage() {
  std::fprintf(stderr,
               "usage: prt-bench-glossy [SCENE.glb|--default] [--order N] [--samples N] [--bounces N]\n"
               "                        [--threads N] [--local] [--f0 F] [--exponent S]\n"
               "  scenes without glossy materials get f0 = F (0.5) and exponent S (32) on every vertex\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenePath;
  bool useDefault = false, local = false;
  bake::BakeOptions o;
  o.order = 5;
  o.samples = 1024;
  o.glossy = true;
  o.glossyBounces = 1;
  o.maxBounces = 1;
  float f0 = 0.5f, exponent = 32.0f;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (a == "--default")
      useDefault = true;
    else if (a == "--local")
      local = true;
    else if (a == "--order" && (v = next()))
      o.order = std::atoi(v);
    else if (a == "--samples" && (v = next()))
      o.samples = static_cast<std::size_t>(std::atoll(v));
    else if (a == "--bounces" && (v = next()))
      o.glossyBounces = o.maxBounces = std::atoi(v);
    else if (a == "--threads" && (v = next()))
      o.threads = static_cast<unsigned>(std::atoi(v));
    else if (a == "--f0" && (v = next()))
      f0 = static_cast<float>(std::atof(v));
    else if (a == "--exponent" && (v = next()))
      exponent = static_cast<float>(std::atof(v));
    else if (!a.empty() && a[0] != '-' && scenePath.empty())
      scenePath = a;
    else
      return usage();
  }
  if (scenePath.empty() && !useDefault) return usage();
  bake::Scene scene;
  if (useDefault) {
    scene = bake::makeDefaultScene();
  } else if (Status s = bake::loadGltf(scenePath, &scene); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-glossy: %s\n", s.message().c_str());
    return 1;
  }
  const bool assigned = scene.specular.empty();
  if (assigned) scene.specular.assign(scene.positions.size(), SpecularMaterial{{f0, f0, f0}, exponent});
  if (local) {
    o.lighting.model = LightingModel::kLocalSphere;
    // The default sphere: bounding-box centre, half the diagonal.
    Vec3 lo = scene.positions.empty() ? Vec3{} : scene.positions[0], hi = lo;
    for (const Vec3& p : scene.positions) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    o.lighting.center = (lo + hi) * 0.5f;
    o.lighting.radius = std::max(1e-3f, 0.5f * length(hi - lo));
  }
  const unsigned threads = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  o.progress = [](const bake::BakeProgress& p) {
    if (p.done == p.total) std::fprintf(stderr, "  %s: %zu vertices\n", p.pass, p.total);
  };

  const CpuInfo cpu = readCpuInfo();
  openblas_set_num_threads(1);
  const double sgemmPeak = measuredSgemmPeak();
  const double nominalPeak = cpu.mhz * 1e-3 * cpu.flopsPerCycle;

  bake::BakeResult r;
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = bake::bakeTransfer(scene, o, &r); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-glossy: %s\n", s.message().c_str());
    return 1;
  }
  const double total = seconds(t0);
  const double rate =
      r.glossyRankUpdate.threadSeconds > 0 ? r.glossyRankUpdate.flops / r.glossyRankUpdate.threadSeconds * 1e-9 : 0.0;

  std::ostringstream j;
  j.precision(6);
  j << "{\n  \"scene\": " << jsonString(useDefault ? "built-in default" : scenePath) << ",\n";
  j << "  \"vertices\": " << scene.positions.size() << ",\n  \"triangles\": " << scene.indices.size() / 3 << ",\n";
  j << "  \"materials\": "
    << jsonString(assigned ? "assigned by the benchmark (f0 " + std::to_string(f0) + ", exponent " +
                                 std::to_string(exponent) + ")"
                           : "from the scene")
    << ",\n";
  j << "  \"order\": " << o.order << ",\n  \"samples\": " << o.samples
    << ",\n  \"lighting\": " << jsonString(lightingModelName(o.lighting.model)) << ",\n  \"threads\": " << threads
    << ",\n";
  j << "  \"glossy_bounces\": " << r.glossyBounces << ",\n  \"diffuse_bounces\": " << r.bounces << ",\n";
  j << "  \"bake_seconds\": " << total << ",\n  \"peak_rss_mib\": " << peakMiB() << ",\n  \"passes\": [";
  for (std::size_t i = 0; i < r.passes.size(); ++i) {
    j << (i ? ", " : "") << "{\"name\": " << jsonString(r.passes[i].name) << ", \"seconds\": " << r.passes[i].seconds
      << ", \"rays\": " << r.passes[i].rays << "}";
  }
  j << "],\n  \"rank_update\": {\"kernel\": " << jsonString(local ? "sgemm" : "ssyrk")
    << ", \"gflop\": " << r.glossyRankUpdate.flops * 1e-9
    << ", \"thread_seconds\": " << r.glossyRankUpdate.threadSeconds << ", \"gflops_per_core\": " << rate
    << ", \"fraction_of_measured_peak\": " << (sgemmPeak > 0 ? rate / sgemmPeak : 0.0)
    << ", \"fraction_of_nominal_peak\": " << (nominalPeak > 0 ? rate / nominalPeak : 0.0) << "},\n";
  j << "  \"peak\": {\"cpu\": " << jsonString(cpu.model) << ", \"simd\": " << jsonString(cpu.simd)
    << ", \"cpu_mhz\": " << cpu.mhz << ", \"flops_per_cycle\": " << cpu.flopsPerCycle
    << ", \"nominal_gflops_per_core\": " << nominalPeak << ", \"measured_sgemm_1024_gflops_per_core\": " << sgemmPeak
    << ", \"hardware_threads\": " << std::thread::hardware_concurrency() << "}\n}\n";
  std::fputs(j.str().c_str(), stdout);
  return 0;
}
