#include "access_log.h"

#include <cstdio>

namespace prt::serve {
namespace {

constexpr std::size_t kMaxTarget = 512;

void appendEscaped(std::string& out, std::string_view field, std::size_t limit) {
  if (field.empty()) {
    out += '-';
    return;
  }
  static constexpr char kHex[] = "0123456789abcdef";
  for (std::size_t i = 0; i < field.size(); ++i) {
    if (i == limit) {
      out += "...";
      return;
    }
    const auto u = static_cast<unsigned char>(field[i]);
    if (u <= 0x20 || u >= 0x7f || u == '"' || u == '\\') {
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += static_cast<char>(u);
    }
  }
}

}  // namespace

std::string formatAccessLine(const AccessRecord& r) {
  std::string line;
  line.reserve(96 + r.target.size());
  line += r.peer.empty() ? std::string_view("-") : r.peer;
  line += ' ';
  appendEscaped(line, r.method, 32);
  line += ' ';
  appendEscaped(line, r.target, kMaxTarget);
  line += ' ' + std::to_string(r.status) + ' ' + std::to_string(r.bytes) + ' ' + std::to_string(r.micros) + "us\n";
  return line;
}

void AccessLog::write(const AccessRecord& record) const {
  if (!enabled_) return;
  const std::string line = formatAccessLine(record);
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace prt::serve
