#include "json_text.h"

#include <cmath>
#include <cstdio>

namespace prt {

std::string jsonString(const std::string& s) {
  std::string r = "\"";
  char buf[8];
  for (std::size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c == '"' || c == '\\') {
      r += '\\';
      r += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      r += buf;
    } else if (c < 0x80) {
      r += static_cast<char>(c);
    } else {
      // Length of a well-formed UTF-8 sequence starting here, or 0.
      const std::size_t n = c >= 0xf0 && c < 0xf5 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 && c < 0xe0 ? 2 : 0;
      bool ok = n > 0 && i + n <= s.size();
      for (std::size_t k = 1; ok && k < n; ++k) ok = (static_cast<unsigned char>(s[i + k]) & 0xc0) == 0x80;
      if (ok) {
        r.append(s, i, n);
        i += n - 1;
      } else {
        std::snprintf(buf, sizeof buf, "\\u%04x", c);
        r += buf;
      }
    }
  }
  return r + "\"";
}

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace prt
