#include "options.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string_view>

namespace prt::serve {
namespace {

Status usage(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

Status parseInt(std::string_view flag, const std::string& text, int min, int max, int* out) {
  int v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || v < min || v > max) {
    return usage(std::string(flag) + " must be a whole number from " + std::to_string(min) + " to " +
                 std::to_string(max) + ", not '" + text + "'");
  }
  *out = v;
  return Status::ok();
}

Status parseSeconds(std::string_view flag, const std::string& text, double* out) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v) || v < 0.05 || v > 86400) {
    return usage(std::string(flag) + " must be a number of seconds from 0.05 to 86400, not '" + text + "'");
  }
  *out = v;
  return Status::ok();
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
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string flag = args[i];
    std::string value;
    bool hasInlineValue = false;
    if (flag.starts_with("--") && flag.find('=') != std::string::npos) {
      value = flag.substr(flag.find('=') + 1);
      flag = flag.substr(0, flag.find('='));
      hasInlineValue = true;
    }
    if (flag == "-h" || flag == "--help") {
      out->help = true;
      continue;
    }
    if (flag == "--version") {
      out->version = true;
      continue;
    }
    if (flag == "--quiet") {
      if (hasInlineValue) return usage("--quiet takes no value");
      out->quiet = true;
      continue;
    }
    static constexpr std::string_view kValued[] = {"--root", "--web", "--bind", "--port", "--threads",
                                                   "--max-connections", "--max-connections-per-client",
                                                   "--read-timeout", "--write-timeout", "--max-parts-mib"};
    bool known = false;
    for (std::string_view k : kValued) known = known || flag == k;
    if (!known) {
      return usage(flag.starts_with("-") ? "unknown option '" + flag + "'" : "unexpected argument '" + flag + "'");
    }
    if (!hasInlineValue) {
      if (i + 1 >= args.size()) return usage(flag + " needs a value");
      value = args[++i];
    }
    Status s;
    if (flag == "--root") out->root = value;
    else if (flag == "--web") out->web = value;
    else if (flag == "--bind") out->bind = value;
    else if (flag == "--port") s = parseInt(flag, value, 0, 65535, &out->port);
    else if (flag == "--threads") s = parseInt(flag, value, 1, 256, &out->threads);
    else if (flag == "--max-connections") s = parseInt(flag, value, 1, 1000000, &out->maxConnections);
    else if (flag == "--max-connections-per-client") {
      s = parseInt(flag, value, 1, 1000000, &out->maxConnectionsPerClient);
    }
    else if (flag == "--read-timeout") s = parseSeconds(flag, value, &out->readTimeoutSeconds);
    else if (flag == "--write-timeout") s = parseSeconds(flag, value, &out->writeTimeoutSeconds);
    else if (flag == "--max-parts-mib") s = parseInt(flag, value, 0, 1024, &out->maxPartsMiB);
    if (!s.isOk()) return s;
  }
  if (out->help || out->version) return Status::ok();
  if (out->root.empty()) return usage("--root DIR is required");
  return Status::ok();
}

}  // namespace prt::serve
