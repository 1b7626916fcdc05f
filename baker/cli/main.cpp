// prt-bake: the offline baker's command-line entry point. Dispatches to one command per
// file (probe_command.cpp, ...) and is the last wall before the OS: nothing throws past it.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "baker/cli/asset_commands.h"
#include "baker/cli/bake_command.h"
#include "native/exit_status.h"
#include "native/file_io.h"
#include "baker/cli/compress_command.h"
#include "baker/cli/probe_command.h"
#include "baker/cli/rtt_command.h"
#include "baker/cli/shard_commands.h"
#include "baker/transfer/glossy_bake.h"

#ifndef PRT_VERSION
#define PRT_VERSION "unknown"
#endif

namespace {

constexpr const char* kHelp =
    "Usage: prt-bake SCENE.gltf|SCENE.glb -o ASSET [options]   bake a scene\n"
    "       prt-bake --default -o ASSET [options]              bake the built-in room\n"
    "       prt-bake <command> [options]\n"
    "\n"
    "Offline baker of the PRT project: diffuse SH transfer with Embree.\n"
    "\n"
    "Commands:\n"
    "  probe      project an environment map (EXR, HDR, PNG, JPEG) onto spherical harmonics\n"
    "  info       verify a baked asset and print what it holds\n"
    "  shade      print every vertex's exit radiance under a light, from an asset\n"
    "  compress-report  size and exit-radiance error of every codec setting on an asset\n"
    "  plan       split a bake into shards for several machines (docs/scale-out.md)\n"
    "  bake-shard bake one shard of one pass of a plan\n"
    "  merge      check and merge a pass's shards, or every shard into the asset\n"
    "  rtt        bake a radiance transfer texture of a meso-scale patch (docs/bi-scale.md)\n"
    "\n"
    "Bake options: 'prt-bake --default --help'.\n"
    "\n"
    "Options:\n"
    "  -h, --help     show this help ('prt-bake <command> --help' for a command's options)\n"
    "  --version      print the version\n";

int usageError(const std::string& message) {
  std::fprintf(stderr, "prt-bake: error: %s\nTry 'prt-bake --help'.\n", message.c_str());
  return prt::kExitUsage;
}

int run(const std::vector<std::string>& args) {
  if (args.empty()) return usageError("missing command");
  const std::string& command = args[0];
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kHelp, stdout);
    std::fputs("\n", stdout);
    std::fputs(prt::exitStatusHelp(), stdout);
    return prt::kExitOk;
  }
  if (command == "--version") {
    std::printf("prt-bake %s\n", PRT_VERSION);
    return prt::kExitOk;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (command == "probe") return prt::runProbeCommand(rest, stdout, stderr);
  if (command == "info") return prt::runInfoCommand(rest, stdout, stderr);
  if (command == "shade") return prt::runShadeCommand(rest, stdout, stderr);
  if (command == "compress-report") return prt::runCompressReportCommand(rest, stdout, stderr);
  if (command == "plan") return prt::runPlanCommand(rest, stdout, stderr);
  if (command == "bake-shard") return prt::runBakeShardCommand(rest, stdout, stderr);
  if (command == "merge") return prt::runMergeCommand(rest, stdout, stderr);
  if (command == "rtt") return prt::runRttCommand(rest, stdout, stderr);
  // Anything else is a bake: `prt-bake SCENE -o ASSET ...` or `prt-bake --default ...`,
  // except a bare word that is neither a file nor a glTF name: most likely a mistyped command.
  const bool looksLikeScene = command[0] == '-' || command.find('.') != std::string::npos ||
                              command.find('/') != std::string::npos || access(command.c_str(), F_OK) == 0;
  if (!looksLikeScene) {
    return usageError("unknown command '" + command + "' (commands: probe, info, shade, compress-report, plan, bake-shard, merge, rtt; or a SCENE.gltf/.glb to bake)");
  }
  return prt::runBakeCommand(args, stdout, stderr);
}

}  // namespace

int main(int argc, char** argv) {
  // Before anything else: OpenBLAS's idle workers would spin for a tenth of a second.
  prt::bake::releaseBlasThreads();
  int code = prt::kExitInternal;
  try {
    code = run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::bad_alloc&) {
    std::fputs("prt-bake: error: out of memory\n", stderr);
    return prt::exitStatusFor(prt::StatusCode::kResourceExhausted);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt-bake: error: internal error: %s\n", e.what());
    return prt::exitStatusFor(prt::StatusCode::kInternal);
  } catch (...) {
    std::fputs("prt-bake: error: internal error (unknown exception)\n", stderr);
    return prt::exitStatusFor(prt::StatusCode::kInternal);
  }
  // A full disk or a closed pipe must not pass for success.
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    const int savedErrno = errno;
    std::fprintf(stderr, "prt-bake: error: cannot write to standard output: %s\n", std::strerror(savedErrno));
    return prt::exitStatusFor(prt::statusCodeForErrno(savedErrno));
  }
  return code;
}
