#include "baker/cli/bake_command.h"

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "baker/cli/report_failure.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "baker/scene/default_scene.h"
#include "native/file_io.h"
#include "baker/scene/gltf_loader.h"
#include "baker/scene/uv_atlas_check.h"
#include "native/json_text.h"
#include "baker/transfer/bake_asset.h"
#include "baker/cli/progress_bar.h"
#include "prt/asset.h"
#include "prt/rtt.h"
#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"

namespace prt {
namespace {

constexpr FlagSpec kBakeFlags[] = {
    {"--default", false}, {"-o", true},        {"--output", true},  {"--order", true},
    {"--samples", true},  {"--bounces", true}, {"--bounce-threshold", true}, {"--sampling", true},
    {"--seed", true},     {"--threads", true}, {"--passes", true},  {"--quiet", false},
    {"--json", false},    {"--lighting", true}, {"--light-center", true}, {"--light-radius", true},
    {"--name", true},     {"--compress", true}, {"--compress-matrices", true}, {"--glossy", false}, {"--glossy-bounces", true},
    {"--specular-exponent", true}, {"--max-specular-exponent", true},
    {"--texels", false}, {"--texture-size", true}, {"--texels-per-unit", true}, {"--atlas-padding", true},
    {"--dilation", true}, {"--unwrap", true}, {"--blender", true}, {"--unwrap-timeout", true},
    {"--texel-glossy", false}, {"--visibility-order", true}, {"--texture-sets", true},
    {"--rtt", true}, {"--patches-per-uv", true}, {"--patch-uv-set", true}, {"--patch-width", true}, {"--cell-patches", true},
    {"--id-map-size", true},
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
    "  --compress-matrices SETTING  the glossy matrix passes' setting, when it differs from\n"
    "                            --compress (which it needs), e.g. cpca16b8@0.045; CPCA also takes\n"
    "                            a basis limit, cpca16b8n8@0.045 (default: the --compress setting)\n"
    "  --glossy                  also bake glossy transfer matrices (docs/glossy.md): the base\n"
    "                            colour splits into (1 - metallic) x base (diffuse) and a Phong\n"
    "                            lobe of f0 = mix(0.04, base, metallic) and an exponent from\n"
    "                            roughness; stores the shadowed matrix and, with glossy bounces,\n"
    "                            the interreflected one (matrix memory: order^4 floats per vertex\n"
    "                            and channel, 2.5 KB at order 5)\n"
    "  --glossy-bounces N        bounces gathered into the interreflected matrix, 0..--bounces\n"
    "                            (default 1; 0 stores the shadowed matrix only)\n"
    "  --specular-exponent S     one Phong exponent S >= 0 for every vertex instead of roughness\n"
    "                            (with --glossy or --texel-glossy)\n"
    "  --max-specular-exponent S the exponent roughness 0 (a mirror) maps to (default 10000)\n"
    "  --texels                  also bake the vector passes per texel (transfer textures,\n"
    "                            docs/transfer-textures.md) over the glTF's lightmap atlas:\n"
    "                            TEXCOORD_1 when it is a valid atlas, else TEXCOORD_0, else one\n"
    "                            generated with Blender's Smart UV Project (--unwrap)\n"
    "  --texture-size N          atlas side in texels, 1..16384 (default 512); with several atlases\n"
    "                            a budget of N x N texels shared so every object gets the same\n"
    "                            texels per metre\n"
    "  --texels-per-unit D       instead: each atlas's side gives about D texels per metre of surface\n"
    "  --texture-sets auto|scene|object\n"
    "                            atlases (PRTT texture sets): scene, one for the whole scene; object,\n"
    "                            one per object (glTF node instance), each from its own UVs or\n"
    "                            generated; auto (default): one, unless the scene's UV sets are\n"
    "                            invalid only because objects overlap each other (instances), or\n"
    "                            objects' texel densities differ by more than 2x: then one per object\n"
    "  --atlas-padding P         gutter texels the atlas must keep between charts (default 2)\n"
    "  --dilation N              gutter texels filled from the charts for filtering (default 3)\n"
    "  --unwrap auto|never       auto (default): generate an atlas when neither UV set is valid;\n"
    "                            never: fail instead\n"
    "  --blender PATH            the Blender that generates it (default: blender on PATH)\n"
    "  --unwrap-timeout S        seconds one Blender run may take before it is killed (default 600)\n"
    "  --texel-glossy            also bake each texel's visibility vector for glossy shading by\n"
    "                            the triple product (TPFL, docs/transfer-textures.md), with the\n"
    "                            glossy material split of --glossy (needs --texels, distant lighting)\n"
    "  --visibility-order M      its SH bands, 2..16 (default 2N-1 for --order N: exact; M = N is\n"
    "                            the economy form, M^2 floats a texel, and an approximation)\n"
    "  --rtt FILE                bi-scale radiance transfer (docs/bi-scale.md): store this RTT\n"
    "                            (prt-bake rtt) with tangent frames and its placement through a\n"
    "                            UV set, for the page's meso scale (needs --glossy: the matrices\n"
    "                            are the macro scale)\n"
    "  --patches-per-uv X        patch repeats per UV unit, > 0 (default 8)\n"
    "  --patch-uv-set K          the UV set the patch follows, 0 or 1 (default: TEXCOORD_0 if the\n"
    "                            scene has it, else TEXCOORD_1)\n"
    "  --patch-width W           instead, a synthesised id map: patches W metres wide placed in\n"
    "                            cells over the surface with random phases (needs no UVs; an atlas\n"
    "                            is generated with Blender when the scene's UVs are not one)\n"
    "  --cell-patches C          a cell's mean diameter in patch widths, >= 1 (default 3)\n"
    "  --id-map-size N           store the id map over an atlas of N x N texels, 16..8192, instead\n"
    "                            of per triangle (the default, for meshes finer than a cell)\n"
    "  --quiet                   no progress output\n"
    "  --json                    print bake statistics as JSON on stdout\n";

struct BakeCli {
  std::string scene;  // empty with --default
  std::string output;
  bake::AssetBakeOptions bake;
  bool quiet = false, json = false;
};

Status usage(std::string m) { return usageError(std::move(m)); }

// --rtt FILE (read and verified here, so a bad file fails before the bake), --patches-per-uv,
// --patch-uv-set.
Status parseBiScaleArgs(const ParsedArgs& p, BakeCli* c) {
  for (const char* flag : {"--patches-per-uv", "--patch-uv-set", "--patch-width", "--cell-patches", "--id-map-size"}) {
    if (p.has(flag) && !p.has("--rtt")) return usage(std::string(flag) + " needs --rtt");
  }
  for (const char* flag : {"--cell-patches", "--id-map-size"}) {
    if (p.has(flag) && !p.has("--patch-width")) return usage(std::string(flag) + " needs --patch-width (the synthesised id map)");
  }
  if (p.has("--patch-width") && (p.has("--patches-per-uv") || p.has("--patch-uv-set"))) {
    return usage("give --patch-width (a synthesised id map) or --patches-per-uv/--patch-uv-set (through a UV set), not both");
  }
  const std::string* path = p.value("--rtt");
  if (path == nullptr) return Status::ok();
  if (!c->bake.transfer.glossy) return usage("--rtt needs --glossy (the glossy matrices are bi-scale's macro scale)");
  bake::AssetBakeOptions::BiScale b;
  if (const std::string* s = p.value("--patches-per-uv")) {
    float x = 0;
    if (!parseFloatArg("--patches-per-uv", *s, 0.0f, 1e6f, &x).isOk() || !(x > 0.0f)) {
      return usage("--patches-per-uv expects a number > 0 (patch repeats per UV unit), got '" + *s + "'");
    }
    b.placement.patchesPerUv = x;
  }
  if (const std::string* s = p.value("--patch-uv-set")) {
    int k = 0;
    PRT_RETURN_IF_ERROR(parseIntArg("--patch-uv-set", *s, 0, 1, &k));
    b.placement.texcoord = k;
  }
  if (const std::string* s = p.value("--patch-width")) {
    float w = 0;
    if (!parseFloatArg("--patch-width", *s, 0.0f, 1e6f, &w).isOk() || !(w > 0.0f)) {
      return usage("--patch-width expects a width in metres > 0, got '" + *s + "'");
    }
    bake::IdMapSettings m;
    m.patchWidth = w;
    if (const std::string* cp = p.value("--cell-patches")) {
      float x = 0;
      if (!parseFloatArg("--cell-patches", *cp, 1.0f, 1e6f, &x).isOk()) return usage("--cell-patches expects a number >= 1, got '" + *cp + "'");
      m.cellPatches = x;
    }
    if (const std::string* n = p.value("--id-map-size")) PRT_RETURN_IF_ERROR(parseIntArg("--id-map-size", *n, 16, 8192, &b.idMapSize));
    b.synthesised = m;
  }
  constexpr std::uint64_t kMaxRttFileBytes = 1ull << 30;
  PRT_RETURN_IF_ERROR(readFileBytes(*path, kMaxRttFileBytes, &b.rtt));
  Rtt rtt;
  if (Status s = decodeRtt(b.rtt, &rtt); !s.isOk()) return Status::error(s.code(), *path + ": " + s.message());
  c->bake.biScale = std::move(b);
  return Status::ok();
}

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
  c->bake.transfer.lighting.model = model;
  const bool local = isLocalLighting(model);
  for (const char* flag : {"--light-center", "--light-radius"}) {
    if (p.has(flag) && !local) return usage(std::string(flag) + " needs --lighting local or local-paper");
  }
  if (const std::string* s = p.value("--light-center")) {
    Vec3 centre;
    if (Status st = parseTriple("--light-center", *s, &centre); !st.isOk()) return st;
    c->bake.lightCenter = centre;
  }
  if (const std::string* s = p.value("--light-radius")) {
    const float big = std::numeric_limits<float>::max();
    float r = 0.0f;
    if (!parseFloatArg("--light-radius", *s, -big, big, &r).isOk() || !(r > 0.0f)) {
      return usage("--light-radius expects a finite number > 0, got '" + *s + "'");
    }
    c->bake.lightRadius = r;
  }
  return Status::ok();
}

// --unwrap, --blender, --unwrap-timeout: whether and how an atlas is generated.
Status parseUnwrapArgs(const ParsedArgs& p, bake::TexelBakeSettings* t) {
  const std::string* mode = p.value("--unwrap");
  if (mode != nullptr && *mode != "auto" && *mode != "never") {
    return usage("unknown --unwrap '" + *mode + "' (expected auto or never)");
  }
  if (mode != nullptr && *mode == "never") {
    for (const char* flag : {"--blender", "--unwrap-timeout"}) {
      if (p.has(flag)) return usage(std::string(flag) + " needs --unwrap auto");
    }
    return Status::ok();
  }
  bake::UvUnwrapOptions u;
  if (const std::string* s = p.value("--blender")) {
    if (s->empty()) return usage("--blender needs a path or a program name");
    u.blender = *s;
  }
  if (const std::string* s = p.value("--unwrap-timeout")) {
    float seconds = 0.0f;
    if (!parseFloatArg("--unwrap-timeout", *s, 0.0f, 1e7f, &seconds).isOk() || !(seconds > 0.0f)) {
      return usage("--unwrap-timeout expects seconds > 0, got '" + *s + "'");
    }
    u.timeoutSeconds = seconds;
  }
  t->unwrap = u;
  return Status::ok();
}

Status parseTexelArgs(const ParsedArgs& p, BakeCli* c) {
  for (const char* flag : {"--texture-size", "--texels-per-unit", "--atlas-padding", "--dilation", "--unwrap",
                           "--blender", "--unwrap-timeout", "--texel-glossy", "--texture-sets"}) {
    if (p.has(flag) && !p.has("--texels")) return usage(std::string(flag) + " needs --texels");
  }
  if (p.has("--visibility-order") && !p.has("--texel-glossy")) return usage("--visibility-order needs --texel-glossy");
  if (!p.has("--texels")) return Status::ok();
  bake::TexelBakeSettings t;
  if (p.has("--texture-size") && p.has("--texels-per-unit")) {
    return usage("give --texture-size or --texels-per-unit, not both");
  }
  int v = 0;
  if (const std::string* s = p.value("--texture-size")) {
    if (Status st = parseIntArg("--texture-size", *s, 1, bake::kMaxAtlasSize, &v); !st.isOk()) return st;
    t.textureSize = v;
  }
  if (const std::string* s = p.value("--texels-per-unit")) {
    float d = 0.0f;
    if (!parseFloatArg("--texels-per-unit", *s, 0.0f, 1e9f, &d).isOk() || !(d > 0.0f)) {
      return usage("--texels-per-unit expects a number > 0 (texels per metre), got '" + *s + "'");
    }
    t.texelsPerUnit = d;
  }
  if (const std::string* s = p.value("--atlas-padding")) {
    if (Status st = parseIntArg("--atlas-padding", *s, 0, bake::kMaxAtlasPadding, &v); !st.isOk()) return st;
    t.padding = v;
  }
  if (const std::string* s = p.value("--dilation")) {
    if (Status st = parseIntArg("--dilation", *s, 0, 64, &v); !st.isOk()) return st;
    t.dilation = v;
  }
  if (const std::string* s = p.value("--texture-sets")) {
    if (*s == "auto") t.sets = bake::TextureSets::kAuto;
    else if (*s == "scene") t.sets = bake::TextureSets::kScene;
    else if (*s == "object") t.sets = bake::TextureSets::kObject;
    else return usage("unknown --texture-sets '" + *s + "' (expected auto, scene or object)");
  }
  if (Status st = parseUnwrapArgs(p, &t); !st.isOk()) return st;
  if (p.has("--texel-glossy")) {
    // TPFL is a product with distant light (docs/transfer-textures.md, "Glossy by the triple product").
    if (isLocalLighting(c->bake.transfer.lighting.model)) {
      return usage("--texel-glossy needs distant lighting (the default --lighting): TPFL multiplies each texel's "
                   "visibility with the distant light, which local lighting is not");
    }
    t.visibilityOrder = 2 * c->bake.transfer.order - 1;  // exact (docs/triple-product.md)
    if (const std::string* s = p.value("--visibility-order")) {
      if (Status st = parseIntArg("--visibility-order", *s, kMinVisibilityOrder, kMaxShOrder, &v); !st.isOk()) return st;
      t.visibilityOrder = v;
    }
  }
  c->bake.texels = t;
  return Status::ok();
}

// --glossy-bounces (default 1), against the diffuse bounces it gathers from.
Status parseGlossyBounces(const ParsedArgs& p, BakeCli* c) {
  bake::BakeOptions& t = c->bake.transfer;
  t.glossyBounces = 1;
  if (const std::string* s = p.value("--glossy-bounces")) {
    int v = 0;
    if (Status st = parseIntArg("--glossy-bounces", *s, 0, 64, &v); !st.isOk()) return st;
    t.glossyBounces = v;
  }
  if (t.glossyBounces > 0 && !c->bake.storeInterreflected) {
    return usage("--glossy-bounces " + std::to_string(t.glossyBounces) +
                 " gathers from the diffuse bounces: keep interreflected in --passes, or give --glossy-bounces 0");
  }
  if (t.glossyBounces > t.maxBounces) {
    return usage("--glossy-bounces " + std::to_string(t.glossyBounces) + " exceeds --bounces " + std::to_string(t.maxBounces));
  }
  return Status::ok();
}

// --specular-exponent and --max-specular-exponent: the glossy material split's lobe.
Status parseGlossyMaterialArgs(const ParsedArgs& p, BakeCli* c) {
  const float big = std::numeric_limits<float>::max();
  float x = 0.0f;
  if (const std::string* s = p.value("--specular-exponent")) {
    if (Status st = parseFloatArg("--specular-exponent", *s, 0.0f, big, &x); !st.isOk()) return st;
    c->bake.glossyMaterials.exponent = x;
  }
  if (const std::string* s = p.value("--max-specular-exponent")) {
    if (Status st = parseFloatArg("--max-specular-exponent", *s, 0.0f, big, &x); !st.isOk()) return st;
    c->bake.glossyMaterials.maxExponent = x;
  }
  return Status::ok();
}

// The material flags apply to both glossy bakes (matrices, --glossy, and texel visibility,
// --texel-glossy), which split the material the same way; the bounces only to matrices.
Status parseGlossyArgs(const ParsedArgs& p, BakeCli* c) {
  bake::BakeOptions& t = c->bake.transfer;
  t.glossy = p.has("--glossy");
  const bool materials = t.glossy || p.has("--texel-glossy");
  if (p.has("--glossy-bounces") && !t.glossy) return usage("--glossy-bounces needs --glossy");
  for (const char* flag : {"--specular-exponent", "--max-specular-exponent"}) {
    if (p.has(flag) && !materials) return usage(std::string(flag) + " needs --glossy or --texel-glossy");
  }
  if (!materials) return Status::ok();
  if (t.glossy) PRT_RETURN_IF_ERROR(parseGlossyBounces(p, c));
  return parseGlossyMaterialArgs(p, c);
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
    c->bake.transfer.order = v;
  }
  if (const std::string* s = p.value("--samples")) {
    if (Status st = parseIntArg("--samples", *s, 16, 1 << 20, &v); !st.isOk()) return st;
    c->bake.transfer.samples = static_cast<std::size_t>(v);
  }
  if (const std::string* s = p.value("--sampling")) {
    if (*s == "hammersley") c->bake.transfer.sampling = bake::Sampling::kHammersley;
    else if (*s == "stratified") c->bake.transfer.sampling = bake::Sampling::kStratified;
    else return usage("unknown --sampling '" + *s + "' (expected hammersley or stratified)");
  }
  if (c->bake.transfer.sampling == bake::Sampling::kStratified) {
    std::size_t side = 1;
    while (side * side < c->bake.transfer.samples) ++side;
    if (side * side != c->bake.transfer.samples) {
      return usage("--sampling stratified needs a square --samples (e.g. 1024 = 32^2), got " +
                   std::to_string(c->bake.transfer.samples));
    }
  }
  if (const std::string* s = p.value("--seed")) {
    if (Status st = parseIntArg("--seed", *s, 0, 2147483647, &v); !st.isOk()) return st;
    c->bake.transfer.seed = static_cast<std::uint64_t>(v);
  }
  if (const std::string* s = p.value("--bounces")) {
    if (Status st = parseIntArg("--bounces", *s, 0, 64, &v); !st.isOk()) return st;
    c->bake.transfer.maxBounces = v;
    c->bake.transfer.bounceThreshold = 0.0;  // exactly N
  }
  if (const std::string* s = p.value("--bounce-threshold")) {
    if (p.has("--bounces")) return usage("give --bounces (exact count) or --bounce-threshold, not both");
    float t = 0;
    if (Status st = parseFloatArg("--bounce-threshold", *s, 0.0f, 1.0f, &t); !st.isOk()) return st;
    c->bake.transfer.bounceThreshold = t;
  }
  if (const std::string* s = p.value("--threads")) {
    if (Status st = parseIntArg("--threads", *s, 1, 1024, &v); !st.isOk()) return st;
    c->bake.transfer.threads = static_cast<unsigned>(v);
  }
  if (const std::string* s = p.value("--passes")) {
    c->bake.storeUnshadowed = c->bake.storeShadowed = c->bake.storeInterreflected = false;
    std::size_t start = 0;
    while (start <= s->size()) {
      const std::size_t comma = s->find(',', start);
      const std::string name = s->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      if (name == "unshadowed") c->bake.storeUnshadowed = true;
      else if (name == "shadowed") c->bake.storeShadowed = true;
      else if (name == "interreflected") c->bake.storeInterreflected = true;
      else return usage("unknown pass '" + name + "' in --passes (expected unshadowed, shadowed, interreflected)");
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  if (Status st = parseLightingArgs(p, c); !st.isOk()) return st;
  if (Status st = parseGlossyArgs(p, c); !st.isOk()) return st;
  if (Status st = parseTexelArgs(p, c); !st.isOk()) return st;
  if (Status st = parseBiScaleArgs(p, c); !st.isOk()) return st;
  if (const std::string* s = p.value("--name")) {
    if (!isValidAssetName(*s)) {
      return usage("--name must be at most " + std::to_string(kMaxAssetNameBytes) + " bytes of UTF-8 without control characters");
    }
    c->bake.name = *s;
  }
  if (const std::string* s = p.value("--compress")) {
    TransferCodecSettings settings;
    if (Status st = parseTransferSetting(*s, TransferCodecSettings{}, &settings); !st.isOk()) {
      return usage("--compress: " + st.message());
    }
    c->bake.compress = settings;
  }
  if (const std::string* s = p.value("--compress-matrices")) {
    if (!c->bake.compress) return usage("--compress-matrices needs --compress (the setting of the vector passes)");
    if (!c->bake.transfer.glossy) return usage("--compress-matrices needs --glossy (there are no matrix passes without it)");
    TransferCodecSettings settings;
    if (Status st = parseTransferSetting(*s, TransferCodecSettings{}, &settings); !st.isOk()) {
      return usage("--compress-matrices: " + st.message());
    }
    c->bake.compressMatrices = settings;
  }
  c->quiet = p.has("--quiet");
  c->json = p.has("--json");
  return Status::ok();
}

// "unshadowed 1234 -> 567 bytes (relative RMS error 1.00e-02, 12 clusters); ..."
std::string describeCompression(const std::vector<bake::CompressedPass>& passes) {
  std::string summary;
  for (const bake::CompressedPass& p : passes) {
    char line[200];
    std::snprintf(line, sizeof line, "%s%s%s %zu -> %zu bytes (relative RMS error %.2e%s)", summary.empty() ? "" : "; ",
                  transferKindName(p.kind),
                  p.form == TransferForm::kMatrix         ? " glossy"
                  : p.form == TransferForm::kVisibility   ? " texel visibility"
                  : p.domain == TransferDomain::kTexel    ? " texel"
                                                          : "", p.floatBytes, p.encodedBytes, p.codec.relativeError,
                  p.codec.clusters > 0 ? (", " + std::to_string(p.codec.clusters) + " clusters").c_str() : "");
    summary += line;
  }
  return summary;
}

// "TEXCOORD_1", or "generated atlas (Blender Smart UV Project, 2 attempts, margin 0.0156, 9.1 s)".
std::string describeAtlas(const bake::TexelAtlasReport& t) {
  if (!t.generated) return "TEXCOORD_" + std::to_string(t.texcoord);
  const bake::UvUnwrapReport& g = *t.generated;
  char text[160];
  std::snprintf(text, sizeof text, "generated atlas (Blender Smart UV Project, %zu attempt%s, margin %.4g, %.1f s)",
                g.attempts.size(), g.attempts.size() == 1 ? "" : "s", g.attempts.back().margin, g.seconds);
  return text;
}

// "RTT order 5, 1 channel, 64x64 samples x 8x8 views" (the bytes were verified when parsed).
std::string describeRtt(const std::vector<std::uint8_t>& bytes) {
  Rtt r;
  if (!decodeRtt(bytes, &r).isOk()) return "RTT";
  char text[160];
  std::snprintf(text, sizeof text, "RTT order %d, %d channel%s, %dx%d samples x %dx%d views", r.order, r.channels,
                r.channels == 1 ? "" : "s", r.spatial, r.spatial, r.views, r.views);
  return text;
}

double peakMemoryMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace

const char* bakeHelpText() { return kHelp; }

Status parseBakeCommandLine(std::span<const std::string> args, BakeCommandLine* out) {
  BakeCli c;
  PRT_RETURN_IF_ERROR(parseBakeArgs(args, &c));
  out->scene = std::move(c.scene);
  out->output = std::move(c.output);
  out->bake = std::move(c.bake);
  out->quiet = c.quiet;
  out->json = c.json;
  return Status::ok();
}

int runBakeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(kHelp, out);
    std::fputs("\n", out);
    std::fputs(exitStatusHelp(), out);
    return kExitOk;
  }
  BakeCli c;
  if (Status s = parseBakeArgs(args, &c); !s.isOk()) return reportFailure(err, "", s);
  std::vector<std::string> inputs;
  if (!c.scene.empty()) inputs.push_back(c.scene);
  // Before the bake, not after it: a bad -o must not cost the user a long bake.
  if (Status s = checkOutputPath(c.output, inputs); !s.isOk()) return reportFailure(err, "", s);

  const auto t0 = std::chrono::steady_clock::now();
  bake::Scene scene;
  if (c.scene.empty()) {
    scene = defaultSceneFor(c.bake);
  } else {
    std::vector<std::string> warnings;
    if (Status s = bake::loadGltf(c.scene, &scene, &warnings); !s.isOk()) return reportFailure(err, "", s);
    if (!c.quiet)
      for (const std::string& w : warnings) std::fprintf(err, "prt-bake: warning: %s\n", w.c_str());
  }
  if (!scene.normalMaps.empty() && !c.bake.texels && !c.quiet) {
    // A vertex cannot resolve a normal map's detail; say so rather than ignore it silently.
    std::fprintf(err, "prt-bake: note: the scene's %zu normal map%s shade only texel passes (--texels); vertex passes "
                      "use the vertex normals\n",
                 scene.normalMaps.size(), scene.normalMaps.size() == 1 ? "" : "s");
  }

  bake::ProgressBar bar(err, !c.quiet);
  c.bake.transfer.progress = [&bar](const bake::BakeProgress& p) { bar.update(p); };
  if (c.bake.texels && c.bake.texels->unwrap && !c.quiet) {
    c.bake.texels->unwrap->log = [err](const std::string& line) { std::fprintf(err, "prt-bake: %s\n", line.c_str()); };
  }
  const auto started = [&](const bake::AssetBakeReport& r) {
    if (c.quiet) return;
    std::fprintf(err, "prt-bake: %s: %zu vertices, %zu triangles; order %d, %zu samples; lighting %s\n",
                 c.scene.empty() ? "default scene" : c.scene.c_str(), r.vertices, r.triangles, c.bake.transfer.order,
                 c.bake.transfer.samples, describeLighting(r.lighting).c_str());
    if (r.texels) {
      const std::size_t n = r.texels->atlases.size();
      std::fprintf(err, "prt-bake: texture sets: %zu atlas%s: %s\n", n, n == 1 ? "" : "es", r.texels->sets.c_str());
    }
  };
  bake::AssetBakeReport report;
  std::vector<std::uint8_t> bytes;
  {
    BakedAsset asset;
    const Status baked = bake::bakeAsset(std::move(scene), c.bake, &asset, &report, started);
    bar.finish();
    if (!baked.isOk()) return reportFailure(err, "", baked);
    if (report.texels && !c.quiet) {
      const bake::TexelBakeReport& t = *report.texels;
      if (t.atlases.size() == 1) {
        std::fprintf(err, "prt-bake: transfer textures: %s, %dx%d atlas, %llu of %llu texels sampled, %zu charts\n",
                     describeAtlas(t.atlases[0]).c_str(), t.size, t.size, static_cast<unsigned long long>(t.sampledTexels),
                     static_cast<unsigned long long>(t.texels), t.charts);
      } else {
        std::fprintf(err, "prt-bake: transfer textures: %zu atlases (%s), %llu of %llu texels sampled, %zu charts\n",
                     t.atlases.size(), t.sets.c_str(), static_cast<unsigned long long>(t.sampledTexels),
                     static_cast<unsigned long long>(t.texels), t.charts);
        for (std::size_t a = 0; a < t.atlases.size(); ++a) {
          const bake::TexelAtlasReport& x = t.atlases[a];
          std::fprintf(err, "prt-bake: atlas %zu: %s: %s, %dx%d, %zu triangles, %llu texels sampled, %.3g texels/m\n", a,
                       x.object.c_str(), describeAtlas(x).c_str(), x.size, x.size, x.triangles,
                       static_cast<unsigned long long>(x.sampledTexels), x.texelsPerMetre);
        }
      }
      for (const std::string& line : t.rejected) std::fprintf(err, "prt-bake: not used: %s\n", line.c_str());
      if (t.normalMappedTexels > 0) {
        std::fprintf(err, "prt-bake: transfer textures: %zu texels shaded with normal maps\n", t.normalMappedTexels);
      }
      if (t.visibilityOrder > 0) {
        // 2n - 1 bands make TPFL exact; fewer are the economy form (docs/transfer-textures.md).
        const int exact = 2 * c.bake.transfer.order - 1;
        std::fprintf(err, "prt-bake: transfer textures: TPFL glossy visibility, order %d (%d coefficients a texel; %s)\n",
                     t.visibilityOrder, t.visibilityOrder * t.visibilityOrder,
                     t.visibilityOrder >= exact ? "exact for this lighting order"
                                                : ("approximate: exact needs " + std::to_string(exact)).c_str());
      }
    }
    if (report.verticesOutsideLight > 0 && !c.quiet) {
      std::fprintf(err,
                   "prt-bake: warning: %zu of %zu vertices lie outside the lighting sphere (%s); their rays that "
                   "miss it receive no light\n",
                   report.verticesOutsideLight, report.vertices, describeLighting(report.lighting).c_str());
    }
    if (c.bake.biScale && !c.quiet) {
      const auto& b = *c.bake.biScale;
      if (b.synthesised) {
        const std::string where = report.idMapSize > 0 ? std::to_string(report.idMapSize) + "x" + std::to_string(report.idMapSize) + " atlas"
                                                       : std::string("per triangle");
        std::fprintf(err, "prt-bake: bi-scale: %s (%zu bytes), synthesised id map: %zu cells of %g patches %g m wide, %s\n",
                     describeRtt(b.rtt).c_str(), b.rtt.size(), report.placements, b.synthesised->cellPatches, b.synthesised->patchWidth,
                     where.c_str());
      } else {
        std::fprintf(err, "prt-bake: bi-scale: %s (%zu bytes), %g patches per UV unit; %zu vertices with no UV direction\n",
                     describeRtt(b.rtt).c_str(), b.rtt.size(), b.placement.patchesPerUv, report.tangentFallbacks);
      }
    }
    if (c.bake.compress && !c.quiet) {
      const std::string setting = transferSettingName(*c.bake.compress) +
                                  (c.bake.compressMatrices ? ", matrices " + transferSettingName(*c.bake.compressMatrices) : "");
      std::fprintf(err, "prt-bake: %s: %s\n", setting.c_str(), describeCompression(report.compressed).c_str());
    }
    if (Status s = encodeAsset(asset, &bytes); !s.isOk()) return reportFailure(err, "", Status::error(s.code(), "cannot encode asset: " + s.message()));
  }
  if (Status s = writeFileAtomically(c.output, bytes, inputs); !s.isOk()) return reportFailure(err, "", s);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!c.quiet) {
    std::fprintf(err, "prt-bake: wrote %s (%zu bytes, %d bounces) in %.2f s, peak memory %.0f MiB\n", c.output.c_str(),
                 bytes.size(), report.bounces, total, peakMemoryMiB());
  }
  if (c.json) {
    std::string s = "{\n  \"scene\": " + jsonString(c.scene.empty() ? "default" : c.scene) + ",\n";
    s += "  \"output\": " + jsonString(c.output) + ",\n";
    s += "  \"bytes\": " + std::to_string(bytes.size()) + ",\n";
    s += "  \"vertices\": " + std::to_string(report.vertices) + ",\n";
    s += "  \"triangles\": " + std::to_string(report.triangles) + ",\n";
    s += "  \"order\": " + std::to_string(c.bake.transfer.order) + ",\n";
    s += "  \"samples\": " + std::to_string(c.bake.transfer.samples) + ",\n";
    s += "  \"bounces\": " + std::to_string(report.bounces) + ",\n";
    s += "  \"glossy\": " + std::string(c.bake.transfer.glossy ? "true" : "false") + ",\n";
    s += "  \"glossy_bounces\": " + std::to_string(report.glossyBounces) + ",\n";
    if (c.bake.biScale) {
      s += "  \"bi_scale\": {\"rtt_bytes\": " + std::to_string(c.bake.biScale->rtt.size()) +
           ", \"patches_per_uv\": " + jsonNumber(c.bake.biScale->placement.patchesPerUv) +
           ", \"tangent_fallbacks\": " + std::to_string(report.tangentFallbacks) +
           ", \"id_map\": " + jsonString(c.bake.biScale->synthesised ? "synthesised" : "parametric") +
           ", \"placements\": " + std::to_string(report.placements) + "},\n";
    }
    const LightingInfo& l = report.lighting;
    s += "  \"lighting\": {\"model\": " + jsonString(lightingModelName(l.model));
    if (isLocalLighting(l.model)) {
      s += ", \"center\": [" + jsonNumber(l.center.x) + ", " + jsonNumber(l.center.y) + ", " + jsonNumber(l.center.z) +
           "], \"radius\": " + jsonNumber(l.radius) + ", \"vertices_outside\": " + std::to_string(report.verticesOutsideLight);
    }
    s += "},\n";
    if (report.texels) {
      const bake::TexelBakeReport& t = *report.texels;
      const bool generated = t.atlases.size() == 1 && t.atlases[0].generated;
      s += "  \"texels\": {\"texcoord\": " + std::to_string(t.texcoord) +
           ", \"atlas\": " + jsonString(generated ? "generated" : t.texcoord < 0 ? "mixed" : "TEXCOORD_" + std::to_string(t.texcoord)) +
           ", \"sets\": " + jsonString(t.sets) + ", \"atlases\": [";
      for (std::size_t a = 0; a < t.atlases.size(); ++a) {
        const bake::TexelAtlasReport& x = t.atlases[a];
        s += std::string(a ? ", " : "") + "{\"object\": " + jsonString(x.object) +
             ", \"uv\": " + jsonString(x.generated ? "generated" : "TEXCOORD_" + std::to_string(x.texcoord)) +
             ", \"size\": " + std::to_string(x.size) + ", \"triangles\": " + std::to_string(x.triangles) +
             ", \"charts\": " + std::to_string(x.charts) + ", \"sampled\": " + std::to_string(x.sampledTexels) +
             ", \"texels_per_metre\": " + jsonNumber(x.texelsPerMetre) + "}";
      }
      s += "]";
      if (t.generated) {
        const bake::UvUnwrapReport& g = *t.generated;
        s += ", \"unwrap\": {\"attempts\": " + std::to_string(g.attempts.size()) +
             ", \"margin\": " + jsonNumber(g.attempts.back().margin) + ", \"seconds\": " + jsonNumber(g.seconds) + "}";
      }
      s += ", \"size\": " + std::to_string(t.size) +
           ", \"texels\": " + std::to_string(t.texels) + ", \"sampled\": " + std::to_string(t.sampledTexels) +
           ", \"charts\": " + std::to_string(t.charts) + ", \"normal_mapped\": " + std::to_string(t.normalMappedTexels) +
           ", \"bounces\": " + std::to_string(t.bounces) + ", \"visibility_order\": " + std::to_string(t.visibilityOrder) +
           ", \"passes\": [";
      for (std::size_t i = 0; i < t.passes.size(); ++i) {
        s += std::string(i ? ", " : "") + "{\"name\": " + jsonString(t.passes[i].name) +
             ", \"seconds\": " + jsonNumber(t.passes[i].seconds) + ", \"rays\": " + std::to_string(t.passes[i].rays) + "}";
      }
      s += "]},\n";
    }
    s += "  \"bounce_energy\": [";
    const std::vector<double>& energy = report.bounceEnergy;
    for (std::size_t i = 0; i < energy.size(); ++i) s += (i ? ", " : "") + jsonNumber(energy[i]);
    s += "],\n  \"passes\": [\n";
    const std::vector<bake::PassStats>& passes = report.passes;
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

bake::Scene defaultSceneFor(const bake::AssetBakeOptions& options) {
  // The built-in atlas's gutters follow the side it is baked at (texels per unit: the default).
  const auto& t = options.texels;
  return t && t->textureSize > 0 ? bake::makeDefaultScene(t->textureSize, t->padding) : bake::makeDefaultScene();
}

}  // namespace prt
