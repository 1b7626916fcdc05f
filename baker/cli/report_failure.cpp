#include "baker/cli/report_failure.h"

#include <cassert>

#include "native/exit_status.h"

namespace prt {

Status usageError(std::string message) { return Status::error(StatusCode::kUsage, std::move(message)); }

int reportFailure(std::FILE* err, std::string_view command, const Status& failure) {
  assert(!failure.isOk());
  std::fprintf(err, "prt-bake: error: %s\n", failure.message().c_str());
  if (failure.code() == StatusCode::kUsage) {
    std::fprintf(err, "Try 'prt-bake%s%.*s --help'.\n", command.empty() ? "" : " ", static_cast<int>(command.size()),
                 command.data());
  }
  return failure.isOk() ? kExitInternal : exitStatusFor(failure.code());
}

}  // namespace prt
