#include "baker/cli/asset_commands.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <optional>
#include <span>
#include <vector>

#include "baker/cli/report_failure.h"
#include "baker/cli/rtt_command.h"
#include "baker/cli/shade_texels.h"
#include "baker/scene/uv_atlas_check.h"
#include "baker/texture/asset_texels.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "native/environment_map.h"
#include "native/file_io.h"
#include "native/image_io.h"
#include "native/json_text.h"
#include "prt/asset.h"
#include "prt/rtt.h"
#include "prt/exit_radiance.h"
#include "prt/glossy_radiance.h"
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
    "model its transfer was baked for included (distant, or a local sphere's centre and radius),\n"
    "each pass's domain (per vertex, or per texel of the transfer-texture atlases), its order (a\n"
    "TPFL visibility pass has its own) and the atlases. Given a radiance transfer texture\n"
    "(prt-bake rtt), verifies it and prints its shape and coefficient range instead.\n";

// The atlases of a verified asset as a JSON array: [{"width": W, "height": H,
// "firstTriangle": F, "triangleCount": C}, ...]; [] without texel passes.
std::string infoAtlasesJson(const std::vector<TextureAtlas>& atlases) {
  std::string s = "[";
  for (std::size_t i = 0; i < atlases.size(); ++i) {
    const TextureAtlas& a = atlases[i];
    s += std::string(i ? ", " : "") + "{\"width\": " + std::to_string(a.width) + ", \"height\": " + std::to_string(a.height) +
         ", \"firstTriangle\": " + std::to_string(a.firstTriangle) + ", \"triangleCount\": " + std::to_string(a.triangleCount) + "}";
  }
  return s + "]";
}

// "atlases: 2, 22 texels: 4x3 (triangles 0-5), 2x5 (triangles 6-9)"; the first few atlases
// only, as an asset may have up to kMaxAssetAtlases of them.
std::string infoAtlasesLine(const std::vector<TextureAtlas>& atlases, std::uint64_t texels) {
  constexpr std::size_t kListed = 8;
  std::string s = "atlases: " + std::to_string(atlases.size()) + ", " + std::to_string(texels) + " texels:";
  for (std::size_t i = 0; i < atlases.size() && i < kListed; ++i) {
    const TextureAtlas& a = atlases[i];
    s += std::string(i ? ", " : " ") + std::to_string(a.width) + "x" + std::to_string(a.height) + " (triangles " +
         std::to_string(a.firstTriangle) + "-" + std::to_string(std::uint64_t{a.firstTriangle} + a.triangleCount - 1) + ")";
  }
  if (atlases.size() > kListed) s += ", ... " + std::to_string(atlases.size() - kListed) + " more";
  return s + "\n";
}

// Per atlas, its texels' coverage counts: sampled (1) and filled by dilation (2), and its charts.
struct AtlasUsage {
  std::uint64_t sampled = 0, dilated = 0;
  std::size_t charts = 0;
};
// `a` holds the atlas sections (decodeAssetAtlases); the charts come from the geometry of `file`.
Status atlasUsage(std::span<const std::uint8_t> file, const BakedAsset& a, std::vector<AtlasUsage>* out) {
  out->assign(a.atlases.size(), {});
  if (a.atlases.empty()) return Status::ok();
  std::uint64_t first = 0;
  for (std::size_t i = 0; i < a.atlases.size(); ++i) {
    const std::uint64_t n = std::uint64_t{a.atlases[i].width} * a.atlases[i].height;
    for (std::uint64_t t = first; t < first + n && t < a.texelCoverage.size(); ++t) {
      (*out)[i].sampled += a.texelCoverage[t] == 1;
      (*out)[i].dilated += a.texelCoverage[t] == 2;
    }
    first += n;
  }
  BakedAsset geometry;
  if (Status s = decodeAssetGeometry(file, &geometry); !s.isOk()) return s;
  std::vector<bake::Uv> uvs(a.atlasUv.size() / 2);
  for (std::size_t v = 0; v < uvs.size(); ++v) uvs[v] = {a.atlasUv[2 * v], a.atlasUv[2 * v + 1]};
  for (std::size_t i = 0; i < a.atlases.size(); ++i) {
    const std::span<const std::uint32_t> indices(geometry.indices);
    const std::size_t begin = 3 * std::size_t{a.atlases[i].firstTriangle}, count = 3 * std::size_t{a.atlases[i].triangleCount};
    if (begin + count > indices.size()) return Status::error(StatusCode::kCorrupt, "an atlas covers triangles past the mesh");
    if (Status s = bake::countUvCharts(geometry.positions, indices.subspan(begin, count), uvs, &(*out)[i].charts); !s.isOk()) return s;
  }
  return Status::ok();
}

// One line per atlas: "atlas 1: 64x64, triangles 12-23 (12), 3 charts, 812 texels sampled (19.8%), 301 dilated".
std::string infoAtlasLines(const std::vector<TextureAtlas>& atlases, const std::vector<AtlasUsage>& usage) {
  std::string s;
  for (std::size_t i = 0; i < atlases.size(); ++i) {
    const TextureAtlas& a = atlases[i];
    const double texels = static_cast<double>(a.width) * a.height;
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.1f%%", 100.0 * static_cast<double>(usage[i].sampled) / texels);
    s += "atlas " + std::to_string(i) + ": " + std::to_string(a.width) + "x" + std::to_string(a.height) + ", triangles " +
         std::to_string(a.firstTriangle) + "-" + std::to_string(std::uint64_t{a.firstTriangle} + a.triangleCount - 1) + " (" +
         std::to_string(a.triangleCount) + "), " + std::to_string(usage[i].charts) + (usage[i].charts == 1 ? " chart, " : " charts, ") +
         std::to_string(usage[i].sampled) + " texels sampled (" + pct + "), " +
         std::to_string(usage[i].dilated) + " dilated\n";
  }
  return s;
}

constexpr const char* kShadeHelp =
    "Usage: prt-bake shade ASSET --light constant|ENVMAP [--pass P] [--view X,Y,Z [--glossy-only]]\n"
    "                        [--order N] [--texels] [--json]\n"
    "\n"
    "Prints every vertex's position and RGB exit radiance under a light (with --texels, every\n"
    "sampled texel's atlas, texel, position, normal and exit radiance):\n"
    "  --light constant    uniform white radiance 1 from every direction\n"
    "  --light ENVMAP      an environment image (EXR, HDR, PNG, JPEG; layout from its aspect)\n"
    "  --pass P            unshadowed, shadowed or interreflected (default: the richest stored);\n"
    "                      glossy-shadowed or glossy-interreflected: that diffuse pass plus the\n"
    "                      glossy matrix pass of the same kind, seen from --view (docs/glossy.md);\n"
    "                      glossy: the richest such pair\n"
    "  --view X,Y,Z        the eye position (world units) for a glossy pass\n"
    "  --glossy-only       print the glossy term alone (k_s x the lobe integral), no diffuse\n"
    "  --order N           truncate to N bands (default: the asset's order)\n"
    "  --texels            the transfer-texture pass instead (bake --texels): the texel's own\n"
    "                      stored transfer, unfiltered; with --pass glossy or glossy-shadowed\n"
    "                      (and --view) the texel diffuse pass plus the TPFL glossy term of the\n"
    "                      visibility pass (bake --texels --texel-glossy), the texel's material\n"
    "                      interpolated from its triangle's vertices\n"
    "  --json              JSON instead of a table\n";

// "X,Y,Z": three finite numbers.
Status parseEye(const std::string& text, Vec3* out) {
  float v[3] = {};
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos)) {
      return usageError("--view expects X,Y,Z (three numbers separated by commas), got '" + text + "'");
    }
    const std::string part = text.substr(start, i < 2 ? comma - start : std::string::npos);
    const float big = 3.0e38f;
    if (!parseFloatArg("--view", part, -big, big, &v[i]).isOk()) {
      return usageError("--view expects X,Y,Z of finite numbers; component " + std::to_string(i + 1) + " '" + part +
                        "' is not one");
    }
    start = comma + 1;
  }
  *out = {v[0], v[1], v[2]};
  return Status::ok();
}

struct ShadePass {
  std::optional<TransferKind> kind;  // unset: the richest stored
  bool glossy = false;
};

Status parseShadePass(const std::string& name, ShadePass* out) {
  const std::string glossyPrefix = "glossy-";
  std::string kind = name;
  if (name == "glossy") {
    out->glossy = true;
    return Status::ok();
  }
  if (name.rfind(glossyPrefix, 0) == 0) {
    out->glossy = true;
    kind = name.substr(glossyPrefix.size());
  }
  if (kind == "unshadowed" && !out->glossy) out->kind = TransferKind::kUnshadowed;
  else if (kind == "shadowed") out->kind = TransferKind::kShadowed;
  else if (kind == "interreflected") out->kind = TransferKind::kInterreflected;
  else return usageError("unknown --pass '" + name + "' (expected unshadowed, shadowed, interreflected, glossy, "
                         "glossy-shadowed or glossy-interreflected)");
  return Status::ok();
}

// Writes *text to `out` and empties it once it passes 1 MiB, so a large scene's output
// streams instead of growing one string.
void flushWhenLarge(std::string* text, std::FILE* out) {
  if (text->size() <= (1u << 20)) return;
  std::fputs(text->c_str(), out);
  text->clear();
}

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
  if (looksLikeRtt(bytes)) return infoRtt(path, bytes, p.has("--json"), out, err);
  AssetSummary sum;
  if (Status s = verifyAsset(bytes, &sum); !s.isOk()) return reportFailure(err, "info", Status::error(s.code(), prefixed(path, s)));
  BakedAsset atlases;  // only the atlas fields (and the texel normals) are filled
  if (Status s = decodeAssetAtlases(bytes, &atlases); !s.isOk()) {
    return reportFailure(err, "info", Status::error(s.code(), prefixed(path, s)));
  }
  if (Status s = decodeAssetBiScale(bytes, &atlases); !s.isOk()) {
    return reportFailure(err, "info", Status::error(s.code(), prefixed(path, s)));
  }
  Rtt rtt;  // verified by verifyAsset: cannot fail
  if (!atlases.rtt.empty() && !decodeRtt(atlases.rtt, &rtt).isOk()) rtt = Rtt{};
  const std::uint64_t texels = assetTexelCount(atlases);
  std::vector<AtlasUsage> usage;
  if (Status s = atlasUsage(bytes, atlases, &usage); !s.isOk()) return reportFailure(err, "info", Status::error(s.code(), prefixed(path, s)));
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
      s += std::string(i ? ", " : "") + "{\"kind\": \"" + transferKindName(ps.kind) + "\", \"form\": \"" +
           transferFormName(ps.form) + "\", \"domain\": \"" + transferDomainName(ps.domain) +
           "\", \"order\": " + std::to_string(ps.form == TransferForm::kVisibility ? ps.order : sum.shOrder) +
           ", \"channels\": " + std::to_string(ps.channels) +
           ", \"bounces\": " + std::to_string(ps.bounces) + ", \"encoded\": " + (ps.encoded ? "true" : "false") +
           ", \"bytes\": " + std::to_string(ps.bytes) + "}";
    }
    s += "],\n  \"texels\": " + std::to_string(texels) + ",\n  \"atlases\": " + infoAtlasesJson(atlases.atlases) +
         ",\n  \"atlas_usage\": [";
    for (std::size_t i = 0; i < usage.size(); ++i) {
      s += std::string(i ? ", " : "") + "{\"charts\": " + std::to_string(usage[i].charts) + ", \"sampled\": " + std::to_string(usage[i].sampled) +
           ", \"dilated\": " + std::to_string(usage[i].dilated) + "}";
    }
    s += "],\n  \"texel_normals\": ";
    // null without the section (no normal map: the glossy term uses the interpolated normal).
    s += atlases.texelNormals.empty() ? std::string("null")
                                      : "{\"encoding\": \"octahedral snorm16\", \"bytes\": " +
                                            std::to_string(atlases.texelNormals.size() * 2) + "}";
    // null without an RTT (docs/bi-scale.md).
    s += ",\n  \"bi_scale\": ";
    s += atlases.rtt.empty() ? std::string("null")
                             : "{\"rtt_bytes\": " + std::to_string(atlases.rtt.size()) + ", \"order\": " + std::to_string(rtt.order) +
                                   ", \"channels\": " + std::to_string(rtt.channels) + ", \"spatial\": " + std::to_string(rtt.spatial) +
                                   ", \"views\": " + std::to_string(rtt.views) +
                                   ", \"placements\": " + std::to_string(atlases.patchPlacements.size()) + "}";
    s += "\n}\n";
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
      if (ps.form == TransferForm::kVisibility) {
        // TPFL glossy (docs/transfer-textures.md): exact when the order is 2n - 1.
        const int exact = 2 * sum.shOrder - 1;
        std::fprintf(out, "pass: texel %s visibility (TPFL glossy), order %d (%d coefficients per texel, %s)",
                     transferKindName(ps.kind), ps.order, ps.order * ps.order,
                     ps.order >= exact ? "exact" : ("approximate: exact needs " + std::to_string(exact)).c_str());
      } else if (ps.form == TransferForm::kMatrix) {
        const MatrixPacking packing = matrixPackingFor(ps.kind, sum.lighting.model);
        std::fprintf(out, "pass: %s glossy matrix, %s, %s packing (%zu entries per channel)", transferKindName(ps.kind),
                     ps.channels == 3 ? "RGB" : "scalar (one matrix for r, g, b)", matrixPackingName(packing),
                     matrixEntryCount(sum.shOrder, packing));
      } else {
        std::fprintf(out, "pass: %s%s, %s", ps.domain == TransferDomain::kTexel ? "texel " : "", transferKindName(ps.kind),
                     ps.channels == 3 ? "RGB" : "scalar (x albedo)");
      }
      if (ps.kind == TransferKind::kInterreflected) std::fprintf(out, ", %d bounces", ps.bounces);
      std::fprintf(out, ", %s, %llu bytes\n", ps.encoded ? "encoded" : "float32", static_cast<unsigned long long>(ps.bytes));
    }
    if (!atlases.atlases.empty()) {
      std::fputs(infoAtlasesLine(atlases.atlases, texels).c_str(), out);
      std::fputs(infoAtlasLines(atlases.atlases, usage).c_str(), out);
    }
    if (!atlases.texelNormals.empty()) {
      std::fprintf(out, "texel normals: normal-mapped shading normals for the glossy term, octahedral 2 x 16 bits (snorm), %llu bytes\n",
                   static_cast<unsigned long long>(atlases.texelNormals.size() * 2));
    }
    if (!atlases.rtt.empty()) {
      const std::string placement = atlases.idMap.empty()
                                        ? std::string("tangents and patch uv per vertex")
                                        : "tangents per vertex, synthesised id map of " + std::to_string(atlases.patchPlacements.size()) +
                                              (atlases.idMapPerTriangle ? " placements per triangle" : " placements over the atlas");
      std::fprintf(out, "bi-scale: RTT order %d, %d channel%s, %dx%d samples x %dx%d views, %zu bytes; %s\n", rtt.order, rtt.channels,
                   rtt.channels == 1 ? "" : "s", rtt.spatial, rtt.spatial, rtt.views, rtt.views, atlases.rtt.size(), placement.c_str());
    }
  }
  return kExitOk;
}

int runShadeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(kShadeHelp, out);
    return kExitOk;
  }
  static constexpr FlagSpec kFlags[] = {{"--light", true}, {"--pass", true},         {"--order", true},
                                         {"--json", false},  {"--view", true},         {"--glossy-only", false},
                                         {"--texels", false}};
  ParsedArgs p;
  std::string path;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return reportFailure(err, "shade", s);
  if (Status s = oneAsset(p, &path); !s.isOk()) return reportFailure(err, "shade", s);
  const std::string* light = p.value("--light");
  if (!light) return reportFailure(err, "shade", usageError("missing --light constant|ENVMAP"));
  ShadePass wanted;
  if (const std::string* ps = p.value("--pass")) {
    if (Status s = parseShadePass(*ps, &wanted); !s.isOk()) return reportFailure(err, "shade", s);
  }
  Vec3 eye{};
  if (wanted.glossy) {
    const std::string* view = p.value("--view");
    if (!view) return reportFailure(err, "shade", usageError("a glossy --pass needs --view X,Y,Z (the eye position)"));
    if (Status s = parseEye(*view, &eye); !s.isOk()) return reportFailure(err, "shade", s);
  } else {
    for (const char* flag : {"--view", "--glossy-only"}) {
      if (p.has(flag)) return reportFailure(err, "shade", usageError(std::string(flag) + " needs a glossy --pass"));
    }
  }
  const bool glossyOnly = p.has("--glossy-only");
  const bool texels = p.has("--texels");
  if (texels && wanted.glossy && wanted.kind == TransferKind::kInterreflected) {
    return reportFailure(err, "shade", usageError("texel glossy is the shadowed TPFL visibility pass (it has no bounces): "
                                                  "use --pass glossy or glossy-shadowed with --texels"));
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
  const TransferPass* matrix = nullptr;
  const auto noPass = [&](TransferKind k, const char* what) {
    return reportFailure(err, "shade", Status::error(StatusCode::kInvalidArgument, "'" + path + "' has no " +
                                                                                      transferKindName(k) + what));
  };
  const TransferDomain domain = texels ? TransferDomain::kTexel : TransferDomain::kVertex;
  const char* domainWhat = texels ? " texel pass (bake with --texels)" : " pass";
  // Texel glossy is the visibility pass (TPFL), shaded with the texel diffuse pass asked for.
  const TransferPass* visibility = nullptr;
  if (texels && wanted.glossy) {
    visibility = findPass(asset, TransferKind::kShadowed, TransferForm::kVisibility, TransferDomain::kTexel);
    if (!visibility) {
      return reportFailure(err, "shade", Status::error(StatusCode::kInvalidArgument,
                                                       "'" + path + "' has no texel visibility pass (bake with --texels --texel-glossy)"));
    }
  }
  if (wanted.kind) {
    pass = findPass(asset, *wanted.kind, TransferForm::kVector, domain);
    if (!pass) return noPass(*wanted.kind, domainWhat);
    if (wanted.glossy && !texels) {
      matrix = findPass(asset, *wanted.kind, TransferForm::kMatrix);
      if (!matrix) return noPass(*wanted.kind, " glossy matrix pass (bake with --glossy)");
    }
  } else {
    for (TransferKind k : {TransferKind::kInterreflected, TransferKind::kShadowed, TransferKind::kUnshadowed}) {
      const TransferPass* vector = findPass(asset, k, TransferForm::kVector, domain);
      const TransferPass* m = findPass(asset, k, TransferForm::kMatrix);
      const bool vertexGlossy = wanted.glossy && !texels;  // texel glossy pairs with any texel pass
      if (pass || !vector || (vertexGlossy && !m)) continue;
      pass = vector;
      matrix = vertexGlossy ? m : nullptr;
    }
    if (!pass) {
      return reportFailure(err, "shade", Status::error(StatusCode::kInvalidArgument,
                                                       "'" + path + "' has no " +
                                                           (texels ? "texel transfer pass (bake with --texels)"
                                                            : wanted.glossy ? "glossy matrix pass with its diffuse pass (bake with --glossy)"
                                                                          : "transfer pass")));
    }
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
  if (texels) return printTexels(asset, {pass, visibility, eye, glossyOnly}, path, *light, order, lighting, p.has("--json"), out, err);
  std::vector<float> exit(3 * asset.positions.size(), 0.0f);
  if (!glossyOnly) {
    if (Status s = exitRadiance(pass->coeffs, pass->channels, n2, asset.albedo, lighting, exit); !s.isOk()) {
      return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
    }
  }
  if (matrix) {
    std::vector<float> glossy(exit.size());
    const Status s = glossyExitRadiance(matrix->coeffs, asset.shOrder, matrixPackingFor(matrix->kind, asset.lighting.model),
                                        matrix->channels, asset.positions, asset.normals, asset.specular,
                                        GlossyView{eye, true}, lighting, glossy);
    if (!s.isOk()) return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
    for (std::size_t i = 0; i < exit.size(); ++i) exit[i] += glossy[i];
  }
  const bool json = p.has("--json");
  std::string passName = std::string(matrix ? "glossy-" : "") + transferKindName(pass->kind);
  std::string text;
  if (json) {
    text = "{\n  \"asset\": " + jsonString(path) + ",\n  \"pass\": \"" + passName + "\",\n  \"order\": " +
           std::to_string(order) + ",\n  \"light\": " + jsonString(*light) + ",\n";
    if (matrix) {
      text += "  \"view\": [" + jsonNumber(eye.x) + ", " + jsonNumber(eye.y) + ", " + jsonNumber(eye.z) +
              "],\n  \"terms\": \"" + (glossyOnly ? "glossy" : "diffuse+glossy") + "\",\n";
    }
    text += "  \"vertices\": [\n";
  }
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
    flushWhenLarge(&text, out);
  }
  if (json) text += "  ]\n}\n";
  std::fputs(text.c_str(), out);
  return kExitOk;
}

}  // namespace prt
