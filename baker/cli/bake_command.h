// `prt-bake SCENE.gltf|SCENE.glb -o ASSET [options]` and `prt-bake --default -o ASSET`:
// loads a scene, bakes its transfer passes with Embree and writes the asset atomically.
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

// Help text of the bake command.
const char* bakeHelpText();

// Runs a bake with the full argument list (the scene path or --default included). Progress
// and errors go to `err`, --json statistics to `out`. Returns the exit status (native/exit_status.h).
int runBakeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
