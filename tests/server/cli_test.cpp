// prt-serve's command line: help, usage errors, and clear failures for a missing
// directory or a busy port, each with its exit status from native/exit_status.h.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>

#include <fstream>

#include "serve_env.h"

namespace prt::serve::test {
namespace {

constexpr auto kQuick = std::chrono::seconds(30);

// The statuses of native/exit_status.h, spelled out: the test pins the numbers scripts see.
constexpr int kUsage = 2;
constexpr int kNotFound = 3;
constexpr int kUnavailable = 7;

TEST(Cli, HelpAndVersion) {
  const ExitResult help = runServe({"--help"}, kQuick);
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("Usage: prt-serve --root DIR"), std::string::npos);
  for (const char* flag : {"--web", "--bind", "--port", "--threads", "--max-connections", "--read-timeout", "--quiet",
                           "--max-parts-mib"}) {
    EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
  }
  // The exit-status table closes the help, so scripts can look the numbers up.
  const std::size_t table = help.out.find("Exit status:");
  ASSERT_NE(table, std::string::npos) << help.out;
  for (const char* row : {"  2  usage", "  3  a file is missing", "  7  unavailable"}) {
    EXPECT_NE(help.out.find(row, table), std::string::npos) << row;
  }
  EXPECT_EQ(runServe({"-h"}, kQuick).exitCode, 0);
  // Help wins over every error, as for prt-bake.
  EXPECT_EQ(runServe({"--bogus", "--port", "x", "--help"}, kQuick).exitCode, 0);
  const ExitResult version = runServe({"--version"}, kQuick);
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_TRUE(version.out.starts_with("prt-serve "));
}

TEST(Cli, UsageErrors) {
  const TestTree tree = makeTestTree(workDir());
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  for (const Case& c : {
           Case{{}, "--root DIR is required"},
           Case{{"--root"}, "--root needs a value"},
           Case{{"--root", "--quiet"}, "--root needs a value"},  // a forgotten value, not the value "--quiet"
           Case{{"--root", tree.root, "--bogus"}, "unknown option '--bogus'"},
           Case{{"--root", tree.root, "extra"}, "unexpected argument 'extra'"},
           Case{{"--root", tree.root, "--port", "1", "--port", "2"}, "option --port given more than once"},
           Case{{"--root", tree.root, "--port", "70000"}, "--port '70000' is out of range; expected an integer in [0, 65535]"},
           Case{{"--root", tree.root, "--port", "http"}, "--port expects an integer in [0, 65535], got 'http'"},
           Case{{"--root", tree.root, "--port", "99999999999999999999"}, "--port '99999999999999999999' is out of range"},
           Case{{"--root", tree.root, "--threads", "0"}, "--threads '0' is out of range; expected an integer in [1, 256]"},
           Case{{"--root", tree.root, "--read-timeout", "-1"},
                "--read-timeout '-1' is out of range; expected a number in [0.05, 86400]"},
           Case{{"--root", tree.root, "--write-timeout", "soon"}, "--write-timeout expects a number in [0.05, 86400], got 'soon'"},
           Case{{"--root", tree.root, "--read-timeout", "inf"}, "--read-timeout expects a number"},
           Case{{"--root", tree.root, "--max-parts-mib", "-1"},
                "--max-parts-mib '-1' is out of range; expected an integer in [0, 1024]"},
           Case{{"--root", tree.root, "--max-parts-mib", "2048"}, "--max-parts-mib '2048' is out of range"},
           Case{{"--root", tree.root, "--max-connections-per-client", "0"},
                "--max-connections-per-client '0' is out of range; expected an integer in [1, 1000000]"},
           Case{{"--root", tree.root, "--quiet=yes"}, "--quiet takes no value"},
           Case{{"--root", tree.root, "--bind", "not-an-address"}, "--bind 'not-an-address' is not an IP address"},
       }) {
    const ExitResult r = runServe(c.args, kQuick);
    EXPECT_EQ(r.exitCode, kUsage) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("Try 'prt-serve --help'"), std::string::npos);
  }
}

TEST(Cli, MissingDirectoriesAreClearErrors) {
  const TestTree tree = makeTestTree(workDir());
  ExitResult r = runServe({"--root", tree.dir + "/nope", "--port", "0"}, kQuick);
  EXPECT_EQ(r.exitCode, kNotFound);
  EXPECT_NE(r.err.find("--root '" + tree.dir + "/nope' is not a directory: No such file or directory"), std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("Try 'prt-serve --help'"), std::string::npos) << "not a usage error: " << r.err;
  r = runServe({"--root", tree.root + "/room.prt", "--port", "0"}, kQuick);
  EXPECT_EQ(r.exitCode, kNotFound);
  EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
  r = runServe({"--root", tree.root + "/room.prt/below", "--port", "0"}, kQuick);  // ENOTDIR
  EXPECT_EQ(r.exitCode, kNotFound);
  EXPECT_NE(r.err.find("is not a directory: Not a directory"), std::string::npos) << r.err;
  r = runServe({"--root", tree.root, "--web", tree.dir + "/missing-web", "--port", "0"}, kQuick);
  EXPECT_EQ(r.exitCode, kNotFound);
  EXPECT_NE(r.err.find("--web '" + tree.dir + "/missing-web' is not a directory"), std::string::npos) << r.err;
}

TEST(Cli, BusyPortIsAClearError) {
  const TestTree tree = makeTestTree(workDir());
  auto first = startServer(tree, {}, "first.log");
  ASSERT_TRUE(first);
  const std::string port = std::to_string(first->port());
  const ExitResult second = runServe({"--root", tree.root, "--port", port}, kQuick);
  EXPECT_EQ(second.exitCode, kUnavailable);
  EXPECT_NE(second.err.find("cannot listen on 127.0.0.1:" + port), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("in use"), std::string::npos) << second.err;
  EXPECT_TRUE(healthy(first->port()));  // the first server is unaffected
  EXPECT_EQ(first->stop(SIGINT, std::chrono::seconds(20)), 0);  // SIGINT stops it like SIGTERM
}

TEST(Cli, PortHeldByAnyProgramIsUnavailable) {
  // A plain listening socket, not a prt-serve: the status depends on the port, not on who
  // holds it.
  boost::asio::io_context ioc;
  boost::asio::ip::tcp::acceptor holder(ioc, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const std::string port = std::to_string(holder.local_endpoint().port());
  const TestTree tree = makeTestTree(workDir());
  const ExitResult r = runServe({"--root", tree.root, "--port", port}, kQuick);
  EXPECT_EQ(r.exitCode, kUnavailable) << r.err;
  EXPECT_NE(r.err.find("another server is using the port"), std::string::npos) << r.err;
}

TEST(Cli, AddressNoInterfaceHasIsUnavailable) {
  // 192.0.2.1 is TEST-NET-1 (RFC 5737), never assigned to a host. Where the kernel lets
  // programs bind addresses they do not have, the bind would succeed and the server run.
  std::ifstream nonlocal("/proc/sys/net/ipv4/ip_nonlocal_bind");
  int allowed = 0;
  if (nonlocal >> allowed && allowed != 0) GTEST_SKIP() << "net.ipv4.ip_nonlocal_bind is set";
  const TestTree tree = makeTestTree(workDir());
  const ExitResult r = runServe({"--root", tree.root, "--bind", "192.0.2.1", "--port", "0"}, kQuick);
  EXPECT_EQ(r.exitCode, kUnavailable) << r.err;
  EXPECT_NE(r.err.find("cannot listen on 192.0.2.1:0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("check --bind"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace prt::serve::test
