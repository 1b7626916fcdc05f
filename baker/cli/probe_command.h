// `prt-bake probe`: projects one environment (an image file or a built-in one) onto SH and
// prints the coefficients as a table or as JSON.
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace prt {

// Help text of `prt-bake probe --help`.
const char* probeHelpText();

// Runs the command on the arguments after "probe". Results go to `out`; notes and
// "prt-bake: error: ..." lines go to `err`. Returns the exit status (native/exit_status.h).
// Lets only std::bad_alloc escape.
int runProbeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err);

}  // namespace prt
