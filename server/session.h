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
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "access_log.h"
#include "session_registry.h"
#include "reply.h"
#include "router.h"

namespace prt::serve {

namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;

struct SessionContext {
  Router& router;
  const AccessLog& log;
  SessionRegistry& registry;
  std::chrono::milliseconds readTimeout;   // to receive a whole request head, idle time included
  std::chrono::milliseconds writeTimeout;  // without any progress while sending
};

class Session : public std::enable_shared_from_this<Session> {
 public:
  // `client`: the peer's address, for the per-client cap. `admission`: what the registry
  // decided; a refusal makes the session answer 503 and close.
  Session(tcp::socket socket, SessionContext& context, std::string client, Admission admission);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Registers with the registry and starts reading (or refusing).
  void start();
  // Thread-safe: finish the response in flight, if any, then close.
  void stop();
  // Thread-safe; called by the registry, which has chosen this idle session to make room
  // for a new connection: close it unless it is already reading a request.
  void evict();

 private:
  // kIdle: no byte of the next request yet (evictable); kReading: a request head is
  // arriving; kWaiting: its reply is being made off the I/O threads.
  enum class State { kIdle, kReading, kWaiting, kWriting, kClosing, kClosed };

  // Waits for the next request: for its first byte (idle) unless one is buffered already.
  void readHead();
  // Closes the idle connection at headDeadline_, unless the client is still receiving.
  void awaitIdleDeadline();
  void onReadable(beast::error_code ec);
  // Bytes written to the socket and not yet acknowledged by the client.
  std::uint64_t unacknowledgedBytes();
  void readHeadUntil(std::chrono::steady_clock::time_point deadline);
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
  // Logs the request once the client has acknowledged the last byte of what was written
  // for it (the access log's time is to the last byte received, not to the last write).
  void logRequest(unsigned status, std::uint64_t bytes);
  // Writes the pending lines whose bytes are acknowledged (all of them when `all`).
  void flushLogs(bool all);

  beast::tcp_stream stream_;
  asio::steady_timer timer_;  // deadlines Beast's stream does not keep: idle wait, sendfile
  SessionContext& context_;
  const std::string client_;
  const Admission admission_;
  const bool refuse_;
  bool registered_ = false;
  std::chrono::steady_clock::time_point headDeadline_;
  std::uint64_t idleUnacknowledged_ = 0;  // at the last idle deadline, to tell progress
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

  // Access-log lines waiting for their response's last byte to be acknowledged.
  struct PendingLog {
    std::uint64_t end;  // written_ after the response's last byte
    unsigned status;
    std::uint64_t bytes;
    std::string method;
    std::string target;
    std::chrono::steady_clock::time_point started;
  };
  std::uint64_t written_ = 0;  // bytes written to the socket, all responses together
  std::deque<PendingLog> pendingLogs_;
  asio::steady_timer ackTimer_;
  bool ackTimerArmed_ = false;
  std::chrono::microseconds ackPoll_{200};

  std::array<char, 4096> drainBuffer_{};
  std::size_t drained_ = 0;
};

}  // namespace prt::serve
