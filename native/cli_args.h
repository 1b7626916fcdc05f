// A deliberately small command-line parser for the project's tools: long flags ("--order 3" or
// "--order=3"), boolean switches, positionals, "--" to end the flags. Strict by design:
// a typo should stop a long bake before it starts, not be ignored.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "prt/status.h"

namespace prt {

struct FlagSpec {
  std::string_view name;  // with the dashes: "--order"
  bool takesValue;        // false: a switch such as "--json"
};

struct ParsedArgs {
  std::vector<std::string> positionals;
  std::map<std::string, std::string, std::less<>> values;  // flag -> value ("" for switches)

  bool has(std::string_view flag) const { return values.find(flag) != values.end(); }
  // The flag's value, or nullptr when the flag was not given.
  const std::string* value(std::string_view flag) const;
};

// True when args (before any "--") hold "--help" or "-h": help wins over every other error.
bool wantsHelp(std::span<const std::string> args);

// Splits `args` by `specs`. Errors (kUsage): unknown flag, missing value, a value given to
// a switch, a flag given twice.
Status parseArgs(std::span<const std::string> args, std::span<const FlagSpec> specs, ParsedArgs* out);

// Parses a whole decimal integer in [min, max]; trailing characters, overflow and values out
// of range are errors (kUsage) that name the flag and the valid range.
Status parseIntArg(std::string_view flag, std::string_view text, int min, int max, int* out);

// Parses a whole finite decimal number in [min, max], same rules as parseIntArg.
Status parseFloatArg(std::string_view flag, std::string_view text, float min, float max, float* out);

}  // namespace prt
