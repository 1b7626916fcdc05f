// Requests a hostile client sends, each followed by a check that the server still
// answers ordinary requests: traversal in every spelling, symlinks out of the roots,
// unsupported methods, oversized and malformed requests, slow clients, connection floods.
#include <gtest/gtest.h>

#include <unistd.h>

#include <thread>

#include "serve_env.h"

namespace prt::serve::test {
namespace {

// A raw request line for `target` (sent as is, no client-side normalisation).
std::string rawGet(const std::string& target, const std::string& extra = "") {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\n" + extra + "Connection: close\r\n\r\n";
}

// How many times `needle` occurs in the server's access log.
int countInLog(const ServerProcess& server, const std::string& needle) {
  const std::string log = server.log();
  int n = 0;
  for (std::size_t at = log.find(needle); at != std::string::npos; at = log.find(needle, at + 1)) ++n;
  return n;
}

// Waits (up to 5 s) until the access log holds `count` lines with `needle`. A response's
// line is written by the server's handler that ran after its last write, on the way to
// waiting for the next request (the moment a connection becomes idle): unlike the client
// having the bytes, it does not race that handler being scheduled on a loaded machine.
bool waitForLogged(const ServerProcess& server, const std::string& needle, int count) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (countInLog(server, needle) < count) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

void expectNoSecret(const std::string& received, const std::string& what) {
  EXPECT_EQ(received.find("top secret"), std::string::npos) << what;
  EXPECT_EQ(received.find("root:x:0"), std::string::npos) << what;
  EXPECT_EQ(received.find("PASSWORD"), std::string::npos) << what;
}

TEST(Hostile, TraversalInEverySpellingNeverLeavesTheRoots) {
  SharedServer& s = sharedServer();
  const std::string secretAsset = "/assets/" + hexHash(s.tree.small);
  for (const std::string& target : std::vector<std::string>{"/../../../../etc/passwd", "/..%2f..%2f..%2fetc%2fpasswd", "/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
        "/%2E%2E/%2E%2E/etc/passwd", "/.%2e/.%2e/etc/passwd", "/docs/../../outside/secret.txt",
        "/docs/%2e%2e/%2e%2e/outside/secret.txt", "/..\\..\\..\\etc\\passwd", "/..%5c..%5c..%5cetc%5cpasswd",
        "/%5c..%5c..%5coutside%5csecret.txt", "/%00", "/index.html%00.png", "/%00../../etc/passwd",
        "//etc/passwd", "/%2fetc%2fpasswd", "/%2F%2Fetc/passwd", "/etc/passwd", "/leak.txt", "/leakdir/secret.txt",
        "/.env", "/docs/.env", "/%2eenv", "/assets/../../outside/secret.prt", "/assets/%2e%2e/outside/secret.prt",
        secretAsset + "/escape.prt", secretAsset + "/secret.prt", "/api/../../etc/passwd",
        "/api/lights/preview/../../../etc/passwd", "http://127.0.0.1/etc/passwd", "/%252e%252e/%252e%252e/etc/passwd",
        "/\xc0\xae\xc0\xae/etc/passwd", "/%c0%ae%c0%ae/etc/passwd"}) {
    const RawResult r = rawExchange(s.port, rawGet(target), std::chrono::seconds(5));
    const int status = rawStatus(r.received);
    EXPECT_TRUE(status == 400 || status == 404) << target << " -> " << r.received.substr(0, 200);
    expectNoSecret(r.received, target);
    EXPECT_TRUE(healthy(s.port)) << "after " << target;
  }
  // The same through the client library, and a symlink that stays inside is fine.
  EXPECT_EQ(fetch(s.port, "/leak.txt").status, 404);
  EXPECT_EQ(fetch(s.port, "/alias.html").status, 200);
}

TEST(Hostile, NulByteInTheRequestLine) {
  SharedServer& s = sharedServer();
  using namespace std::string_literals;
  const RawResult r = rawExchange(s.port, "GET /index.html\0/../../etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n"s,
                                  std::chrono::seconds(5));
  EXPECT_EQ(rawStatus(r.received), 400);
  EXPECT_TRUE(r.closedByServer);
  expectNoSecret(r.received, "NUL");
  EXPECT_TRUE(healthy(s.port));
}

TEST(Hostile, OtherMethodsAre405) {
  SharedServer& s = sharedServer();
  for (const char* method : {"POST", "PUT", "DELETE", "PATCH", "OPTIONS", "TRACE", "PROPFIND", "BREW"}) {
    const RawResult r = rawExchange(s.port, std::string(method) + " /api/scenes HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n",
                                    std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(r.received), 405) << method << ": " << r.received.substr(0, 100);
    EXPECT_NE(r.received.find("Allow: GET, HEAD"), std::string::npos) << method;
    EXPECT_TRUE(healthy(s.port)) << method;
  }
  // With a body the server will not read: 405, then the connection closes.
  const RawResult post = rawExchange(
      s.port, "POST /api/scenes HTTP/1.1\r\nHost: x\r\nContent-Length: 11\r\n\r\nhello world", std::chrono::seconds(5));
  EXPECT_EQ(rawStatus(post.received), 405);
  EXPECT_TRUE(post.closedByServer);
  const RawResult chunked = rawExchange(
      s.port, "PUT /x HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n", std::chrono::seconds(5));
  EXPECT_EQ(rawStatus(chunked.received), 405);
  EXPECT_TRUE(healthy(s.port));
}

TEST(Hostile, OversizedRequestLineAndHeaders) {
  SharedServer& s = sharedServer();
  const std::vector<std::string> requests{
      rawGet("/" + std::string(20000, 'a')),
      rawGet("/", "X-Big: " + std::string(20000, 'b') + "\r\n"),
      [] {
        std::string many;
        for (int i = 0; i < 2000; ++i) many += "X-H" + std::to_string(i) + ": v\r\n";
        return rawGet("/", many);
      }(),
      "GET /" + std::string(1 << 20, 'c'),  // a megabyte of request line, never finished
  };
  for (const std::string& req : requests) {
    const RawResult r = rawExchange(s.port, req, std::chrono::seconds(10));
    const int status = rawStatus(r.received);
    EXPECT_TRUE(status == 431 || status == 400) << status << " for a " << req.size() << "-byte request";
    EXPECT_TRUE(r.closedByServer);
    EXPECT_TRUE(healthy(s.port));
  }
}

TEST(Hostile, MalformedRequestsGet400AndClose) {
  SharedServer& s = sharedServer();
  std::string junk;
  for (int i = 0; i < 1000; ++i) junk += static_cast<char>((i * 7919) % 251 + 1);
  const std::vector<std::string> requests{
      "GARBAGE\r\n\r\n",
      "GET\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: x\r\nBad Header\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: x\r\n: no name\r\n\r\n",
      "GET / HTTP/1.1\nHost: x\n\n",
      "GET / HTTP/1.1\r\n\r\n",  // HTTP/1.1 without Host
      "GET / HTTP/2.0\r\nHost: x\r\n\r\n",
      "GET / HTTX/1.1\r\nHost: x\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: abc\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n",
      "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\n\r\nhello",  // a body on GET
      "GET / HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n",
      "GET /\xff\xfe HTTP/1.1\r\nHost: x\r\n\r\n",
      "GET /a b HTTP/1.1\r\nHost: x\r\n\r\n",
      junk + "\r\n\r\n",
  };
  for (const std::string& req : requests) {
    const RawResult r = rawExchange(s.port, req, std::chrono::seconds(10));
    const int status = rawStatus(r.received);
    EXPECT_TRUE(status == 400 || status == 505) << status << " for " << testing::PrintToString(req.substr(0, 60));
    EXPECT_TRUE(r.closedByServer) << testing::PrintToString(req.substr(0, 60));
    EXPECT_TRUE(healthy(s.port)) << "after " << testing::PrintToString(req.substr(0, 60));
  }
}

// How many responses (status lines) a raw exchange received.
int responseCount(const std::string& received) {
  int n = 0;
  for (std::size_t at = received.find("HTTP/1."); at != std::string::npos; at = received.find("HTTP/1.", at + 1)) {
    if (at == 0 || received.compare(at - 2, 2, "\r\n") == 0) ++n;
  }
  return n;
}

TEST(Hostile, TransferEncodingOtherThanChunkedIs400AndNothingIsSmuggled) {
  SharedServer& s = sharedServer();
  // RFC 9112 §6.3: a request whose Transfer-Encoding does not end in chunked (or holds a
  // coding the server does not know) has no reliable length: 400, then close. Served as
  // bodiless instead, the bytes after the head would be answered as a second request.
  const std::vector<std::pair<std::string, std::string>> cases{
      {"1.1", "Transfer-Encoding: gzip\r\n"},
      {"1.1", "Transfer-Encoding: identity\r\n"},
      {"1.1", "Transfer-Encoding: xchunked\r\n"},
      {"1.1", "Transfer-Encoding: chunked, identity\r\n"},
      {"1.1", "Transfer-Encoding: gzip, chunked\r\n"},
      {"1.1", "Transfer-Encoding: chunked, chunked\r\n"},
      {"1.1", "Transfer-Encoding: chunked;ext=1\r\n"},
      {"1.1", "Transfer-Encoding: gzip\r\nTransfer-Encoding: chunked\r\n"},
      {"1.1", "Transfer-Encoding: \r\n"},
      {"1.1", "Transfer-Encoding: gzip\r\nContent-Length: 0\r\n"},
      {"1.1", "Content-Length: 0\r\nTransfer-Encoding: chunked\r\n"},
      {"1.0", "Transfer-Encoding: chunked\r\n"},
      {"1.0", "Transfer-Encoding: gzip\r\n"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [version, te] = cases[i];
    const std::string smuggled = "/smuggled-" + std::to_string(::getpid()) + "-" + std::to_string(i);
    const std::string req = "GET /api/scenes HTTP/" + version + "\r\nHost: x\r\n" + te + "\r\n" + "GET " + smuggled +
                            " HTTP/1.1\r\nHost: x\r\n\r\n";
    const RawResult r = rawExchange(s.port, req, std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(r.received), 400) << testing::PrintToString(te) << ": " << r.received.substr(0, 120);
    EXPECT_EQ(responseCount(r.received), 1) << testing::PrintToString(te);
    EXPECT_TRUE(r.closedByServer) << testing::PrintToString(te);
    EXPECT_EQ(s.server->log().find(smuggled), std::string::npos) << "smuggled request answered: " << te;
  }
  // Chunked alone still frames a body, which GET may not have: 400 as before; other
  // methods get 405 and the connection closes.
  EXPECT_EQ(rawStatus(rawExchange(s.port, "GET / HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: Chunked\r\n\r\n0\r\n\r\n",
                                  std::chrono::seconds(5)).received), 400);
  EXPECT_TRUE(healthy(s.port));
}

TEST(Hostile, HostMustBeOneValidField) {
  SharedServer& s = sharedServer();
  // RFC 9112 §3.2: 400 for an HTTP/1.1 request without Host, for more than one Host line,
  // and for a Host value that is not uri-host[:port].
  const std::vector<std::string> bad{
      "GET /api/scenes HTTP/1.1\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a\r\nHost: a\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n",
      "GET /api/scenes HTTP/1.0\r\nHost: a\r\nHost: b\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a b\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a/b\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a@b\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a:b\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: a:80:80\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: [::1\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: [zz::1]\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: %zz\r\n\r\n",
  };
  for (const std::string& req : bad) {
    const RawResult r = rawExchange(s.port, req, std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(r.received), 400) << testing::PrintToString(req) << ": " << r.received.substr(0, 120);
    EXPECT_TRUE(r.closedByServer) << testing::PrintToString(req);
  }
  const std::vector<std::string> good{
      "GET /api/scenes HTTP/1.1\r\nHost: 127.0.0.1:8080\r\nConnection: close\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: [::1]:80\r\nConnection: close\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost: prt.example.com\r\nConnection: close\r\n\r\n",
      "GET /api/scenes HTTP/1.1\r\nHost:\r\nConnection: close\r\n\r\n",  // empty: allowed
      "GET /api/scenes HTTP/1.0\r\n\r\n",                                  // HTTP/1.0 needs none
  };
  for (const std::string& req : good) {
    EXPECT_EQ(rawStatus(rawExchange(s.port, req, std::chrono::seconds(5)).received), 200) << testing::PrintToString(req);
  }
  EXPECT_TRUE(healthy(s.port));
}

TEST(Hostile, UnsupportedVersionsAre505AndMalformedOnes400) {
  SharedServer& s = sharedServer();
  for (const std::string line : {"GET / HTTP/2.0", "GET / HTTP/1.2", "GET / HTTP/0.9", "GET / HTTP/3.0", "PRI * HTTP/2.0"}) {
    const RawResult r = rawExchange(s.port, line + "\r\nHost: x\r\n\r\n", std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(r.received), 505) << line << ": " << r.received.substr(0, 120);
    EXPECT_TRUE(r.closedByServer) << line;
  }
  for (const std::string line : {"GET / HTTP/1.10", "GET / HTTX/1.1", "GET / HTTP/1.x", "GET / HTTP/11"}) {
    const RawResult r = rawExchange(s.port, line + "\r\nHost: x\r\n\r\n", std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(r.received), 400) << line << ": " << r.received.substr(0, 120);
    EXPECT_TRUE(r.closedByServer) << line;
  }
  EXPECT_TRUE(healthy(s.port));
}

TEST(Hostile, SlowClientsAreCutOffAndDoNotHoldTheServer) {
  const TestTree tree = makeTestTree(workDir());
  auto server = startServer(tree, {"--read-timeout", "1", "--threads", "2"}, "slow.log");
  ASSERT_TRUE(server);
  const int port = server->port();
  // Slowloris: many connections, each trickling a request head a byte at a time.
  constexpr int kSlow = 40;
  std::vector<std::thread> slow;
  std::vector<RawResult> results(kSlow);
  std::atomic<bool> done{false};
  for (int i = 0; i < kSlow; ++i) {
    slow.emplace_back([&, i] {
      boost::asio::io_context ioc;
      boost::asio::ip::tcp::socket sock(ioc);
      boost::system::error_code ec;
      sock.connect({boost::asio::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)}, ec);
      if (ec) return;
      const std::string head = "GET / HTTP/1.1\r\nHost: x\r\nX-Slow: " + std::string(200, 'z');
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t k = 0; k < head.size() && !done; ++k) {
        if (::send(sock.native_handle(), head.data() + k, 1, MSG_NOSIGNAL) != 1) {
          results[static_cast<std::size_t>(i)].closedByServer = true;
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      results[static_cast<std::size_t>(i)].elapsed =
          std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start);
    });
  }
  // An idle connection that never sends anything is dropped too.
  const RawResult silent = rawExchange(port, "", std::chrono::seconds(5));
  EXPECT_TRUE(silent.closedByServer);
  EXPECT_LT(silent.elapsed.count(), 3000);
  // Meanwhile ordinary requests are answered promptly.
  for (int i = 0; i < 10; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_TRUE(healthy(port));
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::seconds(2));
  done = true;
  for (std::thread& t : slow) t.join();
  for (int i = 0; i < kSlow; ++i) {
    // Cut off after about the read timeout, long before the 21 s the trickle would take.
    EXPECT_TRUE(results[static_cast<std::size_t>(i)].closedByServer) << i;
    EXPECT_LT(results[static_cast<std::size_t>(i)].elapsed.count(), 4000) << i;
  }
  EXPECT_TRUE(healthy(port));
  EXPECT_NE(server->log().find(" 408 0 "), std::string::npos);
  EXPECT_EQ(server->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

TEST(Hostile, ConnectionCapAnswers503WhenNoneIsIdleAndRecovers) {
  const TestTree tree = makeTestTree(workDir());
  auto server = startServer(tree, {"--max-connections", "8", "--max-connections-per-client", "8", "--read-timeout", "30"},
                            "cap.log");
  ASSERT_TRUE(server);
  const int port = server->port();
  // Eight connections each in the middle of a request head: busy, so none can be evicted.
  std::vector<std::unique_ptr<RawConnection>> held;
  for (int i = 0; i < 8; ++i) {
    held.push_back(std::make_unique<RawConnection>(port));
    ASSERT_TRUE(held.back()->send("GET /api/scenes HTTP/1.1\r\nHost: x\r\n"));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the server has seen their bytes
  for (int i = 0; i < 5; ++i) {
    const RawResult over = rawExchangeFrom(i % 2 ? "127.0.0.2" : "127.0.0.1", port, rawGet("/api/scenes"),
                                           std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(over.received), 503) << over.received.substr(0, 100);
    EXPECT_NE(over.received.find("Retry-After: 1\r\n"), std::string::npos);
    EXPECT_TRUE(over.closedByServer);
  }
  for (const auto& c : held) EXPECT_FALSE(c->closedWithin(std::chrono::milliseconds(50)));
  held.clear();  // the held connections close; their slots free up
  bool recovered = false;
  for (int i = 0; i < 50 && !recovered; ++i) {
    recovered = healthy(port);
    if (!recovered) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(recovered);
  EXPECT_EQ(server->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

TEST(Hostile, IdleConnectionsMakeRoomOldestFirst) {
  // The report: 1,024 idle sockets locked every other client out until the read timeout.
  // At the cap, a new client now gets the slot of the oldest idle connection.
  const TestTree tree = makeTestTree(workDir());
  auto server = startServer(tree, {"--max-connections", "8", "--max-connections-per-client", "8", "--read-timeout", "30"},
                            "idle-cap.log");
  ASSERT_TRUE(server);
  const int port = server->port();
  // Idle connections, oldest first: four that never send anything, then four kept alive
  // after one request each. The server accepts in arrival order, so once the last kept-
  // alive one is answered all eight are registered (the test cannot ask the server).
  std::vector<std::unique_ptr<RawConnection>> silent;
  for (int i = 0; i < 4; ++i) silent.push_back(std::make_unique<RawConnection>(port));
  // A connection turns idle when the server has finished its response, which can be a
  // moment after the client has it (later still when the machine is busy): each step waits
  // for the response's log line, then pauses, to keep "oldest idle" in the order below.
  const std::string served = " GET /api/scenes 200 ";
  int logged = countInLog(*server, served);
  const auto settle = [&] {
    EXPECT_TRUE(waitForLogged(*server, served, ++logged)) << server->log();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  };
  std::vector<std::unique_ptr<HttpConnection>> keptAlive;
  for (int i = 0; i < 4; ++i) {
    keptAlive.push_back(std::make_unique<HttpConnection>(port, std::chrono::seconds(2)));
    ASSERT_EQ(keptAlive.back()->request("GET", "/api/scenes").status, 200);
    settle();
  }

  // Other clients, each keeping its connection: every one is served, and the idle
  // connections make room in the order they became idle.
  std::vector<std::unique_ptr<RawConnection>> others;
  const std::string keepAliveGet = "GET /api/scenes HTTP/1.1\r\nHost: x\r\n\r\n";
  for (int i = 0; i < 8; ++i) {
    others.push_back(std::make_unique<RawConnection>(port, i < 4 ? "127.0.0.2" : "127.0.0.3"));
    ASSERT_TRUE(others.back()->send(keepAliveGet));
    EXPECT_TRUE(others.back()->awaitResponse(std::chrono::seconds(5))) << i;
    EXPECT_EQ(rawStatus(others.back()->received()), 200) << i << ": " << others.back()->received().substr(0, 100);
    settle();
    if (i < 4) {
      EXPECT_TRUE(silent[static_cast<std::size_t>(i)]->closedWithin(std::chrono::seconds(2))) << i;
    } else {
      // Closed by the server: the next request on it gets no response.
      EXPECT_EQ(keptAlive[static_cast<std::size_t>(i - 4)]->request("GET", "/api/scenes").status, 0) << i;
    }
  }
  // Now every connection is a served one that became idle after its response: the next
  // client takes the oldest of those.
  EXPECT_EQ(rawStatus(rawExchangeFrom("127.0.0.4", port, rawGet("/api/scenes"), std::chrono::seconds(5)).received), 200);
  EXPECT_TRUE(others[0]->closedWithin(std::chrono::seconds(2)));
  EXPECT_FALSE(others[1]->closedWithin(std::chrono::milliseconds(50)));
  EXPECT_TRUE(healthy(port));
  EXPECT_EQ(server->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

TEST(Hostile, PerClientCapLeavesRoomForOtherClients) {
  const TestTree tree = makeTestTree(workDir());
  auto server = startServer(tree, {"--max-connections", "16", "--max-connections-per-client", "4", "--read-timeout", "30"},
                            "client-cap.log");
  ASSERT_TRUE(server);
  const int port = server->port();
  {
    // Four busy connections from one address: its fifth is refused, another address is served.
    std::vector<std::unique_ptr<RawConnection>> busy;
    for (int i = 0; i < 4; ++i) {
      busy.push_back(std::make_unique<RawConnection>(port));
      ASSERT_TRUE(busy.back()->send("GET /api/scenes HTTP/1.1\r\nHost: x\r\n"));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const RawResult fifth = rawExchange(port, rawGet("/api/scenes"), std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(fifth.received), 503) << fifth.received.substr(0, 100);
    EXPECT_NE(fifth.received.find("from your address"), std::string::npos);
    EXPECT_TRUE(fifth.closedByServer);
    const RawResult other = rawExchangeFrom("127.0.0.2", port, rawGet("/api/scenes"), std::chrono::seconds(5));
    EXPECT_EQ(rawStatus(other.received), 200);
    for (const auto& c : busy) EXPECT_FALSE(c->closedWithin(std::chrono::milliseconds(50)));
  }
  // With its share held idle, a client's new connection takes the place of its oldest idle
  // one (another address, so the connections above, still closing, do not count).
  std::vector<std::unique_ptr<RawConnection>> idle;
  const std::string keepAliveGet = "GET /api/scenes HTTP/1.1\r\nHost: x\r\n\r\n";
  const std::string served = "127.0.0.4:";  // the access log's peer field
  for (int i = 0; i < 4; ++i) {
    idle.push_back(std::make_unique<RawConnection>(port, "127.0.0.4"));
    ASSERT_TRUE(idle.back()->send(keepAliveGet));
    EXPECT_TRUE(idle.back()->awaitResponse(std::chrono::seconds(5))) << i;
    ASSERT_EQ(rawStatus(idle.back()->received()), 200) << i;
    // Idle once the server has finished it: its log line is written on the way (see
    // waitForLogged), and the pause covers the rest of that handler.
    EXPECT_TRUE(waitForLogged(*server, served, i + 1)) << server->log();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(rawStatus(rawExchangeFrom("127.0.0.4", port, rawGet("/api/scenes"), std::chrono::seconds(5)).received), 200);
  EXPECT_TRUE(idle[0]->closedWithin(std::chrono::seconds(2)));  // the oldest made room
  for (std::size_t i = 1; i < 4; ++i) EXPECT_FALSE(idle[i]->closedWithin(std::chrono::milliseconds(50))) << i;
  EXPECT_EQ(server->stop(SIGTERM, std::chrono::seconds(20)), 0);
}

}  // namespace
}  // namespace prt::serve::test
