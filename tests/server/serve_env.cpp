#include "serve_env.h"

#include <brotli/decode.h>
#include <gtest/gtest.h>
#include <zlib.h>
#include <zstd.h>

#include <unistd.h>

#include "content_hash.h"

namespace prt::serve::test {

std::string workDir() { return PRT_SERVE_WORK_DIR; }

std::unique_ptr<ServerProcess> startServer(const TestTree& tree, const std::vector<std::string>& extraArgs,
                                           const std::string& logName) {
  std::vector<std::string> args{"--root", tree.root, "--web", tree.web};
  args.insert(args.end(), extraArgs.begin(), extraArgs.end());
  std::string error;
  auto server = ServerProcess::start(args, tree.dir + "/" + logName, &error);
  if (!server) ADD_FAILURE() << error;
  return server;
}

SharedServer& sharedServer() {
  // A static object, not a leaked pointer: its destructor stops the server at exit.
  static SharedServer shared = [] {
    SharedServer s;
    s.tree = makeTestTree(workDir());
    s.server = startServer(s.tree, {"--threads", "4", "--read-timeout", "3"}, "shared.log");
    s.port = s.server ? s.server->port() : 0;
    return s;
  }();
  if (!shared.server) ADD_FAILURE() << "the shared server is not running";
  return shared;
}

bool healthy(int port) {
  const HttpResponse r = fetch(port, "/api/scenes");
  return r.status == 200 && r.body.starts_with("{\"scenes\":");
}

std::string gunzip(const std::string& data) {
  z_stream z{};
  if (inflateInit2(&z, 15 + 16) != Z_OK) return {};
  std::string out;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  char buf[65536];
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buf, sizeof buf - z.avail_out);
  }
  inflateEnd(&z);
  return rc == Z_STREAM_END ? out : std::string("<gunzip failed>");
}

std::string unzstd(const std::string& data) {
  const unsigned long long size = ZSTD_getFrameContentSize(data.data(), data.size());
  if (size == ZSTD_CONTENTSIZE_ERROR || size == ZSTD_CONTENTSIZE_UNKNOWN) return "<unzstd failed>";
  std::string out(static_cast<std::size_t>(size), '\0');
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
  return ZSTD_isError(n) || n != size ? std::string("<unzstd failed>") : out;
}

std::string unbrotli(const std::string& data) {
  BrotliDecoderState* st = BrotliDecoderCreateInstance(nullptr, nullptr, nullptr);
  std::string out;
  std::size_t availIn = data.size();
  const auto* next = reinterpret_cast<const std::uint8_t*>(data.data());
  BrotliDecoderResult r = BROTLI_DECODER_RESULT_NEEDS_MORE_OUTPUT;
  while (r == BROTLI_DECODER_RESULT_NEEDS_MORE_OUTPUT) {
    std::uint8_t buf[65536];
    std::uint8_t* outNext = buf;
    std::size_t availOut = sizeof buf;
    r = BrotliDecoderDecompressStream(st, &availIn, &next, &availOut, &outNext, nullptr);
    out.append(reinterpret_cast<char*>(buf), sizeof buf - availOut);
  }
  BrotliDecoderDestroyInstance(st);
  return r == BROTLI_DECODER_RESULT_SUCCESS ? out : std::string("<unbrotli failed>");
}

bool parseJson(std::string_view text, Json* out, std::string* error) {
  try {
    *out = Json::parse(text);  // strict by default: no comments, no trailing bytes
    return true;
  } catch (const Json::parse_error& e) {
    *out = nullptr;
    *error = e.what();
    return false;
  }
}

const Json::array_t& asArray(const Json& j) { return j.get_ref<const Json::array_t&>(); }

std::string hexHash(const std::vector<std::uint8_t>& bytes) { return hashHex(xxh64(bytes)); }

}  // namespace prt::serve::test
