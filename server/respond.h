// HTTP semantics in one place: from a request and a Resource to the reply, with encoding
// negotiation, conditional requests, byte ranges and HEAD.
#pragma once

#include <boost/beast/http/fields.hpp>

#include <string_view>

#include "reply.h"
#include "resource.h"

namespace prt::serve {

using RequestHead = http::request_header<>;

// The reply to GET or HEAD `request` for `resource`: picks the variant Accept-Encoding
// prefers (Vary: Accept-Encoding when there is more than one), answers a matching
// If-None-Match with 304, a single satisfiable Range (honouring If-Range) with 206 and an
// unsatisfiable one with 416, and sends no body for HEAD.
Reply respond(const RequestHead& request, const Resource& resource);

// A short error reply: JSON {"error": message} when `json`, plain text otherwise, never
// cached. `close` asks the session to close the connection after it.
Reply errorReply(unsigned version, http::status status, std::string_view message, bool json, bool close = false);

// Headers every reply carries (Server, Date, X-Content-Type-Options).
void addCommonHeaders(http::response<http::empty_body>& head);

}  // namespace prt::serve
