#include "options.h"

#include <boost/asio/ip/address.hpp>

#include <string_view>

#include "native/cli_args.h"

namespace prt::serve {
namespace {

Status usage(std::string message) { return Status::error(StatusCode::kUsage, std::move(message)); }

constexpr FlagSpec kFlags[] = {
    {"--root", true},          {"--web", true},
    {"--bind", true},          {"--port", true},
    {"--threads", true},       {"--max-connections", true},
    {"--max-connections-per-client", true},
    {"--read-timeout", true},  {"--write-timeout", true},
    {"--max-parts-mib", true}, {"--quiet", false},
    {"--version", false},
};

// Timeouts: from 50 ms (a fraction of a second is a useful setting) to a day.
constexpr float kMinSeconds = 0.05f;
constexpr float kMaxSeconds = 86400.0f;

Status parseSeconds(const ParsedArgs& p, std::string_view flag, double* out) {
  const std::string* text = p.value(flag);
  if (!text) return Status::ok();
  float v = 0;
  PRT_RETURN_IF_ERROR(parseFloatArg(flag, *text, kMinSeconds, kMaxSeconds, &v));
  *out = v;
  return Status::ok();
}

Status parseInt(const ParsedArgs& p, std::string_view flag, int min, int max, int* out) {
  const std::string* text = p.value(flag);
  return text ? parseIntArg(flag, *text, min, max, out) : Status::ok();
}

}  // namespace

const char* serveHelpText() {
  return "Usage: prt-serve --root DIR [--web DIR] [--bind ADDR] [--port N] [--threads N] [options]\n"
         "\n"
         "Serves baked PRT assets (*.prt) and environment-map lighting from DIR, and the web\n"
         "client's files, over HTTP/1.1.\n"
         "\n"
         "Endpoints:\n"
         "  GET /api/scenes                 JSON catalogue of the assets under --root (each verified)\n"
         "  GET /assets/<hash>/<name>.prt   an asset at its content-addressed, immutable URL\n"
         "  GET /parts/<hash>               one piece of an asset (the catalogue lists them), immutable\n"
         "  GET /api/lights[?order=N]       the EXR/HDR maps under --root as SH coefficients (order 1..16, default 5)\n"
         "  GET /api/lights/preview/<hash>.png   a small tone-mapped preview of a map\n"
         "  GET /...                        the files under --web (index.html for directories)\n"
         "\n"
         "Options:\n"
         "  --root DIR             baked assets and environment maps (required)\n"
         "  --web DIR              the web client's static files\n"
         "  --bind ADDR            address to listen on (default 127.0.0.1; 0.0.0.0 or :: for all)\n"
         "  --port N               TCP port (default 8080; 0 picks a free one and prints it)\n"
         "  --threads N            I/O threads (default: one per hardware thread)\n"
         "  --max-connections N    open connections served at once; when all are busy more get 503,\n"
         "                         when some are idle the oldest idle one is closed (default 1024)\n"
         "  --max-connections-per-client N\n"
         "                         connections one client address may hold (default: a quarter of\n"
         "                         --max-connections, 256); behind a proxy, set it to --max-connections\n"
         "  --read-timeout S       seconds a client has to send a request head, idle time\n"
         "                         between keep-alive requests included (default 15)\n"
         "  --write-timeout S      seconds a client may stall a response before it is dropped (default 30)\n"
         "  --max-parts-mib N      assets up to N MiB are also served as parts, held in memory\n"
         "                         (about 3x their size); 0: none (default 64)\n"
         "  --quiet                no access log (one line per request on stderr otherwise)\n"
         "  -h, --help             show this help\n"
         "  --version              print the version\n"
         "\n"
         "SIGINT or SIGTERM stops the server gracefully: it stops accepting, lets responses in\n"
         "flight finish (up to 10 s) and exits 0. A second signal stops it at once.\n";
}

Status parseServeOptions(std::span<const std::string> args, ServeOptions* out) {
  if (wantsHelp(args)) {
    out->help = true;
    return Status::ok();
  }
  ParsedArgs p;
  PRT_RETURN_IF_ERROR(parseArgs(args, kFlags, &p));
  if (!p.positionals.empty()) return usage("unexpected argument '" + p.positionals.front() + "'");
  if (const std::string* v = p.value("--root")) out->root = *v;
  if (const std::string* v = p.value("--web")) out->web = *v;
  if (const std::string* v = p.value("--bind")) {
    // Checked here, with the other values, so a typo is a usage error (exit 2) reported
    // before the directories are opened.
    boost::system::error_code ec;
    boost::asio::ip::make_address(*v, ec);
    if (ec) return usage("--bind '" + *v + "' is not an IP address");
    out->bind = *v;
  }
  PRT_RETURN_IF_ERROR(parseInt(p, "--port", 0, 65535, &out->port));
  PRT_RETURN_IF_ERROR(parseInt(p, "--threads", 1, 256, &out->threads));
  PRT_RETURN_IF_ERROR(parseInt(p, "--max-connections", 1, 1000000, &out->maxConnections));
  PRT_RETURN_IF_ERROR(parseInt(p, "--max-connections-per-client", 1, 1000000, &out->maxConnectionsPerClient));
  PRT_RETURN_IF_ERROR(parseSeconds(p, "--read-timeout", &out->readTimeoutSeconds));
  PRT_RETURN_IF_ERROR(parseSeconds(p, "--write-timeout", &out->writeTimeoutSeconds));
  PRT_RETURN_IF_ERROR(parseInt(p, "--max-parts-mib", 0, 1024, &out->maxPartsMiB));
  out->quiet = p.has("--quiet");
  out->version = p.has("--version");
  if (out->version) return Status::ok();
  if (out->root.empty()) return usage("--root DIR is required");
  return Status::ok();
}

}  // namespace prt::serve
