// prt-bench-matrix-codec: time and size of the matrix CPCA encoder on a synthetic glossy
// pass (docs/transfer-codec.md "Matrices", measured numbers). Not a test: it prints what it
// measures. Default: 100k vertices, order 5, RGB, full packing (D = 3 * 625 = 1875 values
// per vertex, 750 MB as float32), the matrices clustered low-rank plus noise:
//   x_v = P_{c(v)} + sum_{r < 8} a_vr B_{c(v) r} + 0.01 noise,  64 prototypes c.
// Usage: prt-bench-matrix-codec [vertices] [order] [setting ...]   (settings: cpca8@0.05, ...)
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "native/byte_compressors.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"

namespace {

struct Lcg {
  std::uint64_t s;
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  }
  float gauss() {
    const double u = 1.0 - next(), v = next();
    return static_cast<float>(std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v));
  }
};

// Peak resident set from /proc/self/status (VmHWM), in MiB; -1 when unavailable.
double peakRssMiB() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return -1.0;
  char line[256];
  double kib = -1.0;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::string(line).rfind("VmHWM:", 0) == 0) kib = std::atof(line + 6);
  }
  std::fclose(f);
  return kib / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t V = argc > 1 ? static_cast<std::size_t>(std::atol(argv[1])) : 100000;
  const int order = argc > 2 ? std::atoi(argv[2]) : 5;
  std::vector<std::string> settings;
  for (int i = 3; i < argc; ++i) settings.emplace_back(argv[i]);
  if (settings.empty()) settings = {"cpca8@0.05", "cpca16@0.02"};
  const int channels = 3;
  const prt::MatrixPacking packing = prt::MatrixPacking::kFull;
  const std::size_t D = static_cast<std::size_t>(channels) * prt::matrixEntryCount(order, packing);
  constexpr int kPrototypes = 64, kRank = 8;

  Lcg g{12345};
  std::vector<float> protos(kPrototypes * D), dirs(static_cast<std::size_t>(kPrototypes * kRank) * D);
  for (float& x : protos) x = g.gauss();
  for (float& x : dirs) x = g.gauss() * static_cast<float>(0.5 / std::sqrt(static_cast<double>(D)) * 8.0);
  std::vector<float> x(V * D);
  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t c = static_cast<std::size_t>(g.next() * kPrototypes);
    float a[kRank];
    for (float& w : a) w = g.gauss();
    float* row = &x[v * D];
    const float* p = &protos[c * D];
    for (std::size_t d = 0; d < D; ++d) row[d] = p[d] + 0.01f * g.gauss();
    for (int r = 0; r < kRank; ++r) {
      const float* b = &dirs[(c * kRank + static_cast<std::size_t>(r)) * D];
      for (std::size_t d = 0; d < D; ++d) row[d] += a[r] * b[d];
    }
  }
  const double inputMiB = static_cast<double>(x.size()) * 4.0 / (1024.0 * 1024.0);
  const double rssBefore = peakRssMiB();
  std::printf("matrix CPCA: %zu vertices, order %d, %d channels, %s packing, D = %zu, input %.1f MiB (peak RSS so far %.1f MiB)\n",
              V, order, channels, prt::matrixPackingName(packing), D, inputMiB, rssBefore);
  std::printf("| setting | clusters | N' | bytes/vertex | relative error | max abs error | zstd-19 bytes/vertex | encode s (wall) | encode s (CPU) | decode s | peak RSS MiB |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : settings) {
    prt::TransferCodecSettings s;
    if (!prt::parseTransferSetting(name, {}, &s).isOk()) {
      std::fprintf(stderr, "bad setting %s\n", name.c_str());
      return 2;
    }
    std::vector<std::uint8_t> blob;
    prt::TransferEncodeReport report;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();  // process CPU time: the machine may be shared
    const prt::Status st = prt::encodeTransferMatrix(x, order, packing, channels, s, &blob, &report);
    const std::clock_t c1 = std::clock();
    const auto t1 = std::chrono::steady_clock::now();
    if (!st.isOk()) {
      std::fprintf(stderr, "%s: %s\n", name.c_str(), st.toString().c_str());
      return 1;
    }
    std::vector<float> decoded(x.size());
    const auto t2 = std::chrono::steady_clock::now();
    const prt::Status ds = prt::decodeTransferMatrix(blob, order, decoded);
    const auto t3 = std::chrono::steady_clock::now();
    if (!ds.isOk()) {
      std::fprintf(stderr, "%s decode: %s\n", name.c_str(), ds.toString().c_str());
      return 1;
    }
    std::size_t zstdBytes = 0;
    if (!prt::zstdCompressedSize(blob, 19, &zstdBytes).isOk()) zstdBytes = 0;
    std::printf("| %s | %d | %d | %.1f | %.5f | %.4g | %.1f | %.1f | %.1f | %.2f | %.0f |\n", name.c_str(), report.clusters,
                report.vectorsPerBand.empty() ? 0 : report.vectorsPerBand[0], static_cast<double>(blob.size()) / static_cast<double>(V),
                report.relativeError, report.maxAbsError, static_cast<double>(zstdBytes) / static_cast<double>(V),
                std::chrono::duration<double>(t1 - t0).count(),
                static_cast<double>(c1 - c0) / CLOCKS_PER_SEC,
                std::chrono::duration<double>(t3 - t2).count(), peakRssMiB());
    std::fflush(stdout);
  }
  return 0;
}
