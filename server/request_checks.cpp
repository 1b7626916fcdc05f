#include "request_checks.h"

#include <boost/asio/ip/address_v6.hpp>

#include <string>

namespace prt::serve {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isHex(char c) { return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }
bool isUnreserved(char c) { return isAlpha(c) || isDigit(c) || c == '-' || c == '.' || c == '_' || c == '~'; }
bool isSubDelim(char c) { return std::string_view("!$&'()*+,;=").find(c) != std::string_view::npos; }

// RFC 3986 reg-name (which also covers IPv4address): unreserved, sub-delims, %XX.
bool validRegName(std::string_view s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '%') {
      if (i + 2 >= s.size() || !isHex(s[i + 1]) || !isHex(s[i + 2])) return false;
      i += 2;
    } else if (!isUnreserved(c) && !isSubDelim(c)) {
      return false;
    }
  }
  return true;
}

// The inside of "[...]": an IPv6 address, or IPvFuture ("v" 1*HEXDIG "." 1*(unreserved / sub-delims / ":")).
bool validIpLiteral(std::string_view s) {
  if (!s.empty() && (s[0] == 'v' || s[0] == 'V')) {
    const std::size_t dot = s.find('.');
    if (dot == std::string_view::npos || dot < 2 || dot + 1 >= s.size()) return false;
    for (std::size_t i = 1; i < dot; ++i) {
      if (!isHex(s[i])) return false;
    }
    for (std::size_t i = dot + 1; i < s.size(); ++i) {
      if (!isUnreserved(s[i]) && !isSubDelim(s[i]) && s[i] != ':') return false;
    }
    return true;
  }
  // No zone identifiers ("%25eth0"): RFC 9110 URIs do not carry them.
  if (s.find('%') != std::string_view::npos) return false;
  boost::system::error_code ec;
  boost::asio::ip::make_address_v6(std::string(s), ec);
  return !ec;
}

bool allDigits(std::string_view s) {
  for (const char c : s) {
    if (!isDigit(c)) return false;
  }
  return true;
}

std::string_view trimOws(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool equalsChunked(std::string_view s) {
  constexpr std::string_view kChunked = "chunked";
  if (s.size() != kChunked.size()) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = (s[i] >= 'A' && s[i] <= 'Z') ? static_cast<char>(s[i] - 'A' + 'a') : s[i];
    if (c != kChunked[i]) return false;
  }
  return true;
}

}  // namespace

bool validHostValue(std::string_view value) {
  if (!value.empty() && value.front() == '[') {
    const std::size_t close = value.find(']');
    if (close == std::string_view::npos || !validIpLiteral(value.substr(1, close - 1))) return false;
    const std::string_view rest = value.substr(close + 1);
    return rest.empty() || (rest.front() == ':' && allDigits(rest.substr(1)));
  }
  const std::size_t colon = value.rfind(':');
  if (colon == std::string_view::npos) return validRegName(value);
  return validRegName(value.substr(0, colon)) && allDigits(value.substr(colon + 1));
}

bool onlyChunked(std::string_view values) {
  int codings = 0;
  bool chunked = false;
  while (!values.empty()) {
    const std::size_t comma = values.find(',');
    const std::string_view element = trimOws(values.substr(0, comma));
    values = comma == std::string_view::npos ? std::string_view() : values.substr(comma + 1);
    if (element.empty()) continue;
    ++codings;
    chunked = equalsChunked(element);
  }
  return codings == 1 && chunked;
}

bool wellFormedButUnsupportedVersion(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const std::size_t first = line.find(' ');
  const std::size_t last = line.rfind(' ');
  if (first == std::string_view::npos || first == 0 || last == first + 1 || line.find(' ', first + 1) != last) {
    return false;
  }
  const std::string_view v = line.substr(last + 1);
  if (v.size() != 8 || v.substr(0, 5) != "HTTP/" || !isDigit(v[5]) || v[6] != '.' || !isDigit(v[7])) return false;
  return v != "HTTP/1.0" && v != "HTTP/1.1";
}

std::string_view requestHeadProblem(const RequestHead& request) {
  const bool http11 = request.version() == 11;
  const auto te = request.equal_range(http::field::transfer_encoding);
  if (te.first != te.second) {
    // An HTTP/1.0 recipient must treat any Transfer-Encoding as faulty framing (RFC 9112 §6.1).
    if (!http11) return "Transfer-Encoding is not allowed in an HTTP/1.0 request";
    std::string values;
    for (auto it = te.first; it != te.second; ++it) values.append(it->value()).push_back(',');
    if (!onlyChunked(values)) {
      return "Transfer-Encoding must be exactly \"chunked\" (no other transfer coding is accepted)";
    }
  }
  const std::size_t hosts = request.count(http::field::host);
  if (hosts == 0 && http11) return "HTTP/1.1 requests need a Host field";
  if (hosts > 1) return "a request may carry only one Host field";
  if (hosts == 1 && !validHostValue(request[http::field::host])) return "the Host field is not a valid host[:port]";
  return {};
}

}  // namespace prt::serve
