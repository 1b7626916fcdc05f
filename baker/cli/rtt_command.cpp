#include "baker/cli/rtt_command.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "baker/cli/report_failure.h"
#include "baker/rtt/rtt_bake.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "native/file_io.h"
#include "native/image_io.h"
#include "native/json_text.h"

namespace prt {
namespace {

constexpr FlagSpec kRttFlags[] = {
    {"--patch", true},       {"--height", true},     {"--height-scale", true},  {"--albedo-map", true},
    {"--albedo", true},      {"--size", true},       {"--order", true},         {"--spatial", true},
    {"--views", true},       {"--supersample", true}, {"--light-polar", true},  {"--light-azimuth", true},
    {"--bounces", true},     {"--threads", true},    {"-o", true},              {"--quiet", false},
    {"--json", false},
};

struct RttOptions {
  std::string patch, height, albedoMap, output;
  float heightScale = 0.1f, albedo = 0.8f;
  int size = 128;
  bool quiet = false, json = false;
  bake::RttSettings settings;
};

Status parseRttOptions(std::span<const std::string> args, RttOptions* o) {
  ParsedArgs p;
  if (Status s = parseArgs(args, kRttFlags, &p); !s.isOk()) return s;
  if (!p.positionals.empty()) return usageError("unexpected argument '" + p.positionals[0] + "' (give the patch by --patch or --height)");
  const std::string* patch = p.value("--patch");
  const std::string* height = p.value("--height");
  if (!patch == !height) return usageError("give exactly one of --patch NAME (" + std::string(bake::kProceduralPatchNames) + ") and --height FILE");
  if (patch) o->patch = *patch;
  if (height) o->height = *height;
  if (const std::string* a = p.value("--albedo-map")) {
    if (!height) return usageError("--albedo-map goes with --height");
    o->albedoMap = *a;
  }
  if (p.has("--height-scale") && !height) return usageError("--height-scale goes with --height");
  if (p.has("--size") && !patch) return usageError("--size goes with --patch (an image has its own size)");
  const std::string* output = p.value("-o");
  if (!output) return usageError("missing -o OUT.rtt");
  o->output = *output;
  struct IntFlag {
    const char* name;
    int min, max;
    int* value;
  };
  const IntFlag ints[] = {{"--size", 8, 2048, &o->size},
                          {"--order", 1, kMaxRttOrder, &o->settings.order},
                          {"--spatial", 1, kMaxRttSpatial, &o->settings.spatial},
                          {"--views", 1, kMaxRttViews, &o->settings.views},
                          {"--supersample", 1, 16, &o->settings.supersample},
                          {"--light-polar", 1, 256, &o->settings.lightPolar},
                          {"--light-azimuth", 1, 512, &o->settings.lightAzimuth},
                          {"--bounces", 0, 16, &o->settings.bounces}};
  for (const IntFlag& f : ints) {
    if (const std::string* v = p.value(f.name)) {
      if (Status s = parseIntArg(f.name, *v, f.min, f.max, f.value); !s.isOk()) return s;
    }
  }
  // The paper's diffuse special case samples space more finely (128^2) than the view-dependent one (64^2).
  if (!p.has("--spatial") && o->settings.views == 1) o->settings.spatial = 128;
  int threads = 0;
  if (const std::string* v = p.value("--threads")) {
    if (Status s = parseIntArg("--threads", *v, 0, 1024, &threads); !s.isOk()) return s;
  }
  o->settings.threads = static_cast<unsigned>(threads);
  if (const std::string* v = p.value("--height-scale")) {
    if (Status s = parseFloatArg("--height-scale", *v, -100.0f, 100.0f, &o->heightScale); !s.isOk()) return s;
  }
  if (const std::string* v = p.value("--albedo")) {
    if (Status s = parseFloatArg("--albedo", *v, 0.0f, 1.0f, &o->albedo); !s.isOk()) return s;
  }
  o->quiet = p.has("--quiet");
  o->json = p.has("--json");
  return Status::ok();
}

Status loadPatch(const RttOptions& o, bake::HeightPatch* patch) {
  if (!o.patch.empty()) return bake::makeProceduralPatch(o.patch, o.size, o.albedo, patch);
  RgbImage height, albedo;
  if (Status s = loadImage(o.height, &height); !s.isOk()) return s;
  if (!o.albedoMap.empty()) {
    if (Status s = loadImage(o.albedoMap, &albedo); !s.isOk()) return s;
  }
  if (Status s = bake::makeImagePatch(height, o.heightScale, o.albedoMap.empty() ? nullptr : &albedo, o.albedo, patch); !s.isOk()) {
    return Status::error(s.code(), "'" + o.height + "': " + s.message());
  }
  return Status::ok();
}

}  // namespace

const char* rttHelpText() {
  return "Usage: prt-bake rtt --patch NAME -o OUT.rtt [options]\n"
         "       prt-bake rtt --height HEIGHT.png [--albedo-map ALBEDO.png] -o OUT.rtt [options]\n"
         "\n"
         "Bakes a radiance transfer texture (Sloan et al. 2003, bi-scale radiance transfer):\n"
         "a meso-scale patch's exit radiance per SH lighting coefficient, per position and\n"
         "view direction, with the patch's self-shadowing and interreflection (docs/bi-scale.md).\n"
         "\n"
         "Patch:\n"
         "  --patch NAME         built in: flat, weave, holes, stucco\n"
         "  --size N             its grid points a side, 8 to 2048 (default 128)\n"
         "  --height FILE        a square height map (EXR, HDR, PNG, JPEG; red channel), periodic\n"
         "  --height-scale S     height of map value 1, in patch widths (default 0.1)\n"
         "  --albedo-map FILE    linear RGB albedo in [0, 1], the height map's size: an RGB RTT\n"
         "  --albedo A           grey albedo otherwise, 0 to 1 (default 0.8)\n"
         "\n"
         "Sampling (defaults: the paper's):\n"
         "  --order N            SH bands, 1 to 8 (default 5)\n"
         "  --spatial N          N x N spatial samples, 1 to 1024 (default 64; 128 with --views 1)\n"
         "  --views N            N x N view directions, 1 to 32 (default 8); 1: view-independent\n"
         "  --supersample N      N x N view rays a spatial sample, 1 to 16 (default 2)\n"
         "  --light-polar N      light directions: Gauss-Legendre nodes in cos(theta), 1 to 256 (default 8)\n"
         "  --light-azimuth N    times uniform azimuths, 1 to 512 (default 16)\n"
         "  --bounces N          meso-scale interreflection bounces, 0 to 16 (default 1)\n"
         "  --threads N          worker threads, 0 = all (default 0)\n"
         "\n"
         "Output:\n"
         "  -o OUT.rtt           the RTT file (written atomically; format in docs/bi-scale.md)\n"
         "  --quiet              no progress on stderr\n"
         "  --json               print a JSON summary instead of a line\n"
         "  -h, --help           show this help\n"
         "\n"
         "Exit status: 0 success, 1 bad input (unreadable or invalid image), 2 bad command\n"
         "line, 3 a file missing or unwritable, 4 invalid content, 6 out of memory or disk.\n";
}

int runRttCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(rttHelpText(), out);
    return kExitOk;
  }
  RttOptions o;
  if (Status s = parseRttOptions(args, &o); !s.isOk()) return reportFailure(err, "rtt", s);
  std::vector<std::string> inputs;
  if (!o.height.empty()) inputs.push_back(o.height);
  if (!o.albedoMap.empty()) inputs.push_back(o.albedoMap);
  if (Status s = checkOutputPath(o.output, inputs); !s.isOk()) return reportFailure(err, "rtt", s);
  bake::HeightPatch patch;
  if (Status s = loadPatch(o, &patch); !s.isOk()) return reportFailure(err, "rtt", s);

  const auto start = std::chrono::steady_clock::now();
  std::mutex printing;
  std::string stage;
  const bake::RttProgress progress = [&](const char* name, std::size_t, std::size_t) {
    if (o.quiet) return;
    std::lock_guard<std::mutex> lock(printing);
    if (stage == name) return;
    stage = name;
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(err, "prt-bake: rtt: %s (%.1f s)\n", name, t);
  };
  Rtt rtt;
  if (Status s = bake::bakeRtt(patch, o.settings, progress, &rtt); !s.isOk()) return reportFailure(err, "rtt", s);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::uint8_t> bytes;
  if (Status s = encodeRtt(rtt, &bytes); !s.isOk()) return reportFailure(err, "rtt", s);
  if (Status s = writeFileAtomically(o.output, bytes, inputs); !s.isOk()) return reportFailure(err, "rtt", s);
  const std::string source = o.patch.empty() ? o.height : o.patch;
  if (o.json) {
    std::fprintf(out,
                 "{\"output\": %s, \"patch\": %s, \"order\": %d, \"channels\": %d, \"spatial\": %d, \"views\": %d, "
                 "\"light_directions\": %d, \"bounces\": %d, \"bytes\": %zu, \"seconds\": %.3f}\n",
                 jsonString(o.output).c_str(), jsonString(source).c_str(), rtt.order, rtt.channels, rtt.spatial, rtt.views,
                 o.settings.lightPolar * o.settings.lightAzimuth, o.settings.bounces, bytes.size(), seconds);
  } else {
    std::fprintf(out, "%s: RTT of %s, %dx%d positions x %dx%d views, order %d, %d channel(s), %zu bytes, %.1f s\n", o.output.c_str(),
                 source.c_str(), rtt.spatial, rtt.spatial, rtt.views, rtt.views, rtt.order, rtt.channels, bytes.size(), seconds);
  }
  return kExitOk;
}

bool looksLikeRtt(std::span<const std::uint8_t> bytes) {
  static constexpr char kMagic[] = "PRTRTT1\n";
  return bytes.size() >= 8 && std::memcmp(bytes.data(), kMagic, 8) == 0;
}

int infoRtt(const std::string& path, std::span<const std::uint8_t> bytes, bool json, std::FILE* out, std::FILE* err) {
  Rtt rtt;
  if (Status s = decodeRtt(bytes, &rtt); !s.isOk()) return reportFailure(err, "info", Status::error(s.code(), "'" + path + "': " + s.message()));
  float lo = 0.0f, hi = 0.0f;
  if (!rtt.coeffs.empty()) {
    const auto [a, b] = std::minmax_element(rtt.coeffs.begin(), rtt.coeffs.end());
    lo = *a;
    hi = *b;
  }
  if (json) {
    std::fprintf(out,
                 "{\n  \"file\": %s,\n  \"kind\": \"rtt\",\n  \"bytes\": %zu,\n  \"order\": %d,\n  \"channels\": %d,\n"
                 "  \"spatial\": %d,\n  \"views\": %d,\n  \"view_dependent\": %s,\n  \"min\": %s,\n  \"max\": %s\n}\n",
                 jsonString(path).c_str(), bytes.size(), rtt.order, rtt.channels, rtt.spatial, rtt.views, rtt.views > 1 ? "true" : "false",
                 jsonNumber(lo).c_str(), jsonNumber(hi).c_str());
  } else {
    std::fprintf(out,
                 "%s: radiance transfer texture (docs/bi-scale.md), %zu bytes, checksum ok\n"
                 "  order %d (%d coefficients), %d channel(s)\n  %dx%d positions x %dx%d views%s\n  coefficients %g .. %g\n",
                 path.c_str(), bytes.size(), rtt.order, rtt.order * rtt.order, rtt.channels, rtt.spatial, rtt.spatial, rtt.views, rtt.views,
                 rtt.views > 1 ? "" : " (view-independent)", static_cast<double>(lo), static_cast<double>(hi));
  }
  return kExitOk;
}

}  // namespace prt
