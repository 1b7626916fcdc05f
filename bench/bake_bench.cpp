// prt-bench-bake: bakes a glTF scene the way the baker's benchmark asks (order 5, 1024
// samples, shadowed + 3 bounces, vertices in meshoptimizer order as prt-bake bakes them) and
// casts the same direct-pass rays as bare Embree queries in the same run, handed over four
// ways (single rays, a stream per receiver, packets of 8 and 16), as occlusion and as
// nearest-hit queries, so the direct pass is reported against Embree's own rates on this
// machine and the ways of tracing against one another. Prints tables; --json/--md write them.
#include <sys/resource.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "native/file_io.h"
#include "baker/scene/gltf_loader.h"
#include "baker/scene/mesh_order.h"
#include "baker/transfer/raw_rays.h"
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

double peakMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

Status writeText(const std::string& path, const std::string& text) {
  return writeFileAtomically(path, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenePath, jsonPath, mdPath, label = "scene";
  const char* usage = "usage: prt-bench-bake SCENE.glb [--label NAME] [--json PATH] [--md PATH]\n";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json" && i + 1 < argc) jsonPath = argv[++i];
    else if (a == "--md" && i + 1 < argc) mdPath = argv[++i];
    else if (a == "--label" && i + 1 < argc) label = argv[++i];
    else if (scenePath.empty() && a[0] != '-') scenePath = a;
    else {
      std::fputs(usage, stderr);
      return 2;
    }
  }
  if (scenePath.empty()) {
    std::fputs(usage, stderr);
    return 2;
  }
  bake::Scene scene;
  if (Status s = bake::loadGltf(scenePath, &scene); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-bake: %s\n", s.message().c_str());
    return 1;
  }
  bake::optimizeMeshOrder(&scene);  // as prt-bake bakes it: ray coherence depends on the order
  bake::BakeOptions o;
  o.order = 5;
  o.samples = 1024;
  o.maxBounces = 3;
  o.bounceThreshold = 0.0;

  // Raw Embree in two rounds, one before and one after the bake, each mode's better round
  // kept: the machine is shared, and interleaving spreads its noise over every mode alike.
  const bake::RawRays modes[] = {bake::RawRays::kSingle, bake::RawRays::kVertexStream, bake::RawRays::kPackets8,
                                 bake::RawRays::kPackets16};
  double raw[4][2] = {};  // [mode][occlusion, nearest hit] -> best rays/s
  auto rawRound = [&]() -> bool {
    for (int m = 0; m < 4; ++m) {
      for (int hit = 0; hit < 2; ++hit) {
        bake::PassStats p;
        if (Status s = bake::measureRawRays(scene, o, modes[m], hit != 0, &p); !s.isOk()) {
          std::fprintf(stderr, "prt-bench-bake: %s\n", s.message().c_str());
          return false;
        }
        raw[m][hit] = std::max(raw[m][hit], static_cast<double>(p.rays) / p.seconds);
      }
    }
    return true;
  };
  if (!rawRound()) return 1;
  const auto t0 = std::chrono::steady_clock::now();
  bake::BakeResult r;
  if (Status s = bake::bakeTransfer(scene, o, &r); !s.isOk()) {
    std::fprintf(stderr, "prt-bench-bake: %s\n", s.message().c_str());
    return 1;
  }
  const double bakeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!rawRound()) return 1;
  const double peak = peakMiB();

  const bake::PassStats& direct = r.passes[0];
  const double directRate = static_cast<double>(direct.rays) / direct.seconds;
  const double single = raw[0][0], singleHit = raw[0][1];

  std::ostringstream table;
  char line[240];
  table << "| rays handed to Embree as | occlusion, Mrays/s | nearest hit, Mrays/s | occlusion / single rays |\n"
        << "|---|---:|---:|---:|\n";
  for (int m = 0; m < 4; ++m) {
    std::snprintf(line, sizeof line, "| %s | %.2f | %.2f | %.2fx |\n", bake::rawRaysName(modes[m]), raw[m][0] * 1e-6,
                  raw[m][1] * 1e-6, raw[m][0] / single);
    table << line;
  }
  table << "\n| measure | value |\n|---|---:|\n";
  auto row = [&](const std::string& name, const char* fmt, double v) {
    std::snprintf(line, sizeof line, fmt, v);
    table << "| " << name << " | " << line << " |\n";
  };
  row("vertices", "%.0f", static_cast<double>(scene.positions.size()));
  row("triangles", "%.0f", static_cast<double>(scene.indices.size() / 3));
  row("direct pass (single rays, nearest hits + hit records + SH), s", "%.2f", direct.seconds);
  row("direct pass, Mrays/s", "%.2f", directRate * 1e-6);
  row("direct pass / raw single-ray occlusion", "%.2fx", directRate / single);
  row("direct pass / raw single-ray nearest hit", "%.2fx", directRate / singleHit);
  for (std::size_t i = 1; i < r.passes.size(); ++i) {
    char name[80];
    std::snprintf(name, sizeof name, "%s, s (%.0f%% of direct)", r.passes[i].name.c_str(),
                  100.0 * r.passes[i].seconds / direct.seconds);
    row(name, "%.2f", r.passes[i].seconds);
  }
  row("whole bake (in memory, no file), s", "%.2f", bakeSeconds);
  row("peak resident memory, MiB", "%.0f", peak);
  const std::string tableText = table.str();
  std::fputs(tableText.c_str(), stdout);

  utsname un{};
  uname(&un);
  const std::string machine = cpuModel() + ", " + std::to_string(std::thread::hardware_concurrency()) + " threads, " +
                              un.sysname + " " + un.release;
  if (!mdPath.empty()) {
    std::string md = "# Bake benchmark: " + label + "\n\nGenerated by `scripts/bench-bake.sh` (`prt-bench-bake`, bench/bake_bench.cpp).\n\n";
    md += "- Date: " + utcNow() + "\n- Machine: " + machine + "\n- Scene: " + scenePath + ", vertices in meshoptimizer order as prt-bake bakes them\n";
    md += "- Settings: order 5, 1024 samples (Hammersley), shadowed + exactly 3 bounces, all threads\n";
    md += "- Raw Embree (`measureRawRays`, baker/transfer/raw_rays.h): the direct pass's exact rays with no other work, "
          "timed while tracing only (packing packets included), each mode's better of two rounds, one before and one after the bake\n\n";
    md += tableText;
    if (Status s = writeText(mdPath, md); !s.isOk()) std::fprintf(stderr, "%s\n", s.message().c_str());
  }
  if (!jsonPath.empty()) {
    std::ostringstream j;
    j << "{\n  \"date\": \"" << utcNow() << "\",\n  \"machine\": \"" << machine << "\",\n  \"label\": \"" << label
      << "\",\n  \"vertices\": " << scene.positions.size() << ",\n  \"triangles\": " << scene.indices.size() / 3
      << ",\n  \"order\": 5,\n  \"samples\": 1024,\n  \"bounces\": " << r.bounces << ",\n  \"raw_rays_per_second\": {";
    const char* keys[] = {"single", "vertex_stream", "packets8", "packets16"};
    for (int m = 0; m < 4; ++m) {
      j << (m ? ", " : "") << "\"" << keys[m] << "\": {\"occlusion\": " << raw[m][0] << ", \"nearest_hit\": " << raw[m][1] << "}";
    }
    j << "},\n  \"direct_seconds\": " << direct.seconds << ",\n  \"direct_rays\": " << direct.rays
      << ",\n  \"direct_rays_per_second\": " << directRate << ",\n  \"direct_over_raw_single_occlusion\": " << directRate / single
      << ",\n  \"direct_over_raw_single_nearest_hit\": " << directRate / singleHit << ",\n  \"bounce_seconds\": [";
    for (std::size_t i = 1; i < r.passes.size(); ++i) j << (i > 1 ? ", " : "") << r.passes[i].seconds;
    j << "],\n  \"bake_seconds\": " << bakeSeconds << ",\n  \"peak_memory_mib\": " << peak << "\n}\n";
    if (Status s = writeText(jsonPath, j.str()); !s.isOk()) std::fprintf(stderr, "%s\n", s.message().c_str());
  }
  return 0;
}
