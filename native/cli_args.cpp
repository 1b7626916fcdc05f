#include "native/cli_args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

namespace prt {
namespace {

// kUsage: every error here is about the command line, so callers can map it to exit
// status 2 (native/exit_status.h) without knowing which check failed.
Status usage(std::string message) { return Status::error(StatusCode::kUsage, std::move(message)); }

const FlagSpec* findSpec(std::span<const FlagSpec> specs, std::string_view name) {
  for (const FlagSpec& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

bool looksLikeFlag(std::string_view arg) { return arg.size() > 1 && arg[0] == '-'; }

// Compact text for range messages ("[0, 1000]", not "[0.000000, 1000.000000]").
std::string formatNumber(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
  return buf;
}

// "--order '99' is out of range; expected an integer in [1, 16]" or "--order expects an
// integer in [1, 16], got 'abc'". Built by appending: GCC 12 misreports `"x" + std::string`
// temporaries under -Wrestrict (GCC PR 105329).
Status badNumber(std::string_view flag, std::string_view text, const char* kind, const std::string& range,
                 bool outOfRange) {
  std::string m(flag);
  if (outOfRange) {
    m.append(" '").append(text).append("' is out of range; expected ").append(kind);
  } else {
    m.append(" expects ").append(kind);
  }
  m.append(" in [").append(range).append("]");
  if (!outOfRange) m.append(", got '").append(text).append("'");
  return usage(std::move(m));
}

}  // namespace

const std::string* ParsedArgs::value(std::string_view flag) const {
  auto it = values.find(flag);
  return it == values.end() ? nullptr : &it->second;
}

bool wantsHelp(std::span<const std::string> args) {
  for (const std::string& a : args) {
    if (a == "--") return false;
    if (a == "--help" || a == "-h") return true;
  }
  return false;
}

Status parseArgs(std::span<const std::string> args, std::span<const FlagSpec> specs, ParsedArgs* out) {
  *out = ParsedArgs{};
  bool flagsEnded = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (flagsEnded || !looksLikeFlag(arg)) {
      out->positionals.push_back(arg);
      continue;
    }
    if (arg == "--") {
      flagsEnded = true;
      continue;
    }
    const std::size_t eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const FlagSpec* spec = findSpec(specs, name);
    if (!spec) return usage("unknown option '" + name + "'");
    if (out->has(name)) return usage("option " + name + " given more than once");
    std::string value;
    if (!spec->takesValue) {
      if (eq != std::string::npos) return usage("option " + name + " takes no value");
    } else if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
      if (value.empty()) return usage("option " + name + " needs a value");
    } else {
      // "--order --json" is a forgotten value, not the value "--json"; "-1" stays a value
      // so that range errors can name it.
      if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0) return usage("option " + name + " needs a value");
      value = args[++i];
    }
    out->values.emplace(name, std::move(value));
  }
  return Status::ok();
}

Status parseIntArg(std::string_view flag, std::string_view text, int min, int max, int* out) {
  const std::string range = std::to_string(min) + ", " + std::to_string(max);
  long long v = 0;
  const char* begin = text.data();
  const char* end = begin + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec == std::errc::result_out_of_range) return badNumber(flag, text, "an integer", range, true);
  if (ec != std::errc() || ptr != end || begin == end) return badNumber(flag, text, "an integer", range, false);
  if (v < min || v > max) return badNumber(flag, text, "an integer", range, true);
  *out = static_cast<int>(v);
  return Status::ok();
}

Status parseFloatArg(std::string_view flag, std::string_view text, float min, float max, float* out) {
  const std::string range = formatNumber(min) + ", " + formatNumber(max);
  float v = 0.0f;
  const char* begin = text.data();
  const char* end = begin + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, v, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return badNumber(flag, text, "a number", range, true);
  // from_chars also reads "inf" and "nan"; the isfinite test turns those away.
  if (ec != std::errc() || ptr != end || begin == end || !std::isfinite(v)) {
    return badNumber(flag, text, "a number", range, false);
  }
  if (v < min || v > max) return badNumber(flag, text, "a number", range, true);
  *out = v;
  return Status::ok();
}

}  // namespace prt
