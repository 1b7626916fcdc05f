#include "session.h"

#include <linux/sockios.h>
#include <sys/ioctl.h>
#include <sys/sendfile.h>

#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/buffers_range.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/serializer.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "public_error.h"
#include "request_checks.h"
#include "respond.h"

namespace prt::serve {
namespace {

constexpr std::uint32_t kMaxHeadBytes = 8192;        // request line and header fields together
constexpr std::size_t kReadBufferBytes = 16384;      // holds a head plus a pipelined next one
constexpr std::size_t kMaxSendfileChunk = 1u << 30;  // below sendfile's 0x7ffff000 cap
constexpr std::size_t kMaxDrainBytes = 1u << 20;
constexpr auto kDrainTimeout = std::chrono::seconds(2);
constexpr auto kStoppingDrainTimeout = std::chrono::milliseconds(300);
constexpr std::chrono::microseconds kFirstAckPoll{200};
constexpr std::chrono::microseconds kMaxAckPoll{20000};

// The head as bytes, written by Beast's serializer.
std::string serializeHead(http::response<http::empty_body>& head) {
  http::response_serializer<http::empty_body> sr{head};
  sr.split(true);
  std::string out;
  beast::error_code ec;
  while (!ec && !sr.is_header_done()) {
    sr.next(ec, [&](beast::error_code& e, const auto& buffers) {
      e = {};
      for (const auto b : beast::buffers_range_ref(buffers)) out.append(static_cast<const char*>(b.data()), b.size());
      sr.consume(beast::buffer_bytes(buffers));
    });
  }
  return out;
}

bool isHttpParseError(const beast::error_code& ec) {
  return ec.category() == beast::error_code(http::error::bad_method).category();
}

}  // namespace

// ---- Session --------------------------------------------------------------------------

Session::Session(tcp::socket socket, SessionContext& context, std::string client, Admission admission)
    : stream_(std::move(socket)),
      timer_(stream_.get_executor()),
      context_(context),
      client_(std::move(client)),
      admission_(admission),
      refuse_(admission != Admission::kServe),
      buffer_(kReadBufferBytes),
      ackTimer_(stream_.get_executor()) {
  beast::error_code ec;
  const tcp::endpoint remote = stream_.socket().remote_endpoint(ec);
  peer_ = ec ? "-" : remote.address().to_string() + ":" + std::to_string(remote.port());
  // Heads and small bodies go out at once rather than waiting for the previous ACK.
  stream_.socket().set_option(tcp::no_delay(true), ec);
  // sendfile must never block an I/O thread: with O_NONBLOCK it returns EAGAIN instead.
  stream_.socket().native_non_blocking(true, ec);
}

Session::~Session() {
  flushLogs(true);  // at exit, responses still waiting for their acknowledgement
  if (registered_) context_.registry.remove(this);
}

void Session::start() {
  context_.registry.add(this, shared_from_this(), client_, refuse_);
  registered_ = true;
  asio::dispatch(stream_.get_executor(), [self = shared_from_this()] {
    if (self->refuse_) {
      self->method_ = "-";
      self->target_ = "-";
      self->started_ = std::chrono::steady_clock::now();
      const char* why = self->admission_ == Admission::kRefuseClient
                            ? "too many connections from your address; reuse or close some and try again"
                            : "too many connections; try again";
      Reply reply = errorReply(11, http::status::service_unavailable, why, false, true);
      reply.head.set(http::field::retry_after, "1");
      self->send(std::move(reply), false);
    } else {
      self->readHead();
    }
  });
}

void Session::stop() {
  asio::post(stream_.get_executor(), [self = shared_from_this()] {
    self->stopping_ = true;
    // A response being written or made finishes (onSent then closes); a wait for the
    // next request, or a lingering close, ends now.
    const State st = self->state_;
    if (st == State::kIdle || st == State::kReading || st == State::kClosing) self->closeNow();
  });
}

void Session::evict() {
  asio::post(stream_.get_executor(), [self = shared_from_this()] {
    // Closed like a keep-alive timeout: a client retries an idempotent request it may
    // have sent meanwhile (RFC 9112 §9.3.1). Past kIdle, onReadable closes instead.
    if (self->state_ == State::kIdle) self->closeNow();
  });
}

void Session::readHead() {
  if (stopping_) return closeGracefully();
  const auto deadline = std::chrono::steady_clock::now() + context_.readTimeout;
  if (buffer_.size() > 0) return readHeadUntil(deadline);  // a pipelined request is here already
  // Idle until the first byte: only now may the registry evict this connection to make
  // room, and the read timeout (idle time included) runs from here.
  state_ = State::kIdle;
  headDeadline_ = deadline;
  idleUnacknowledged_ = 0;
  context_.registry.markIdle(this);
  awaitIdleDeadline();
  stream_.socket().async_wait(tcp::socket::wait_read,
                              [self = shared_from_this()](beast::error_code ec) { self->onReadable(ec); });
}

void Session::awaitIdleDeadline() {
  timer_.expires_at(headDeadline_);
  timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (ec || self->state_ != State::kIdle) return;
    // The last write finished long ago, but a slow client may still be receiving the
    // response from the socket buffers (megabytes of them): its idle time has not begun.
    // While it makes progress the deadline moves on; a client that stopped reading goes.
    const std::uint64_t unacknowledged = self->unacknowledgedBytes();
    if (unacknowledged > 0 && unacknowledged != self->idleUnacknowledged_) {
      self->idleUnacknowledged_ = unacknowledged;
      self->headDeadline_ = std::chrono::steady_clock::now() + self->context_.readTimeout;
      return self->awaitIdleDeadline();
    }
    self->closeNow();  // idle too long: nothing to log
  });
}

std::uint64_t Session::unacknowledgedBytes() {
  // SIOCOUTQ: bytes written to the socket that the peer has not acknowledged yet (sent
  // or still queued). A slow client can leave megabytes there after the last write.
  int n = 0;
  if (::ioctl(stream_.socket().native_handle(), SIOCOUTQ, &n) != 0 || n < 0) return 0;
  return static_cast<std::uint64_t>(n);
}

void Session::onReadable(beast::error_code ec) {
  if (state_ != State::kIdle) return;  // closed: timed out, evicted or stopped
  timer_.cancel();
  if (!context_.registry.leaveIdle(this)) return closeNow();  // evicted meanwhile
  if (ec) return closeNow();
  readHeadUntil(headDeadline_);
}

void Session::readHeadUntil(std::chrono::steady_clock::time_point deadline) {
  state_ = State::kReading;
  parser_.emplace();
  parser_->header_limit(kMaxHeadBytes);
  stream_.expires_at(deadline);
  http::async_read_header(stream_, buffer_, *parser_,
                          [self = shared_from_this()](beast::error_code ec, std::size_t) { self->onHead(ec); });
}

void Session::onHead(beast::error_code ec) {
  if (state_ == State::kClosed) return;
  started_ = std::chrono::steady_clock::now();
  if (ec) {
    method_ = "-";
    target_ = "-";
    if (ec == http::error::header_limit || ec == http::error::buffer_overflow) {
      return send(errorReply(11, http::status::request_header_fields_too_large,
                             "request line and header fields may hold at most 8192 bytes", false, true),
                  false);
    }
    if (ec == beast::error::timeout) {
      // Beast has closed the socket already; a slow client that sent part of a request is
      // logged, one that merely idled between requests is not.
      if (buffer_.size() > 0 || parser_->got_some()) logRequest(408, 0);
      return closeNow();
    }
    if (ec == http::error::bad_version) {
      // Beast rejects every version but 1.0 and 1.1 alike; RFC 9110 §15.6.6 wants 505 for a
      // well-formed version the server does not support, 400 stays for a malformed one.
      const std::string_view data(static_cast<const char*>(buffer_.data().data()), buffer_.size());
      if (wellFormedButUnsupportedVersion(data.substr(0, data.find('\n')))) {
        return send(errorReply(11, http::status::http_version_not_supported,
                               "only HTTP/1.0 and HTTP/1.1 are served", false, true),
                    false);
      }
    }
    if (ec != http::error::partial_message && ec != http::error::end_of_stream && isHttpParseError(ec)) {
      return send(errorReply(11, http::status::bad_request, "malformed request: " + ec.message(), false, true), false);
    }
    return closeNow();  // the client went away (cleanly or not) or the server is stopping
  }
  stream_.expires_never();
  const auto& request = parser_->get();
  method_ = std::string(request.method_string());
  target_ = std::string(request.target());
  Reply reply;
  const bool getOrHead = request.method() == http::verb::get || request.method() == http::verb::head;
  // (The parser has already refused every version but 1.0 and 1.1.)
  if (const std::string_view problem = requestHeadProblem(request); !problem.empty()) {
    reply = errorReply(request.version(), http::status::bad_request, problem, false, true);
  } else if (!parser_->is_done() && getOrHead) {
    // A body on GET/HEAD has no meaning here, and not reading it leaves no way to find
    // the next request: refuse and close.
    reply = errorReply(request.version(), http::status::bad_request, "GET and HEAD requests take no body", false, true);
  } else {
    Answer answer = context_.router.handle(request);
    if (answer.deferred) return awaitReply(std::move(answer.deferred), request.method() == http::verb::head,
                                           request.keep_alive(), !parser_->is_done());
    reply = std::move(answer.reply);
    // Any other method with a body: 405, and the unread body makes the connection unusable.
    if (!parser_->is_done()) reply.close = true;
  }
  if (request.method() == http::verb::head) reply.length = 0;
  send(std::move(reply), request.keep_alive() && !stopping_);
}

void Session::awaitReply(std::function<void(ReplySink)> work, bool isHead, bool keepAlive, bool unreadBody) {
  // Neither reading nor writing: the reply is being made elsewhere. A stop lets it finish,
  // like a response being written; the sink brings it back onto this connection's strand.
  state_ = State::kWaiting;
  work([self = shared_from_this(), isHead, keepAlive, unreadBody](Reply reply) {
    asio::post(self->stream_.get_executor(), [self, reply = std::move(reply), isHead, keepAlive, unreadBody]() mutable {
      if (self->state_ != State::kWaiting) return;
      if (isHead) reply.length = 0;
      if (unreadBody) reply.close = true;
      self->send(std::move(reply), keepAlive && !self->stopping_);
    });
  });
}

void Session::send(Reply reply, bool keepAlive) {
  state_ = State::kWriting;
  reply_ = std::move(reply);
  keepAlive_ = keepAlive && !reply_.close;
  reply_.head.keep_alive(keepAlive_);
  head_ = serializeHead(reply_.head);
  bodySent_ = 0;
  stream_.expires_after(context_.writeTimeout);
  auto self = shared_from_this();
  if (reply_.length > 0 && reply_.body.memory) {
    const std::array<asio::const_buffer, 2> buffers{
        asio::buffer(head_), asio::buffer(reply_.body.memory->data() + reply_.offset, reply_.length)};
    asio::async_write(stream_, buffers, [self](beast::error_code ec, std::size_t n) {
      self->written_ += n;
      self->onSent(ec, n > self->head_.size() ? n - self->head_.size() : 0);
    });
  } else if (reply_.length > 0 && reply_.body.file) {
    asio::async_write(stream_, asio::buffer(head_), [self](beast::error_code ec, std::size_t n) {
      self->written_ += n;
      self->onHeadSent(ec);
    });
  } else {
    asio::async_write(stream_, asio::buffer(head_), [self](beast::error_code ec, std::size_t n) {
      self->written_ += n;
      self->onSent(ec, 0);
    });
  }
}

void Session::onHeadSent(beast::error_code ec) {
  if (ec) return onSent(ec, 0);
  stream_.expires_never();
  fileOffset_ = reply_.offset;
  remaining_ = reply_.length;
  sendFileSome();
}

void Session::sendFileSome() {
  const int sock = stream_.socket().native_handle();
  const int fd = reply_.body.file->fd();
  while (remaining_ > 0) {
    off_t offset = static_cast<off_t>(fileOffset_);
    const std::size_t chunk = remaining_ < kMaxSendfileChunk ? static_cast<std::size_t>(remaining_) : kMaxSendfileChunk;
    const ssize_t n = ::sendfile(sock, fd, &offset, chunk);
    if (n > 0) {
      fileOffset_ += static_cast<std::uint64_t>(n);
      remaining_ -= static_cast<std::uint64_t>(n);
      bodySent_ += static_cast<std::uint64_t>(n);
      written_ += static_cast<std::uint64_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      // The socket buffer is full: wait until the client reads, but not forever.
      timer_.expires_after(context_.writeTimeout);
      timer_.async_wait([self = shared_from_this()](beast::error_code tec) {
        if (!tec && self->timer_.expiry() <= std::chrono::steady_clock::now()) {
          beast::error_code ignored;
          self->stream_.socket().cancel(ignored);
        }
      });
      stream_.socket().async_wait(tcp::socket::wait_write, [self = shared_from_this()](beast::error_code wec) {
        self->timer_.cancel();
        if (wec) return self->onSent(wec, self->bodySent_);
        self->sendFileSome();
      });
      return;
    }
    if (n < 0 && (errno == EPIPE || errno == ECONNRESET)) {
      return onSent(beast::error_code(errno, beast::system_category()), bodySent_);  // the client left
    }
    // n == 0: the file ended early; n < 0: a read error (EIO). The client was promised
    // more bytes. A reset rather than a FIN, so no client or cache in between can take the
    // bytes it has for a whole, shorter body.
    const int err = n == 0 ? EIO : errno;
    logRequest(reply_.head.result_int(), bodySent_);
    logDetail("sending " + target_ + " failed after " + std::to_string(bodySent_) + " body bytes",
              std::strerror(err));
    reply_ = Reply{};
    return abortNow();
  }
  onSent({}, bodySent_);
}

void Session::onSent(beast::error_code ec, std::uint64_t bodyBytes) {
  stream_.expires_never();
  logRequest(reply_.head.result_int(), bodyBytes);
  reply_ = Reply{};  // drop the file reference now, not at the next request
  if (ec) return closeNow();
  if (keepAlive_ && !stopping_) return readHead();
  closeGracefully();
}

void Session::closeGracefully() {
  // Half-close, then read and discard until the client closes too: closing with unread
  // input makes the kernel send RST, which can destroy the response before the client
  // has read it (the "lingering close" of RFC 9112 §9.6).
  state_ = State::kClosing;
  beast::error_code ec;
  stream_.socket().shutdown(tcp::socket::shutdown_send, ec);
  if (ec) return closeNow();
  drained_ = 0;
  // While the server stops, a client that keeps its end open must not delay the exit long.
  stream_.expires_after(stopping_ ? kStoppingDrainTimeout : kDrainTimeout);
  drain();
}

void Session::drain() {
  stream_.async_read_some(asio::buffer(drainBuffer_), [self = shared_from_this()](beast::error_code ec, std::size_t n) {
    self->drained_ += n;
    if (ec || self->drained_ > kMaxDrainBytes || self->state_ != State::kClosing) return self->closeNow();
    self->drain();
  });
}

void Session::abortNow() {
  // SO_LINGER with a zero timeout: close() sends RST and drops whatever is still queued.
  beast::error_code ignored;
  stream_.socket().set_option(asio::socket_base::linger(true, 0), ignored);
  closeNow();
}

void Session::closeNow() {
  if (state_ == State::kClosed) return;
  flushLogs(true);
  state_ = State::kClosed;
  timer_.cancel();
  ackTimer_.cancel();
  stream_.close();
}

void Session::logRequest(unsigned status, std::uint64_t bytes) {
  if (!context_.log.enabled()) return;
  pendingLogs_.push_back({written_, status, bytes, method_, target_, started_});
  flushLogs(false);
}

void Session::flushLogs(bool all) {
  const std::uint64_t acknowledged = all ? written_ : written_ - std::min(written_, unacknowledgedBytes());
  const auto now = std::chrono::steady_clock::now();
  while (!pendingLogs_.empty() && (all || pendingLogs_.front().end <= acknowledged)) {
    const PendingLog& p = pendingLogs_.front();
    const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(now - p.started).count();
    context_.log.write({peer_, p.method, p.target, p.status, p.bytes, static_cast<std::int64_t>(micros)});
    pendingLogs_.pop_front();
  }
  if (pendingLogs_.empty()) {
    ackPoll_ = kFirstAckPoll;
    return;
  }
  if (ackTimerArmed_) return;
  // No event says "acknowledged": look again soon, then less often (the error in the
  // logged time stays under kMaxAckPoll, or half the time waited).
  ackTimerArmed_ = true;
  ackTimer_.expires_after(ackPoll_);
  ackPoll_ = std::min<std::chrono::microseconds>(ackPoll_ * 2, kMaxAckPoll);
  ackTimer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    self->ackTimerArmed_ = false;
    if (!ec && self->state_ != State::kClosed) self->flushLogs(false);
  });
}

}  // namespace prt::serve
