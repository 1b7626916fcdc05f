// Helpers for tests that check the loader's warning lines.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace prt::bake::test {

// The lines, each on its own indented line (for failure messages).
inline std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += "\n  " + l;
  return s;
}

// Whether any line contains `fragment`.
inline bool anyContains(const std::vector<std::string>& lines, const std::string& fragment) {
  return std::any_of(lines.begin(), lines.end(),
                     [&](const std::string& l) { return l.find(fragment) != std::string::npos; });
}

}  // namespace prt::bake::test
