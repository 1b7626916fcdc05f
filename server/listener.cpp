#include "listener.h"

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>

#include <cstdio>
#include <string>

namespace prt::serve {
namespace {

// The key of the per-client cap: the peer's address, an IPv4-mapped IPv6 one as IPv4.
std::string clientOf(const tcp::socket& socket) {
  beast::error_code ec;
  asio::ip::address a = socket.remote_endpoint(ec).address();
  if (ec) return "-";
  if (a.is_v6() && a.to_v6().is_v4_mapped()) a = asio::ip::make_address_v4(asio::ip::v4_mapped, a.to_v6());
  return a.to_string();
}

}  // namespace

Listener::Listener(asio::io_context& ioc, tcp::acceptor acceptor, SessionContext& context, std::size_t maxConnections,
                   std::size_t maxPerClient)
    : ioc_(ioc),
      strand_(asio::make_strand(ioc)),
      acceptor_(std::move(acceptor)),
      retry_(strand_),
      context_(context),
      maxConnections_(maxConnections),
      maxPerClient_(maxPerClient) {}

void Listener::start() {
  asio::dispatch(strand_, [self = shared_from_this()] { self->accept(); });
}

void Listener::stop() {
  asio::post(strand_, [self = shared_from_this()] {
    self->stopped_ = true;
    beast::error_code ec;
    self->acceptor_.close(ec);
    self->retry_.cancel();
  });
}

void Listener::accept() {
  if (stopped_) return;
  // Each connection gets its own strand: its handlers never run concurrently, while
  // different connections use every thread.
  acceptor_.async_accept(asio::make_strand(ioc_), asio::bind_executor(strand_, [self = shared_from_this()](
                                                                                  beast::error_code ec, tcp::socket s) {
                           self->onAccept(ec, std::move(s));
                         }));
}

void Listener::onAccept(beast::error_code ec, tcp::socket socket) {
  if (stopped_ || ec == asio::error::operation_aborted) return;
  if (ec) {
    // Out of descriptors (EMFILE) or similar: pause instead of spinning on the error.
    std::fprintf(stderr, "prt-serve: accept failed: %s; retrying in 100 ms\n", ec.message().c_str());
    retry_.expires_after(std::chrono::milliseconds(100));
    retry_.async_wait([self = shared_from_this()](beast::error_code tec) {
      if (!tec) self->accept();
    });
    return;
  }
  std::string client = clientOf(socket);
  const Admission admission = context_.registry.admit(client, maxConnections_, maxPerClient_);
  if (admission == Admission::kDrop) {
    beast::error_code ignored;
    socket.close(ignored);
  } else {
    std::make_shared<Session>(std::move(socket), context_, std::move(client), admission)->start();
  }
  accept();
}

}  // namespace prt::serve
