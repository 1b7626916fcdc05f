// A response ready to send: the head as Beast builds it, and which bytes of which body
// follow it. The session sends the head with Beast and the body with sendfile (files) or
// in the same write as the head (memory).
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>

#include <cstdint>

#include "resource.h"

namespace prt::serve {

namespace http = boost::beast::http;

struct Reply {
  http::response<http::empty_body> head;  // Content-Length already set
  BodySource body;                        // may be empty (HEAD, 304, 416)
  std::uint64_t offset = 0;               // first byte of `body` to send
  std::uint64_t length = 0;               // bytes to send after the head
  bool close = false;                     // close the connection after this reply
};

}  // namespace prt::serve
