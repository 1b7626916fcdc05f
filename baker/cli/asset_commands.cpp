#include "baker/cli/asset_commands.h"

#include <cmath>
#include <optional>
#include <vector>

#include "baker/cli/report_failure.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "native/environment_map.h"
#include "native/file_io.h"
#include "native/image_io.h"
#include "native/json_text.h"
#include "prt/asset.h"
#include "prt/exit_radiance.h"
#include "prt/sh_basis.h"

namespace prt {
namespace {

constexpr std::uint64_t kMaxAssetFileBytes = std::uint64_t{16} << 30;

Status oneAsset(const ParsedArgs& p, std::string* path) {
  if (p.positionals.size() != 1) {
    return usageError(p.positionals.empty() ? "missing ASSET" : "expected one ASSET");
  }
  *path = p.positionals[0];
  return Status::ok();
}

Status readAsset(const std::string& path, std::vector<std::uint8_t>* bytes) {
  return readFileBytes(path, kMaxAssetFileBytes, bytes);
}

std::string prefixed(const std::string& path, const Status& s) { return "'" + path + "': " + s.toString(); }

constexpr const char* kInfoHelp =
    "Usage: prt-bake info ASSET [--json]\n"
    "\n"
    "Verifies a baked asset (every checksum and value) and prints its contents, the lighting\n"
    "model its transfer was baked for included (distant, or a local sphere's centre and radius).\n";

constexpr const char* kShadeHelp =
    "Usage: prt-bake shade ASSET --light constant|ENVMAP [--pass P] [--order N] [--json]\n"
    "\n"
    "Prints every vertex's position and RGB exit radiance under a light:\n"
    "  --light constant    uniform white radiance 1 from every direction\n"
    "  --light ENVMAP      an environment image (EXR, HDR, PNG, JPEG; layout from its aspect)\n"
    "  --pass P            unshadowed, shadowed or interreflected (default: the richest stored)\n"
    "  --order N           truncate to N bands (default: the asset's order)\n"
    "  --json              JSON instead of a table\n";

}  // namespace

int runInfoCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(kInfoHelp, out);
    return kExitOk;
  }
  static constexpr FlagSpec kFlags[] = {{"--json", false}};
  ParsedArgs p;
  std::string path;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return reportFailure(err, "info", s);
  if (Status s = oneAsset(p, &path); !s.isOk()) return reportFailure(err, "info", s);
  std::vector<std::uint8_t> bytes;
  if (Status s = readAsset(path, &bytes); !s.isOk()) return reportFailure(err, "info", s);
  AssetSummary sum;
  if (Status s = verifyAsset(bytes, &sum); !s.isOk()) return reportFailure(err, "info", Status::error(s.code(), prefixed(path, s)));
  if (p.has("--json")) {
    std::string s = "{\n  \"file\": " + jsonString(path) + ",\n  \"bytes\": " + std::to_string(bytes.size()) + ",\n";
    s += "  \"version\": \"" + std::to_string(sum.versionMajor) + "." + std::to_string(sum.versionMinor) + "\",\n";
    s += "  \"name\": " + jsonString(sum.name) + ",\n";
    s += "  \"order\": " + std::to_string(sum.shOrder) + ",\n";
    s += "  \"vertices\": " + std::to_string(sum.vertexCount) + ",\n";
    s += "  \"triangles\": " + std::to_string(sum.triangleCount) + ",\n";
    s += "  \"samples\": " + std::to_string(sum.samples) + ",\n";
    s += "  \"seed\": " + std::to_string(sum.seed) + ",\n";
    s += "  \"sampling\": " + jsonString(sum.sampling) + ",\n";
    s += "  \"lighting\": {\"model\": " + jsonString(lightingModelName(sum.lighting.model));
    if (isLocalLighting(sum.lighting.model)) {
      const Vec3 c = sum.lighting.center;
      s += ", \"center\": [" + jsonNumber(c.x) + ", " + jsonNumber(c.y) + ", " + jsonNumber(c.z) +
           "], \"radius\": " + jsonNumber(sum.lighting.radius);
    }
    s += "},\n  \"passes\": [";
    for (std::size_t i = 0; i < sum.passes.size(); ++i) {
      const auto& ps = sum.passes[i];
      s += std::string(i ? ", " : "") + "{\"kind\": \"" + transferKindName(ps.kind) +
           "\", \"channels\": " + std::to_string(ps.channels) + ", \"bounces\": " + std::to_string(ps.bounces) + "}";
    }
    s += "]\n}\n";
    std::fputs(s.c_str(), out);
  } else {
    std::fprintf(out, "%s: PRT asset v%u.%u, %zu bytes, checksums ok\n", path.c_str(), sum.versionMajor,
                 sum.versionMinor, bytes.size());
    std::fprintf(out, "name: %s\nvertices: %u\ntriangles: %u\nSH order: %d (%d coefficients)\n", sum.name.c_str(),
                 sum.vertexCount, sum.triangleCount, sum.shOrder, shCoeffCount(sum.shOrder));
    std::fprintf(out, "bake: %llu samples (%s), seed %llu\n", static_cast<unsigned long long>(sum.samples),
                 sum.sampling.c_str(), static_cast<unsigned long long>(sum.seed));
    if (isLocalLighting(sum.lighting.model)) {
      const Vec3 c = sum.lighting.center;
      std::fprintf(out, "lighting: %s, centre (%.9g, %.9g, %.9g), radius %.9g\n", lightingModelName(sum.lighting.model),
                   static_cast<double>(c.x), static_cast<double>(c.y), static_cast<double>(c.z),
                   static_cast<double>(sum.lighting.radius));
    } else {
      std::fprintf(out, "lighting: %s\n", lightingModelName(sum.lighting.model));
    }
    for (const auto& ps : sum.passes) {
      std::fprintf(out, "pass: %s, %s", transferKindName(ps.kind), ps.channels == 3 ? "RGB" : "scalar (x albedo)");
      if (ps.kind == TransferKind::kInterreflected) std::fprintf(out, ", %d bounces", ps.bounces);
      std::fputc('\n', out);
    }
  }
  return kExitOk;
}

int runShadeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(kShadeHelp, out);
    return kExitOk;
  }
  static constexpr FlagSpec kFlags[] = {{"--light", true}, {"--pass", true}, {"--order", true}, {"--json", false}};
  ParsedArgs p;
  std::string path;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return reportFailure(err, "shade", s);
  if (Status s = oneAsset(p, &path); !s.isOk()) return reportFailure(err, "shade", s);
  const std::string* light = p.value("--light");
  if (!light) return reportFailure(err, "shade", usageError("missing --light constant|ENVMAP"));
  std::optional<TransferKind> wanted;
  if (const std::string* ps = p.value("--pass")) {
    if (*ps == "unshadowed") wanted = TransferKind::kUnshadowed;
    else if (*ps == "shadowed") wanted = TransferKind::kShadowed;
    else if (*ps == "interreflected") wanted = TransferKind::kInterreflected;
    else return reportFailure(err, "shade", usageError("unknown --pass '" + *ps + "' (expected unshadowed, shadowed or interreflected)"));
  }
  int order = 0;
  if (const std::string* o = p.value("--order")) {
    if (Status s = parseIntArg("--order", *o, 1, kMaxShOrder, &order); !s.isOk()) return reportFailure(err, "shade", s);
  }

  std::vector<std::uint8_t> bytes;
  if (Status s = readAsset(path, &bytes); !s.isOk()) return reportFailure(err, "shade", s);
  BakedAsset asset;
  if (Status s = decodeAsset(bytes, &asset); !s.isOk()) return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
  bytes = {};
  if (order == 0) order = asset.shOrder;
  if (order > asset.shOrder) {
    return reportFailure(err, "shade", usageError("--order " + std::to_string(order) + " exceeds the asset's order " + std::to_string(asset.shOrder)));
  }
  const TransferPass* pass = nullptr;
  if (wanted) {
    pass = findPass(asset, *wanted);
    if (!pass) return reportFailure(err, "shade", Status::error(StatusCode::kInvalidArgument, "'" + path + "' has no " + transferKindName(*wanted) + " pass"));
  } else {
    for (TransferKind k : {TransferKind::kInterreflected, TransferKind::kShadowed, TransferKind::kUnshadowed})
      if (!pass) pass = findPass(asset, k);
  }

  std::vector<Rgb> lighting(static_cast<std::size_t>(shCoeffCount(order)));
  if (*light == "constant") {
    lighting[0] = Rgb{1, 1, 1} * static_cast<float>(2.0 * std::sqrt(kPi));  // radiance 1 everywhere
  } else {
    RgbImage image;
    if (Status s = loadImage(*light, &image); !s.isOk()) return reportFailure(err, "shade", s);
    const char* aspect = "";
    const std::optional<EnvLayout> layout = guessLayout(image.width, image.height, &aspect);
    if (!layout) return reportFailure(err, "shade", Status::error(StatusCode::kInvalidArgument, "'" + *light + "': cannot guess its layout from its aspect ratio"));
    if (Status s = projectLayout(*layout, order, image, &lighting); !s.isOk()) return reportFailure(err, "shade", s);
  }

  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(asset.shOrder));
  std::vector<float> exit(3 * asset.positions.size());
  if (Status s = exitRadiance(pass->coeffs, pass->channels, n2, asset.albedo, lighting, exit); !s.isOk()) {
    return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
  }
  const bool json = p.has("--json");
  std::string text = json ? "{\n  \"asset\": " + jsonString(path) + ",\n  \"pass\": \"" + transferKindName(pass->kind) +
                                "\",\n  \"order\": " + std::to_string(order) + ",\n  \"light\": " + jsonString(*light) +
                                ",\n  \"vertices\": [\n"
                          : "";
  for (std::size_t v = 0; v < asset.positions.size(); ++v) {
    const Rgb radiance{exit[3 * v], exit[3 * v + 1], exit[3 * v + 2]};
    const Vec3 x = asset.positions[v];
    if (json) {
      text += "    {\"position\": [" + jsonNumber(x.x) + ", " + jsonNumber(x.y) + ", " + jsonNumber(x.z) +
              "], \"radiance\": [" + jsonNumber(radiance.r) + ", " + jsonNumber(radiance.g) + ", " +
              jsonNumber(radiance.b) + "]}" + (v + 1 < asset.positions.size() ? ",\n" : "\n");
    } else {
      char line[200];
      std::snprintf(line, sizeof line, "%zu %.6g %.6g %.6g %.6g %.6g %.6g\n", v, static_cast<double>(x.x),
                    static_cast<double>(x.y), static_cast<double>(x.z), static_cast<double>(radiance.r),
                    static_cast<double>(radiance.g), static_cast<double>(radiance.b));
      text += line;
    }
    if (text.size() > (1u << 20)) {
      std::fputs(text.c_str(), out);
      text.clear();
    }
  }
  if (json) text += "  ]\n}\n";
  std::fputs(text.c_str(), out);
  return kExitOk;
}

}  // namespace prt
