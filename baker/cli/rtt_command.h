// prt-bake rtt: bakes a radiance transfer texture from a meso-scale patch (docs/bi-scale.md).
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

namespace prt {

const char* rttHelpText();
// Runs `prt-bake rtt ARGS`; returns the process exit status.
int runRttCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

// True when `bytes` start with the RTT file's magic: `prt-bake info` then describes it with
// infoRtt instead of reading an asset.
bool looksLikeRtt(std::span<const std::uint8_t> bytes);
// `prt-bake info` of RTT file `path` (its `bytes`): verified by decodeRtt, then its shape,
// size and coefficient range, as a table or JSON; returns the exit status.
int infoRtt(const std::string& path, std::span<const std::uint8_t> bytes, bool json, std::FILE* out, std::FILE* err);

}  // namespace prt
