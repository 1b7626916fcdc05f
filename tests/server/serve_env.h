// The server most tests share: one tree and one prt-serve per test process, started on
// first use so tests that need no server pay nothing.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "http_client.h"
#include "server_process.h"
#include "test_tree.h"

namespace prt::serve::test {

struct SharedServer {
  TestTree tree;
  std::unique_ptr<ServerProcess> server;
  int port = 0;
};

// The shared tree and server (--root, --web, 4 threads, --read-timeout 3); the test fails
// when it cannot start.
SharedServer& sharedServer();

// Where tests put their trees and logs.
std::string workDir();

// A fresh tree plus a server on it with `extraArgs`; null (with a test failure) if it
// does not start.
std::unique_ptr<ServerProcess> startServer(const TestTree& tree, const std::vector<std::string>& extraArgs,
                                           const std::string& logName);

// True when GET /api/scenes answers 200 with a JSON body: the server is still healthy.
bool healthy(int port);

// Decoders for the encodings the server offers.
std::string gunzip(const std::string& data);
std::string unzstd(const std::string& data);
std::string unbrotli(const std::string& data);

// The server's JSON documents, read with nlohmann_json. Tests reach members with at(),
// which throws (failing the test) when a member is absent, rather than operator[], which
// on a const document is undefined behaviour for a missing key.
using Json = nlohmann::json;

// Parses the whole of `text` strictly (RFC 8259: no comments, nothing but white space after
// the value, UTF-8 checked); false with *error (the parser's message, naming the byte
// offset) and *out null otherwise.
bool parseJson(std::string_view text, Json* out, std::string* error);

// `j` as an array; throws (failing the test) when it is anything else, so that a loop over
// a document's list cannot pass by iterating an object's values or a lone scalar.
const Json::array_t& asArray(const Json& j);

// XXH64 of `bytes` as the server writes it (16 hex digits).
std::string hexHash(const std::vector<std::uint8_t>& bytes);

}  // namespace prt::serve::test
