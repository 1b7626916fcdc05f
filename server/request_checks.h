// The RFC 9112 rules a request head must pass before it is routed. A Transfer-Encoding
// this server cannot frame, or a missing, repeated or malformed Host, is answered 400 and
// the connection closed: otherwise bytes after the head could be read as a second request
// (request smuggling), or a proxy in front and this server could disagree on the target.
#pragma once

#include <string_view>

#include "respond.h"

namespace prt::serve {

// Why `request` must be refused with 400 and the connection closed, or "" when it passes:
// Transfer-Encoding (RFC 9112 §6.1, §6.3: only "chunked", exactly once, last; none at all
// on HTTP/1.0) and Host (§3.2: exactly one on HTTP/1.1, at most one on HTTP/1.0, each a
// valid uri-host [":" port]).
std::string_view requestHeadProblem(const RequestHead& request);

// True when `value` is a valid Host field value (RFC 9110 §7.2: uri-host [":" port], with
// uri-host an IP literal in brackets, an IPv4 address or a reg-name of RFC 3986 §3.2.2).
// Empty is valid (a target without authority).
bool validHostValue(std::string_view value);

// True when the Transfer-Encoding field values `values` (each field line, in order) list
// exactly one transfer coding, "chunked" (case-insensitive, no parameters): the only framing
// this server reads. Empty list elements are ignored, as RFC 9110 §5.6.1 requires.
bool onlyChunked(std::string_view values);

// True when `requestLine` (the first line of a request, CR LF stripped or not) is
// "method SP target SP HTTP/d.d" with a version other than 1.0 and 1.1: such a request
// is answered 505, while a version that is not even well-formed is a 400.
bool wellFormedButUnsupportedVersion(std::string_view requestLine);

}  // namespace prt::serve
