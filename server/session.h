// One client connection: read a request head (with a deadline), answer it, repeat while
// keep-alive allows, then close politely. Bodies from files go out with sendfile(2), so
// asset bytes never pass through user space; memory bodies share the head's write.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/http/parser.hpp>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

#include "access_log.h"
#include "reply.h"
#include "router.h"

namespace prt::serve {

namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;

class Session;

// Every open connection, for the connection cap and for shutdown. Thread-safe.
class SessionRegistry {
 public:
  // Registers a session (`refusing`: it only sends 503 and closes).
  void add(Session* session, const std::shared_ptr<Session>& shared, bool refusing);
  // Forgets a session; called from its destructor.
  void remove(Session* session, bool refusing);
  std::size_t active() const;    // sessions serving requests
  std::size_t refusing() const;  // sessions only sending 503 before closing
  // Asks every session to finish its current response and close.
  void stopAll();
  // Waits until no session is left or `deadline` passes; true when none is left.
  bool waitEmpty(std::chrono::steady_clock::time_point deadline);

 private:
  mutable std::mutex mutex_;
  std::condition_variable empty_;
  std::unordered_map<Session*, std::weak_ptr<Session>> sessions_;
  std::size_t refusing_ = 0;
};

struct SessionContext {
  Router& router;
  const AccessLog& log;
  SessionRegistry& registry;
  std::chrono::milliseconds readTimeout;   // to receive a whole request head, idle time included
  std::chrono::milliseconds writeTimeout;  // without any progress while sending
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  // `refuse`: the server is at its connection cap; answer 503 and close.
  Session(tcp::socket socket, SessionContext& context, bool refuse);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Registers with the registry and starts reading (or refusing).
  void start();
  // Thread-safe: finish the response in flight, if any, then close.
  void stop();

 private:
  enum class State { kReading, kWaiting, kWriting, kClosing, kClosed };

  void readHead();
  void onHead(beast::error_code ec);
  // Hands `work` a sink for the reply it makes off the I/O threads, and sends it when it comes.
  void awaitReply(std::function<void(ReplySink)> work, bool isHead, bool keepAlive, bool unreadBody);
  void send(Reply reply, bool keepAlive);
  void onHeadSent(beast::error_code ec);
  void sendFileSome();
  void onSent(beast::error_code ec, std::uint64_t bodyBytes);
  void closeGracefully();
  void drain();
  void closeNow();
  // Ends the connection with a TCP reset: for a body that cannot be completed as promised.
  void abortNow();
  void logRequest(unsigned status, std::uint64_t bytes);

  beast::tcp_stream stream_;
  asio::steady_timer timer_;  // the sendfile phase's write deadline
  SessionContext& context_;
  const bool refuse_;
  bool registered_ = false;
  std::string peer_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::empty_body>> parser_;
  State state_ = State::kReading;
  bool stopping_ = false;
  bool keepAlive_ = false;

  // The reply in flight and what the access log needs about its request.
  Reply reply_;
  std::string head_;
  std::uint64_t fileOffset_ = 0;
  std::uint64_t remaining_ = 0;
  std::uint64_t bodySent_ = 0;
  std::string method_;
  std::string target_;
  std::chrono::steady_clock::time_point started_;

  std::array<char, 4096> drainBuffer_{};
  std::size_t drained_ = 0;
};

}  // namespace prt::serve
