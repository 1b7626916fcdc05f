// prt-bake rtt: bakes a radiance transfer texture from a meso-scale patch (docs/bi-scale.md).
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

const char* rttHelpText();
// Runs `prt-bake rtt ARGS`; returns the process exit status.
int runRttCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
