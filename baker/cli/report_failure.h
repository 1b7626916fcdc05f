// How every prt-bake command ends on an error: one "prt-bake: error: ..." line, a pointer to
// --help for usage errors, and the exit status chosen from the failure's code
// (native/exit_status.h), so the same kind of failure exits the same way in every command.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include "prt/status.h"

namespace prt {

// A command-line error (StatusCode::kUsage) with `message`.
Status usageError(std::string message);

// Prints `failure` to `err` as "prt-bake: error: <message>", followed for a usage error by
// "Try 'prt-bake[ <command>] --help'." (`command` empty: the bake itself). Returns the
// exit status for failure.code(); `failure` must not be ok.
int reportFailure(std::FILE* err, std::string_view command, const Status& failure);

}  // namespace prt
