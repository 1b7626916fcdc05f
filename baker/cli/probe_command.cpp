#include "baker/cli/probe_command.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "baker/cli/builtin_environment.h"
#include "baker/cli/report_failure.h"
#include "native/cli_args.h"
#include "native/exit_status.h"
#include "native/environment_map.h"
#include "native/json_text.h"
#include "native/image_io.h"
#include "prt/cubemap.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "prt/sh_window.h"

namespace prt {
namespace {

constexpr float kMaxWindowWidth = 1000.0f;

constexpr FlagSpec kProbeFlags[] = {
    {"--order", true},        {"--format", true},  {"--window", true},
    {"--window-width", true}, {"--builtin", true}, {"--json", false},
};

struct ProbeOptions {
  std::string image;    // empty with --builtin
  std::string builtin;  // empty with an image
  int order = 0;
  std::optional<EnvLayout> layout;  // unset: guess from the aspect ratio
  ShWindow window = ShWindow::kNone;
  float windowWidth = 0.0f;  // 0: the order (shWindowWeights' default)
  bool json = false;
};

// Turns the command line into options; every error here is a usage error.
Status parseProbeOptions(std::span<const std::string> args, ProbeOptions* o) {
  ParsedArgs p;
  if (Status s = parseArgs(args, kProbeFlags, &p); !s.isOk()) return s;
  auto usage = [](std::string m) { return usageError(std::move(m)); };

  if (p.positionals.size() > 1) {
    return usage("expected one IMAGE, got " + std::to_string(p.positionals.size()) + " ('" + p.positionals[0] +
                 "', '" + p.positionals[1] + "', ...)");
  }
  if (const std::string* b = p.value("--builtin")) {
    if (!p.positionals.empty()) return usage("give either IMAGE or --builtin, not both");
    if (!isBuiltinEnvironment(*b)) return usage("unknown --builtin '" + *b + "' (known: " + kBuiltinEnvironmentNames + ")");
    o->builtin = *b;
  } else if (p.positionals.empty()) {
    return usage("missing IMAGE (or --builtin sky)");
  } else {
    o->image = p.positionals[0];
  }

  const std::string* order = p.value("--order");
  if (!order) {
    return usage("missing --order N (number of SH bands, " + std::to_string(kMinShOrder) + " to " +
                 std::to_string(kMaxShOrder) + ")");
  }
  if (Status s = parseIntArg("--order", *order, kMinShOrder, kMaxShOrder, &o->order); !s.isOk()) return s;

  if (const std::string* f = p.value("--format")) {
    EnvLayout layout{};
    if (Status s = parseLayout(*f, &layout); !s.isOk()) return usage(s.message());
    if (!o->builtin.empty() && layout != EnvLayout::kEquirect) {
      return usage("--format " + *f + " does not apply to --builtin (built-in environments are equirect)");
    }
    o->layout = layout;
  }
  if (const std::string* w = p.value("--window")) {
    if (Status s = parseShWindow(*w, &o->window); !s.isOk()) return usage("--window: " + s.message());
  }
  if (const std::string* ww = p.value("--window-width")) {
    if (o->window == ShWindow::kNone) return usage("--window-width needs --window hanning or --window lanczos");
    if (Status s = parseFloatArg("--window-width", *ww, 0.0f, kMaxWindowWidth, &o->windowWidth); !s.isOk()) return s;
  }
  o->json = p.has("--json");
  return Status::ok();
}

// The width shWindowWeights uses: 0 stands for the order.
double effectiveWindowWidth(const ProbeOptions& o) { return o.windowWidth > 0.0f ? o.windowWidth : o.order; }

struct ProbeResult {
  std::string source;  // path, or "builtin:sky"
  EnvLayout layout = EnvLayout::kEquirect;
  bool layoutGuessed = false;
  const char* aspect = "";
  int width = 0, height = 0;
  std::vector<Rgb> coeffs;
};

std::string formatJson(const ProbeOptions& o, const ProbeResult& r) {
  std::string s = "{\n";
  s += "  \"source\": " + jsonString(r.source) + ",\n";
  s += std::string("  \"format\": \"") + layoutName(r.layout) + "\",\n";
  s += std::string("  \"format_guessed\": ") + (r.layoutGuessed ? "true" : "false") + ",\n";
  s += "  \"width\": " + std::to_string(r.width) + ",\n";
  s += "  \"height\": " + std::to_string(r.height) + ",\n";
  s += "  \"order\": " + std::to_string(o.order) + ",\n";
  s += std::string("  \"window\": \"") + shWindowName(o.window) + "\",\n";
  if (o.window != ShWindow::kNone) {
    s += "  \"window_width\": " + jsonNumber(effectiveWindowWidth(o)) + ",\n";
  }
  s += "  \"index_convention\": \"i = l(l+1)+m\",\n";
  s += "  \"coefficients\": [\n";
  for (std::size_t i = 0; i < r.coeffs.size(); ++i) {
    const Rgb& c = r.coeffs[i];
    s += "    [" + jsonNumber(c.r) + ", " + jsonNumber(c.g) + ", " + jsonNumber(c.b) + "]" + (i + 1 < r.coeffs.size() ? ",\n" : "\n");
  }
  s += "  ]\n}\n";
  return s;
}

std::string formatTable(const ProbeOptions& o, const ProbeResult& r) {
  char line[160];
  std::string s = "source: " + r.source + "\n";
  std::snprintf(line, sizeof line, "format: %s, %dx%d%s%s%s\n", layoutName(r.layout), r.width, r.height,
                r.layoutGuessed ? " (guessed from the " : "", r.layoutGuessed ? r.aspect : "",
                r.layoutGuessed ? " aspect; --format overrides)" : "");
  s += line;
  std::snprintf(line, sizeof line, "order: %d (%d coefficients, index i = l(l+1)+m), window: %s", o.order,
                shCoeffCount(o.order), shWindowName(o.window));
  s += line;
  if (o.window != ShWindow::kNone) s += " (width " + jsonNumber(effectiveWindowWidth(o)) + " bands)";
  s += "\n";
  std::snprintf(line, sizeof line, "%5s %3s %3s %16s %16s %16s\n", "i", "l", "m", "r", "g", "b");
  s += line;
  for (int i = 0; i < static_cast<int>(r.coeffs.size()); ++i) {
    const int l = shBandOf(i), m = i - shIndex(l, 0);
    const Rgb& c = r.coeffs[static_cast<std::size_t>(i)];
    std::snprintf(line, sizeof line, "%5d %3d %3d %16.9g %16.9g %16.9g\n", i, l, m, static_cast<double>(c.r),
                  static_cast<double>(c.g), static_cast<double>(c.b));
    s += line;
  }
  return s;
}

// Loads the environment and projects it; every error here is an input error.
Status probe(const ProbeOptions& o, std::FILE* err, ProbeResult* r) {
  RgbImage image;
  if (!o.builtin.empty()) {
    if (Status s = makeBuiltinEnvironment(o.builtin, &image); !s.isOk()) return s;
    r->source = "builtin:" + o.builtin;
    r->layout = EnvLayout::kEquirect;
  } else {
    if (Status s = loadImage(o.image, &image); !s.isOk()) return s;
    r->source = o.image;
  }
  r->width = image.width;
  r->height = image.height;
  const std::string where = "'" + r->source + "'";
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);

  if (o.layout) {
    r->layout = *o.layout;
  } else if (o.builtin.empty()) {
    const std::optional<EnvLayout> guess = guessLayout(image.width, image.height, &r->aspect);
    if (!guess) {
      return Status::error(StatusCode::kInvalidArgument,
                           where + " is " + size + ": cannot guess its layout from the aspect ratio (2:1 equirect, "
                           "1:1 angular, 4:3 or 3:4 cross); pass --format");
    }
    r->layout = *guess;
    r->layoutGuessed = true;
    std::fprintf(err, "prt-bake: note: %s is %s (%s): reading it as %s; --format overrides\n", where.c_str(),
                 size.c_str(), r->aspect, layoutName(r->layout));
  }
  if (r->layout == EnvLayout::kEquirect && image.width != 2 * image.height) {
    std::fprintf(err, "prt-bake: warning: %s is %s, not 2:1; projecting it as equirect anyway\n", where.c_str(),
                 size.c_str());
  }

  if (Status s = projectLayout(r->layout, o.order, image, &r->coeffs); !s.isOk()) {
    return Status::error(s.code(), where + " as " + layoutName(r->layout) + ": " + s.message());
  }
  if (Status s = applyShWindow(o.window, o.order, o.windowWidth, r->coeffs); !s.isOk()) return s;
  for (const Rgb& c : r->coeffs) {
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b)) {
      return Status::error(StatusCode::kNotFinite, where + ": the projection overflowed (pixel values too large)");
    }
  }
  return Status::ok();
}

}  // namespace

const char* probeHelpText() {
  return "Usage: prt-bake probe IMAGE --order N [options]\n"
         "       prt-bake probe --builtin sky --order N [options]\n"
         "\n"
         "Projects an environment map onto real spherical harmonics (n bands, n*n\n"
         "coefficients per colour channel, index i = l(l+1)+m) and prints the coefficients.\n"
         "IMAGE is OpenEXR, Radiance HDR, PNG or JPEG (recognised by content; PNG and JPEG\n"
         "are taken as sRGB and linearised).\n"
         "\n"
         "Options:\n"
         "  --order N            SH order (bands), 1 to 16; required\n"
         "  --format LAYOUT      equirect | angular | cross; default: guessed from the aspect\n"
         "                       ratio (2:1 equirect, 1:1 angular, 4:3 or 3:4 cross)\n"
         "  --window NAME        none | hanning | lanczos (default none): damps ringing\n"
         "  --window-width W     window width in bands, 0 to 1000; 0 (default) means N\n"
         "  --builtin sky        project a built-in procedural sky instead of IMAGE\n"
         "  --json               print one JSON object instead of a table\n"
         "  -h, --help           show this help\n"
         "\n"
         "World frame: right-handed, +y up (glTF). Equirect: column 0 looks along -x, the\n"
         "centre column along +x, longitude increasing toward +z.\n"
         "\n"
         "Exit status: 0 success, 1 bad input (missing, unreadable or corrupt file),\n"
         "2 bad command line.\n";
}

int runProbeCommand(std::span<const std::string> args, std::FILE* out, std::FILE* err) {
  if (wantsHelp(args)) {
    std::fputs(probeHelpText(), out);
    return kExitOk;
  }
  ProbeOptions o;
  if (Status s = parseProbeOptions(args, &o); !s.isOk()) return reportFailure(err, "probe", s);
  ProbeResult r;
  if (Status s = probe(o, err, &r); !s.isOk()) return reportFailure(err, "probe", s);
  const std::string text = o.json ? formatJson(o, r) : formatTable(o, r);
  std::fputs(text.c_str(), out);
  return kExitOk;
}

}  // namespace prt
