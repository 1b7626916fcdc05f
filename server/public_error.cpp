#include "public_error.h"

#include <cstdio>

namespace prt::serve {

bool mentionsAbsolutePath(std::string_view text) {
  for (std::size_t i = 0; i + 1 < text.size(); ++i) {
    if (text[i] != '/') continue;
    const char before = i == 0 ? ' ' : text[i - 1];
    const char after = text[i + 1];
    const bool opensWord = std::string_view(" \t'\"(<[=:,").find(before) != std::string_view::npos;
    const bool pathChar = after != ' ' && after != '\t' && after != '\'' && after != '"' && after != ')';
    if (opensWord && pathChar) return true;
  }
  return false;
}

std::string publicMessage(std::string_view detail, std::string_view absPath, std::string_view relPath,
                          std::string_view root, std::string_view fallback) {
  std::string out(detail);
  if (!absPath.empty()) {
    std::string prefix(1, '\'');
    prefix.append(absPath).append("': ");
    if (out.starts_with(prefix)) out.erase(0, prefix.size());
    for (std::size_t at = out.find(absPath); at != std::string::npos; at = out.find(absPath, at + relPath.size())) {
      out.replace(at, absPath.size(), relPath);
    }
  }
  if ((root.size() > 1 && out.find(root) != std::string::npos) || mentionsAbsolutePath(out)) return std::string(fallback);
  return out;
}

void logDetail(std::string_view what, std::string_view detail) {
  const std::string line = "prt-serve: " + std::string(what) + ": " + std::string(detail) + "\n";
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace prt::serve
