#include "baker/cli/bake_command.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "native/cli_args.h"
#include "baker/scene/default_scene.h"
#include "native/file_io.h"
#include "baker/scene/gltf_loader.h"
#include "native/json_text.h"
#include "baker/transfer/local_sphere.h"
#include "baker/cli/progress_bar.h"
#include "prt/asset.h"
#include "prt/sh_basis.h"
#include "baker/scene/mesh_order.h"
#include "prt/transfer_codec.h"
#include "baker/transfer/transfer_bake.h"

namespace prt {
namespace {

constexpr FlagSpec kBakeFlags[] = {
    {"--default", false}, {"-o", true},        {"--output", true},  {"--order", true},
    {"--samples", true},  {"--bounces", true}, {"--bounce-threshold", true}, {"--sampling", true},
    {"--seed", true},     {"--threads", true}, {"--passes", true},  {"--quiet", false},
    {"--json", false},    {"--lighting", true}, {"--light-center", true}, {"--light-radius", true},
    {"--name", true},     {"--compress", true},
};

constexpr const char* kHelp =
    "Usage: prt-bake SCENE.gltf|SCENE.glb -o ASSET [options]\n"
    "       prt-bake --default -o ASSET [options]\n"
    "\n"
    "Bakes diffuse PRT transfer (SH, per vertex) with Embree and writes a .prt asset\n"
    "(docs/asset-format.md). --default bakes the built-in room scene.\n"
    "\n"
    "Options:\n"
    "  -o, --output ASSET        where to write the asset (atomically: temp file + rename)\n"
    "  --order N                 SH bands, 2..8 (default 5: 25 coefficients)\n"
    "  --samples N               sample directions over the sphere, 16..1048576 (default 1024)\n"
    "  --sampling NAME           hammersley (default) or stratified (needs a square N)\n"
    "  --seed S                  rotates/jitters the sample set (default 1); same seed, same bytes\n"
    "  --bounces N               exactly N interreflection bounces (0..64); default: until a\n"
    "                            bounce adds less than --bounce-threshold of the direct energy, at most 8\n"
    "  --bounce-threshold X      relative energy threshold for stopping (default 0.001)\n"
    "  --passes LIST             comma-separated subset of unshadowed,shadowed,interreflected\n"
    "                            (default: all three)\n"
    "  --threads N               worker threads (default: all cores); results do not depend on it\n"
    "  --lighting MODEL          what the transfer is lit by (docs/spatially-varying.md):\n"
    "                              distant      lighting at infinity, one direction set (default)\n"
    "                              local        radiance on a sphere around the scene, emitted\n"
    "                                           inward (spatially varying; area form)\n"
    "                              local-paper  the same sphere, Fujita & Kanai 2004's weighting\n"
    "  --light-center X,Y,Z      centre of the lighting sphere, where the client renders its\n"
    "                            light cube map (local only; default: the scene's bounds centre)\n"
    "  --light-radius R          its radius, > 0 (local only; default: half the bounds diagonal,\n"
    "                            so every vertex is inside)\n"
    "  --name NAME               the asset's name in catalogues (default: the scene's)\n"
    "  --compress SETTING        store the transfer with the transfer codec (docs/transfer-codec.md):\n"
    "                            f16, q16, q8, cpca8 or cpca16, CPCA with an optional target\n"
    "                            relative error, e.g. cpca8@0.02 (default: float32, uncompressed)\n"
    "  --quiet                   no progress output\n"
    "  --json                    print bake statistics as JSON on stdout\n";

struct BakeCli {
  std::string scene;  // empty with --default
  std::string output;
  std::optional<std::string> name;
  std::optional<TransferCodecSettings> compress;
  bake::BakeOptions options;
  // Local lighting's centre and radius when given; the scene's bounds supply the others.
  std::optional<Vec3> lightCenter;
  std::optional<float> lightRadius;
  bool storeUnshadowed = true, storeShadowed = true, storeInterreflected = true;
  bool quiet = false, json = false;
};

Status usage(std::string m) { return Status::error(StatusCode::kInvalidArgument, std::move(m)); }

// "X,Y,Z": exactly three finite numbers.
Status parseTriple(std::string_view flag, const std::string& text, Vec3* out) {
  float v[3] = {};
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos)) {
      return usage(std::string(flag) + " expects X,Y,Z (three numbers separated by commas), got '" + text + "'");
    }
    const std::string part = text.substr(start, i < 2 ? comma - start : std::string::npos);
    const float big = std::numeric_limits<float>::max();
    if (Status s = parseFloatArg(flag, part, -big, big, &v[i]); !s.isOk()) {
      return usage(std::string(flag) + " expects X,Y,Z of finite numbers; component " + std::to_string(i + 1) + " '" + part +
                   "' is not one");
    }
    start = comma + 1;
  }
  *out = {v[0], v[1], v[2]};
  return Status::ok();
}

Status parseLightingArgs(const ParsedArgs& p, BakeCli* c) {
  LightingModel model = LightingModel::kDistant;
  if (const std::string* s = p.value("--lighting")) {
    if (*s == "distant") model = LightingModel::kDistant;
    else if (*s == "local") model = LightingModel::kLocalSphere;
    else if (*s == "local-paper") model = LightingModel::kLocalSpherePaper;
    else return usage("unknown --lighting '" + *s + "' (expected distant, local or local-paper)");
  }
  c->options.lighting.model = model;
  const bool local = isLocalLighting(model);
  for (const char* flag : {"--light-center", "--light-radius"}) {
    if (p.has(flag) && !local) return usage(std::string(flag) + " needs --lighting local or local-paper");
  }
  if (const std::string* s = p.value("--light-center")) {
    Vec3 centre;
    if (Status st = parseTriple("--light-center", *s, &centre); !st.isOk()) return st;
    c->lightCenter = centre;
  }
  if (const std::string* s = p.value("--light-radius")) {
    const float big = std::numeric_limits<float>::max();
    float r = 0.0f;
    if (!parseFloatArg("--light-radius", *s, -big, big, &r).isOk() || !(r > 0.0f)) {
      return usage("--light-radius expects a finite number > 0, got '" + *s + "'");
    }
    c->lightRadius = r;
  }
  return Status::ok();
}

// Local lighting's defaults from the scene (defaultLightingSphere) where not given.
void completeLighting(const bake::Scene& scene, BakeCli* c) {
  LightingInfo& l = c->options.lighting;
  if (!isLocalLighting(l.model)) return;
  const LightingInfo fallback = bake::defaultLightingSphere(scene, l.model);
  l.center = c->lightCenter.value_or(fallback.center);
  l.radius = c->lightRadius.value_or(fallback.radius);
}

std::string describeLighting(const LightingInfo& l) {
  if (!isLocalLighting(l.model)) return lightingModelName(l.model);
  char text[200];
  std::snprintf(text, sizeof text, "%s, centre (%.6g, %.6g, %.6g), radius %.6g", lightingModelName(l.model),
                static_cast<double>(l.center.x), static_cast<double>(l.center.y), static_cast<double>(l.center.z),
                static_cast<double>(l.radius));
  return text;
}

Status parseBakeArgs(std::span<const std::string> args, BakeCli* c) {
  ParsedArgs p;
  if (Status s = parseArgs(args, kBakeFlags, &p); !s.isOk()) return s;
  if (p.has("--default")) {
    if (!p.positionals.empty()) return usage("give either SCENE or --default, not both");
  } else if (p.positionals.size() != 1) {
    return p.positionals.empty() ? usage("missing SCENE (a .gltf or .glb file) or --default")
                                 : usage("expected one SCENE, got " + std::to_string(p.positionals.size()));
  } else {
    c->scene = p.positionals[0];
  }
  const std::string* o1 = p.value("-o");
  const std::string* o2 = p.value("--output");
  if (o1 && o2) return usage("give -o or --output, not both");
  if (!o1 && !o2) return usage("missing -o ASSET (where to write the baked asset)");
  c->output = o1 ? *o1 : *o2;
  if (c->output.empty()) return usage("-o needs a file name");

  int v = 0;
  if (const std::string* s = p.value("--order")) {
    if (Status st = parseIntArg("--order", *s, 2, 8, &v); !st.isOk()) return st;
    c->options.order = v;
  }
  if (const std::string* s = p.value("--samples")) {
    if (Status st = parseIntArg("--samples", *s, 16, 1 << 20, &v); !st.isOk()) return st;
    c->options.samples = static_cast<std::size_t>(v);
  }
  if (const std::string* s = p.value("--sampling")) {
    if (*s == "hammersley") c->options.sampling = bake::Sampling::kHammersley;
    else if (*s == "stratified") c->options.sampling = bake::Sampling::kStratified;
    else return usage("unknown --sampling '" + *s + "' (expected hammersley or stratified)");
  }
  if (c->options.sampling == bake::Sampling::kStratified) {
    std::size_t side = 1;
    while (side * side < c->options.samples) ++side;
    if (side * side != c->options.samples) {
      return usage("--sampling stratified needs a square --samples (e.g. 1024 = 32^2), got " +
                   std::to_string(c->options.samples));
    }
  }
  if (const std::string* s = p.value("--seed")) {
    if (Status st = parseIntArg("--seed", *s, 0, 2147483647, &v); !st.isOk()) return st;
    c->options.seed = static_cast<std::uint64_t>(v);
  }
  if (const std::string* s = p.value("--bounces")) {
    if (Status st = parseIntArg("--bounces", *s, 0, 64, &v); !st.isOk()) return st;
    c->options.maxBounces = v;
    c->options.bounceThreshold = 0.0;  // exactly N
  }
  if (const std::string* s = p.value("--bounce-threshold")) {
    if (p.has("--bounces")) return usage("give --bounces (exact count) or --bounce-threshold, not both");
    float t = 0;
    if (Status st = parseFloatArg("--bounce-threshold", *s, 0.0f, 1.0f, &t); !st.isOk()) return st;
    c->options.bounceThreshold = t;
  }
  if (const std::string* s = p.value("--threads")) {
    if (Status st = parseIntArg("--threads", *s, 1, 1024, &v); !st.isOk()) return st;
    c->options.threads = static_cast<unsigned>(v);
  }
  if (const std::string* s = p.value("--passes")) {
    c->storeUnshadowed = c->storeShadowed = c->storeInterreflected = false;
    std::size_t start = 0;
    while (start <= s->size()) {
      const std::size_t comma = s->find(',', start);
      const std::string name = s->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      if (name == "unshadowed") c->storeUnshadowed = true;
      else if (name == "shadowed") c->storeShadowed = true;
      else if (name == "interreflected") c->storeInterreflected = true;
      else return usage("unknown pass '" + name + "' in --passes (expected unshadowed, shadowed, interreflected)");
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  c->options.interreflection = c->storeInterreflected;
  if (Status st = parseLightingArgs(p, c); !st.isOk()) return st;
  if (const std::string* s = p.value("--name")) {
    if (!isValidAssetName(*s)) {
      return usage("--name must be at most " + std::to_string(kMaxAssetNameBytes) + " bytes of UTF-8 without control characters");
    }
    c->name = *s;
  }
  if (const std::string* s = p.value("--compress")) {
    TransferCodecSettings settings;
    if (Status st = parseTransferSetting(*s, TransferCodecSettings{}, &settings); !st.isOk()) {
      return usage("--compress: " + st.message());
    }
    c->compress = settings;
  }
  c->quiet = p.has("--quiet");
  c->json = p.has("--json");
  return Status::ok();
}

BakedAsset makeAsset(bake::Scene&& scene, bake::BakeResult&& r, const BakeCli& c) {
  BakedAsset a;
  a.shOrder = r.order;
  a.positions = std::move(scene.positions);
  a.normals = std::move(scene.normals);
  a.albedo = std::move(scene.albedo);
  a.indices = std::move(scene.indices);
  a.name = c.name.value_or(scene.name);
  a.lighting = c.options.lighting;
  a.samples = c.options.samples;
  a.seed = c.options.seed;
  a.sampling = c.options.sampling == bake::Sampling::kStratified ? "stratified" : "hammersley";
  if (c.storeUnshadowed) a.passes.push_back({TransferKind::kUnshadowed, 1, 0, std::move(r.unshadowed), {}});
  if (c.storeShadowed) a.passes.push_back({TransferKind::kShadowed, 1, 0, std::move(r.shadowed), {}});
  if (c.storeInterreflected) a.passes.push_back({TransferKind::kInterreflected, 3, r.bounces, std::move(r.interreflected), {}});
  return a;
}

// Encodes every pass of `a` with the codec; the floats are dropped once encoded.
Status compressPasses(const TransferCodecSettings& settings, BakedAsset* a, std::string* summary) {
  for (TransferPass& pass : a->passes) {
    TransferEncodeReport report;
    if (Status s = encodeTransfer(pass.coeffs, a->shOrder, pass.channels, settings, &pass.encoded, &report); !s.isOk()) {
      return Status::error(s.code(), std::string(transferKindName(pass.kind)) + " transfer: " + s.message());
    }
    char line[200];
    std::snprintf(line, sizeof line, "%s%s %zu -> %zu bytes (relative RMS error %.2e%s)", summary->empty() ? "" : "; ",
                  transferKindName(pass.kind), pass.coeffs.size() * 4, pass.encoded.size(), report.relativeError,
                  report.clusters > 0 ? (", " + std::to_string(report.clusters) + " clusters").c_str() : "");
    *summary += line;
    pass.coeffs.clear();
    pass.coeffs.shrink_to_fit();
  }
  return Status::ok();
}

double peakMemoryMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

int fail(std::FILE* err, int code, const std::string& message) {
  std::fprintf(err, "prt-bake: error: %s\n", message.c_str());
  if (code == kExitUsageError) std::fputs("Try 'prt-bake --help'.\n", err);
  return code;
}

}  // namespace

const char* bakeHelpText() { return kHelp; }

int runBakeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(kHelp, out);
    return kExitOk;
  }
  BakeCli c;
  if (Status s = parseBakeArgs(args, &c); !s.isOk()) return fail(err, kExitUsageError, s.message());
  std::vector<std::string> inputs;
  if (!c.scene.empty()) inputs.push_back(c.scene);
  // Before the bake, not after it: a bad -o must not cost the user a long bake.
  if (Status s = checkOutputPath(c.output, inputs); !s.isOk()) return fail(err, kExitInputError, s.message());

  const auto t0 = std::chrono::steady_clock::now();
  bake::Scene scene;
  if (c.scene.empty()) {
    scene = bake::makeDefaultScene();
  } else {
    std::vector<std::string> warnings;
    if (Status s = bake::loadGltf(c.scene, &scene, &warnings); !s.isOk()) return fail(err, kExitInputError, s.message());
    if (!c.quiet)
      for (const std::string& w : warnings) std::fprintf(err, "prt-bake: warning: %s\n", w.c_str());
  }
  bake::optimizeMeshOrder(&scene);
  const std::size_t vertexCount = scene.positions.size(), triangleCount = scene.indices.size() / 3;
  completeLighting(scene, &c);
  if (!c.quiet) {
    std::fprintf(err, "prt-bake: %s: %zu vertices, %zu triangles; order %d, %zu samples; lighting %s\n",
                 c.scene.empty() ? "default scene" : c.scene.c_str(), vertexCount, triangleCount, c.options.order,
                 c.options.samples, describeLighting(c.options.lighting).c_str());
  }

  bake::ProgressBar bar(err, !c.quiet);
  c.options.progress = [&bar](const bake::BakeProgress& p) { bar.update(p); };
  bake::BakeResult result;
  const Status baked = bake::bakeTransfer(scene, c.options, &result);
  bar.finish();
  if (!baked.isOk()) return fail(err, kExitInputError, baked.message());
  const std::size_t outsideLight = result.verticesOutsideLight;
  if (outsideLight > 0 && !c.quiet) {
    std::fprintf(err,
                 "prt-bake: warning: %zu of %zu vertices lie outside the lighting sphere (%s); their rays that "
                 "miss it receive no light\n",
                 outsideLight, vertexCount, describeLighting(c.options.lighting).c_str());
  }

  const int bounces = result.bounces;
  const std::vector<bake::PassStats> passes = result.passes;
  const std::vector<double> energy = result.bounceEnergy;
  std::vector<std::uint8_t> bytes;
  {
    BakedAsset asset = makeAsset(std::move(scene), std::move(result), c);
    if (c.compress) {
      std::string summary;
      if (Status s = compressPasses(*c.compress, &asset, &summary); !s.isOk()) {
        return fail(err, kExitInputError, "cannot compress: " + s.message());
      }
      if (!c.quiet) std::fprintf(err, "prt-bake: %s: %s\n", transferSettingName(*c.compress).c_str(), summary.c_str());
    }
    if (Status s = encodeAsset(asset, &bytes); !s.isOk()) return fail(err, kExitInputError, "cannot encode asset: " + s.message());
  }
  if (Status s = writeFileAtomically(c.output, bytes, inputs); !s.isOk()) return fail(err, kExitInputError, s.message());
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!c.quiet) {
    std::fprintf(err, "prt-bake: wrote %s (%zu bytes, %d bounces) in %.2f s, peak memory %.0f MiB\n", c.output.c_str(),
                 bytes.size(), bounces, total, peakMemoryMiB());
  }
  if (c.json) {
    std::string s = "{\n  \"scene\": " + jsonString(c.scene.empty() ? "default" : c.scene) + ",\n";
    s += "  \"output\": " + jsonString(c.output) + ",\n";
    s += "  \"bytes\": " + std::to_string(bytes.size()) + ",\n";
    s += "  \"vertices\": " + std::to_string(vertexCount) + ",\n";
    s += "  \"triangles\": " + std::to_string(triangleCount) + ",\n";
    s += "  \"order\": " + std::to_string(c.options.order) + ",\n";
    s += "  \"samples\": " + std::to_string(c.options.samples) + ",\n";
    s += "  \"bounces\": " + std::to_string(bounces) + ",\n";
    const LightingInfo& l = c.options.lighting;
    s += "  \"lighting\": {\"model\": " + jsonString(lightingModelName(l.model));
    if (isLocalLighting(l.model)) {
      s += ", \"center\": [" + jsonNumber(l.center.x) + ", " + jsonNumber(l.center.y) + ", " + jsonNumber(l.center.z) +
           "], \"radius\": " + jsonNumber(l.radius) + ", \"vertices_outside\": " + std::to_string(outsideLight);
    }
    s += "},\n";
    s += "  \"bounce_energy\": [";
    for (std::size_t i = 0; i < energy.size(); ++i) s += (i ? ", " : "") + jsonNumber(energy[i]);
    s += "],\n  \"passes\": [\n";
    for (std::size_t i = 0; i < passes.size(); ++i) {
      const auto& p = passes[i];
      s += "    {\"name\": " + jsonString(p.name) + ", \"seconds\": " + jsonNumber(p.seconds) +
           ", \"rays\": " + std::to_string(p.rays) +
           ", \"rays_per_second\": " + jsonNumber(p.seconds > 0 ? static_cast<double>(p.rays) / p.seconds : 0.0) + "}" +
           (i + 1 < passes.size() ? ",\n" : "\n");
    }
    s += "  ],\n  \"total_seconds\": " + jsonNumber(total) + ",\n";
    s += "  \"peak_memory_mib\": " + jsonNumber(peakMemoryMiB()) + "\n}\n";
    std::fputs(s.c_str(), out);
  }
  return kExitOk;
}

}  // namespace prt
