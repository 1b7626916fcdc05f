// `prt-bake compress-report`: encodes an asset's transfer with each transfer-codec setting
// (shared/prt/transfer_codec.h) and reports size (raw, zstd -19, brotli 11) and exit-radiance
// error under a fixed set of test lightings (compress_lightings.h). docs/transfer-codec.md.
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

// Help text of `prt-bake compress-report --help`.
const char* compressReportHelpText();

// Runs the command on the arguments after "compress-report". The report goes to `out`;
// progress notes and "prt-bake: error: ..." lines to `err`. Returns the exit status
// (native/exit_status.h).
int runCompressReportCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
