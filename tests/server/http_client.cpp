#include "http_client.h"

#include <sys/socket.h>
#include <sys/time.h>

#include <boost/asio/connect.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <boost/beast/http/write.hpp>

#include <cctype>
#include <cstdlib>

namespace prt::serve::test {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using tcp = asio::ip::tcp;

namespace {

void setReceiveTimeout(tcp::socket& s, std::chrono::milliseconds timeout) {
  timeval tv{};
  tv.tv_sec = static_cast<time_t>(timeout.count() / 1000);
  tv.tv_usec = static_cast<suseconds_t>((timeout.count() % 1000) * 1000);
  ::setsockopt(s.native_handle(), SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  ::setsockopt(s.native_handle(), SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
}

bool connectTo(tcp::socket& s, int port, const std::string& source = "127.0.0.1") {
  beast::error_code ec;
  s.open(tcp::v4(), ec);
  if (source != "127.0.0.1") s.bind(tcp::endpoint(asio::ip::make_address(source), 0), ec);
  if (ec) return false;
  s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)), ec);
  return !ec;
}

// Reads what is there until EOF or reset (true) or `timeout` (false); the socket has a
// 100 ms receive timeout.
bool readUntilClosed(tcp::socket& s, std::string* out, std::chrono::milliseconds timeout) {
  const auto start = std::chrono::steady_clock::now();
  char buf[4096];
  while (std::chrono::steady_clock::now() - start < timeout) {
    const ssize_t n = ::recv(s.native_handle(), buf, sizeof buf, 0);
    if (n > 0) {
      out->append(buf, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) return true;
  }
  return false;
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

}  // namespace

std::string HttpResponse::header(const std::string& lowerName) const {
  const auto it = headers.find(lowerName);
  return it == headers.end() ? std::string() : it->second;
}

HttpConnection::HttpConnection(int port, std::chrono::milliseconds timeout) : socket_(ioc_) {
  connected_ = connectTo(socket_, port);
  if (connected_) setReceiveTimeout(socket_, timeout);
}

HttpResponse HttpConnection::request(std::string_view method, std::string_view target, const Headers& headers) {
  HttpResponse out;
  if (!connected_) {
    out.error = "not connected";
    return out;
  }
  http::request<http::empty_body> req;
  req.method_string(method);
  req.target(target);
  req.version(11);
  req.set(http::field::host, "127.0.0.1");
  for (const auto& [name, value] : headers) req.set(name, value);
  beast::error_code ec;
  http::write(socket_, req, ec);
  if (ec) {
    out.error = "write: " + ec.message();
    return out;
  }
  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(256u << 20);
  if (method == "HEAD") parser.skip(true);
  http::read(socket_, buffer, parser, ec);
  if (ec) {
    out.error = "read: " + ec.message();
    return out;
  }
  const auto& res = parser.get();
  out.status = static_cast<int>(res.result_int());
  for (const auto& field : res) {
    const std::string name = lower(field.name_string());
    // Repeated fields fold into one, comma-separated, as RFC 9110 §5.3 allows.
    auto [it, inserted] = out.headers.emplace(name, std::string(field.value()));
    if (!inserted) it->second += ", " + std::string(field.value());
  }
  out.body = res.body();
  out.keepAlive = res.keep_alive();
  return out;
}

HttpResponse fetch(int port, std::string_view target, const Headers& headers, std::string_view method) {
  HttpConnection c(port);
  return c.request(method, target, headers);
}

RawResult rawExchange(int port, std::string_view bytes, std::chrono::milliseconds timeout) {
  return rawExchangeFrom("127.0.0.1", port, bytes, timeout);
}

RawResult rawExchangeFrom(const std::string& source, int port, std::string_view bytes,
                          std::chrono::milliseconds timeout) {
  asio::io_context ioc;
  tcp::socket s(ioc);
  RawResult r;
  const auto start = std::chrono::steady_clock::now();
  if (!connectTo(s, port, source)) return r;
  setReceiveTimeout(s, std::chrono::milliseconds(100));
  beast::error_code ec;
  if (!bytes.empty()) asio::write(s, asio::buffer(bytes.data(), bytes.size()), ec);
  r.closedByServer = readUntilClosed(s, &r.received, timeout);
  r.elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
  return r;
}

bool connectSlowReader(asio::ip::tcp::socket& sock, int port) {
  beast::error_code ec;
  sock.open(asio::ip::tcp::v4(), ec);
  if (ec) return false;
  sock.set_option(asio::socket_base::receive_buffer_size(16384), ec);
  sock.connect({asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)}, ec);
  return !ec;
}

RawConnection::RawConnection(int port, const std::string& source) : socket_(ioc_) {
  connected_ = connectTo(socket_, port, source);
  if (connected_) setReceiveTimeout(socket_, std::chrono::milliseconds(100));
}

bool RawConnection::send(std::string_view bytes) {
  beast::error_code ec;
  asio::write(socket_, asio::buffer(bytes.data(), bytes.size()), ec);
  return !ec;
}

bool RawConnection::closedWithin(std::chrono::milliseconds timeout) {
  return connected_ && readUntilClosed(socket_, &received_, timeout);
}

bool RawConnection::awaitResponse(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buf[4096];
  while (connected_ && std::chrono::steady_clock::now() < deadline) {
    const std::size_t end = received_.find("\r\n\r\n");
    if (end != std::string::npos) {
      const std::string head = lower(received_.substr(0, end));
      const std::size_t at = head.find("\r\ncontent-length:");
      const std::size_t length = at == std::string::npos ? 0 : std::strtoull(head.c_str() + at + 17, nullptr, 10);
      if (received_.size() >= end + 4 + length) return true;
    }
    const ssize_t n = ::recv(socket_.native_handle(), buf, sizeof buf, 0);
    if (n > 0) {
      received_.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      return false;
    }
  }
  return false;
}

int rawStatus(std::string_view received) {
  if (!received.starts_with("HTTP/1.") || received.size() < 12) return 0;
  return std::atoi(std::string(received.substr(9, 3)).c_str());
}

}  // namespace prt::serve::test
