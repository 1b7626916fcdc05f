#include "baker/cli/shard_commands.h"

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <unistd.h>

#include <vector>
#include <optional>

#include "baker/cli/bake_command.h"
#include "baker/cli/progress_bar.h"
#include "baker/cli/report_failure.h"
#include "baker/scene/default_scene.h"
#include "baker/scene/glossy_materials.h"
#include "baker/scene/gltf_loader.h"
#include "baker/shard/bake_plan.h"
#include "baker/shard/plan_scene.h"
#include "baker/shard/sharded_bake.h"
#include "baker/shard/sharded_texels.h"
#include "baker/transfer/bake_asset.h"
#include "baker/transfer/texture_sets.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "native/file_io.h"
#include "native/json_text.h"
#include "prt/asset.h"

namespace prt {
namespace {

constexpr const char* kPlanHelp =
    "Usage: prt-bake plan SCENE.gltf|SCENE.glb|--default -o PLAN --shards N [bake options]\n"
    "\n"
    "Plans a bake split into N shards (docs/scale-out.md): records the scene, its hash, the bake\n"
    "options and N vertex ranges in PLAN. Then run, for each pass K = 0 .. passes-1,\n"
    "'prt-bake bake-shard --plan PLAN --shard I --pass K' for every I and 'prt-bake merge --plan\n"
    "PLAN --pass K', and finally 'prt-bake merge --plan PLAN -o ASSET' (scripts/slurm-bake.sh does\n"
    "this on Slurm). The asset is byte for byte the one of 'prt-bake SCENE -o ASSET [options]'.\n"
    "Bake options: those of 'prt-bake --default --help' (with --texels, the plan picks or generates\n"
    "the atlas once and splits its texel receivers too; normal-mapped scenes are not sharded yet).\n"
    "--json prints the plan's passes and shards on stdout.\n";

constexpr const char* kShardHelp =
    "Usage: prt-bake bake-shard --plan PLAN --shard I --pass K [--threads N] [--quiet]\n"
    "\n"
    "Bakes shard I (0-based) of pass K (0: the direct pass; K >= 1: bounce K, which reads merged\n"
    "pass K-1) and writes PLAN.passK.shardI atomically. When the bounce series ended before\n"
    "pass K it says so and writes nothing (exit 0).\n";

constexpr const char* kMergeHelp =
    "Usage: prt-bake merge --plan PLAN --pass K [--threads N] [--quiet]\n"
    "       prt-bake merge --plan PLAN -o ASSET [--json] [--quiet]\n"
    "\n"
    "--pass K: checks every shard of pass K (present, of this plan, checksums, ranges) and writes\n"
    "the merged pass PLAN.passK.merged that pass K+1 reads. -o: checks every shard and merged pass\n"
    "up to the last bounce and writes the asset. A missing or damaged file is named in the error.\n";

int printHelp(std::FILE* out, const char* text) {
  std::fputs(text, out);
  std::fputs("\n", out);
  std::fputs(exitStatusHelp(), out);
  return kExitOk;
}

// A texel bake of a normal-mapped scene: the prepared scene does not hold the normal maps
// (images and tangents) the texel receivers' shading normals come from. Bi-scale: not yet.
Status refuseUnsharded(const BakeCommandLine& c, const bake::Scene& scene) {
  if (c.bake.biScale) {
    return Status::error(StatusCode::kInvalidArgument,
                         "sharded bakes do not support --rtt yet (bi-scale, docs/bi-scale.md); bake it on one machine");
  }
  if (!c.bake.texels || std::none_of(scene.normalMapOf.begin(), scene.normalMapOf.end(), [](std::int32_t m) { return m >= 0; })) {
    return Status::ok();
  }
  return Status::error(StatusCode::kInvalidArgument,
                       "sharded bakes do not support --texels on a normal-mapped scene yet (the prepared scene does not "
                       "hold the normal maps: docs/scale-out.md); bake it on one machine");
}

// `files`: every file the load read (none for the built-in room).
Status loadScene(const std::string& path, const bake::AssetBakeOptions& options, bool quiet, std::FILE* err, bake::Scene* scene,
                 std::vector<bake::SceneFile>* files) {
  files->clear();
  if (path.empty()) {
    *scene = defaultSceneFor(options);
    return Status::ok();
  }
  std::vector<std::string> warnings;
  PRT_RETURN_IF_ERROR(bake::loadGltf(path, scene, &warnings, files));
  if (!quiet)
    for (const std::string& w : warnings) std::fprintf(err, "prt-bake: warning: %s\n", w.c_str());
  return Status::ok();
}

// The plan at `planPath`, its bake options re-parsed, the scene's files checked unchanged and
// the prepared scene `plan` stored read (no glTF load, no preparation: docs/scale-out.md).
struct LoadedPlan {
  bake::BakePlan plan;
  BakeCommandLine bake;
  bake::Scene scene;
  bake::BakeOptions transfer;
  std::optional<bake::TexelShardContext> texels;  // a texel plan's receivers, rasterised again (deterministic)
  bake::ShardContext context(const std::string& planPath) const {
    return {&plan, planPath, &scene, &transfer, texels ? &*texels : nullptr};
  }
};

// `needs`: what of a texel plan's receivers the command uses (sharded_texels.h).
Status loadPlan(const std::string& planPath, const ParsedArgs& p, bake::TexelNeeds needs, LoadedPlan* out) {
  std::vector<std::uint8_t> bytes;
  PRT_RETURN_IF_ERROR(readFileBytes(planPath, std::uint64_t{1} << 30, &bytes));
  if (Status s = bake::decodeBakePlan(bytes, &out->plan); !s.isOk()) {
    return Status::error(s.code(), "'" + planPath + "': " + s.message());
  }
  if (Status s = parseBakeCommandLine(out->plan.bakeArgs, &out->bake); !s.isOk()) {
    return Status::error(StatusCode::kCorrupt, "'" + planPath + "': its bake options do not parse: " + s.message());
  }
  if (const std::string* s = p.value("--threads")) {
    int v = 0;
    PRT_RETURN_IF_ERROR(parseIntArg("--threads", *s, 1, 1024, &v));
    out->bake.bake.transfer.threads = static_cast<unsigned>(v);
  }
  PRT_RETURN_IF_ERROR(bake::checkSceneFiles(out->plan));
  std::vector<bake::Uv> atlasUv;
  PRT_RETURN_IF_ERROR(bake::readPreparedScene(out->plan, planPath, &out->scene, &atlasUv));
  out->transfer = bake::vertexBakeOptions(out->bake.bake, out->scene);
  if (out->bake.bake.texels.has_value() != !out->plan.atlases.empty()) {
    return Status::error(StatusCode::kCorrupt, "'" + planPath + "': its bake options and its atlases disagree on --texels");
  }
  if (!out->plan.atlases.empty()) {
    out->texels.emplace();
    if (Status s = bake::prepareTexelShards(out->plan, out->scene, std::move(atlasUv),
                                            bake::texelBakeOptions(out->bake.bake, out->transfer), needs, &*out->texels);
        !s.isOk()) {
      return Status::error(s.code(), "'" + planPath + "': " + s.message());
    }
  }
  return Status::ok();
}

Status requiredPlan(const ParsedArgs& p, std::string* plan) {
  const std::string* s = p.value("--plan");
  if (!s || s->empty()) return usageError("missing --plan PLAN (written by 'prt-bake plan')");
  *plan = *s;
  return Status::ok();
}

Status parseIndex(const ParsedArgs& p, const char* flag, std::uint32_t* out) {
  const std::string* s = p.value(flag);
  if (!s) return usageError(std::string("missing ") + flag);
  int v = 0;
  PRT_RETURN_IF_ERROR(parseIntArg(flag, *s, 0, 1 << 30, &v));
  *out = static_cast<std::uint32_t>(v);
  return Status::ok();
}

}  // namespace

int runPlanCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) return printHelp(out, kPlanHelp);
  // --shards is the plan's own flag; everything else is the bake's, recorded as given.
  std::vector<std::string> bakeArgs;
  std::optional<std::string> shardsText;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--") {
      bakeArgs.insert(bakeArgs.end(), args.begin() + static_cast<std::ptrdiff_t>(i), args.end());
      break;
    }
    if (args[i] == "--shards" || args[i].rfind("--shards=", 0) == 0) {
      if (shardsText) return reportFailure(err, "plan", usageError("--shards given twice"));
      if (args[i] == "--shards") {
        if (i + 1 >= args.size()) return reportFailure(err, "plan", usageError("--shards needs a value"));
        shardsText = args[++i];
      } else {
        shardsText = args[i].substr(9);
      }
      continue;
    }
    bakeArgs.push_back(args[i]);
  }
  if (!shardsText) return reportFailure(err, "plan", usageError("missing --shards N (how many vertex ranges)"));
  int shards = 0;
  if (Status s = parseIntArg("--shards", *shardsText, 1, static_cast<int>(bake::kMaxShards), &shards); !s.isOk()) {
    return reportFailure(err, "plan", s);
  }
  BakeCommandLine c;
  if (Status s = parseBakeCommandLine(bakeArgs, &c); !s.isOk()) return reportFailure(err, "plan", s);
  std::vector<std::string> inputs;
  if (!c.scene.empty()) inputs.push_back(c.scene);
  if (Status s = checkOutputPath(c.output, inputs); !s.isOk()) return reportFailure(err, "plan", s);

  bake::BakePlan plan;
  char cwd[PATH_MAX];
  if (!getcwd(cwd, sizeof cwd)) {
    return reportFailure(err, "plan", Status::error(StatusCode::kIoError, "cannot read the working directory"));
  }
  plan.workingDirectory = cwd;
  if (!c.scene.empty()) {
    // Shards may run elsewhere in the shared filesystem: record where the scene is, absolutely.
    char real[PATH_MAX];
    if (!realpath(c.scene.c_str(), real)) {
      return reportFailure(err, "plan", Status::error(StatusCode::kNotFound, "'" + c.scene + "': no such scene file"));
    }
    plan.scenePath = real;
  }
  bake::Scene scene;
  if (Status s = loadScene(plan.scenePath, c.bake, c.quiet, err, &scene, &plan.sceneFiles); !s.isOk()) return reportFailure(err, "plan", s);
  if (Status s = refuseUnsharded(c, scene); !s.isOk()) return reportFailure(err, "plan", s);
  bake::BakeOptions transfer;
  bake::TextureSetPlan atlas;
  if (Status s = bake::prepareAssetScene(c.bake, &scene, &transfer, &atlas); !s.isOk()) return reportFailure(err, "plan", s);
  // A texel bake's atlas is picked (or generated) here, once: the shards read it from the plan
  // and the prepared scene, and rasterise the same receivers from it.
  std::vector<bake::Uv> atlasUv;
  std::uint64_t texelReceivers = 0;
  if (c.bake.texels) {
    plan.atlases = bake::texelAtlasesOf(atlas, scene.indices.size() / 3);
    atlasUv = scene.texcoord[atlas.texcoord];
    bake::TexelReceivers receivers;
    if (Status s = bake::prepareTexelReceivers(scene, atlasUv, plan.atlases, bake::texelBakeOptions(c.bake, transfer), &receivers);
        !s.isOk()) {
      return reportFailure(err, "plan", s);
    }
    texelReceivers = receivers.count();
  }
  plan.bakeArgs = bakeArgs;
  plan.sceneHash = bake::sceneHash(scene, atlasUv);
  plan.sceneName = scene.name;
  plan.vertices = scene.positions.size();
  plan.triangles = scene.indices.size() / 3;
  plan.order = static_cast<std::uint32_t>(transfer.order);
  plan.passes = bake::plannedPasses(transfer);
  if (Status s = bake::planRanges(plan.vertices, static_cast<std::uint32_t>(shards), &plan.shards); !s.isOk()) {
    return reportFailure(err, "plan", s);
  }
  if (c.bake.texels) {
    plan.texelReceivers = texelReceivers;
    if (Status s = bake::planRanges(texelReceivers, static_cast<std::uint32_t>(shards), &plan.texelShards, "texel receivers");
        !s.isOk()) {
      return reportFailure(err, "plan", s);
    }
  }
  const std::vector<std::uint8_t> bytes = bake::encodeBakePlan(&plan);
  // The prepared scene first: a plan on disk always has its scene (a scene without its plan
  // is never read).
  if (Status s = checkOutputPath(bake::preparedScenePath(c.output), inputs); !s.isOk()) return reportFailure(err, "plan", s);
  if (Status s = bake::writePreparedScene(plan, c.output, scene, atlasUv, inputs); !s.isOk()) return reportFailure(err, "plan", s);
  if (Status s = writeFileAtomically(c.output, bytes, inputs); !s.isOk()) return reportFailure(err, "plan", s);
  if (!c.quiet) {
    std::fprintf(err, "prt-bake: plan %s: %s, %llu vertices%s in %d shards, up to %u passes (plan id %08x)\n", c.output.c_str(),
                 plan.scenePath.empty() ? "default scene" : plan.scenePath.c_str(),
                 static_cast<unsigned long long>(plan.vertices),
                 c.bake.texels ? (" and " + std::to_string(texelReceivers) + " texel receivers").c_str() : "", shards, plan.passes,
                 plan.id);
  }
  if (c.json) {
    std::fprintf(out, "{\"plan\": %s, \"id\": \"%08x\", \"vertices\": %llu, \"texelReceivers\": %llu, \"shards\": %d, \"passes\": %u}\n",
                 jsonString(c.output).c_str(), plan.id, static_cast<unsigned long long>(plan.vertices),
                 static_cast<unsigned long long>(texelReceivers), shards, plan.passes);
  }
  return kExitOk;
}

int runBakeShardCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) return printHelp(out, kShardHelp);
  static constexpr FlagSpec kFlags[] = {{"--plan", true}, {"--shard", true}, {"--pass", true}, {"--threads", true}, {"--quiet", false}};
  ParsedArgs p;
  std::string planPath;
  std::uint32_t shard = 0, pass = 0;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return reportFailure(err, "bake-shard", s);
  if (!p.positionals.empty()) return reportFailure(err, "bake-shard", usageError("unexpected argument '" + p.positionals[0] + "'"));
  for (Status s : {requiredPlan(p, &planPath), parseIndex(p, "--shard", &shard), parseIndex(p, "--pass", &pass)}) {
    if (!s.isOk()) return reportFailure(err, "bake-shard", s);
  }
  const bool quiet = p.has("--quiet");
  LoadedPlan l;
  const bake::TexelNeeds needs = pass == 0 ? bake::TexelNeeds::kReceivers : bake::TexelNeeds::kSeams;
  if (Status s = loadPlan(planPath, p, needs, &l); !s.isOk()) return reportFailure(err, "bake-shard", s);
  bake::ProgressBar bar(err, !quiet);
  l.transfer.progress = [&bar](const bake::BakeProgress& pr) { bar.update(pr); };
  if (l.texels) l.texels->options = bake::texelBakeOptions(l.bake.bake, l.transfer);  // its bar too: "texel ..."
  const bake::ShardContext ctx = l.context(planPath);
  bool skipped = false;
  bake::PassStats stats;
  Status s = bake::bakeShard(ctx, pass, shard, &skipped, &stats);
  // The texel series (a texel plan) in its own files: it may go on after the vertex series ended, or stop before.
  if (s.isOk() && l.texels) {
    bool texelSkipped = false;
    bake::PassStats texelStats;
    s = bake::bakeTexelShard(ctx, pass, shard, &texelSkipped, &texelStats);
    skipped = skipped && texelSkipped;
    stats.seconds += texelStats.seconds;
  }
  bar.finish();
  if (!s.isOk()) return reportFailure(err, "bake-shard", s);
  if (!quiet) {
    if (skipped) {
      std::fprintf(err, "prt-bake: pass %u is not needed: the bounce series ended before it; nothing written\n", pass);
    } else {
      std::fprintf(err, "prt-bake: wrote %s (vertices %llu … %llu, %.2f s)\n", bake::shardPath(planPath, pass, shard).c_str(),
                   static_cast<unsigned long long>(l.plan.shards[shard].begin),
                   static_cast<unsigned long long>(l.plan.shards[shard].end), stats.seconds);
    }
  }
  return kExitOk;
}

int runMergeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) return printHelp(out, kMergeHelp);
  static constexpr FlagSpec kFlags[] = {{"--plan", true},    {"--pass", true}, {"-o", true},
                                        {"--output", true}, {"--threads", true}, {"--quiet", false}, {"--json", false}};
  ParsedArgs p;
  std::string planPath;
  if (Status s = parseArgs(args, kFlags, &p); !s.isOk()) return reportFailure(err, "merge", s);
  if (!p.positionals.empty()) return reportFailure(err, "merge", usageError("unexpected argument '" + p.positionals[0] + "'"));
  if (Status s = requiredPlan(p, &planPath); !s.isOk()) return reportFailure(err, "merge", s);
  const std::string* output = p.value("-o") ? p.value("-o") : p.value("--output");
  if (p.has("-o") && p.has("--output")) return reportFailure(err, "merge", usageError("give -o or --output, not both"));
  if (p.has("--pass") == (output != nullptr)) {
    return reportFailure(err, "merge", usageError("give --pass K (merge one pass) or -o ASSET (write the asset), not both or neither"));
  }
  const bool quiet = p.has("--quiet");
  if (output && output->empty()) return reportFailure(err, "merge", usageError("-o needs a file name"));
  if (output) {
    if (Status s = checkOutputPath(*output, std::vector<std::string>{planPath}); !s.isOk()) return reportFailure(err, "merge", s);
  }
  std::uint32_t pass = 0;
  if (!output) {
    if (Status s = parseIndex(p, "--pass", &pass); !s.isOk()) return reportFailure(err, "merge", s);
  }
  // merge --pass K >= 1 sums energies only; pass 0 computes B^0 of the receivers; -o scatters.
  const bake::TexelNeeds needs = output ? bake::TexelNeeds::kSeams : pass == 0 ? bake::TexelNeeds::kReceivers : bake::TexelNeeds::kNothing;
  LoadedPlan l;
  if (Status s = loadPlan(planPath, p, needs, &l); !s.isOk()) return reportFailure(err, "merge", s);
  const bake::ShardContext ctx = l.context(planPath);
  if (!output) {
    bool skipped = false, final = false;
    if (Status s = bake::mergePass(ctx, pass, &skipped, &final); !s.isOk()) return reportFailure(err, "merge", s);
    if (l.texels) {
      bool texelSkipped = false, texelFinal = false;
      if (Status s = bake::mergeTexelPass(ctx, pass, &texelSkipped, &texelFinal); !s.isOk()) return reportFailure(err, "merge", s);
      final = (final || skipped) && (texelFinal || texelSkipped);  // the last pass of both series
      skipped = skipped && texelSkipped;
    }
    if (!quiet) {
      if (skipped) std::fprintf(err, "prt-bake: pass %u is not needed: the bounce series ended before it; nothing written\n", pass);
      else std::fprintf(err, "prt-bake: wrote %s%s\n", bake::mergedPassPath(planPath, pass).c_str(), final ? " (the last pass)" : "");
    }
    return kExitOk;
  }
  bake::BakeResult result;
  if (Status s = bake::mergeShards(ctx, &result); !s.isOk()) return reportFailure(err, "merge", s);
  const int bounces = result.bounces;
  BakedAsset asset;
  std::vector<bake::CompressedPass> compressed;
  if (l.texels) {
    bake::TexelBakeResult texels;
    if (Status s = bake::mergeTexelShards(ctx, &texels); !s.isOk()) return reportFailure(err, "merge", s);
    if (Status s = bake::assembleTexelAsset(std::move(l.scene), std::move(result), std::move(texels), l.texels->atlasUv,
                                            l.plan.atlases, l.bake.bake, l.transfer.lighting, &asset, &compressed);
        !s.isOk()) {
      return reportFailure(err, "merge", s);
    }
  } else if (Status s = bake::assembleVertexAsset(std::move(l.scene), std::move(result), l.bake.bake, l.transfer.lighting,
                                                  &asset, &compressed);
             !s.isOk()) {
    return reportFailure(err, "merge", s);
  }
  std::vector<std::uint8_t> bytes;
  if (Status s = encodeAsset(asset, &bytes); !s.isOk()) {
    return reportFailure(err, "merge", Status::error(s.code(), "cannot encode asset: " + s.message()));
  }
  if (Status s = writeFileAtomically(*output, bytes, std::vector<std::string>{planPath}); !s.isOk()) {
    return reportFailure(err, "merge", s);
  }
  if (!quiet) std::fprintf(err, "prt-bake: wrote %s (%zu bytes, %d bounces)\n", output->c_str(), bytes.size(), bounces);
  if (p.has("--json")) {
    std::fprintf(out, "{\"output\": %s, \"bytes\": %zu, \"bounces\": %d, \"shards\": %zu}\n", jsonString(*output).c_str(),
                 bytes.size(), bounces, l.plan.shards.size());
  }
  return kExitOk;
}

}  // namespace prt
