// prt-gpu-frames: frame times of the web client's renderer on a real GPU, without a browser.
//
// It runs the client's own C++ (ClientApp, GlRenderer, the same embedded shaders) on an
// off-screen OpenGL ES 3 context (egl_context.cpp) and times the settings the page's
// benchmarks time through window.prtApp (bench/web_glossy_bench.mjs, web_texel_bench.mjs):
// each sample is `--frames` frames back to back, each ended by a 1-pixel glReadPixels (the
// page's timeFrames), or `--frames` glossy passes ended by a read-back (timeGlossy);
// `--rounds` interleaved rounds, the best round kept. What differs from the page: no browser,
// no ANGLE translation, no compositor; the shaders and draw calls are the same.
//
// Usage: prt-gpu-frames ASSET [--width 1280] [--height 720] [--frames 10] [--rounds 5]
//                             [--mode interreflected|shadowed|unshadowed] [--order 5] [--tolerance 1e-4]
// Prints a JSON object on stdout (the table's rows, GL_RENDERER, GL_VERSION, and for a glossy
// asset the check of the GPU's per-vertex glossy radiance against the CPU reference); exit
// status 0, 1 on a runtime failure (no context, a bad asset, the check failing: then the
// timings are not printed), 2 on bad arguments. Diagnostics go to stderr.
#include <GLES3/gl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "client_app.h"

namespace {

using prt::web::ClientApp;
using prt::web::GlossyMix;
using prt::web::ShadingMode;

struct Options {
  std::string asset;
  int width = 1280, height = 720, frames = 10, rounds = 5, order = 5;
  double tolerance = 1e-4;  // --tolerance: the glossy check's largest error, as a fraction of the peak
  ShadingMode mode = ShadingMode::kInterreflected;
};

int usage(const std::string& why) {
  std::fprintf(stderr,
               "prt-gpu-frames: %s\n"
               "usage: prt-gpu-frames ASSET [--width W] [--height H] [--frames N] [--rounds R]\n"
               "                      [--mode interreflected|shadowed|unshadowed] [--order N] [--tolerance T]\n",
               why.c_str());
  return 2;
}

// Parses a whole decimal integer in [lo, hi]; nullopt otherwise.
std::optional<int> parseInt(const std::string& s, int lo, int hi) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const int v = std::stoi(s);
  if (v < lo || v > hi) return std::nullopt;
  return v;
}

// "" or why the arguments are wrong.
std::string parseArgs(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) != 0) {
      if (!o->asset.empty()) return "more than one ASSET ('" + o->asset + "' and '" + a + "')";
      o->asset = a;
      continue;
    }
    if (i + 1 >= argc) return a + " needs a value";
    const std::string v = argv[++i];
    struct IntFlag { const char* name; int* target; int lo, hi; };
    const IntFlag ints[] = {{"--width", &o->width, 1, 8192}, {"--height", &o->height, 1, 8192},
                            {"--frames", &o->frames, 1, 10000}, {"--rounds", &o->rounds, 1, 1000},
                            {"--order", &o->order, 1, 8}};
    bool known = false;
    for (const IntFlag& f : ints) {
      if (a != f.name) continue;
      const auto n = parseInt(v, f.lo, f.hi);
      if (!n) return a + " takes an integer in [" + std::to_string(f.lo) + ", " + std::to_string(f.hi) + "], not '" + v + "'";
      *f.target = *n;
      known = true;
    }
    if (a == "--tolerance") {
      char* end = nullptr;
      const double t = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(t > 0.0 && t < 1.0)) return "--tolerance takes a number in (0, 1), not '" + v + "'";
      o->tolerance = t;
      known = true;
    }
    if (a == "--mode") {
      if (v == "interreflected") o->mode = ShadingMode::kInterreflected;
      else if (v == "shadowed") o->mode = ShadingMode::kShadowed;
      else if (v == "unshadowed") o->mode = ShadingMode::kUnshadowed;
      else return "--mode takes interreflected, shadowed or unshadowed, not '" + v + "'";
      known = true;
    }
    if (!known) return "unknown option " + a;
  }
  if (o->asset.empty()) return "no ASSET given";
  return "";
}

// An order-8 RGB environment with every band lit (values of no physical meaning: the frame
// cost does not depend on them, only on the order, which the page's forest map fills too).
std::vector<float> syntheticEnvironment() {
  std::vector<float> flat;
  for (int l = 0; l < 8; ++l) {
    for (int m = -l; m <= l; ++m) {
      const float a = std::pow(0.6f, static_cast<float>(l)) * (m % 2 == 0 ? 1.0f : -0.5f);
      flat.insert(flat.end(), {a, 0.9f * a, 0.8f * a});
    }
  }
  return flat;
}

struct Setting {
  std::string name;
  ShadingMode mode;
  GlossyMix mix;
  prt::TransferDomain source = prt::TransferDomain::kVertex;
  bool relight = false;
  int glossyWork = -1;  // >= 0: time ClientApp::shadeGlossyVertices(work) instead of frames
};

// Mean milliseconds per frame (or glossy pass) of `n` back to back, as the page's test hook.
double timeSetting(ClientApp& app, const Options& o, const Setting& s, int n) {
  const auto t0 = std::chrono::steady_clock::now();
  if (s.glossyWork >= 0) {
    constexpr int kViewOnly = 3, kTransfer = 4;
    if (s.glossyWork == kViewOnly && !app.shadeGlossyVertices(kTransfer)) return std::nan("");
    for (int i = 0; i < n; ++i) {
      if (!app.shadeGlossyVertices(s.glossyWork)) return std::nan("");
    }
    app.finishGlossy(s.glossyWork);
  } else {
    unsigned char pixel[4];
    for (int i = 0; i < n; ++i) {
      if (s.relight) app.touchLighting();
      app.render(o.width, o.height);
      glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    }
  }
  const std::chrono::duration<double, std::milli> dt = std::chrono::steady_clock::now() - t0;
  return dt.count() / n;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += ' ';
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string glString(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "";
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const std::string e = parseArgs(argc, argv, &o); !e.empty()) return usage(e);

  std::ifstream in(o.asset, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "prt-gpu-frames: cannot open '%s'\n", o.asset.c_str());
    return 1;
  }
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  ClientApp app(prt::web::GlContextOptions{"", o.width, o.height});
  if (!app.error().empty()) {
    std::fprintf(stderr, "prt-gpu-frames: %s\n", app.error().c_str());
    return 1;
  }
  std::uint8_t* dst = app.reserveAsset(bytes.size());
  if (!dst) {
    std::fprintf(stderr, "prt-gpu-frames: out of memory for %zu asset bytes\n", bytes.size());
    return 1;
  }
  std::copy(bytes.begin(), bytes.end(), dst);
  if (const std::string e = app.loadAsset(); !e.empty()) {
    std::fprintf(stderr, "prt-gpu-frames: '%s': %s\n", o.asset.c_str(), e.c_str());
    return 1;
  }
  if (const std::string e = app.setEnvironment(syntheticEnvironment(), 8); !e.empty()) {
    std::fprintf(stderr, "prt-gpu-frames: %s\n", e.c_str());
    return 1;
  }
  app.setBackgroundMode(prt::web::BackgroundMode::kNone);  // as the page's benchmarks: background off
  if (!app.hasPass(o.mode)) {
    std::fprintf(stderr, "prt-gpu-frames: '%s' has no vertex pass of the chosen --mode\n", o.asset.c_str());
    return 1;
  }

  const ShadingMode m = o.mode;
  std::vector<Setting> settings = {
      {"lambert", ShadingMode::kLambert, GlossyMix::kDiffuse},
      {"diffuse PRT", m, GlossyMix::kDiffuse},
      {"diffuse PRT, lights moving", m, GlossyMix::kDiffuse, prt::TransferDomain::kVertex, true},
  };
  const bool glossy = app.hasGlossy(m);
  if (glossy) {
    settings.push_back({"diffuse + glossy, camera moving", m, GlossyMix::kBoth});
    settings.push_back({"diffuse + glossy, lights moving", m, GlossyMix::kBoth, prt::TransferDomain::kVertex, true});
    settings.push_back({"glossy: cluster table alone", m, GlossyMix::kBoth, prt::TransferDomain::kVertex, false, 1});
    settings.push_back({"glossy: table + fused step (lights moving)", m, GlossyMix::kBoth, prt::TransferDomain::kVertex, false, 2});
    settings.push_back({"glossy: table + transferred radiance + view step", m, GlossyMix::kBoth,
                        prt::TransferDomain::kVertex, false, 4});
    settings.push_back({"glossy: view step alone", m, GlossyMix::kBoth, prt::TransferDomain::kVertex, false, 3});
  }
  const bool texel = app.hasSource(prt::TransferDomain::kTexel);
  if (texel) {
    settings.push_back({"texel PRT", m, GlossyMix::kDiffuse, prt::TransferDomain::kTexel});
    settings.push_back({"texel PRT, lights moving", m, GlossyMix::kDiffuse, prt::TransferDomain::kTexel, true});
    if (app.hasTexelGlossy()) {
      settings.push_back({"texel PRT + TPFL glossy", m, GlossyMix::kBoth, prt::TransferDomain::kTexel});
      settings.push_back({"texel PRT + TPFL glossy, lights moving", m, GlossyMix::kBoth, prt::TransferDomain::kTexel, true});
    }
  }

  std::vector<double> best(settings.size(), std::numeric_limits<double>::infinity());
  for (int round = 0; round < o.rounds; ++round) {
    for (std::size_t i = 0; i < settings.size(); ++i) {
      const Setting& s = settings[i];
      app.setSource(s.source);
      app.setMode(s.mode);
      app.setDisplayOrder(o.order);
      if (prt::web::isPassKind(s.mode)) app.setGlossyMix(s.mode, s.mix);
      (void)timeSetting(app, o, s, 2);  // warm-up, as the page's benchmarks
      best[i] = std::min(best[i], timeSetting(app, o, s, o.frames));
    }
  }
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    std::fprintf(stderr, "prt-gpu-frames: GL error 0x%x after the runs\n", e);
    return 1;
  }

  // The timings are only worth reporting if the GPU computed the right thing: its per-vertex
  // glossy radiance against the CPU reference (prt::glossyExitRadiance on the expanded matrices).
  double checkError = 0.0, checkPeak = 0.0;
  if (glossy) {
    app.setSource(prt::TransferDomain::kVertex);
    app.setMode(m);
    app.setGlossyMix(m, GlossyMix::kBoth);
    app.orbit(0.3f, 0.1f);  // an eye of its own, off the timing runs' one
    // Both glossy steps: a frame whose lighting changed (the fused step), then one where only
    // the camera could have moved (the view step on the transferred radiance).
    for (const char* step : {"fused", "view"}) {
      if (std::string(step) == "fused") app.touchLighting();
      app.render(o.width, o.height);
      if (app.lastGlossyStep() != step) {
        std::fprintf(stderr, "prt-gpu-frames: the glossy check's frame took the '%s' step, not '%s'\n", app.lastGlossyStep().c_str(), step);
        return 1;
      }
      const std::vector<float> gpu = app.vertexGlossy(), ref = app.glossyReference(m);
      if (gpu.size() != ref.size() || ref.empty()) {
        std::fprintf(stderr, "prt-gpu-frames: no glossy radiance to check (%zu GPU values, %zu reference)\n", gpu.size(), ref.size());
        return 1;
      }
      for (std::size_t i = 0; i < ref.size(); ++i) {
        checkError = std::max(checkError, static_cast<double>(std::fabs(gpu[i] - ref[i])));
        checkPeak = std::max(checkPeak, static_cast<double>(std::fabs(ref[i])));
      }
    }
    if (!(checkError <= o.tolerance * checkPeak)) {
      std::fprintf(stderr, "prt-gpu-frames: the GPU's glossy radiance differs from the CPU reference by %g (peak %g, tolerance %g of it)\n",
                   checkError, checkPeak, o.tolerance);
      return 1;
    }
  }

  const auto diffuseRow = std::find_if(settings.begin(), settings.end(), [](const Setting& s) { return s.name == "diffuse PRT"; });
  const double diffuse = best[static_cast<std::size_t>(diffuseRow - settings.begin())];
  std::ostringstream json;
  json << "{\n  \"renderer\": " << jsonString(glString(GL_RENDERER)) << ",\n  \"version\": "
       << jsonString(glString(GL_VERSION)) << ",\n  \"asset\": " << jsonString(o.asset) << ",\n  \"vertices\": "
       << app.vertexCount() << ",\n  \"viewport\": \"" << o.width << "x" << o.height << "\",\n  \"order\": "
       << app.displayOrder() << ",\n";
  if (glossy) {
    const auto shape = app.glossyShape(m);
    json << "  \"glossy\": {\"bands\": " << app.glossyBands(m) << ", \"clusters\": " << shape[0]
         << ", \"vectors\": " << shape[1] << ", \"channels\": " << shape[2] << "},\n";
    json << "  \"glossy_check\": {\"steps\": [\"fused\", \"view\"], \"max_abs_error\": " << checkError << ", \"peak\": " << checkPeak
         << ", \"tolerance_of_peak\": " << o.tolerance << "},\n";
  }
  json << "  \"method\": " << jsonString(std::to_string(o.frames) +
                                         " frames (or glossy passes) back to back, each frame ended by a 1-pixel "
                                         "glReadPixels; " + std::to_string(o.rounds) + " interleaved rounds, best round")
       << ",\n  \"rows\": [\n";
  for (std::size_t i = 0; i < settings.size(); ++i) {
    json << "    {\"setting\": " << jsonString(settings[i].name) << ", \"ms\": " << best[i]
         << ", \"over_diffuse_prt\": " << best[i] / diffuse << "}" << (i + 1 < settings.size() ? ",\n" : "\n");
  }
  json << "  ]\n}\n";
  std::fputs(json.str().c_str(), stdout);
  return 0;
}
