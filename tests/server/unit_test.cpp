// The server's pure pieces, checked directly: content hash, request-target parsing,
// content negotiation, ranges, log escaping, media types, options, the Status codes of
// failed system calls.
#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <limits>
#include <cstdlib>
#include <string>
#include <vector>

#include "access_log.h"
#include "content_hash.h"
#include "light_preview.h"
#include "mime_types.h"
#include "negotiation.h"
#include "options.h"
#include "os_error.h"
#include "public_error.h"
#include "request_checks.h"
#include "request_target.h"
#include "root_dir.h"
#include "temp_file.h"

namespace prt::serve {
namespace {

std::uint64_t hashOf(std::string_view s) {
  return xxh64({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
}

TEST(ContentHash, MatchesXxh64ReferenceValues) {
  // From the xxHash reference implementation (xxhsum, python-xxhash).
  EXPECT_EQ(hashOf(""), 0xef46db3751d8e999ULL);
  EXPECT_EQ(hashOf("a"), 0xd24ec4f1a98c6e5bULL);
  EXPECT_EQ(hashOf("abc"), 0x44bc2cf5ad770999ULL);
  EXPECT_EQ(hashOf("Nobody inspects the spammish repetition"), 0xfbcea83c8a378bf1ULL);
  EXPECT_EQ(hashHex(0x0123456789abcdefULL), "0123456789abcdef");
  EXPECT_EQ(hashHex(0), "0000000000000000");
}

TEST(ContentHash, EveryTailLengthAndStripeChangesTheHash) {
  std::string s;
  std::uint64_t previous = hashOf(s);
  for (int i = 0; i < 100; ++i) {
    s.push_back(static_cast<char>('a' + i % 26));
    const std::uint64_t h = hashOf(s);
    EXPECT_NE(h, previous) << i;
    previous = h;
  }
}

TEST(RequestTarget, AcceptsOrdinaryPaths) {
  RequestTarget t;
  ASSERT_TRUE(parseTarget("/", &t).isOk());
  EXPECT_EQ(t.path, "/");
  ASSERT_TRUE(parseTarget("/a/b%20c.html?x=1&y", &t).isOk());
  EXPECT_EQ(t.path, "/a/b c.html");
  EXPECT_EQ(t.query, "x=1&y");
  ASSERT_TRUE(parseTarget("/docs/", &t).isOk());
  EXPECT_EQ(t.path, "/docs/");
  ASSERT_TRUE(parseTarget("/%252e%252e/x", &t).isOk());  // double-encoded: a literal "%2e%2e" name
  EXPECT_EQ(t.path, "/%2e%2e/x");
  ASSERT_TRUE(parseTarget("/a..b/...", &t).isOk());  // dots inside names are fine
  ASSERT_TRUE(parseTarget("/caf%C3%A9", &t).isOk());   // UTF-8 arrives %-encoded
  EXPECT_EQ(t.path, "/caf\xC3\xA9");
}

TEST(RequestTarget, RejectsEverythingThatCouldEscape) {
  for (const char* bad : {"", "*", "http://host/x", "x/y", "/..", "/../etc/passwd", "/a/../../b", "/.", "/./x",
                          "/%2e%2e/etc", "/%2E%2E/etc", "/.%2e/x", "/%2e./x", "/..%2fetc", "/..%2Fetc",
                          "/a/%2e%2e%2f%2e%2e/b", "//etc/passwd", "/%2fetc/passwd", "/a//b", "/a\\b",
                          "/..%5c..%5cetc", "/%5c", "/%00", "/index.html%00.png", "/%0a", "/%7f", "/%", "/%2",
                          "/%zz", "/a#frag", "/caf\xC3\xA9", "/a b", "/\x7f", "/\t"}) {
    RequestTarget t;
    EXPECT_FALSE(parseTarget(bad, &t).isOk()) << bad;
  }
}

TEST(RequestTarget, QueryValues) {
  std::string v;
  EXPECT_TRUE(queryValue("order=3", "order", &v));
  EXPECT_EQ(v, "3");
  EXPECT_TRUE(queryValue("a=1&order=%33&order=4", "order", &v));
  EXPECT_EQ(v, "3");
  EXPECT_TRUE(queryValue("order", "order", &v));
  EXPECT_EQ(v, "");
  EXPECT_FALSE(queryValue("orders=3", "order", &v));
  EXPECT_FALSE(queryValue("", "order", &v));
  EXPECT_EQ(encodePathSegment("a b/c%d.prt"), "a%20b%2Fc%25d.prt");
}

TEST(RequestHead, HostValues) {
  for (const char* ok : {"", "a", "localhost", "127.0.0.1", "127.0.0.1:8080", "prt.example.com:443", "[::1]",
                         "[::1]:80", "[2001:db8::7]", "[v1.fe80::a+en1]", "x:", "xn--bcher-kva.example", "a%41b",
                         "a-b_c~d!$&'()*+,;="}) {
    EXPECT_TRUE(validHostValue(ok)) << ok;
  }
  for (const char* bad : {"a b", "a/b", "a@b", "a:b", "a:80:80", "[::1", "::1", "[zz::1]", "[::1]x", "[::1]:x",
                          "%zz", "%4", "a\tb", "a,b c", "[fe80::1%25eth0]", "[v.x]", "[vZ.x]", "a\\b", "\"a\""}) {
    EXPECT_FALSE(validHostValue(bad)) << bad;
  }
}

TEST(RequestHead, TransferEncodingMustBeChunkedAlone) {
  EXPECT_TRUE(onlyChunked("chunked"));
  EXPECT_TRUE(onlyChunked("Chunked,"));
  EXPECT_TRUE(onlyChunked(" , chunked ,"));
  for (const char* bad : {"", ",", "gzip", "identity", "xchunked", "chunked, identity", "gzip, chunked",
                          "chunked, chunked", "chunked;x=1", "chunked x"}) {
    EXPECT_FALSE(onlyChunked(bad)) << bad;
  }
}

TEST(RequestHead, VersionsWorthA505) {
  for (const char* line : {"GET / HTTP/2.0", "GET / HTTP/1.2\r", "PRI * HTTP/2.0", "GET /x HTTP/0.9"}) {
    EXPECT_TRUE(wellFormedButUnsupportedVersion(line)) << line;
  }
  for (const char* line : {"GET / HTTP/1.1", "GET / HTTP/1.0\r", "GET / HTTP/1.10", "GET / HTTX/2.0", "GET / HTTP/2",
                           "GET /  HTTP/2.0", "GET HTTP/2.0", "GET / HTTP/2.0 x", "", " / HTTP/2.0"}) {
    EXPECT_FALSE(wellFormedButUnsupportedVersion(line)) << line;
  }
}

TEST(PublicError, PathsStayOnTheServer) {
  const std::string abs = "/srv/prt/maps/sub/bad.exr";
  EXPECT_EQ(publicMessage("'" + abs + "': unknown image format (starts with 68 65)", abs, "sub/bad.exr", "/srv/prt/maps", "F"),
            "unknown image format (starts with 68 65)");
  EXPECT_EQ(publicMessage("'" + abs + "': cannot read: Cannot read image file \"" + abs + "\". Bad magic.", abs,
                          "sub/bad.exr", "/srv/prt/maps", "F"),
            "cannot read: Cannot read image file \"sub/bad.exr\". Bad magic.");
  EXPECT_EQ(publicMessage("cannot open /etc/OpenEXR/x.conf", abs, "sub/bad.exr", "/srv/prt/maps", "F"), "F");
  EXPECT_EQ(publicMessage("under /srv/prt/maps", abs, "sub/bad.exr", "/srv/prt/maps", "F"), "F");
  EXPECT_EQ(publicMessage("truncated: asset is 1000 bytes but its header declares 4879144", "", "", "/", "F"),
            "truncated: asset is 1000 bytes but its header declares 4879144");
  EXPECT_EQ(publicMessage("its size 3x7 matches no layout (2:1 equirect, 1:1 angular map, 4:3 or 3:4 cross)", abs, "x",
                          "/srv", "F"),
            "its size 3x7 matches no layout (2:1 equirect, 1:1 angular map, 4:3 or 3:4 cross)");
  for (const char* yes : {"/etc/passwd", "at '/srv/x'", "file \"/a\"", "(/tmp/x)", "path=/x", "x: /y"}) {
    EXPECT_TRUE(mentionsAbsolutePath(yes)) << yes;
  }
  for (const char* no : {"a/b", "sub/bad.exr", "1/2", "w / h", "", "/", "and/or"}) EXPECT_FALSE(mentionsAbsolutePath(no)) << no;
}

TEST(Negotiation, PicksTheBestAcceptableEncoding) {
  const EncodingOffer offers[] = {{Encoding::kIdentity, 1000}, {Encoding::kBrotli, 300}, {Encoding::kZstd, 320},
                                  {Encoding::kGzip, 400}};
  EXPECT_EQ(chooseEncoding("", offers), 0u);
  EXPECT_EQ(chooseEncoding("gzip", offers), 3u);
  EXPECT_EQ(chooseEncoding("gzip, deflate, br, zstd", offers), 1u);  // all q=1: the smallest
  EXPECT_EQ(chooseEncoding("gzip;q=1, br;q=0.5", offers), 3u);
  EXPECT_EQ(chooseEncoding("br;q=0, zstd", offers), 2u);
  EXPECT_EQ(chooseEncoding("*", offers), 1u);
  EXPECT_EQ(chooseEncoding("*;q=0.5, gzip", offers), 3u);
  EXPECT_EQ(chooseEncoding("ZSTD", offers), 2u);
  EXPECT_EQ(chooseEncoding("compress, deflate", offers), 0u);
  EXPECT_EQ(chooseEncoding("identity;q=0", offers), 0u);  // nothing else acceptable: identity anyway
  EXPECT_EQ(chooseEncoding("gzip;q=0.5, identity;q=0.9", offers), 0u);  // identity named and preferred
  EXPECT_EQ(chooseEncoding("zstd;q=0.1", offers), 2u);  // unnamed identity is only the fallback
  EXPECT_EQ(chooseEncoding("gzip;q=bogus", offers), 0u);
  EXPECT_EQ(chooseEncoding(" gzip ; q=0.8 ,br;q=0.9", offers), 1u);
}

TEST(Negotiation, IfNoneMatch) {
  EXPECT_TRUE(ifNoneMatchHits("\"abc\"", "\"abc\""));
  EXPECT_TRUE(ifNoneMatchHits("W/\"abc\"", "\"abc\""));
  EXPECT_TRUE(ifNoneMatchHits("\"x\", \"abc\"", "\"abc\""));
  EXPECT_TRUE(ifNoneMatchHits(" * ", "\"abc\""));
  EXPECT_FALSE(ifNoneMatchHits("\"abcd\"", "\"abc\""));
  EXPECT_FALSE(ifNoneMatchHits("abc", "\"abc\""));
  EXPECT_FALSE(ifNoneMatchHits("", "\"abc\""));
  EXPECT_FALSE(ifNoneMatchHits("\"abc", "\"abc\""));
}

TEST(Negotiation, Ranges) {
  ByteRange r;
  EXPECT_EQ(parseRange("bytes=0-99", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.length, 100u);
  EXPECT_EQ(parseRange("bytes=900-", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.first, 900u);
  EXPECT_EQ(r.length, 100u);
  EXPECT_EQ(parseRange("bytes=-10", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.first, 990u);
  EXPECT_EQ(parseRange("bytes=-5000", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.length, 1000u);
  EXPECT_EQ(parseRange("bytes=500-99999", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.length, 500u);
  EXPECT_EQ(parseRange("bytes=999-999", 1000, &r), RangeOutcome::kPartial);
  EXPECT_EQ(r.length, 1u);
  EXPECT_EQ(parseRange("bytes=1000-", 1000, &r), RangeOutcome::kUnsatisfiable);
  EXPECT_EQ(parseRange("bytes=5000-6000", 1000, &r), RangeOutcome::kUnsatisfiable);
  EXPECT_EQ(parseRange("bytes=-0", 1000, &r), RangeOutcome::kUnsatisfiable);
  EXPECT_EQ(parseRange("bytes=0-", 0, &r), RangeOutcome::kUnsatisfiable);
  for (const char* whole : {"", "bytes=", "bytes=a-b", "bytes=5-1", "items=0-1", "bytes=0-1,5-6", "bytes 0-1",
                            "bytes=--1", "bytes=99999999999999999999999-"}) {
    EXPECT_EQ(parseRange(whole, 1000, &r), RangeOutcome::kWhole) << whole;
  }
}

TEST(AccessLog, EscapesWhatCouldForgeALine) {
  const std::string line = formatAccessLine({"127.0.0.1:5", "GET", "/a b\"\n\\\x01\xff", 200, 12, 34});
  EXPECT_EQ(line, "127.0.0.1:5 GET /a\\x20b\\x22\\x0a\\x5c\\x01\\xff 200 12 34us\n");
  EXPECT_EQ(formatAccessLine({"", "", "", 400, 0, 1}), "- - - 400 0 1us\n");
  const std::string longLine = formatAccessLine({"p", "GET", std::string(2000, 'a'), 200, 0, 0});
  EXPECT_LT(longLine.size(), 600u);
  EXPECT_NE(longLine.find("..."), std::string::npos);
}

TEST(MimeTypes, CoverTheClientsFiles) {
  EXPECT_EQ(contentTypeFor("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(contentTypeFor("a/app.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentTypeFor("m.MJS"), "text/javascript; charset=utf-8");
  EXPECT_EQ(contentTypeFor("core.wasm"), "application/wasm");
  EXPECT_EQ(contentTypeFor("s.css"), "text/css; charset=utf-8");
  EXPECT_EQ(contentTypeFor("d.json"), "application/json");
  EXPECT_EQ(contentTypeFor("i.png"), "image/png");
  EXPECT_EQ(contentTypeFor("i.jpeg"), "image/jpeg");
  EXPECT_EQ(contentTypeFor("i.svg"), "image/svg+xml");
  EXPECT_EQ(contentTypeFor("noext"), "application/octet-stream");
  EXPECT_EQ(contentTypeFor("dir.d/noext"), "application/octet-stream");
  EXPECT_TRUE(isCompressibleType("application/wasm"));
  EXPECT_FALSE(isCompressibleType("image/png"));
}

TEST(ServeOptions, EveryFlagReachesItsField) {
  const std::vector<std::string> args{"--root", "/r", "--web=/w", "--bind", "::1", "--port", "0", "--threads", "3",
                                      "--max-connections", "10", "--max-connections-per-client", "5",
                                      "--read-timeout", "0.25", "--write-timeout=7", "--max-parts-mib", "0", "--quiet"};
  ServeOptions o;
  ASSERT_TRUE(parseServeOptions(args, &o).isOk());
  EXPECT_EQ(o.root, "/r");
  EXPECT_EQ(o.web, "/w");
  EXPECT_EQ(o.bind, "::1");
  EXPECT_EQ(o.port, 0);
  EXPECT_EQ(o.threads, 3);
  EXPECT_EQ(o.maxConnections, 10);
  EXPECT_EQ(o.perClientLimit(), 5);
  EXPECT_DOUBLE_EQ(o.readTimeoutSeconds, 0.25);
  EXPECT_DOUBLE_EQ(o.writeTimeoutSeconds, 7.0);
  EXPECT_EQ(o.maxPartsMiB, 0);
  EXPECT_TRUE(o.quiet);
  EXPECT_FALSE(o.help);
  EXPECT_FALSE(o.version);

  ServeOptions d;
  ASSERT_TRUE(parseServeOptions(std::vector<std::string>{"--root", "/r"}, &d).isOk());
  EXPECT_EQ(d.bind, "127.0.0.1");
  EXPECT_EQ(d.port, 8080);
  EXPECT_EQ(d.perClientLimit(), 256);  // a quarter of --max-connections 1024
  EXPECT_FALSE(d.quiet);
}

TEST(ServeOptions, CommandLineErrorsAreUsage) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {}, {"--root"}, {"--root", "/r", "--nope"}, {"--root", "/r", "x"}, {"--root", "/r", "--port", "-1"},
           {"--root", "/r", "--read-timeout", "0.01"}, {"--root", "/r", "--bind", "localhost"},
           {"--root", "/r", "--quiet", "--quiet"}}) {
    ServeOptions o;
    const Status s = parseServeOptions(args, &o);
    EXPECT_EQ(s.code(), StatusCode::kUsage) << s.toString();
    EXPECT_FALSE(s.message().empty());
  }
  ServeOptions v;
  EXPECT_TRUE(parseServeOptions(std::vector<std::string>{"--version"}, &v).isOk());  // no --root needed
  EXPECT_TRUE(v.version);
}

// The errno table itself is tested in tests/native/file_io_test.cpp.
TEST(OsError, CodesFollowErrno) {
  const Status s = errnoStatus(ENOENT, "--root '/x' is not a directory");
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(s.message(), "--root '/x' is not a directory: No such file or directory");
}

TEST(OsError, RootDirAndTempFileReportTheirCodes) {
  RootDir dir;
  EXPECT_EQ(RootDir::open("/nonexistent-prt-serve-test", "--root", &dir).code(), StatusCode::kNotFound);
  EXPECT_EQ(RootDir::open("/proc/self/status", "--root", &dir).code(), StatusCode::kNotFound);  // a file
  EXPECT_EQ(RootDir::open("", "--web", &dir).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(RootDir::open("/", "--root", &dir).isOk());

  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  ::setenv("TMPDIR", "/nonexistent-prt-serve-test", 1);
  FileRef file;
  const Status s = writeTempFile("bytes", &file);
  if (old) ::setenv("TMPDIR", saved.c_str(), 1);
  else ::unsetenv("TMPDIR");
  EXPECT_EQ(s.code(), StatusCode::kNotFound) << s.toString();
  EXPECT_NE(s.message().find("'/nonexistent-prt-serve-test'"), std::string::npos) << s.message();
}

TEST(OsError, ReadAllAtReadsTheDescriptorAndNamesShortFiles) {
  FileRef file;
  ASSERT_TRUE(writeTempFile("abc", &file).isOk());
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(readAllAt(file->fd(), 3, &bytes).isOk());
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "abc");
  EXPECT_EQ(readAllAt(file->fd(), 5, &bytes).code(), StatusCode::kTruncated);  // shrank since its stat
  const Status bad = readAllAt(-1, 3, &bytes);
  EXPECT_EQ(bad.code(), StatusCode::kIoError);
  EXPECT_NE(bad.message().find("Bad file descriptor"), std::string::npos) << bad.message();
}

}  // namespace
}  // namespace prt::serve

// GL's RGB9_E5 (EXT_texture_shared_exponent), decoded as the spec says.
prt::Rgb unpackRgb9e5(std::uint32_t v) {
  const double scale = std::ldexp(1.0, static_cast<int>(v >> 27) - 15 - 9);
  return {static_cast<float>((v & 511u) * scale), static_cast<float>(((v >> 9) & 511u) * scale),
          static_cast<float>(((v >> 18) & 511u) * scale)};
}

TEST(BackgroundTexture, Rgb9e5KnownValues) {
  using prt::serve::packRgb9e5;
  EXPECT_EQ(packRgb9e5({1.0f, 0.0f, 0.0f}), 256u | (16u << 27));  // 256 x 2^(16 - 15 - 9)
  EXPECT_EQ(packRgb9e5({0.0f, 0.0f, 0.0f}), 0u);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(packRgb9e5({-1.0f, nan, 0.0f}), 0u);  // negatives and NaN are black
  // Beyond the largest value (65408): every channel saturates.
  EXPECT_EQ(packRgb9e5({1e9f, std::numeric_limits<float>::infinity(), 65408.0f}), 511u | (511u << 9) | (511u << 18) | (31u << 27));
  // Rounding 511.9 / 256 up carries into a tenth bit: the next exponent, mantissa 256.
  const prt::Rgb carried = unpackRgb9e5(packRgb9e5({511.9f / 256.0f, 0.0f, 0.0f}));
  EXPECT_FLOAT_EQ(carried.r, 2.0f);
}

TEST(BackgroundTexture, Rgb9e5KeepsNineBitsOfTheLargestChannel) {
  std::uint32_t seed = 12345;
  const auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / static_cast<float>(1u << 24);
  };
  for (int i = 0; i < 10000; ++i) {
    const float scale = std::ldexp(1.0f, static_cast<int>(next() * 30.0f) - 14);  // 2^-14 .. 2^15
    const prt::Rgb in{next() * scale, next() * scale, next() * scale};
    const prt::Rgb out = unpackRgb9e5(prt::serve::packRgb9e5(in));
    const float largest = std::max({in.r, in.g, in.b});
    // Half a step of the 9-bit mantissas at the shared exponent (2^-9 of the largest
    // channel's power of two, at least 2^-24, the step at the smallest exponent), which
    // rounding the largest channel up to 512 raises by one.
    const float step = std::max(std::ldexp(1.0f, std::ilogb(largest) - 8), std::ldexp(1.0f, -24));
    const bool carried = (prt::serve::packRgb9e5(in) >> 27) == static_cast<std::uint32_t>(std::ilogb(largest) + 17);
    const float tolerance = (carried ? step : 0.5f * step) + 1e-12f;
    EXPECT_NEAR(out.r, in.r, tolerance) << i;
    EXPECT_NEAR(out.g, in.g, tolerance) << i;
    EXPECT_NEAR(out.b, in.b, tolerance) << i;
  }
}

TEST(BackgroundTexture, BoxFilteredAndPacked) {
  prt::RgbImage image;
  image.width = 8;
  image.height = 4;
  image.rgb.resize(8 * 4 * 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) image.rgb[(y * 8 + x) * 3 + c] = static_cast<float>(x + 8 * y) * (c + 1);
  std::string bytes;
  int w = 0, h = 0;
  ASSERT_TRUE(prt::serve::makeBackgroundRgb9e5(image, 4, &bytes, &w, &h).isOk());
  ASSERT_EQ(w, 4);
  ASSERT_EQ(h, 2);
  ASSERT_EQ(bytes.size(), 4u * 2u * 4u);
  for (int t = 0; t < 8; ++t) {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[t * 4 + k])) << (8 * k);  // little-endian
    const int x = t % 4, y = t / 4;
    // The mean of the 2 x 2 source block: (2x + 0.5) + 8 (2y + 0.5).
    const double mean = 2 * x + 0.5 + 8 * (2 * y + 0.5);
    const prt::Rgb p = unpackRgb9e5(v);
    EXPECT_NEAR(p.r, mean, mean / 256) << t;
    EXPECT_NEAR(p.b, 3 * mean, 3 * mean / 256) << t;
  }
  EXPECT_FALSE(prt::serve::makeBackgroundRgb9e5(prt::RgbImage{}, 4, &bytes, &w, &h).isOk());
}
