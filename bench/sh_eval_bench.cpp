// prt-bench-sh: timing of real-SH basis evaluation (shared/prt/sh_basis.h).
//
// For orders 3, 5 and 8 it measures nanoseconds per direction of
//   batched  evalShBasisBatchUnchecked over N = 4096 random unit directions (SoA x/y/z in,
//            coefficient-major out),
//   single   evalShBasisUnchecked called once per direction over the same directions,
//   naive    bench/naive_sh.h: acos/atan2, then per (l, m) the associated Legendre from scratch,
//            factorials and std::cos/std::sin (the "naive per-(l,m)" baseline),
// each as the best of R repetitions (default 15) of a loop of whole passes lasting ~20 ms.
// Single thread, std::chrono::steady_clock. Before timing, the library's results are checked
// against the naive evaluator (and batched against single); any disagreement aborts the run,
// so the speed comparison is between evaluators that compute the same thing.
//
// Usage: prt-bench-sh [--json PATH] [--md PATH] [--reps R] [--loop-ms MS]
// Prints a table to stdout; --json / --md also write it to files (atomically: temp + rename).
// Exit status: 0 after a run (whether or not the targets are met), 1 if verification fails,
// 2 on a usage or I/O error. It is a benchmark, not a test: MISS lines do not fail it.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "naive_sh.h"
#include "prt/sh_basis.h"
#include "prt/vec3.h"
#include "sh_bench_config.h"

namespace {

using prt::bench::naiveShEval;

constexpr std::size_t kDirections = 4096;
constexpr int kOrders[] = {3, 5, 8};
constexpr std::uint32_t kSeed = 20240607u;

// Targets: the SH library's acceptance numbers (ns per direction).
constexpr double kTargetOrder5Ns = 10.0;
constexpr double kTargetOrder8Ns = 30.0;
constexpr double kTargetSpeedup = 20.0;

// ---------------------------------------------------------------------------------------------
// Buffers: 64-byte aligned float arrays, so timings do not depend on where malloc put them.

struct FreeDeleter {
  void operator()(float* p) const { std::free(p); }
};

class FloatBuffer {
 public:
  explicit FloatBuffer(std::size_t n) : size_(n) {
    const std::size_t bytes = ((n * sizeof(float) + 63) / 64) * 64;
    data_.reset(static_cast<float*>(std::aligned_alloc(64, bytes == 0 ? 64 : bytes)));
    if (!data_) {
      std::fprintf(stderr, "prt-bench-sh: out of memory\n");
      std::exit(2);
    }
    std::fill(data_.get(), data_.get() + n, 0.0f);
  }
  float* data() { return data_.get(); }
  const float* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  float& operator[](std::size_t i) { return data_[i]; }
  float operator[](std::size_t i) const { return data_[i]; }

 private:
  std::size_t size_;
  std::unique_ptr<float[], FreeDeleter> data_;
};

struct Directions {
  FloatBuffer x{kDirections}, y{kDirections}, z{kDirections};
};

// Uniform on the sphere: z uniform in [-1, 1], phi uniform in [0, 2 pi). Fixed seed.
Directions makeDirections() {
  Directions d;
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> uz(-1.0, 1.0), uphi(0.0, 2.0 * prt::kPi);
  for (std::size_t k = 0; k < kDirections; ++k) {
    const double z = uz(rng), phi = uphi(rng);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    d.x[k] = static_cast<float>(r * std::cos(phi));
    d.y[k] = static_cast<float>(r * std::sin(phi));
    d.z[k] = static_cast<float>(z);
  }
  // A few directions that exercise the poles and the axes.
  const float special[][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  for (std::size_t k = 0; k < std::size(special); ++k) {
    d.x[k] = special[k][0];
    d.y[k] = special[k][1];
    d.z[k] = special[k][2];
  }
  return d;
}

// ---------------------------------------------------------------------------------------------
// Verification: the naive evaluator, the single-direction path and the batched path agree.

// |library - naive| <= kAbsTol + kRelTol |naive| (float recurrence against a double reference).
constexpr double kAbsTol = 1e-5;
constexpr double kRelTol = 1e-5;

bool verify(const Directions& d) {
  bool ok = true;
  for (int order = prt::kMinShOrder; order <= prt::kMaxShOrder; ++order) {
    const std::size_t nc = static_cast<std::size_t>(prt::shCoeffCount(order));
    FloatBuffer batched(nc * kDirections);
    prt::evalShBasisBatchUnchecked(order, kDirections, d.x.data(), d.y.data(), d.z.data(),
                                   batched.data());
    std::vector<float> single(nc), naive(nc);
    double worstNaive = 0.0, worstBatch = 0.0;
    std::size_t worstK = 0, worstI = 0;
    for (std::size_t k = 0; k < kDirections; ++k) {
      prt::evalShBasisUnchecked(order, prt::Vec3{d.x[k], d.y[k], d.z[k]}, single.data());
      naiveShEval(order, d.x[k], d.y[k], d.z[k], naive.data());
      for (std::size_t i = 0; i < nc; ++i) {
        const double ref = naive[i];
        const double excess = std::fabs(single[i] - ref) - (kAbsTol + kRelTol * std::fabs(ref));
        const double err = std::fabs(static_cast<double>(single[i]) - ref);
        if (err > worstNaive) {
          worstNaive = err;
          worstK = k;
          worstI = i;
        }
        if (excess > 0.0 || !std::isfinite(single[i])) {
          if (ok) {
            std::fprintf(stderr,
                         "prt-bench-sh: VERIFICATION FAILED: order %d, direction %zu "
                         "(%.7g, %.7g, %.7g), coefficient %zu: evalShBasisUnchecked = %.9g, "
                         "naive = %.9g\n",
                         order, k, static_cast<double>(d.x[k]), static_cast<double>(d.y[k]),
                         static_cast<double>(d.z[k]), i, static_cast<double>(single[i]), ref);
          }
          ok = false;
        }
        const double eb = std::fabs(static_cast<double>(batched[i * kDirections + k]) - single[i]);
        worstBatch = std::max(worstBatch, eb);
        if (!(eb <= kAbsTol + kRelTol * std::fabs(static_cast<double>(single[i])))) {
          if (ok) {
            std::fprintf(stderr,
                         "prt-bench-sh: VERIFICATION FAILED: order %d, direction %zu, coefficient "
                         "%zu: batched = %.9g, single = %.9g\n",
                         order, k, i, static_cast<double>(batched[i * kDirections + k]),
                         static_cast<double>(single[i]));
          }
          ok = false;
        }
      }
    }
    if (std::getenv("PRT_BENCH_VERBOSE") != nullptr) {
      std::printf("verify order %2d: max |single - naive| = %.3g (dir %zu, coeff %zu), "
                  "max |batched - single| = %.3g\n",
                  order, worstNaive, worstK, worstI, worstBatch);
    }
  }
  return ok;
}

// ---------------------------------------------------------------------------------------------
// Timing.

using Clock = std::chrono::steady_clock;

// Sum of everything the timed code wrote, printed at the end so no pass can be discarded.
double g_checksum = 0.0;

// `pass` evaluates all kDirections directions once and returns one of its outputs (a value
// the loop folds into a running sum, so each pass's result is used). Returns the best
// nanoseconds per direction over `reps` repetitions of a loop of whole passes lasting about
// loopSeconds.
template <class Pass>
double bestNsPerDirection(Pass&& pass, int reps, double loopSeconds) {
  double sink = 0.0;
  // Warm-up (caches, lazily built tables, page faults), then size the loop.
  sink += pass(0);
  auto t0 = Clock::now();
  sink += pass(1);
  double one = std::chrono::duration<double>(Clock::now() - t0).count();
  std::size_t iters = 1;
  while (one * static_cast<double>(iters) < loopSeconds * 0.25 && iters < (1u << 24)) {
    // Re-time with more passes when one pass is too short for the clock to resolve well.
    iters *= 2;
  }
  if (iters > 1) {
    t0 = Clock::now();
    for (std::size_t i = 0; i < iters; ++i) sink += pass(i);
    one = std::chrono::duration<double>(Clock::now() - t0).count() / static_cast<double>(iters);
  }
  iters = std::max<std::size_t>(1, static_cast<std::size_t>(loopSeconds / std::max(one, 1e-12)));

  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto start = Clock::now();
    for (std::size_t i = 0; i < iters; ++i) sink += pass(i);
    const double s = std::chrono::duration<double>(Clock::now() - start).count();
    best = std::min(best, s / static_cast<double>(iters * kDirections));
  }
  g_checksum += sink;
  return best * 1e9;
}

double sumOf(const FloatBuffer& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) s += b[i];
  return s;
}

struct Row {
  int order = 0;
  double batchedNs = 0, singleNs = 0, naiveNs = 0;
  double speedupBatched() const { return naiveNs / batchedNs; }
  double speedupSingle() const { return naiveNs / singleNs; }
};

Row measure(int order, const Directions& d, int reps, double loopSeconds) {
  const std::size_t nc = static_cast<std::size_t>(prt::shCoeffCount(order));
  const std::size_t total = nc * kDirections;
  const float* x = d.x.data();
  const float* y = d.y.data();
  const float* z = d.z.data();
  Row row;
  row.order = order;

  FloatBuffer batched(total);  // coefficient-major: [i * N + k]
  row.batchedNs = bestNsPerDirection(
      [&](std::size_t i) {
        prt::evalShBasisBatchUnchecked(order, kDirections, x, y, z, batched.data());
        return static_cast<double>(batched[i % total]);
      },
      reps, loopSeconds);
  g_checksum += sumOf(batched);

  FloatBuffer single(total);  // direction-major: [k * nc + i], the same bytes written
  row.singleNs = bestNsPerDirection(
      [&](std::size_t i) {
        float* out = single.data();
        for (std::size_t k = 0; k < kDirections; ++k) {
          prt::evalShBasisUnchecked(order, prt::Vec3{x[k], y[k], z[k]}, out + k * nc);
        }
        return static_cast<double>(single[i % total]);
      },
      reps, loopSeconds);
  g_checksum += sumOf(single);

  FloatBuffer naive(total);  // direction-major, as single
  row.naiveNs = bestNsPerDirection(
      [&](std::size_t i) {
        float* out = naive.data();
        for (std::size_t k = 0; k < kDirections; ++k) naiveShEval(order, x[k], y[k], z[k], out + k * nc);
        return static_cast<double>(naive[i % total]);
      },
      reps, loopSeconds);
  g_checksum += sumOf(naive);
  return row;
}

// ---------------------------------------------------------------------------------------------
// Environment and report.

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::string machineName() {
  std::string model = "unknown CPU";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) model = trim(line.substr(colon + 1));
      break;
    }
  }
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return model + ", " + std::to_string(n > 0 ? n : 1) + " logical CPUs";
}

std::string compilerName() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("gcc ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string buildFlags() {
  std::string isa;
#if defined(__AVX512F__)
  isa = "AVX-512";
#elif defined(__AVX2__)
  isa = "AVX2";
#elif defined(__AVX__)
  isa = "AVX";
#elif defined(__SSE2__)
  isa = "SSE2";
#elif defined(__aarch64__)
  isa = "NEON";
#else
  isa = "scalar";
#endif
  return trim(std::string(PRT_BENCH_CXX_FLAGS)) + " (" + PRT_BENCH_BUILD_TYPE + "; vector ISA " + isa + ")";
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char esc[8];
          std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned>(c));
          out += esc;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

struct Target {
  std::string name;
  double value = 0, limit = 0;
  bool lowerIsBetter = true;
  std::string unit;
  bool pass() const { return lowerIsBetter ? value <= limit : value >= limit; }
};

std::vector<Target> targets(const std::vector<Row>& rows) {
  std::vector<Target> t;
  for (const Row& r : rows) {
    if (r.order == 5) t.push_back({"order 5 batched", r.batchedNs, kTargetOrder5Ns, true, "ns/dir"});
    if (r.order == 8) t.push_back({"order 8 batched", r.batchedNs, kTargetOrder8Ns, true, "ns/dir"});
  }
  for (const Row& r : rows) {
    t.push_back({"order " + std::to_string(r.order) + " batched speedup over naive",
                 r.speedupBatched(), kTargetSpeedup, false, "x"});
  }
  return t;
}

std::string targetLine(const Target& t) {
  return t.name + ": " + fixed(t.value, t.unit == "x" ? 1 : 2) + " " + t.unit + " (target " +
         (t.lowerIsBetter ? "<= " : ">= ") + fixed(t.limit, 0) + " " + t.unit + ") " +
         (t.pass() ? "PASS" : "MISS");
}

struct Report {
  std::string date, machine, compiler, flags;
  int reps = 0;
  double loopMs = 0;
  std::vector<Row> rows;
};

std::string toJson(const Report& r) {
  std::ostringstream o;
  o << "{\n";
  o << "  \"date\": " << jsonString(r.date) << ",\n";
  o << "  \"machine\": " << jsonString(r.machine) << ",\n";
  o << "  \"compiler\": " << jsonString(r.compiler) << ",\n";
  o << "  \"flags\": " << jsonString(r.flags) << ",\n";
  o << "  \"directions\": " << kDirections << ",\n";
  o << "  \"repetitions\": " << r.reps << ",\n";
  o << "  \"loop_ms\": " << fixed(r.loopMs, 1) << ",\n";
  o << "  \"rows\": [\n";
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const Row& w = r.rows[i];
    o << "    {\"order\": " << w.order << ", \"batched_ns\": " << fixed(w.batchedNs, 3)
      << ", \"single_ns\": " << fixed(w.singleNs, 3) << ", \"naive_ns\": " << fixed(w.naiveNs, 3)
      << ", \"speedup_batched\": " << fixed(w.speedupBatched(), 2)
      << ", \"speedup_single\": " << fixed(w.speedupSingle(), 2) << "}"
      << (i + 1 < r.rows.size() ? "," : "") << "\n";
  }
  o << "  ],\n";
  o << "  \"targets\": [\n";
  const auto ts = targets(r.rows);
  for (std::size_t i = 0; i < ts.size(); ++i) {
    const Target& t = ts[i];
    o << "    {\"name\": " << jsonString(t.name) << ", \"value\": " << fixed(t.value, 3)
      << ", \"limit\": " << fixed(t.limit, 1) << ", \"unit\": " << jsonString(t.unit)
      << ", \"pass\": " << (t.pass() ? "true" : "false") << "}" << (i + 1 < ts.size() ? "," : "")
      << "\n";
  }
  o << "  ]\n";
  o << "}\n";
  return o.str();
}

std::string toMarkdown(const Report& r) {
  std::ostringstream o;
  o << "# SH basis evaluation benchmark\n\n";
  o << "Generated by `scripts/bench-sh.sh` (`prt-bench-sh`, bench/sh_eval_bench.cpp). "
       "Do not edit by hand.\n\n";
  o << "- Date: " << r.date << "\n";
  o << "- Machine: " << r.machine << "\n";
  o << "- Compiler: " << r.compiler << "\n";
  o << "- Flags: " << r.flags << "\n";
  o << "- Method: " << kDirections
    << " random unit directions (SoA x/y/z), single thread, std::chrono::steady_clock; each "
       "figure is the best of "
    << r.reps << " repetitions of a ~" << fixed(r.loopMs, 0)
    << " ms loop of whole passes. *batched* = `evalShBasisBatchUnchecked` (coefficient-major "
       "output), *single* = `evalShBasisUnchecked` once per direction, *naive* = "
       "bench/naive_sh.cpp (acos/atan2, then per (l, m) the associated Legendre recurrence from "
       "P_m^m, factorial normalisation and std::cos/std::sin, in double). All three were checked "
       "to agree (to 1e-5) before timing.\n\n";
  o << "| order | batched ns/dir | single ns/dir | naive ns/dir | naive/batched | naive/single |\n";
  o << "|------:|---------------:|--------------:|-------------:|--------------:|-------------:|\n";
  for (const Row& w : r.rows) {
    o << "| " << w.order << " | " << fixed(w.batchedNs, 2) << " | " << fixed(w.singleNs, 2) << " | "
      << fixed(w.naiveNs, 1) << " | " << fixed(w.speedupBatched(), 1) << "x | "
      << fixed(w.speedupSingle(), 1) << "x |\n";
  }
  o << "\nTargets:\n\n";
  for (const Target& t : targets(r.rows)) o << "- " << targetLine(t) << "\n";
  return o.str();
}

bool writeAtomically(const std::string& path, const std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  // "<path>.<pid>.tmp": matches the repository's *.tmp ignore rule if a crash leaves it behind.
  const std::string tmp = path + "." + std::to_string(static_cast<long>(getpid())) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::fprintf(stderr, "prt-bench-sh: cannot write %s\n", tmp.c_str());
      std::remove(tmp.c_str());
      return false;
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::fprintf(stderr, "prt-bench-sh: cannot rename %s to %s\n", tmp.c_str(), path.c_str());
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

void usage(std::FILE* f) {
  std::fprintf(f,
               "usage: prt-bench-sh [--json PATH] [--md PATH] [--reps R] [--loop-ms MS]\n"
               "  Times SH basis evaluation (batched, single, naive) at orders 3, 5, 8.\n"
               "  --json PATH  also write the results as JSON (atomically)\n"
               "  --md PATH    also write them as a Markdown report (atomically)\n"
               "  --reps R     repetitions per measurement, best is kept (default 15)\n"
               "  --loop-ms MS length of one repetition's loop (default 20)\n"
               "  PRT_BENCH_VERBOSE=1 prints the verification errors per order.\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string jsonPath, mdPath;
  int reps = 15;
  double loopMs = 20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "prt-bench-sh: %s needs a value\n", a.c_str());
        usage(stderr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--json") {
      jsonPath = value();
    } else if (a == "--md") {
      mdPath = value();
    } else if (a == "--reps") {
      reps = std::atoi(value().c_str());
    } else if (a == "--loop-ms") {
      loopMs = std::atof(value().c_str());
    } else if (a == "-h" || a == "--help") {
      usage(stdout);
      return 0;
    } else {
      std::fprintf(stderr, "prt-bench-sh: unknown argument '%s'\n", a.c_str());
      usage(stderr);
      return 2;
    }
  }
  if (reps < 1 || reps > 1000 || !(loopMs > 0.0) || loopMs > 10000.0) {
    std::fprintf(stderr, "prt-bench-sh: --reps must be in [1, 1000], --loop-ms in (0, 10000]\n");
    return 2;
  }

  const Directions dirs = makeDirections();
  if (!verify(dirs)) {
    std::fprintf(stderr,
                 "prt-bench-sh: the library and the naive reference disagree; refusing to "
                 "compare their speed.\n");
    return 1;
  }

  Report report;
  report.date = utcNow();
  report.machine = machineName();
  report.compiler = compilerName();
  report.flags = buildFlags();
  report.reps = reps;
  report.loopMs = loopMs;

  std::printf("SH basis evaluation, %zu directions, best of %d x ~%.0f ms, single thread\n",
              kDirections, reps, loopMs);
  std::printf("machine:  %s\ncompiler: %s\nflags:    %s\n\n", report.machine.c_str(),
              report.compiler.c_str(), report.flags.c_str());
  std::printf("%5s | %14s | %13s | %12s | %13s | %12s\n", "order", "batched ns/dir", "single ns/dir",
              "naive ns/dir", "naive/batched", "naive/single");
  std::printf("------+----------------+---------------+--------------+---------------+-------------\n");
  std::fflush(stdout);
  for (const int order : kOrders) {
    const Row row = measure(order, dirs, reps, loopMs * 1e-3);
    report.rows.push_back(row);
    std::printf("%5d | %14.2f | %13.2f | %12.1f | %12.1fx | %11.1fx\n", row.order, row.batchedNs,
                row.singleNs, row.naiveNs, row.speedupBatched(), row.speedupSingle());
    std::fflush(stdout);
  }
  std::printf("\n");
  for (const Target& t : targets(report.rows)) std::printf("%s\n", targetLine(t).c_str());
  std::printf("\nchecksum: %.6e\n", g_checksum);

  bool ok = true;
  if (!jsonPath.empty()) ok = writeAtomically(jsonPath, toJson(report)) && ok;
  if (!mdPath.empty()) ok = writeAtomically(mdPath, toMarkdown(report)) && ok;
  return ok ? 0 : 2;
}
