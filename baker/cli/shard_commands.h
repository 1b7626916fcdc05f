// `prt-bake plan`, `prt-bake bake-shard` and `prt-bake merge`: a bake split over machines
// (docs/scale-out.md). Thin commands over baker/shard: parse, load, call, report.
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

// `plan SCENE|--default -o PLAN --shards N [bake options]`: writes the plan. Returns the exit status.
int runPlanCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

// `bake-shard --plan PLAN --shard I --pass K [--threads N] [--quiet]`: one range of one pass.
int runBakeShardCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

// `merge --plan PLAN --pass K` (the barrier between passes) or `merge --plan PLAN -o ASSET`.
int runMergeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
