#include "negotiation.h"

#include <cctype>
#include <charconv>
#include <optional>

namespace prt::serve {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}

// A qvalue in thousandths ("1", "0.5", "0.125"); nullopt when malformed.
std::optional<int> parseQ(std::string_view q) {
  if (q.empty() || q.size() > 5) return std::nullopt;
  if (q[0] == '1') {
    for (std::size_t i = 1; i < q.size(); ++i) {
      if (q[i] != (i == 1 ? '.' : '0')) return std::nullopt;
    }
    return 1000;
  }
  if (q[0] != '0') return std::nullopt;
  if (q.size() == 1) return 0;
  if (q[1] != '.') return std::nullopt;
  int value = 0, scale = 100;
  for (std::size_t i = 2; i < q.size(); ++i) {
    if (q[i] < '0' || q[i] > '9') return std::nullopt;
    value += (q[i] - '0') * scale;
    scale /= 10;
  }
  return value;
}

// The q (thousandths) Accept-Encoding gives `token`, or -1 when it is not mentioned.
int qualityOf(std::string_view header, std::string_view token, int* starQ) {
  int found = -1;
  *starQ = -1;
  std::size_t start = 0;
  while (start <= header.size()) {
    std::size_t end = header.find(',', start);
    if (end == std::string_view::npos) end = header.size();
    std::string_view item = header.substr(start, end - start);
    start = end + 1;
    std::string_view name = item, params;
    if (const std::size_t semi = item.find(';'); semi != std::string_view::npos) {
      name = item.substr(0, semi);
      params = item.substr(semi + 1);
    }
    name = trim(name);
    if (name.empty()) continue;
    int q = 1000;
    params = trim(params);
    if (!params.empty()) {
      if (params.size() < 2 || std::tolower(static_cast<unsigned char>(params[0])) != 'q' || params[1] != '=') continue;
      const std::optional<int> parsed = parseQ(trim(params.substr(2)));
      if (!parsed) continue;  // a malformed item is ignored, not taken as q=1
      q = *parsed;
    }
    if (name == "*") {
      *starQ = q;
    } else if (iequals(name, token) && found < 0) {
      found = q;
    }
  }
  return found;
}

bool parseDecimal(std::string_view s, std::uint64_t* out) {
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return ec == std::errc() && ptr == s.data() + s.size();
}

}  // namespace

std::size_t chooseEncoding(std::string_view acceptEncoding, std::span<const EncodingOffer> offers) {
  std::size_t best = 0;
  int bestQ = -1;
  for (std::size_t i = 0; i < offers.size(); ++i) {
    int starQ = -1;
    int q = qualityOf(acceptEncoding, encodingToken(offers[i].encoding), &starQ);
    if (q < 0) q = starQ;
    // Identity is acceptable unless refused by name or by "*;q=0" (RFC 9110 §12.5.3), but
    // only as a fallback: a client that names a coding at any q wants it over identity.
    if (q < 0 && offers[i].encoding == Encoding::kIdentity) q = 1;
    if (q <= 0) continue;
    if (q > bestQ || (q == bestQ && offers[i].size < offers[best].size)) {
      best = i;
      bestQ = q;
    }
  }
  return bestQ > 0 ? best : 0;
}

bool ifNoneMatchHits(std::string_view ifNoneMatch, std::string_view etag) {
  if (trim(ifNoneMatch) == "*") return true;
  if (etag.starts_with("W/")) etag.remove_prefix(2);
  std::size_t i = 0;
  while (i < ifNoneMatch.size()) {
    while (i < ifNoneMatch.size() && (ifNoneMatch[i] == ' ' || ifNoneMatch[i] == '\t' || ifNoneMatch[i] == ',')) ++i;
    if (ifNoneMatch.substr(i).starts_with("W/")) i += 2;
    if (i >= ifNoneMatch.size() || ifNoneMatch[i] != '"') {
      // Not an entity-tag: skip to the next comma.
      const std::size_t comma = ifNoneMatch.find(',', i);
      if (comma == std::string_view::npos) break;
      i = comma;
      continue;
    }
    const std::size_t close = ifNoneMatch.find('"', i + 1);
    if (close == std::string_view::npos) break;
    if (ifNoneMatch.substr(i, close - i + 1) == etag) return true;
    i = close + 1;
  }
  return false;
}

RangeOutcome parseRange(std::string_view range, std::uint64_t size, ByteRange* out) {
  range = trim(range);
  constexpr std::string_view kUnit = "bytes=";
  if (range.size() < kUnit.size() || !iequals(range.substr(0, kUnit.size()), kUnit)) return RangeOutcome::kWhole;
  std::string_view spec = trim(range.substr(kUnit.size()));
  if (spec.find(',') != std::string_view::npos) return RangeOutcome::kWhole;
  const std::size_t dash = spec.find('-');
  if (dash == std::string_view::npos) return RangeOutcome::kWhole;
  const std::string_view a = trim(spec.substr(0, dash)), b = trim(spec.substr(dash + 1));
  std::uint64_t first = 0, last = 0;
  if (a.empty()) {
    // Suffix range "-N": the last N bytes.
    if (!parseDecimal(b, &last)) return RangeOutcome::kWhole;
    if (last == 0 || size == 0) return RangeOutcome::kUnsatisfiable;
    const std::uint64_t n = last < size ? last : size;
    *out = {size - n, n};
    return RangeOutcome::kPartial;
  }
  if (!parseDecimal(a, &first)) return RangeOutcome::kWhole;
  if (b.empty()) {
    last = size == 0 ? 0 : size - 1;
  } else {
    if (!parseDecimal(b, &last) || last < first) return RangeOutcome::kWhole;
    if (last >= size && size > 0) last = size - 1;
  }
  if (first >= size) return RangeOutcome::kUnsatisfiable;
  *out = {first, last - first + 1};
  return RangeOutcome::kPartial;
}

}  // namespace prt::serve
