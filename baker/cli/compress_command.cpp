#include "baker/cli/compress_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "native/byte_compressors.h"
#include "baker/cli/report_failure.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "baker/cli/compress_lightings.h"
#include "baker/cli/rate_distortion_svg.h"
#include "baker/texture/asset_texels.h"
#include "native/file_io.h"
#include "native/json_text.h"
#include "prt/asset.h"
#include "prt/exit_radiance.h"
#include "prt/glossy_codec_weights.h"
#include "prt/glossy_radiance.h"
#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"

namespace prt {
namespace {

constexpr std::uint64_t kMaxAssetFileBytes = std::uint64_t{16} << 30;
constexpr const char* kDefaultEnvDir = "/usr/share/blender/datafiles/studiolights/world";
constexpr const char* kDefaultSettings = "f32,f16,q16,q8,cpca16,cpca8";
constexpr double kDefaultQuality = 0.02;
// Vertices whose reference radiance is below this fraction of the peak are left out of the
// maximum relative error (near-black vertices would make it meaningless).
constexpr double kRelativeErrorFloor = 0.01;

constexpr FlagSpec kFlags[] = {{"--json", false},     {"--settings", true}, {"--quality", true},
                               {"--pass", true},      {"--env-dir", true},  {"--max-clusters", true},
                               {"--per-lighting", false}, {"--save-blobs", true}, {"--views", true},
                               {"--lightings", true}, {"--texels", false}, {"--matrix-metric", true},
                               {"--svg", true}};

struct Options {
  std::string asset;
  std::vector<TransferCodecSettings> settings;
  std::optional<TransferKind> pass;
  bool glossy = false;    // a matrix pass: exit radiance over lightings x views
  bool texels = false;    // the texel pass (transfer textures): error over its sampled texels
  int views = 16;         // eye positions for matrix passes
  // Matrix CPCA's error metric: rows weighted by the asset's sharpest glossy lobe (the
  // exit-radiance metric, prt/glossy_codec_weights.h), or plain (unweighted).
  bool lobeMetric = true;
  int maxLightings = 0;   // 0: every test lighting
  std::string envDir = kDefaultEnvDir;
  bool json = false;
  bool perLighting = false;
  std::string saveBlobs;  // directory for each setting's blob, or empty
  std::string svg;        // the rate-distortion plot's path, or empty
};

Status usage(std::string message) { return usageError(std::move(message)); }

Status parseOptions(std::span<const std::string> args, Options* o) {
  ParsedArgs p;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return s;
  if (p.positionals.size() != 1) return usage(p.positionals.empty() ? "missing ASSET" : "expected one ASSET");
  o->asset = p.positionals[0];
  o->json = p.has("--json");
  o->perLighting = p.has("--per-lighting");
  o->texels = p.has("--texels");
  TransferCodecSettings defaults;
  defaults.cpcaTargetError = kDefaultQuality;
  if (const std::string* q = p.value("--quality")) {
    float quality = 0.0f;
    if (Status s = parseFloatArg("--quality", *q, 0.0f, 1.0f, &quality); !s.isOk()) return s;
    if (!(quality > 0.0f && quality < 1.0f)) return usage("--quality must be a relative error in (0, 1), e.g. 0.02");
    defaults.cpcaTargetError = quality;
  }
  if (const std::string* m = p.value("--max-clusters")) {
    if (Status s = parseIntArg("--max-clusters", *m, 1, static_cast<int>(kMaxTransferClusters), &defaults.cpcaMaxClusters);
        !s.isOk()) {
      return s;
    }
  }
  const std::string list = p.value("--settings") ? *p.value("--settings") : kDefaultSettings;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    TransferCodecSettings s;
    if (Status st = parseTransferSetting(std::string_view(list).substr(start, comma - start), defaults, &s); !st.isOk()) {
      return usage("--settings: " + st.message());
    }
    o->settings.push_back(s);
    start = comma + 1;
  }
  if (const std::string* ps = p.value("--pass")) {
    std::string kind = *ps;
    if (kind.rfind("glossy", 0) == 0) {
      o->glossy = true;
      kind = kind == "glossy" ? "" : kind.substr(7);
    }
    if (kind == "unshadowed" && !o->glossy) o->pass = TransferKind::kUnshadowed;
    else if (kind == "shadowed") o->pass = TransferKind::kShadowed;
    else if (kind == "interreflected") o->pass = TransferKind::kInterreflected;
    else if (!(kind.empty() && o->glossy)) {
      return usage("unknown --pass '" + *ps + "' (expected unshadowed, shadowed, interreflected, glossy, glossy-shadowed "
                   "or glossy-interreflected)");
    }
  }
  if (o->texels && o->glossy) return usage("--texels measures vector passes; transfer textures have no glossy matrices");
  if (const std::string* v = p.value("--views")) {
    if (!o->glossy) return usage("--views needs a glossy --pass");
    if (Status s = parseIntArg("--views", *v, 1, 1024, &o->views); !s.isOk()) return s;
  }
  if (const std::string* m = p.value("--matrix-metric")) {
    if (!o->glossy) return usage("--matrix-metric needs a glossy --pass");
    if (*m != "lobe" && *m != "plain") return usage("unknown --matrix-metric '" + *m + "' (expected lobe or plain)");
    o->lobeMetric = *m == "lobe";
  }
  if (const std::string* v = p.value("--lightings")) {
    if (Status s = parseIntArg("--lightings", *v, 1, 1 << 20, &o->maxLightings); !s.isOk()) return s;
  }
  if (const std::string* d = p.value("--env-dir")) o->envDir = *d;
  if (const std::string* d = p.value("--save-blobs")) {
    if (d->empty()) return usage("--save-blobs needs a directory");
    o->saveBlobs = *d;
  }
  if (const std::string* f = p.value("--svg")) {
    if (f->empty()) return usage("--svg needs a file name");
    o->svg = *f;
  }
  return Status::ok();
}

// Exit radiance of every vertex and channel ([vertex][rgb]) of `transfer` under `light`,
// summed in double (prt/exit_radiance.h).
Status passExitRadiance(const TransferPass& pass, std::span<const float> transfer, const std::vector<Rgb>& albedo, int order,
                        const std::vector<Rgb>& light, std::vector<double>* out) {
  out->assign(albedo.size() * 3, 0.0);
  return exitRadianceDouble(transfer, pass.channels, static_cast<std::size_t>(order * order), albedo, light, *out);
}

// `count` eye positions spread evenly (Fibonacci sphere) at twice the bounding-sphere radius
// around the scene's bounds centre: the views a glossy pass is measured from.
std::vector<Vec3> testViews(const std::vector<Vec3>& positions, int count) {
  Vec3 lo = positions[0], hi = positions[0];
  for (const Vec3& p : positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const Vec3 centre = (lo + hi) * 0.5f;
  const float radius = std::max(length(hi - lo), 1e-3f);  // twice the half diagonal
  std::vector<Vec3> views;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / count, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * k;
    views.push_back(centre + Vec3{static_cast<float>(r * std::cos(phi)), static_cast<float>(z),
                                  static_cast<float>(r * std::sin(phi))} * radius);
  }
  return views;
}

struct LightingError {
  double psnrDb = 0.0;       // peak = max reference radiance; +inf when exact
  double maxRelError = 0.0;  // over vertex channels above kRelativeErrorFloor * peak
};

LightingError compareRadiance(const std::vector<double>& ref, const std::vector<double>& got) {
  double peak = 0.0, sum = 0.0;
  for (double x : ref) peak = std::max(peak, x);
  LightingError e;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double d = got[i] - ref[i];
    sum += d * d;
    if (ref[i] > kRelativeErrorFloor * peak) e.maxRelError = std::max(e.maxRelError, std::fabs(d) / ref[i]);
  }
  const double mse = sum / static_cast<double>(ref.size());
  e.psnrDb = mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
  return e;
}

struct Row {
  std::string setting;
  std::size_t bytes = 0, zstdBytes = 0, brotliBytes = 0;
  double psnrWorst = 0, psnrMean = 0, maxRelWorst = 0, maxRelMean = 0;
  double encodeSeconds = 0;
  TransferEncodeReport report;
  std::vector<LightingError> perLighting;  // with --per-lighting, in lighting order
  std::string error;                       // why the setting could not be encoded ("" if it was)
};

std::string perVertex(std::size_t bytes, std::size_t vertices) {
  char s[32];
  std::snprintf(s, sizeof s, "%.2f", static_cast<double>(bytes) / static_cast<double>(vertices));
  return s;
}

std::string vectorList(const std::vector<int>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(v[i]);
  }
  return s;
}

std::string formatJson(const Options& o, const TransferPass& pass, int order, std::size_t vertices, std::size_t sampled,
                       const std::vector<std::string>& names, const std::vector<Row>& rows) {
  const std::size_t lightings = names.size();
  const double V = static_cast<double>(vertices);
  // Texel mode counts bytes per texel of the whole atlases (what is stored and sent).
  const std::string per = o.texels ? "_per_texel" : "_per_vertex";
  std::string s = "{\n  \"asset\": " + jsonString(o.asset) + ",\n  \"pass\": \"" + (o.glossy ? "glossy-" : "") + transferKindName(pass.kind) +
                  "\",\n  \"domain\": \"" + (o.texels ? "texel" : "vertex") +
                  "\",\n  \"channels\": " + std::to_string(pass.channels) + ",\n  \"order\": " + std::to_string(order) +
                  (o.texels ? ",\n  \"texels\": " + std::to_string(vertices) + ",\n  \"sampled_texels\": " + std::to_string(sampled)
                            : ",\n  \"vertices\": " + std::to_string(vertices)) +
                  ",\n  \"lightings\": " + std::to_string(lightings) +
                  (o.glossy ? std::string(",\n  \"matrix_metric\": \"") + (o.lobeMetric ? "lobe" : "plain") + "\"" : std::string()) +
                  ",\n  \"zstd_level\": " + std::to_string(kReportZstdLevel) + ",\n  \"brotli_quality\": " +
                  std::to_string(kReportBrotliQuality) + ",\n  \"rows\": [\n";
  const Row* f16 = nullptr;
  for (const Row& r : rows) {
    if (r.setting == "f16") f16 = &r;
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    if (!r.error.empty()) {
      s += "    {\"setting\": " + jsonString(r.setting) + ", \"error\": " + jsonString(r.error) + "}" + (i + 1 < rows.size() ? ",\n" : "\n");
      continue;
    }
    s += "    {\"setting\": " + jsonString(r.setting) + ", \"bytes\": " + std::to_string(r.bytes) +
         ", \"bytes" + per + "\": " + jsonNumber(static_cast<double>(r.bytes) / V) +
         ", \"zstd_bytes\": " + std::to_string(r.zstdBytes) + ", \"zstd_bytes" + per + "\": " + jsonNumber(static_cast<double>(r.zstdBytes) / V) +
         ", \"brotli_bytes\": " + std::to_string(r.brotliBytes) +
         ", \"brotli_bytes" + per + "\": " + jsonNumber(static_cast<double>(r.brotliBytes) / V) +
         ", \"zstd_ratio_vs_f16\": " + (f16 ? jsonNumber(static_cast<double>(f16->zstdBytes) / static_cast<double>(r.zstdBytes)) : "null") +
         ", \"psnr_db\": " + jsonNumber(r.psnrWorst) + ", \"psnr_db_mean\": " + jsonNumber(r.psnrMean) +
         ", \"max_rel_error\": " + jsonNumber(r.maxRelWorst) + ", \"max_rel_error_mean\": " + jsonNumber(r.maxRelMean) +
         ", \"transfer_rel_error\": " + jsonNumber(r.report.relativeError) +
         ", \"clusters\": " + std::to_string(r.report.clusters) + ", \"vectors_per_band\": [" + vectorList(r.report.vectorsPerBand) +
         "], \"encode_seconds\": " + jsonNumber(r.encodeSeconds);
    if (!r.perLighting.empty()) {
      s += ", \"per_lighting\": [";
      for (std::size_t j = 0; j < r.perLighting.size(); ++j) {
        s += std::string(j ? ", " : "") + "{\"lighting\": " + jsonString(names[j]) + ", \"psnr_db\": " +
             jsonNumber(r.perLighting[j].psnrDb) + ", \"max_rel_error\": " + jsonNumber(r.perLighting[j].maxRelError) + "}";
      }
      s += "]";
    }
    s += std::string("}") + (i + 1 < rows.size() ? ",\n" : "\n");
  }
  return s + "  ]\n}\n";
}

std::string formatTable(const Options& o, const TransferPass& pass, int order, std::size_t vertices, std::size_t sampled,
                        const std::vector<std::string>& names, const std::vector<Row>& rows) {
  const std::size_t lightings = names.size();
  const std::string rowsText = o.texels ? std::to_string(vertices) + " texels (" + std::to_string(sampled) + " sampled, where the error is measured)"
                                        : std::to_string(vertices) + " vertices";
  std::string s = o.asset + ": " + (o.texels ? "texel " : "") + transferKindName(pass.kind) + (o.glossy ? " glossy matrix" : "") + " transfer, " + std::to_string(pass.channels) + " channel(s), order " +
                  std::to_string(order) + ", " + rowsText + "; " + std::to_string(lightings) +
                  (o.glossy ? " test lighting x view cases" : " test lightings") + " (PSNR: peak = max reference radiance; max rel: " +
                  (o.texels ? "texels" : "vertices") + " above 1% of peak)\n";
  char line[320];
  std::snprintf(line, sizeof line, "%-14s %9s %9s %9s %7s %9s %9s %9s %9s %9s %8s %-14s %8s\n", "setting", o.texels ? "B/texel" : "B/vtx", "zstd-19",
                "brotli", "x f16z", "PSNR min", "PSNR avg", "rel max", "rel avg", "T rel", "clusters", "vectors/band", "enc s");
  s += line;
  const Row* f16 = nullptr;
  for (const Row& r : rows) {
    if (r.setting == "f16") f16 = &r;
  }
  for (const Row& r : rows) {
    if (!r.error.empty()) {
      s += r.setting + std::string(std::max<std::size_t>(15, r.setting.size() + 1) - r.setting.size(), ' ') + "not encoded: " + r.error + "\n";
      continue;
    }
    const std::string ratio = f16 ? perVertex(f16->zstdBytes, r.zstdBytes) : "-";
    std::snprintf(line, sizeof line, "%-14s %9s %9s %9s %7s %9.2f %9.2f %9.5f %9.5f %9.5f %8d %-14s %8.2f\n", r.setting.c_str(),
                  perVertex(r.bytes, vertices).c_str(), perVertex(r.zstdBytes, vertices).c_str(),
                  perVertex(r.brotliBytes, vertices).c_str(), ratio.c_str(), r.psnrWorst, r.psnrMean, r.maxRelWorst, r.maxRelMean,
                  r.report.relativeError, r.report.clusters, r.report.vectorsPerBand.empty() ? "-" : vectorList(r.report.vectorsPerBand).c_str(),
                  r.encodeSeconds);
    s += line;
    for (std::size_t j = 0; j < r.perLighting.size(); ++j) {
      std::snprintf(line, sizeof line, "    %-34s PSNR %9.2f  rel max %9.5f\n", names[j].c_str(), r.perLighting[j].psnrDb,
                    r.perLighting[j].maxRelError);
      s += line;
    }
  }
  return s;
}

// The rate-distortion plot of the encoded rows (bake::rateDistortionSvg); rows that could
// not be encoded are listed under it with the reason.
std::string formatSvg(const Options& o, const TransferPass& pass, std::size_t vertices, const std::vector<Row>& rows) {
  bake::RdPlot plot;
  plot.title = o.asset + ": " + (o.texels ? "texel " : "") + transferKindName(pass.kind) + (o.glossy ? " glossy matrix" : "") +
               " transfer";
  plot.unit = o.texels ? "texel" : "vertex";
  for (const Row& r : rows) {
    if (!r.error.empty()) {
      plot.notEncoded.push_back(r.setting + ": " + r.error);
      continue;
    }
    plot.points.push_back({r.setting, static_cast<double>(r.bytes) / static_cast<double>(vertices), r.psnrWorst});
  }
  return bake::rateDistortionSvg(plot);
}

}  // namespace

const char* compressReportHelpText() {
  return "Usage: prt-bake compress-report ASSET [options]\n"
         "\n"
         "Encodes the asset's transfer with each transfer-codec setting and reports its size\n"
         "(bytes per vertex: raw, zstd -19, brotli 11) and its exit-radiance error against the\n"
         "uncompressed transfer under fixed test lightings: every environment map in --env-dir\n"
         "at 4 rotations, and 6 small caps. Per setting: the worst (and mean) over lightings of\n"
         "PSNR (peak = the lighting's max reference radiance) and of the max relative error over\n"
         "vertices brighter than 1% of the peak. docs/transfer-codec.md.\n"
         "\n"
         "Options:\n"
         "  --settings LIST     comma-separated: f32, f16, q16, q8, cpca8, cpca16, the CPCA ones\n"
         "                      optionally with a target, cpca8@0.01\n"
         "                      (default f32,f16,q16,q8,cpca16,cpca8)\n"
         "  --quality Q         CPCA target relative RMS transfer error where no @ is given\n"
         "                      (default 0.02)\n"
         "  --max-clusters N    CPCA cluster-count limit (default 256)\n"
         "  --pass P            unshadowed, shadowed or interreflected (default: the richest stored);\n"
         "                      glossy-shadowed, glossy-interreflected or glossy (the richest): a\n"
         "                      glossy matrix pass, measured by its glossy exit radiance over every\n"
         "                      lighting seen from each of --views eyes\n"
         "  --views N           eyes for a glossy pass, spread over a sphere twice the scene's size\n"
         "                      (default 16)\n"
         "  --matrix-metric M   a glossy pass's CPCA error metric: lobe (rows weighted by the\n"
         "                      asset's sharpest glossy lobe, the exit-radiance metric; default)\n"
         "                      or plain (unweighted)\n"
         "  --lightings N       use only the first N test lightings (default: all)\n"
         "  --texels            measure the asset's texel pass (transfer textures) instead: bytes per\n"
         "                      texel of all its atlases, error over the sampled texels\n"
         "  --env-dir DIR       directory of .exr environment maps\n"
         "                      (default /usr/share/blender/datafiles/studiolights/world)\n"
         "  --per-lighting      also list PSNR and max relative error of every lighting\n"
         "  --save-blobs DIR    also write each setting's transfer blob to DIR/SETTING.prtt\n"
         "                      (DIR must exist; for benchmarks of the decoder)\n"
         "  --json              one JSON object instead of a table\n"
         "  --svg FILE          also write the rate-distortion plot (raw bytes per vertex, log\n"
         "                      scale, against worst-lighting PSNR; the 40 dB line) to FILE, an\n"
         "                      SVG any browser shows; replaced atomically\n"
         "  -h, --help          show this help\n"
         "\n"
         "A CPCA target a setting cannot reach makes that row say why (JSON: \"error\") and the\n"
         "report goes on with the other settings; it fails (status 4) only when no setting could\n"
         "be encoded.\n";
}

int runCompressReportCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(compressReportHelpText(), out);
    std::fputs("\n", out);
    std::fputs(exitStatusHelp(), out);
    return kExitOk;
  }
  Options o;
  if (Status s = parseOptions(args, &o); !s.isOk()) return reportFailure(err, "compress-report", s);
  if (!o.svg.empty()) {
    // A bad --svg fails before the encoding work, not after it.
    const std::string inputs[] = {o.asset};
    if (Status s = checkOutputPath(o.svg, inputs); !s.isOk()) return reportFailure(err, "compress-report", s);
  }

  std::vector<std::uint8_t> bytes;
  if (Status s = readFileBytes(o.asset, kMaxAssetFileBytes, &bytes); !s.isOk()) return reportFailure(err, "compress-report", s);
  BakedAsset asset;
  if (Status s = decodeAsset(bytes, &asset); !s.isOk()) return reportFailure(err, "compress-report", Status::error(s.code(), "'" + o.asset + "': " + s.toString()));
  bytes = {};
  const TransferForm form = o.glossy ? TransferForm::kMatrix : TransferForm::kVector;
  const TransferDomain domain = o.texels ? TransferDomain::kTexel : TransferDomain::kVertex;
  const char* domainText = o.texels ? " texel" : "";
  const TransferPass* pass = nullptr;
  if (o.pass) {
    pass = findPass(asset, *o.pass, form, domain);
    if (!pass) {
      return reportFailure(err, "compress-report", Status::error(StatusCode::kInvalidArgument, "'" + o.asset + "' has no" +
                                                                                                   domainText + " " +
                                                                                                   transferKindName(*o.pass) +
                                                                                                   (o.glossy ? " glossy matrix" : "") + " pass"));
    }
  } else {
    for (TransferKind k : {TransferKind::kInterreflected, TransferKind::kShadowed, TransferKind::kUnshadowed}) {
      if (!pass) pass = findPass(asset, k, form, domain);
    }
    if (!pass) {
      return reportFailure(err, "compress-report", Status::error(StatusCode::kInvalidArgument, "'" + o.asset + "' has no" +
                                                                                                   domainText + " " +
                                                                                                   (o.glossy ? "glossy matrix pass" : "transfer pass")));
    }
  }
  const int order = asset.shOrder;
  // Texel mode: rows are every texel of the atlases (what the codec encodes); the error is
  // measured at the sampled ones, each with its sample's albedo (gutters only serve filtering).
  std::vector<bake::AtlasTexel> samples;
  std::vector<Rgb> sampleAlbedo;
  if (o.texels) {
    if (Status s = bake::assetTexelSamples(asset, &samples); !s.isOk()) return reportFailure(err, "compress-report", s);
    for (const bake::AtlasTexel& t : samples) sampleAlbedo.push_back(t.albedo);
  }
  const std::size_t vertices = o.texels ? static_cast<std::size_t>(assetTexelCount(asset)) : asset.positions.size();
  const std::size_t rowFloats = static_cast<std::size_t>(pass->channels) * static_cast<std::size_t>(order * order);
  // Texel mode measures the sampled texels' rows only: gathered once per transfer, not per lighting.
  const auto measuredRows = [&](std::span<const float> transfer, std::vector<float>* rows) -> std::span<const float> {
    if (!o.texels) return transfer;
    rows->resize(samples.size() * rowFloats);
    for (std::size_t r = 0; r < samples.size(); ++r) {
      std::copy_n(&transfer[samples[r].index * rowFloats], rowFloats, &(*rows)[r * rowFloats]);
    }
    return *rows;
  };
  const MatrixPacking packing = matrixPackingFor(pass->kind, asset.lighting.model);
  // Matrix CPCA fits in the exit-radiance metric of the asset's lobes (empty: unweighted).
  std::vector<double> rowWeights;
  if (o.glossy && o.lobeMetric) {
    if (Status s = glossyMatrixRowWeights(order, asset.specular, &rowWeights); !s.isOk()) return reportFailure(err, "compress-report", s);
  }

  std::vector<TestLighting> lightings;
  if (Status s = makeTestLightings(o.envDir, order, &lightings); !s.isOk()) return reportFailure(err, "compress-report", s);
  if (o.maxLightings > 0 && lightings.size() > static_cast<std::size_t>(o.maxLightings)) lightings.resize(static_cast<std::size_t>(o.maxLightings));
  // Vector passes: one case per lighting. Matrix passes: one per (lighting, view), the glossy
  // term alone, since the diffuse term does not depend on the matrix codec.
  const std::vector<Vec3> views = o.glossy ? testViews(asset.positions, o.views) : std::vector<Vec3>{Vec3{}};
  const auto evaluate = [&](std::span<const float> transfer, std::size_t lighting, std::size_t view,
                            std::vector<double>* radiance) -> Status {
    if (o.texels) return passExitRadiance(*pass, transfer, sampleAlbedo, order, lightings[lighting].coeffs, radiance);
    if (!o.glossy) return passExitRadiance(*pass, transfer, asset.albedo, order, lightings[lighting].coeffs, radiance);
    radiance->assign(vertices * 3, 0.0);
    return glossyExitRadianceDouble(transfer, order, packing, pass->channels, asset.positions, asset.normals, asset.specular,
                                    GlossyView{views[view], true}, lightings[lighting].coeffs, *radiance);
  };
  std::vector<std::string> names;
  std::vector<std::vector<double>> reference;
  std::vector<float> referenceGathered, decodedGathered;
  const std::span<const float> referenceRows = measuredRows(pass->coeffs, &referenceGathered);
  for (std::size_t i = 0; i < lightings.size(); ++i) {
    for (std::size_t v = 0; v < views.size(); ++v) {
      names.push_back(o.glossy ? lightings[i].name + " view " + std::to_string(v) : lightings[i].name);
      reference.emplace_back();
      if (Status s = evaluate(referenceRows, i, v, &reference.back()); !s.isOk()) return reportFailure(err, "compress-report", s);
    }
  }

  std::vector<Row> rows;
  Status lastError = Status::ok();  // of the last setting that could not be encoded
  std::vector<float> decoded(pass->coeffs.size());
  std::vector<double> radiance;
  for (TransferCodecSettings setting : o.settings) {
    if (o.glossy && setting.encoding == TransferEncoding::kCpca) setting.cpcaMatrixRowWeights = rowWeights;
    Row r;
    r.setting = transferSettingName(setting);
    std::fprintf(err, "prt-bake: note: encoding %s...\n", r.setting.c_str());
    std::vector<std::uint8_t> blob;
    const auto start = std::chrono::steady_clock::now();
    const Status encoded = o.glossy ? encodeTransferMatrix(pass->coeffs, order, packing, pass->channels, setting, &blob, &r.report)
                                    : encodeTransfer(pass->coeffs, order, pass->channels, setting, &blob, &r.report);
    if (!encoded.isOk()) {
      // A target this setting cannot reach is a finding of the report, not a failure of it:
      // the row says so and the other settings are still measured.
      if (encoded.code() != StatusCode::kInvalidArgument) {
        return reportFailure(err, "compress-report", Status::error(encoded.code(), r.setting + ": " + encoded.message()));
      }
      std::fprintf(err, "prt-bake: note: %s: %s\n", r.setting.c_str(), encoded.message().c_str());
      r.error = encoded.message();
      lastError = Status::error(encoded.code(), r.setting + ": " + encoded.message());
      rows.push_back(std::move(r));
      continue;
    }
    r.encodeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Status decodedOk = o.glossy ? decodeTransferMatrix(blob, order, std::span<float>(decoded))
                                      : decodeTransfer(blob, order, std::span<float>(decoded));
    if (Status s = decodedOk; !s.isOk()) {
      return reportFailure(err, "compress-report", Status::error(StatusCode::kInternal, r.setting + ": the blob does not decode: " + s.toString()));
    }
    r.bytes = blob.size();
    if (!o.saveBlobs.empty()) {
      const std::string path = o.saveBlobs + "/" + r.setting + ".prtt";
      const std::string inputs[] = {o.asset};
      if (Status s = writeFileAtomically(path, blob, inputs); !s.isOk()) return reportFailure(err, "compress-report", s);
    }
    if (Status s = zstdCompressedSize(blob, kReportZstdLevel, &r.zstdBytes); !s.isOk()) return reportFailure(err, "compress-report", s);
    if (Status s = brotliCompressedSize(blob, kReportBrotliQuality, kReportBrotliWindow, &r.brotliBytes); !s.isOk()) {
      return reportFailure(err, "compress-report", s);
    }
    r.psnrWorst = std::numeric_limits<double>::infinity();
    double psnrSum = 0.0;
    std::size_t finite = 0;
    const std::span<const float> decodedRows = measuredRows(decoded, &decodedGathered);
    for (std::size_t i = 0; i < reference.size(); ++i) {
      if (Status s = evaluate(decodedRows, i / views.size(), i % views.size(), &radiance); !s.isOk()) {
        return reportFailure(err, "compress-report", s);
      }
      const LightingError e = compareRadiance(reference[i], radiance);
      if (o.perLighting) r.perLighting.push_back(e);
      r.psnrWorst = std::min(r.psnrWorst, e.psnrDb);
      if (std::isfinite(e.psnrDb)) {
        psnrSum += e.psnrDb;
        ++finite;
      }
      r.maxRelWorst = std::max(r.maxRelWorst, e.maxRelError);
      r.maxRelMean += e.maxRelError / static_cast<double>(reference.size());
    }
    r.psnrMean = finite == reference.size() ? psnrSum / static_cast<double>(finite) : std::numeric_limits<double>::infinity();
    rows.push_back(std::move(r));
  }
  if (std::all_of(rows.begin(), rows.end(), [](const Row& r) { return !r.error.empty(); })) {
    return reportFailure(err, "compress-report", lastError);
  }
  const std::string text = o.json ? formatJson(o, *pass, order, vertices, samples.size(), names, rows)
                                  : formatTable(o, *pass, order, vertices, samples.size(), names, rows);
  if (!o.svg.empty()) {
    const std::string svg = formatSvg(o, *pass, vertices, rows);
    const std::string inputs[] = {o.asset};
    const auto* data = reinterpret_cast<const std::uint8_t*>(svg.data());
    if (Status s = writeFileAtomically(o.svg, std::span<const std::uint8_t>(data, svg.size()), inputs); !s.isOk()) {
      return reportFailure(err, "compress-report", s);
    }
  }
  std::fputs(text.c_str(), out);
  return kExitOk;
}

}  // namespace prt
