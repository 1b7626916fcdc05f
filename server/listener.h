// Accepting connections, and the connection caps (the registry decides): a client beyond
// them gets a quick 503 rather than a hang in the listen backlog.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>

#include <cstddef>
#include <memory>

#include "session.h"

namespace prt::serve {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // `acceptor` is bound and listening.
  Listener(asio::io_context& ioc, tcp::acceptor acceptor, SessionContext& context, std::size_t maxConnections,
           std::size_t maxPerClient);

  // Starts the accept loop on the listener's strand.
  void start();
  // Thread-safe: stops accepting (closes the listening socket).
  void stop();

 private:
  void accept();
  void onAccept(beast::error_code ec, tcp::socket socket);

  asio::io_context& ioc_;
  asio::strand<asio::io_context::executor_type> strand_;
  tcp::acceptor acceptor_;
  asio::steady_timer retry_;
  SessionContext& context_;
  std::size_t maxConnections_;
  std::size_t maxPerClient_;
  bool stopped_ = false;
};

}  // namespace prt::serve
