// A response ready to send: the head as Beast builds it, and which bytes of which body
// follow it. The session sends the head with Beast and the body with sendfile (files) or
// in the same write as the head (memory).
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>

#include <cstdint>
#include <functional>
#include <utility>

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

// Hands over a reply that was made off the I/O threads; callable from any thread, once.
using ReplySink = std::function<void(Reply)>;

// What the router answers a request with: a reply now, or work that will hand the reply
// to the sink the session gives it (so a slow document never holds an I/O thread).
struct Answer {
  Answer(Reply now) : reply(std::move(now)) {}  // NOLINT(google-explicit-constructor): the common case
  explicit Answer(std::function<void(ReplySink)> later) : deferred(std::move(later)) {}

  Reply reply;                              // when !deferred
  std::function<void(ReplySink)> deferred;  // set: call it once with the sink
};

}  // namespace prt::serve
