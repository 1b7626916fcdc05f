// The Radiance RGBE reader (native/radiance_hdr.cpp) through loadImage: files from
// stb_image_write (new-style run-length scanlines, or flat below 8 pixels wide), checked
// against stb_image's decoder and the source floats; hand-built bytes for flat scanlines,
// old-style runs, both row orders and header variants; and malformed files.
#include <gtest/gtest.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "native/image_io.h"
#include "native_test_files.h"

namespace prt {
namespace {

using test::Bytes;
using test::cat;
using test::ScratchDir;

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

RgbImage loadOk(const std::string& path) {
  RgbImage image;
  const Status s = loadImage(path, &image);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return image;
}

Status loadFails(const std::string& path) {
  RgbImage image;
  const Status s = loadImage(path, &image);
  EXPECT_FALSE(s.isOk()) << path << " loaded as " << image.width << "x" << image.height;
  EXPECT_TRUE(image.rgb.empty());
  EXPECT_EQ(s.message().rfind(cat("'", path, "': "), 0), 0u) << s.message();
  return s;
}

// "#?RADIANCE", header lines, the blank line, the resolution line.
Bytes hdrHeader(std::string_view resolution, std::string_view lines = "FORMAT=32-bit_rle_rgbe\n",
                std::string_view signature = "#?RADIANCE\n") {
  std::string s(signature);
  s.append(lines).append("\n").append(resolution).append("\n");
  return Bytes(s.begin(), s.end());
}

void append(Bytes& b, std::initializer_list<int> bytes) {
  for (int v : bytes) b.push_back(static_cast<unsigned char>(v));
}

// The reference decoding of one RGBE component, in double: mantissa * 2^(e - 136), and 0
// when the exponent byte is 0 (Radiance's colr_color).
double rgbe(int mantissa, int exponent) { return exponent == 0 ? 0.0 : mantissa * std::ldexp(1.0, exponent - 136); }

void expectRgbe(const RgbImage& image, int x, int y, std::initializer_list<int> px) {
  const int* p = px.begin();
  const Rgb v = image.at(x, y);
  EXPECT_EQ(v.r, rgbe(p[0], p[3])) << "at (" << x << ", " << y << ")";
  EXPECT_EQ(v.g, rgbe(p[1], p[3])) << "at (" << x << ", " << y << ")";
  EXPECT_EQ(v.b, rgbe(p[2], p[3])) << "at (" << x << ", " << y << ")";
}

Bytes stbHdr(int w, int h, const std::vector<float>& rgb) {
  Bytes out;
  const int ok = stbi_write_hdr_to_func(
      [](void* context, void* data, int size) {
        auto* o = static_cast<Bytes*>(context);
        const auto* p = static_cast<const unsigned char*>(data);
        o->insert(o->end(), p, p + size);
      },
      &out, w, h, 3, rgb.data());
  EXPECT_NE(ok, 0);
  return out;
}

// Where the pixel data starts: after the resolution line.
std::size_t dataOffset(const Bytes& file) {
  const std::string_view text(reinterpret_cast<const char*>(file.data()), file.size());
  const std::size_t blank = text.find("\n\n");
  return text.find('\n', blank + 2) + 1;
}

// Smooth areas (long runs), noise (dumps), zeros and a range of exponents.
std::vector<float> testPicture(int w, int h) {
  std::vector<float> px;
  std::uint32_t s = 99;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        s = s * 1664525u + 1013904223u;
        const float noise = static_cast<float>(s >> 8) / 16777216.0f;
        float v = 0.0f;
        if (x < w / 3)
          v = 1.0f + static_cast<float>(c);  // flat: runs
        else if (x < 2 * w / 3)
          v = noise * std::ldexp(1.0f, (x + y) % 24 - 12);  // noisy, wide range
        else if (x % 2 == 0)
          v = 0.0f;  // black
        else
          v = 1000.0f * noise;
        px.push_back(v);
      }
    }
  }
  return px;
}

void expectMatchesStbAndSource(const RgbImage& image, const Bytes& file, const std::vector<float>& source) {
  int w = 0, h = 0, c = 0;
  std::unique_ptr<float, void (*)(void*)> ref(
      stbi_loadf_from_memory(file.data(), static_cast<int>(file.size()), &w, &h, &c, 3), stbi_image_free);
  ASSERT_TRUE(ref) << stbi_failure_reason();
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  ASSERT_EQ(image.rgb.size(), source.size());
  for (std::size_t i = 0; i < image.rgb.size(); ++i) EXPECT_EQ(image.rgb[i], ref.get()[i]) << "value " << i;
  // RGBE keeps 8 mantissa bits relative to the pixel's largest component.
  for (std::size_t p = 0; p < source.size(); p += 3) {
    const float m = std::max({source[p], source[p + 1], source[p + 2]});
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(image.rgb[p + k], source[p + k], m / 128.0f) << "value " << p + k;
  }
}

TEST(RadianceHdr, RunLengthFileFromStbImageWrite) {
  ScratchDir dir;
  const int w = 37, h = 5;
  const std::vector<float> source = testPicture(w, h);
  const Bytes file = stbHdr(w, h, source);
  // New-style run-length scanlines: 2, 2, then the width in 16 bits.
  const std::size_t d = dataOffset(file);
  ASSERT_LT(d + 4, file.size());
  EXPECT_EQ(file[d], 2);
  EXPECT_EQ(file[d + 1], 2);
  EXPECT_EQ((file[d + 2] << 8) | file[d + 3], w);
  EXPECT_LT(file.size() - d, static_cast<std::size_t>(w * h * 4));  // the runs did compress
  const RgbImage image = loadOk(dir.write("rle.hdr", file));
  expectMatchesStbAndSource(image, file, source);
}

TEST(RadianceHdr, FlatFileFromStbImageWrite) {
  ScratchDir dir;
  const int w = 5, h = 4;  // below 8 pixels stb_image_write stores scanlines flat
  const std::vector<float> source = testPicture(w, h);
  const Bytes file = stbHdr(w, h, source);
  EXPECT_EQ(file.size() - dataOffset(file), static_cast<std::size_t>(w * h * 4));
  const RgbImage image = loadOk(dir.write("flat.hdr", file));
  expectMatchesStbAndSource(image, file, source);
}

// Flat scanlines in an image 8 or more wide (the first pixel is not 2, 2, ...); rows top
// first for "-Y"; exponent 0 is black whatever the mantissas.
TEST(RadianceHdr, HandBuiltFlatTopDown) {
  ScratchDir dir;
  Bytes f = hdrHeader("-Y 2 +X 9");
  std::vector<std::vector<int>> px;
  for (int i = 0; i < 18; ++i) px.push_back({(i * 37 + 128) % 256, (i * 11) % 256, 255 - i, i == 4 ? 0 : 120 + i});
  px[0] = {128, 64, 32, 129};  // 1, 0.5, 0.25
  px[9] = {255, 1, 0, 255};    // the largest exponent: finite
  for (const auto& p : px) append(f, {p[0], p[1], p[2], p[3]});
  const RgbImage image = loadOk(dir.write("flat9.hdr", f));
  ASSERT_EQ(image.width, 9);
  ASSERT_EQ(image.height, 2);
  for (int i = 0; i < 18; ++i) {
    const auto& p = px[static_cast<std::size_t>(i)];
    expectRgbe(image, i % 9, i / 9, {p[0], p[1], p[2], p[3]});
  }
  EXPECT_EQ(image.at(0, 0).r, 1.0f);
  EXPECT_EQ(image.at(0, 0).b, 0.25f);
  EXPECT_EQ(image.at(4, 0).r, 0.0f);
  EXPECT_TRUE(std::isfinite(image.at(0, 1).r));
}

// "+Y H +X W": the first scanline is the bottom row.
TEST(RadianceHdr, BottomUpOrientationIsFlipped) {
  ScratchDir dir;
  for (const char* res : {"-Y 3 +X 2", "+Y 3 +X 2"}) {
    Bytes f = hdrHeader(res);
    for (int row = 0; row < 3; ++row)
      for (int x = 0; x < 2; ++x) append(f, {10 * (row + 1) + x, 0, 0, 136});  // value = mantissa
    const RgbImage image = loadOk(dir.write("orient.hdr", f));
    ASSERT_EQ(image.width, 2);
    ASSERT_EQ(image.height, 3);
    const bool bottomUp = res[0] == '+';
    for (int y = 0; y < 3; ++y) {
      const int fileRow = bottomUp ? 2 - y : y;
      for (int x = 0; x < 2; ++x) EXPECT_EQ(image.at(x, y).r, static_cast<float>(10 * (fileRow + 1) + x)) << res;
    }
  }
}

// Old-style runs: 1, 1, 1, n repeats the previous pixel n times, n << 8 for a second run
// in a row.
TEST(RadianceHdr, OldStyleRuns) {
  ScratchDir dir;
  Bytes f = hdrHeader("-Y 2 +X 300");
  append(f, {50, 60, 70, 130, 1, 1, 1, 43, 1, 1, 1, 1});  // 1 + 43 + 256 pixels
  append(f, {9, 8, 7, 131, 5, 6, 7, 132, 1, 1, 1, 2});    // A, B, B, B
  for (int x = 4; x < 300; ++x) append(f, {x % 256, 1, 2, 133});
  const RgbImage image = loadOk(dir.write("old.hdr", f));
  ASSERT_EQ(image.width, 300);
  ASSERT_EQ(image.height, 2);
  for (int x = 0; x < 300; ++x) expectRgbe(image, x, 0, {50, 60, 70, 130});
  expectRgbe(image, 0, 1, {9, 8, 7, 131});
  for (int x = 1; x < 4; ++x) expectRgbe(image, x, 1, {5, 6, 7, 132});
  for (int x = 4; x < 300; ++x) expectRgbe(image, x, 1, {x % 256, 1, 2, 133});
}

// New-style scanlines built by hand: per component, runs (count > 128) and dumps, a dump
// of exactly 128, and a row stored flat between run-length rows.
TEST(RadianceHdr, NewStyleRunsAndDumps) {
  ScratchDir dir;
  const int w = 130;
  Bytes f = hdrHeader("-Y 3 +X 130");
  for (int row = 0; row < 3; ++row) {
    if (row == 1) {
      for (int x = 0; x < w; ++x) append(f, {200, x, 3, 137});  // flat
      continue;
    }
    append(f, {2, 2, 0, w});
    append(f, {128 + 127, 10, 128 + 3, 11});  // R: 127 x 10, 3 x 11
    append(f, {128});                         // G: a dump of 128, then 2
    for (int x = 0; x < 128; ++x) append(f, {x});
    append(f, {2, 250, 251});
    append(f, {128 + 65, 7, 65});  // B: run of 65, dump of 65
    for (int x = 0; x < 65; ++x) append(f, {100 + x});
    append(f, {128 + 127, 140, 128 + 3, 140 + row});  // E
  }
  const RgbImage image = loadOk(dir.write("new.hdr", f));
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, 3);
  for (int row : {0, 2}) {
    for (int x = 0; x < w; ++x) {
      const int r = x < 127 ? 10 : 11;
      const int g = x < 128 ? x : (x == 128 ? 250 : 251);
      const int b = x < 65 ? 7 : 100 + (x - 65);
      const int e = x < 127 ? 140 : 140 + row;
      expectRgbe(image, x, row, {r, g, b, e});
    }
  }
  for (int x = 0; x < w; ++x) expectRgbe(image, x, 1, {200, x, 3, 137});
}

// "#?RGBE" as the program name, other header lines (EXPOSURE is ignored, as documented),
// and no FORMAT line at all (Radiance's default is RGBE).
TEST(RadianceHdr, HeaderVariants) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, std::string>> variants = {
      {"#?RGBE\n", "FORMAT=32-bit_rle_rgbe\n"},
      {"#?RADIANCE\n", "# a comment\nEXPOSURE=4.0\nGAMMA=2.2\nFORMAT=32-bit_rle_rgbe  \nPRIMARIES=0 0 0 0 0 0 0 0\n"},
      {"#?RADIANCE\n", ""},
  };
  for (const auto& [signature, lines] : variants) {
    Bytes f = hdrHeader("-Y 1 +X 2", lines, signature);
    append(f, {128, 128, 128, 129, 64, 32, 16, 130});
    const RgbImage image = loadOk(dir.write("variant.hdr", f));
    ASSERT_EQ(image.width, 2) << lines;
    expectRgbe(image, 0, 0, {128, 128, 128, 129});
    expectRgbe(image, 1, 0, {64, 32, 16, 130});
  }
}

TEST(RadianceHdr, HeaderErrors) {
  ScratchDir dir;
  struct Case {
    std::string text;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n", "unsupported Radiance HDR format '32-bit_rle_xyze'"},
      {"#?RADIANCE\n\n+X 1 -Y 1\n", "unsupported Radiance HDR orientation '+X 1 -Y 1'"},
      {"#?RADIANCE\n\n-Y 1 -X 1\n", "unsupported Radiance HDR orientation"},
      {"#?RADIANCE\n\n-Y 1 +X\n", "corrupt Radiance HDR file: bad resolution line '-Y 1 +X'"},
      {"#?RADIANCE\n\n-Y one +X 1\n", "bad resolution line"},
      {"#?RADIANCE\n\n-Y 1 +X 1 2\n", "bad resolution line"},
      {"#?RADIANCE\n\n-Y 1x +X 1\n", "bad resolution line"},
      {"#?RADIANCE\n\n-Y 99999999999999999999 +X 1\n", "bad resolution line"},
      {"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "corrupt Radiance HDR file: the header has no end"},
      {cat("#?RADIANCE\n", std::string(5000, 'x'), "\n\n-Y 1 +X 1\n"), "the header has no end"},
      {"#?RADIANCE\n\n", "truncated Radiance HDR file"},
      {"#?RADIANCE", "corrupt Radiance HDR file"},
  };
  for (const Case& c : cases) {
    const Status s = loadFails(dir.write("bad.hdr", c.text));
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(s.message(), c.message));
  }
}

TEST(RadianceHdr, ZeroAndHugeSizes) {
  ScratchDir dir;
  struct Case {
    std::string resolution;
    std::string message;
  };
  for (const Case& c :
       std::vector<Case>{{"-Y 0 +X 4", "image has zero size (4x0)"},
                         {"-Y 4 +X 0", "image has zero size (0x4)"},
                         {"-Y -4 +X 4", "image has zero size (4x-4)"},
                         {"-Y 1 +X 40000", "image is too large (40000x1); each side must be at most 32768"},
                         {"+Y 3000000000 +X 1", "image is too large (1x3000000000)"},
                         {"-Y 8193 +X 8192", "image is too large (8192x8193); at most 67108864 pixels"}}) {
    Bytes f = hdrHeader(c.resolution);
    append(f, {128, 128, 128, 129});
    const Status s = loadFails(dir.write("size.hdr", f));
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(s.message(), c.message));
  }
}

// Each malformed scanline: a run or dump longer than what is left of the scanline (a
// count of 0, which makes stb_image's reader spin, among them), a wrong scanline length,
// an old-style run with nothing before it or past the end.
TEST(RadianceHdr, BadScanlines) {
  ScratchDir dir;
  struct Case {
    std::string resolution;
    std::vector<int> data;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"-Y 1 +X 8", {2, 2, 0, 8, 128 + 9, 1}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 8, 128 + 5, 1, 128 + 4, 1}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 8, 9, 1, 2, 3, 4, 5, 6, 7, 8, 9}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 8, 0, 0, 0, 0}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 8, 128, 0, 0, 0}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 8, 128 + 8, 1, 128 + 8, 2, 128 + 8, 3, 0}, "bad run length in a scanline"},
      {"-Y 1 +X 8", {2, 2, 0, 9}, "a scanline's length disagrees with the image width"},
      {"-Y 1 +X 4", {1, 1, 1, 2}, "a run-length pixel has nothing to repeat"},
      {"-Y 1 +X 4", {5, 5, 5, 130, 1, 1, 1, 4}, "a run overflows its scanline"},
      {"-Y 1 +X 300", {5, 5, 5, 130, 1, 1, 1, 0, 1, 1, 1, 2}, "a run overflows its scanline"},  // 0 + 2<<8 > 299
      // A fourth run in a row would repeat n << 24 times.
      {"-Y 1 +X 4", {5, 5, 5, 130, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 0, 1, 1, 1, 1}, ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.message);
    Bytes f = hdrHeader(c.resolution);
    for (int v : c.data) f.push_back(static_cast<unsigned char>(v));
    const Status s = loadFails(dir.write("scan.hdr", f));
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(s.message(), cat("corrupt Radiance HDR file: ", c.message)));
  }
}

// Every cut of a run-length file fails: in the header as corrupt or truncated, in the
// pixels as truncated.
TEST(RadianceHdr, TruncatedAtEveryOffset) {
  ScratchDir dir;
  const int w = 20, h = 3;
  const Bytes full = stbHdr(w, h, testPicture(w, h));
  ASSERT_EQ(loadOk(dir.write("full.hdr", full)).width, w);
  const std::size_t data = dataOffset(full);
  for (std::size_t cut = 2; cut < full.size(); ++cut) {
    SCOPED_TRACE(::testing::Message() << "cut at " << cut << " of " << full.size());
    const Status s =
        loadFails(dir.write("cut.hdr", Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut))));
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    if (cut >= data) {
      EXPECT_TRUE(contains(s.message(), "truncated Radiance HDR file: the data ends before the image is complete"));
    } else {
      EXPECT_TRUE(contains(s.message(), "Radiance HDR")) << s.message();
    }
  }
}

// Single-byte mutations of a small run-length file: whatever the result, no crash (the
// sanitizer build checks for reads out of bounds), and a success has the declared size
// and finite values.
TEST(RadianceHdr, ByteMutationsNeverCrash) {
  ScratchDir dir;
  const int w = 12, h = 2;
  const Bytes full = stbHdr(w, h, testPicture(w, h));
  int accepted = 0, rejected = 0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    for (const unsigned char v : {0x00, 0x01, 0x02, 0x7f, 0x80, 0x81, 0xff}) {
      if (full[i] == v) continue;
      Bytes m = full;
      m[i] = v;
      RgbImage image;
      const Status s = loadImage(dir.write("m.hdr", m), &image);
      if (s.isOk()) {
        ++accepted;
        EXPECT_EQ(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3, image.rgb.size());
        for (float f : image.rgb) EXPECT_TRUE(std::isfinite(f));
      } else {
        ++rejected;
        EXPECT_FALSE(s.message().empty());
      }
    }
  }
  EXPECT_GT(accepted, 0);  // mutated mantissas still decode
  EXPECT_GT(rejected, 0);  // mutated run counts do not
}

}  // namespace
}  // namespace prt
