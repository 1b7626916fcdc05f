// `prt-bake SCENE.gltf|SCENE.glb -o ASSET [options]` and `prt-bake --default -o ASSET`:
// loads a scene, bakes its transfer passes with Embree and writes the asset atomically.
#pragma once

#include <cstdio>
#include <span>
#include <string>

#include "baker/transfer/bake_asset.h"
#include "prt/status.h"

namespace prt {

// Help text of the bake command.
const char* bakeHelpText();

// Runs a bake with the full argument list (the scene path or --default included). Progress
// and errors go to `err`, --json statistics to `out`. Returns the exit status (native/exit_status.h).
int runBakeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

// A bake's command line, parsed: what `prt-bake plan` records and each shard re-reads, so a
// sharded bake takes exactly the options of a one-machine bake.
struct BakeCommandLine {
  std::string scene;  // empty with --default
  std::string output;
  bake::AssetBakeOptions bake;
  bool quiet = false, json = false;
};

// Parses a bake's arguments (the scene or --default, -o and every bake option) as the bake
// command does. Errors: kUsage naming the flag.
Status parseBakeCommandLine(std::span<const std::string> args, BakeCommandLine* out);

// The built-in room (--default) as the bake command bakes it with `options`: with texels at a
// given texture size, its atlas's gutters follow that size and the padding.
bake::Scene defaultSceneFor(const bake::AssetBakeOptions& options);

}  // namespace prt
