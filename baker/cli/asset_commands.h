// `prt-bake info ASSET` and `prt-bake shade ASSET --light ...`: look inside a baked asset
// and evaluate it, so results can be checked from outside the renderer.
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

// `prt-bake info ASSET [--json]`: verifies every checksum and prints counts, order, passes
// and bake metadata. Returns the exit status (native/exit_status.h).
int runInfoCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

// `prt-bake shade ASSET --light constant|ENVMAP [--pass P] [--order N] [--json]`: exit
// radiance of every vertex under the light, from the stored transfer.
int runShadeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
