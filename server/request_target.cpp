#include "request_target.h"

namespace prt::serve {
namespace {

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

Status bad(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

// Decodes %XX escapes (and '+' as a space when `plus`); false on a malformed escape.
bool percentDecode(std::string_view in, bool plus, std::string* out) {
  out->clear();
  out->reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (c == '%') {
      if (in.size() - i < 3) return false;
      const int hi = hexValue(in[i + 1]), lo = hexValue(in[i + 2]);
      if (hi < 0 || lo < 0) return false;
      out->push_back(static_cast<char>(hi * 16 + lo));
      i += 2;
    } else if (plus && c == '+') {
      out->push_back(' ');
    } else {
      out->push_back(c);
    }
  }
  return true;
}

}  // namespace

Status parseTarget(std::string_view target, RequestTarget* out) {
  if (target.empty() || target[0] != '/') return bad("target is not an absolute path (origin form)");
  // RFC 9112 targets are visible ASCII; anything else (raw UTF-8, spaces, controls) is a
  // client error, and decoding is only ever applied to %-escapes.
  for (const char c : target) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 0x20 || u >= 0x7f) return bad("target holds a byte outside visible ASCII");
  }
  const std::size_t q = target.find('?');
  const std::string_view rawPath = target.substr(0, q);
  out->query = q == std::string_view::npos ? std::string() : std::string(target.substr(q + 1));
  if (rawPath.find('#') != std::string_view::npos) return bad("target holds a fragment");
  std::string path;
  if (!percentDecode(rawPath, false, &path)) return bad("malformed percent-escape in the path");
  // Validated after decoding, so an escape cannot smuggle in what the raw form may not hold.
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return bad("control character in the path");
    if (c == '\\') return bad("backslash in the path");
  }
  // Segments between slashes: the first one (before the leading '/') is empty by construction.
  std::size_t start = 1;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    const std::string_view seg = std::string_view(path).substr(start, end - start);
    const bool last = end == path.size();
    if (seg.empty() && !last) return bad("empty path segment");
    if (seg == "." || seg == "..") return bad("dot segment in the path");
    start = end + 1;
  }
  out->path = std::move(path);
  return Status::ok();
}

bool queryValue(std::string_view query, std::string_view key, std::string* value) {
  std::size_t start = 0;
  while (start <= query.size()) {
    std::size_t end = query.find('&', start);
    if (end == std::string_view::npos) end = query.size();
    const std::string_view pair = query.substr(start, end - start);
    const std::size_t eq = pair.find('=');
    std::string name;
    if (!percentDecode(pair.substr(0, eq), true, &name)) return false;
    if (name == key) {
      return percentDecode(eq == std::string_view::npos ? std::string_view() : pair.substr(eq + 1), true, value);
    }
    start = end + 1;
  }
  return false;
}

std::string encodePathSegment(std::string_view segment) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : segment) {
    const auto u = static_cast<unsigned char>(c);
    const bool unreserved = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                            c == '.' || c == '_' || c == '~';
    if (unreserved) {
      out.push_back(c);
    } else {
      out.push_back('%');
      out.push_back(kDigits[u >> 4]);
      out.push_back(kDigits[u & 15]);
    }
  }
  return out;
}

}  // namespace prt::serve
