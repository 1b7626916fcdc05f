// A small blocking HTTP/1.1 client on Boost.Beast for the tests, and raw-socket helpers
// for requests no well-behaved client would send.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include <chrono>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace prt::serve::test {

using Headers = std::vector<std::pair<std::string, std::string>>;

struct HttpResponse {
  int status = 0;            // 0: no response (error says why)
  std::string error;
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;
  bool keepAlive = false;    // the server keeps the connection open

  // The header's value, or "" when absent.
  std::string header(const std::string& lowerName) const;
  bool has(const std::string& lowerName) const { return headers.count(lowerName) > 0; }
};

// One keep-alive connection to 127.0.0.1:port. Every read gives up after `timeout`.
class HttpConnection {
 public:
  explicit HttpConnection(int port, std::chrono::milliseconds timeout = std::chrono::seconds(30));
  bool connected() const { return connected_; }
  // Sends one request (Host and HTTP/1.1 added) and reads the response; a HEAD response is
  // read without a body.
  HttpResponse request(std::string_view method, std::string_view target, const Headers& headers = {});

 private:
  boost::asio::io_context ioc_;
  boost::asio::ip::tcp::socket socket_;
  std::string buffer_;  // bytes read past the last response (never, without pipelining)
  bool connected_ = false;
};

// GET (or `method`) on a fresh connection.
HttpResponse fetch(int port, std::string_view target, const Headers& headers = {}, std::string_view method = "GET");

struct RawResult {
  std::string received;     // everything the server sent
  bool closedByServer = false;  // the server closed (EOF or reset) before the timeout
  std::chrono::milliseconds elapsed{0};
};

// Connects, sends `bytes` as they are, then reads until the
// server closes or `timeout` passes.
RawResult rawExchange(int port, std::string_view bytes, std::chrono::milliseconds timeout);

// The same from source address `source`: any of 127.0.0.0/8, so 127.0.0.2 is another client.
RawResult rawExchangeFrom(const std::string& source, int port, std::string_view bytes,
                          std::chrono::milliseconds timeout);

// A connection held open by the test (idle, or with part of a request sent), from `source`.
class RawConnection {
 public:
  explicit RawConnection(int port, const std::string& source = "127.0.0.1");
  bool connected() const { return connected_; }
  // Sends `bytes` as they are; false when the connection is gone.
  bool send(std::string_view bytes);
  // Reads until the server closes (EOF or reset: true) or `timeout` passes (false).
  bool closedWithin(std::chrono::milliseconds timeout);
  // Reads until received() holds a whole response (head and Content-Length body: true),
  // or the server closes or `timeout` passes (false).
  bool awaitResponse(std::chrono::milliseconds timeout);
  const std::string& received() const { return received_; }

 private:
  boost::asio::io_context ioc_;
  boost::asio::ip::tcp::socket socket_;
  bool connected_ = false;
  std::string received_;
};

// Connects `sock` (on its own io_context) to 127.0.0.1:port as a slow reader: a 16 KiB
// receive buffer, set before connecting so the advertised window stays small and the
// server stalls mid-body on a large response. False when the connection fails.
bool connectSlowReader(boost::asio::ip::tcp::socket& sock, int port);

// The status code of the first response in raw bytes ("HTTP/1.1 400 ..."), or 0.
int rawStatus(std::string_view received);

}  // namespace prt::serve::test
