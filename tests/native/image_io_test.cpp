// native/image_io on images written at test time: OpenEXR through OpenEXR's own writers
// (half and float, RGB with and without alpha, odd channel sets, windows, tiles), PNG and
// JPEG through stb_image_write and hand-built PNG bytes (16 bit), and the failures every
// loader shares (missing, empty, unknown, truncated, oversized). Radiance HDR has its own
// file (radiance_hdr_test.cpp).
#include <gtest/gtest.h>

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfRgbaFile.h>
#include <ImfTileDescription.h>
#include <ImfTiledOutputFile.h>
#include <half.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "native/image_io.h"
#include "native_test_files.h"

namespace prt {
namespace {

using test::Bytes;
using test::cat;
using test::ScratchDir;
using test::srgbToLinearRef;

Status load(const std::string& path, RgbImage* out) {
  // Garbage in `out` first: the loader must replace it on success and clear it on failure.
  out->width = 7;
  out->height = 9;
  out->rgb.assign(5, 1.0f);
  return loadImage(path, out);
}

RgbImage loadOk(const std::string& path) {
  RgbImage image;
  const Status s = load(path, &image);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return image;
}

// Loads `path` expecting a failure: `out` cleared, the message starting with the quoted path.
Status loadFails(const std::string& path) {
  RgbImage image;
  const Status s = load(path, &image);
  EXPECT_FALSE(s.isOk()) << path << " loaded as " << image.width << "x" << image.height;
  EXPECT_EQ(image.width, 0);
  EXPECT_EQ(image.height, 0);
  EXPECT_TRUE(image.rgb.empty());
  EXPECT_EQ(s.message().rfind(cat("'", path, "': "), 0), 0u) << s.message();
  return s;
}

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// ---- OpenEXR ----------------------------------------------------------------------------

// value(c, x, y): channel c at absolute pixel (x, y) of the data window.
using ChannelValue = std::function<float(int c, int x, int y)>;

struct ExrSpec {
  Imath::Box2i display;
  Imath::Box2i data;
  std::vector<std::string> channels = {"R", "G", "B"};
  Imf::PixelType type = Imf::FLOAT;
  Imf::Compression compression = Imf::ZIP_COMPRESSION;
  Imf::LineOrder order = Imf::INCREASING_Y;
  bool tiled = false;
};

ExrSpec exrSpec(int width, int height) {
  ExrSpec s;
  s.display = s.data = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(width - 1, height - 1));
  return s;
}

// Writes through OpenEXR's general interface (Imf::OutputFile / TiledOutputFile), so any
// channel set and pixel type can be stored.
void writeExr(const std::string& path, const ExrSpec& spec, const ChannelValue& value) {
  const int w = spec.data.max.x - spec.data.min.x + 1, h = spec.data.max.y - spec.data.min.y + 1;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<std::vector<float>> floats(spec.channels.size(), std::vector<float>(n));
  std::vector<std::vector<half>> halves(spec.channels.size(), std::vector<half>(n));
  Imf::Header header(spec.display, spec.data, 1.0f, Imath::V2f(0, 0), 1.0f, spec.order, spec.compression);
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < spec.channels.size(); ++c) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        floats[c][i] = value(static_cast<int>(c), spec.data.min.x + x, spec.data.min.y + y);
        halves[c][i] = half(floats[c][i]);
      }
    }
    header.channels().insert(spec.channels[c], Imf::Channel(spec.type));
    const void* base = spec.type == Imf::HALF ? static_cast<const void*>(halves[c].data()) : floats[c].data();
    fb.insert(spec.channels[c], Imf::Slice::Make(spec.type, base, spec.data));
  }
  if (spec.tiled) {
    header.setTileDescription(Imf::TileDescription(4, 4, Imf::ONE_LEVEL));
    Imf::TiledOutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
  } else {
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
  }
}

// Writes through Imf::RgbaOutputFile (half only), which can also store luminance/chroma.
void writeRgbaExr(const std::string& path, int w, int h, Imf::RgbaChannels channels,
                  const std::function<Imf::Rgba(int x, int y)>& value) {
  std::vector<Imf::Rgba> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      px[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = value(x, y);
  Imf::RgbaOutputFile file(path.c_str(), w, h, channels);
  file.setFrameBuffer(px.data(), 1, static_cast<std::size_t>(w));
  file.writePixels(h);
}

// Values exactly representable as half: multiples of 1/16 below 64.
float halfExact(int c, int x, int y) { return static_cast<float>(x + 8 * y) * 0.25f + static_cast<float>(c) * 0.0625f; }

void expectPixel(const RgbImage& image, int x, int y, float r, float g, float b) {
  const Rgb p = image.at(x, y);
  EXPECT_EQ(p.r, r) << "at (" << x << ", " << y << ")";
  EXPECT_EQ(p.g, g) << "at (" << x << ", " << y << ")";
  EXPECT_EQ(p.b, b) << "at (" << x << ", " << y << ")";
}

TEST(ExrLoader, HalfRgbWithAndWithoutAlpha) {
  ScratchDir dir;
  for (const Imf::RgbaChannels channels : {Imf::WRITE_RGB, Imf::WRITE_RGBA}) {
    const std::string path = dir.path(channels == Imf::WRITE_RGB ? "rgb.exr" : "rgba.exr");
    // Alpha 0.25: the colour must come back as stored, neither multiplied nor divided by it.
    writeRgbaExr(path, 8, 4, channels, [](int x, int y) {
      return Imf::Rgba(halfExact(0, x, y), halfExact(1, x, y), halfExact(2, x, y), 0.25f);
    });
    const RgbImage image = loadOk(path);
    ASSERT_EQ(image.width, 8);
    ASSERT_EQ(image.height, 4);
    ASSERT_EQ(image.rgb.size(), 8u * 4u * 3u);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) expectPixel(image, x, y, halfExact(0, x, y), halfExact(1, x, y), halfExact(2, x, y));
  }
}

TEST(ExrLoader, HalfChannelsThroughGeneralWriter) {
  ScratchDir dir;
  ExrSpec spec = exrSpec(5, 3);
  spec.type = Imf::HALF;
  const std::string path = dir.path("half.exr");
  writeExr(path, spec, halfExact);
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 5);
  ASSERT_EQ(image.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) expectPixel(image, x, y, halfExact(0, x, y), halfExact(1, x, y), halfExact(2, x, y));
}

// "EXR and HDR values are used as stored": a float channel keeps its 24-bit mantissa and
// its range. A sun in a float EXR is commonly brighter than half's largest value (65504).
TEST(ExrLoader, FloatChannelsKeepFullPrecision) {
  ScratchDir dir;
  const std::vector<float> values = {0.1f, 1.0f / 3.0f, 3.0e-6f, 1.0e-30f, 2.5f};
  const std::string path = dir.path("float.exr");
  writeExr(path, exrSpec(5, 1),
           [&](int c, int x, int) { return values[static_cast<std::size_t>(x)] * static_cast<float>(c + 1); });
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 5);
  for (int x = 0; x < 5; ++x) {
    const float v = values[static_cast<std::size_t>(x)];
    expectPixel(image, x, 0, v, v * 2.0f, v * 3.0f);
  }
}

TEST(ExrLoader, FloatValuesAboveHalfRangeLoad) {
  ScratchDir dir;
  const std::string path = dir.path("sun.exr");
  writeExr(path, exrSpec(2, 1),
           [](int c, int x, int) { return x == 0 ? 150000.0f + static_cast<float>(c) : 70000.0f; });
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 2);
  expectPixel(image, 0, 0, 150000.0f, 150001.0f, 150002.0f);
  expectPixel(image, 1, 0, 70000.0f, 70000.0f, 70000.0f);
}

TEST(ExrLoader, FloatRgbaDropsAlpha) {
  ScratchDir dir;
  ExrSpec spec = exrSpec(3, 2);
  spec.channels = {"R", "G", "B", "A"};
  const std::string path = dir.path("rgba.exr");
  writeExr(path, spec, [](int c, int x, int y) { return c == 3 ? 0.5f : halfExact(c, x, y) + 0.01f; });
  const RgbImage image = loadOk(path);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      expectPixel(image, x, y, halfExact(0, x, y) + 0.01f, halfExact(1, x, y) + 0.01f, halfExact(2, x, y) + 0.01f);
}

// Missing colour channels read as 0; channels other than R, G, B, Y are ignored.
TEST(ExrLoader, OddChannelSets) {
  ScratchDir dir;
  struct Case {
    std::vector<std::string> channels;
    std::vector<int> rgbFromChannel;  // for R, G, B: the index of the channel holding it, or -1
  };
  const std::vector<Case> cases = {
      {{"R"}, {0, -1, -1}},
      {{"G"}, {-1, 0, -1}},
      {{"B", "R"}, {1, -1, 0}},
      {{"G", "B", "A"}, {-1, 0, 1}},
      {{"A", "B", "G", "R", "Z", "diffuse.R"}, {3, 2, 1}},
  };
  int n = 0;
  for (const Imf::PixelType type : {Imf::HALF, Imf::FLOAT}) {
    for (const Case& c : cases) {
      SCOPED_TRACE(::testing::Message() << "case " << n << (type == Imf::HALF ? " half" : " float"));
      ExrSpec spec = exrSpec(4, 2);
      spec.channels = c.channels;
      spec.type = type;
      const std::string path = dir.path(cat("odd", std::to_string(n++), ".exr"));
      writeExr(path, spec, [](int ch, int x, int y) { return halfExact(0, x, y) + 16.0f * static_cast<float>(ch); });
      const RgbImage image = loadOk(path);
      ASSERT_EQ(image.width, 4);
      ASSERT_EQ(image.height, 2);
      for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 4; ++x) {
          float expected[3];
          for (int k = 0; k < 3; ++k) {
            const int ch = c.rgbFromChannel[static_cast<std::size_t>(k)];
            expected[k] = ch < 0 ? 0.0f : halfExact(0, x, y) + 16.0f * static_cast<float>(ch);
          }
          expectPixel(image, x, y, expected[0], expected[1], expected[2]);
        }
      }
    }
  }
}

// A luminance-only file is grey: R = G = B = Y, as stored.
TEST(ExrLoader, LuminanceOnlyIsGrey) {
  ScratchDir dir;
  for (const Imf::PixelType type : {Imf::HALF, Imf::FLOAT}) {
    ExrSpec spec = exrSpec(4, 3);
    spec.channels = {"Y"};
    spec.type = type;
    const std::string path = dir.path(type == Imf::HALF ? "y_half.exr" : "y_float.exr");
    // 0.3 + ... is not a half value: the float file must keep it exactly.
    const auto value = [type](int, int x, int y) {
      const float v = 0.3f + static_cast<float>(x + 4 * y);
      return type == Imf::HALF ? static_cast<float>(half(v)) : v;
    };
    writeExr(path, spec, value);
    const RgbImage image = loadOk(path);
    ASSERT_EQ(image.width, 4);
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) expectPixel(image, x, y, value(0, x, y), value(0, x, y), value(0, x, y));
  }
}

// Luminance/chroma files (RgbaOutputFile's WRITE_YC) are lossy; a flat colour comes back
// close to what was written.
TEST(ExrLoader, LuminanceChromaFile) {
  ScratchDir dir;
  const std::string path = dir.path("yc.exr");
  writeRgbaExr(path, 16, 8, Imf::WRITE_YC, [](int, int) { return Imf::Rgba(0.5f, 0.25f, 2.0f, 1.0f); });
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 16);
  ASSERT_EQ(image.height, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 16; ++x) {
      const Rgb p = image.at(x, y);
      EXPECT_NEAR(p.r, 0.5f, 0.5f * 0.03f);
      EXPECT_NEAR(p.g, 0.25f, 0.25f * 0.03f);
      EXPECT_NEAR(p.b, 2.0f, 2.0f * 0.03f);
    }
  }
}

TEST(ExrLoader, NoColourChannelIsAnError) {
  ScratchDir dir;
  int n = 0;
  for (const std::vector<std::string>& channels : {std::vector<std::string>{"A"}, {"Z"}, {"diffuse.R", "diffuse.G"}}) {
    ExrSpec spec = exrSpec(2, 2);
    spec.channels = channels;
    const std::string path = dir.path(cat("nocolour", std::to_string(n++), ".exr"));
    writeExr(path, spec, halfExact);
    const Status s = loadFails(path);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(s.message(), "no R, G, B or Y channel"));
  }
}

// Lossless compressions give back the exact values, in both pixel types.
TEST(ExrLoader, LosslessCompressions) {
  ScratchDir dir;
  for (const Imf::Compression compression :
       {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION}) {
    for (const Imf::PixelType type : {Imf::HALF, Imf::FLOAT}) {
      SCOPED_TRACE(::testing::Message() << "compression " << compression << " type " << type);
      ExrSpec spec = exrSpec(8, 8);
      spec.compression = compression;
      spec.type = type;
      const std::string path = dir.path(cat("c", std::to_string(compression), "_", std::to_string(type), ".exr"));
      writeExr(path, spec, halfExact);
      const RgbImage image = loadOk(path);
      ASSERT_EQ(image.width, 8);
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          expectPixel(image, x, y, halfExact(0, x, y), halfExact(1, x, y), halfExact(2, x, y));
    }
  }
}

// Row 0 is the display window's top (its min.y) whatever order the file stores lines in;
// more rows than the loader's 256-row strips, so rows cross strip boundaries.
TEST(ExrLoader, RowsTopFirstInBothLineOrders) {
  ScratchDir dir;
  for (const Imf::LineOrder order : {Imf::INCREASING_Y, Imf::DECREASING_Y}) {
    ExrSpec spec = exrSpec(3, 600);
    spec.order = order;
    const std::string path = dir.path(order == Imf::INCREASING_Y ? "inc.exr" : "dec.exr");
    // Integers below 2048: exact in half and float.
    const auto value = [](int c, int x, int y) { return static_cast<float>(c == 0 ? y : c == 1 ? 1024 + y : x); };
    writeExr(path, spec, value);
    const RgbImage image = loadOk(path);
    ASSERT_EQ(image.height, 600);
    for (int y = 0; y < 600; ++y)
      for (int x = 0; x < 3; ++x) expectPixel(image, x, y, value(0, x, y), value(1, x, y), value(2, x, y));
  }
}

TEST(ExrLoader, TiledFile) {
  ScratchDir dir;
  ExrSpec spec = exrSpec(10, 7);  // not a multiple of the 4x4 tiles
  spec.tiled = true;
  const std::string path = dir.path("tiled.exr");
  writeExr(path, spec, halfExact);
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 10);
  ASSERT_EQ(image.height, 7);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 10; ++x) expectPixel(image, x, y, halfExact(0, x, y), halfExact(1, x, y), halfExact(2, x, y));
}

// The display window is the image; stored pixels outside it are cropped, pixels of it
// that are not stored are black. Coordinates need not start at 0.
TEST(ExrLoader, DataWindowSmallerThanDisplayWindowIsBlackOutside) {
  ScratchDir dir;
  ExrSpec spec;
  spec.display = Imath::Box2i(Imath::V2i(-3, 10), Imath::V2i(4, 15));  // 8 x 6
  spec.data = Imath::Box2i(Imath::V2i(-1, 11), Imath::V2i(2, 13));     // 4 x 3 inside it
  const std::string path = dir.path("inner.exr");
  const auto value = [](int c, int x, int y) {
    return 1.0f + static_cast<float>(x + 3) + 8.0f * static_cast<float>(y - 10) + 0.5f * static_cast<float>(c);
  };
  writeExr(path, spec, value);
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 8);
  ASSERT_EQ(image.height, 6);
  for (int y = 0; y < 6; ++y) {
    for (int x = 0; x < 8; ++x) {
      const int ax = x - 3, ay = y + 10;  // absolute coordinates
      const bool stored = ax >= -1 && ax <= 2 && ay >= 11 && ay <= 13;
      if (stored) {
        expectPixel(image, x, y, value(0, ax, ay), value(1, ax, ay), value(2, ax, ay));
      } else {
        expectPixel(image, x, y, 0.0f, 0.0f, 0.0f);
      }
    }
  }
}

TEST(ExrLoader, DataWindowLargerThanDisplayWindowIsCropped) {
  ScratchDir dir;
  ExrSpec spec;
  spec.display = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(3, 2));  // 4 x 3
  spec.data = Imath::Box2i(Imath::V2i(-2, -1), Imath::V2i(6, 5));   // spills on every side
  const std::string path = dir.path("outer.exr");
  const auto value = [](int c, int x, int y) {
    return static_cast<float>(100 + x + 10 * y) + 0.25f * static_cast<float>(c);
  };
  writeExr(path, spec, value);
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) expectPixel(image, x, y, value(0, x, y), value(1, x, y), value(2, x, y));
}

TEST(ExrLoader, NonFinitePixelsAreRejectedWithTheirPosition) {
  ScratchDir dir;
  struct Case {
    Imf::PixelType type;
    float bad;
  };
  int n = 0;
  for (const Case c : {Case{Imf::HALF, std::numeric_limits<float>::quiet_NaN()},
                       Case{Imf::FLOAT, std::numeric_limits<float>::infinity()},
                       Case{Imf::FLOAT, -std::numeric_limits<float>::quiet_NaN()}}) {
    ExrSpec spec = exrSpec(8, 4);
    spec.type = c.type;
    const std::string path = dir.path(cat("nonfinite", std::to_string(n++), ".exr"));
    writeExr(path, spec, [&](int ch, int x, int y) { return x == 5 && y == 2 && ch == 1 ? c.bad : 1.0f; });
    const Status s = loadFails(path);
    EXPECT_EQ(s.code(), StatusCode::kNotFinite);
    EXPECT_TRUE(contains(s.message(), "pixel (5, 2)"));
  }
}

TEST(ExrLoader, TruncatedFilesFail) {
  ScratchDir dir;
  ExrSpec spec = exrSpec(64, 32);
  spec.compression = Imf::NO_COMPRESSION;  // large chunks, so most cuts land in pixel data
  const std::string source = dir.path("full.exr");
  writeExr(source, spec, [](int c, int x, int y) { return static_cast<float>((x * 7 + y * 13 + c * 5) % 17); });
  const Bytes full = test::readBytes(source);
  ASSERT_GT(full.size(), 1000u);
  ASSERT_TRUE(loadOk(source).width == 64);
  for (std::size_t cut = 4; cut < full.size(); cut += (cut < 400 ? 7 : 211)) {
    SCOPED_TRACE(::testing::Message() << "cut at " << cut << " of " << full.size());
    const std::string path = dir.write("cut.exr", Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut)));
    const Status s = loadFails(path);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    EXPECT_TRUE(contains(s.message(), "OpenEXR"));
  }
}

TEST(ExrLoader, OversizedDisplayWindowFailsBeforeReading) {
  ScratchDir dir;
  ExrSpec wide;
  wide.display = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(kMaxImageSide, 1));  // one pixel too wide
  wide.data = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(0, 0));
  const std::string widePath = dir.path("wide.exr");
  writeExr(widePath, wide, halfExact);
  Status s = loadFails(widePath);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(s.message(), cat("image is too large (", std::to_string(kMaxImageSide + 1), "x2)")));

  ExrSpec many;  // each side allowed, the pixel count not
  many.display = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(8191, 8192));
  many.data = Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(0, 0));
  const std::string manyPath = dir.path("many.exr");
  writeExr(manyPath, many, halfExact);
  s = loadFails(manyPath);
  EXPECT_TRUE(contains(s.message(), "image is too large (8192x8193); at most 67108864 pixels"));
}

// ---- PNG and JPEG -----------------------------------------------------------------------

Bytes toBytes(const std::function<bool(stbi_write_func*, void*)>& write) {
  Bytes out;
  const bool ok = write(
      [](void* context, void* data, int size) {
        auto* o = static_cast<Bytes*>(context);
        const auto* p = static_cast<const unsigned char*>(data);
        o->insert(o->end(), p, p + size);
      },
      &out);
  EXPECT_TRUE(ok);
  return out;
}

Bytes pngBytes(int w, int h, int comp, const std::vector<unsigned char>& px) {
  return toBytes(
      [&](stbi_write_func* f, void* c) { return stbi_write_png_to_func(f, c, w, h, comp, px.data(), w * comp) != 0; });
}

Bytes jpegBytes(int w, int h, const std::vector<unsigned char>& px, int quality) {
  return toBytes(
      [&](stbi_write_func* f, void* c) { return stbi_write_jpg_to_func(f, c, w, h, 3, px.data(), quality) != 0; });
}

// The loader's linear value of an sRGB code must match the reference formula in double.
void expectSrgb(float actual, double code, double levels) {
  EXPECT_NEAR(actual, srgbToLinearRef(code / (levels - 1)), 1e-6) << "code " << code;
}

TEST(PngLoader, EightBitCodesDecodeFromSrgb) {
  ScratchDir dir;
  // 256 x 3: every code in R, reversed in G, a per-row constant in B.
  const int w = 256, h = 3;
  std::vector<unsigned char> px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      px.insert(px.end(), {static_cast<unsigned char>(x), static_cast<unsigned char>(255 - x),
                           static_cast<unsigned char>(y * 100)});
  const std::string path = dir.write("codes.png", pngBytes(w, h, 3, px));
  const RgbImage image = loadOk(path);
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const Rgb p = image.at(x, y);
      expectSrgb(p.r, x, 256);
      expectSrgb(p.g, 255 - x, 256);
      expectSrgb(p.b, y * 100, 256);
    }
  }
  // Fixed points of the curve, and the known value tests/cli relies on.
  EXPECT_EQ(image.at(0, 0).r, 0.0f);
  EXPECT_EQ(image.at(255, 0).r, 1.0f);
  EXPECT_NEAR(image.at(128, 0).r, 0.21586050f, 1e-7f);
}

TEST(PngLoader, AlphaIsDroppedNotApplied) {
  ScratchDir dir;
  const std::vector<unsigned char> px = {200, 100, 50, 0, 200, 100, 50, 128, 200, 100, 50, 255};
  const RgbImage image = loadOk(dir.write("rgba.png", pngBytes(3, 1, 4, px)));
  ASSERT_EQ(image.width, 3);
  for (int x = 0; x < 3; ++x) {
    expectSrgb(image.at(x, 0).r, 200, 256);
    expectSrgb(image.at(x, 0).g, 100, 256);
    expectSrgb(image.at(x, 0).b, 50, 256);
  }
}

TEST(PngLoader, GreyAndGreyAlphaBecomeRgb) {
  ScratchDir dir;
  const RgbImage grey = loadOk(dir.write("grey.png", pngBytes(4, 1, 1, {0, 60, 128, 255})));
  const RgbImage greyAlpha = loadOk(dir.write("greya.png", pngBytes(4, 1, 2, {0, 9, 60, 9, 128, 9, 255, 9})));
  const int codes[] = {0, 60, 128, 255};
  for (const RgbImage* image : {&grey, &greyAlpha}) {
    ASSERT_EQ(image->width, 4);
    ASSERT_EQ(image->height, 1);
    for (int x = 0; x < 4; ++x) {
      const Rgb p = image->at(x, 0);
      expectSrgb(p.r, codes[x], 256);
      EXPECT_EQ(p.g, p.r);
      EXPECT_EQ(p.b, p.r);
    }
  }
}

std::uint32_t crc32(const unsigned char* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void put32(Bytes& v, std::uint32_t x) {
  for (int s = 24; s >= 0; s -= 8) v.push_back(static_cast<unsigned char>(x >> s));
}

void pngChunk(Bytes& f, const char* type, const Bytes& data) {
  put32(f, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = f.size();
  f.insert(f.end(), type, type + 4);
  f.insert(f.end(), data.begin(), data.end());
  put32(f, crc32(&f[start], f.size() - start));
}

// A PNG built by hand: IHDR (colour type 2 or 0), one IDAT holding `raw` (filter bytes
// included) in stored (uncompressed) deflate blocks, IEND.
Bytes handPng(std::uint32_t w, std::uint32_t h, int bitDepth, int colourType, const Bytes& raw) {
  Bytes f = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes ihdr;
  put32(ihdr, w);
  put32(ihdr, h);
  ihdr.insert(ihdr.end(), {static_cast<unsigned char>(bitDepth), static_cast<unsigned char>(colourType), 0, 0, 0});
  pngChunk(f, "IHDR", ihdr);
  Bytes z = {0x78, 0x01};
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min<std::size_t>(raw.size() - pos, 65535);
    z.push_back(pos + n == raw.size() ? 1 : 0);
    z.insert(z.end(), {static_cast<unsigned char>(n), static_cast<unsigned char>(n >> 8),
                       static_cast<unsigned char>(~n), static_cast<unsigned char>(~n >> 8)});
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos),
             raw.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += n;
  } while (pos < raw.size());
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  put32(z, (b << 16) | a);
  pngChunk(f, "IDAT", z);
  pngChunk(f, "IEND", {});
  return f;
}

TEST(PngLoader, SixteenBitKeepsFullPrecision) {
  ScratchDir dir;
  const std::vector<std::uint16_t> samples = {0, 1, 257, 12345, 32768, 65534, 65535, 40000, 3};
  Bytes raw = {0};  // one row, filter 0
  for (std::uint16_t v : samples)
    raw.insert(raw.end(), {static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v)});
  const RgbImage image = loadOk(dir.write("rgb16.png", handPng(3, 1, 16, 2, raw)));
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 1);
  for (std::size_t i = 0; i < samples.size(); ++i) expectSrgb(image.rgb[i], samples[i], 65536);
  // 16 bits resolve what 8 would not: codes 1 and 257 (8-bit 0 and 1) differ.
  EXPECT_GT(image.rgb[1], 0.0f);
  EXPECT_LT(image.rgb[1], image.rgb[2]);

  Bytes grey = {0};
  for (std::uint16_t v : {std::uint16_t{100}, std::uint16_t{50000}})
    grey.insert(grey.end(), {static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v)});
  const RgbImage g = loadOk(dir.write("grey16.png", handPng(2, 1, 16, 0, grey)));
  ASSERT_EQ(g.width, 2);
  expectSrgb(g.at(0, 0).g, 100, 65536);
  expectSrgb(g.at(1, 0).b, 50000, 65536);
}

// The hand-built PNG writer itself, at 8 bits, against stb_image_write's file.
TEST(PngLoader, HandBuiltEightBitMatchesStbWrittenFile) {
  ScratchDir dir;
  const std::vector<unsigned char> px = {10, 20, 30, 40, 50, 60};
  Bytes raw = {0};
  raw.insert(raw.end(), px.begin(), px.end());
  const RgbImage a = loadOk(dir.write("hand.png", handPng(2, 1, 8, 2, raw)));
  const RgbImage b = loadOk(dir.write("stb.png", pngBytes(2, 1, 3, px)));
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.width, 2);
}

TEST(PngLoader, HeaderSizesAreChecked) {
  ScratchDir dir;
  Bytes raw = {0, 0, 0, 0};
  Status s = loadFails(dir.write("wide.png", handPng(static_cast<std::uint32_t>(kMaxImageSide) + 1, 1, 8, 2, raw)));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(contains(s.message(), cat("image is too large (", std::to_string(kMaxImageSide + 1), "x1)")));
  s = loadFails(dir.write("zero.png", handPng(0, 16, 8, 2, raw)));
  EXPECT_TRUE(contains(s.message(), "image has zero size (0x16)"));
  s = loadFails(dir.write("many.png", handPng(8192, 8193, 8, 2, raw)));
  EXPECT_TRUE(contains(s.message(), "at most 67108864 pixels"));
  // A width of 2^32 - 1 must not wrap to a small or negative number.
  s = loadFails(dir.write("huge.png", handPng(0xffffffffu, 1, 8, 2, raw)));
  EXPECT_TRUE(contains(s.message(), "too large"));
}

std::vector<unsigned char> noiseCodes(int w, int h) {
  std::vector<unsigned char> px;
  std::uint32_t s = 12345;
  for (int i = 0; i < w * h * 3; ++i) {
    s = s * 1664525u + 1013904223u;
    px.push_back(static_cast<unsigned char>(s >> 24));
  }
  return px;
}

// Every cut of a PNG fails, except in the final IEND's CRC, which no reader needs. Cuts
// after IHDR say the file is truncated.
TEST(PngLoader, TruncatedAtEveryOffsetFails) {
  ScratchDir dir;
  const Bytes full = pngBytes(32, 16, 3, noiseCodes(32, 16));
  ASSERT_TRUE(loadOk(dir.write("full.png", full)).width == 32);
  for (std::size_t cut = 1; cut + 4 < full.size(); ++cut) {
    SCOPED_TRACE(::testing::Message() << "cut at " << cut << " of " << full.size());
    const std::string path = dir.write("cut.png", Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut)));
    const Status s = loadFails(path);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    if (cut >= 33) {
      EXPECT_TRUE(contains(s.message(), "truncated PNG file"));
    }
  }
}

TEST(JpegLoader, FlatGreyWithinOneCode) {
  ScratchDir dir;
  const int w = 16, h = 8;
  const RgbImage image =
      loadOk(dir.write("grey.jpg", jpegBytes(w, h, std::vector<unsigned char>(w * h * 3, 188), 100)));
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  const double tolerance = srgbToLinearRef(189.0 / 255) - srgbToLinearRef(188.0 / 255);
  for (float v : image.rgb) EXPECT_NEAR(v, srgbToLinearRef(188.0 / 255), tolerance);
}

// A lossy gradient: the loader's values are stb_image's decoded codes through the sRGB
// curve (exactly), and those codes are close to the ones written.
TEST(JpegLoader, GradientDecodesThroughSrgb) {
  ScratchDir dir;
  const int w = 32, h = 16;
  std::vector<unsigned char> px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      px.insert(px.end(), {static_cast<unsigned char>(8 * x), static_cast<unsigned char>(16 * y), 128});
  const Bytes file = jpegBytes(w, h, px, 95);
  const RgbImage image = loadOk(dir.write("gradient.jpg", file));
  ASSERT_EQ(image.width, w);
  ASSERT_EQ(image.height, h);
  int dw = 0, dh = 0, dc = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> codes(
      stbi_load_from_memory(file.data(), static_cast<int>(file.size()), &dw, &dh, &dc, 3), stbi_image_free);
  ASSERT_TRUE(codes) << stbi_failure_reason();
  ASSERT_EQ(dw, w);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    expectSrgb(image.rgb[i], codes.get()[i], 256);
    EXPECT_NEAR(static_cast<int>(codes.get()[i]), static_cast<int>(px[i]), 8) << "sample " << i;
  }
}

// Cuts inside the APP0 segment (bytes 6-10), which stb_image skips past the end of the
// file, used to make loadImage spin forever.
TEST(JpegLoader, TruncatedFilesFail) {
  ScratchDir dir;
  const Bytes full = jpegBytes(32, 32, noiseCodes(32, 32), 90);
  ASSERT_TRUE(loadOk(dir.write("full.jpg", full)).width == 32);
  for (std::size_t cut = 1; cut + 2 < full.size(); cut += (cut < 700 ? 5 : 1)) {
    SCOPED_TRACE(::testing::Message() << "cut at " << cut << " of " << full.size());
    const std::string path = dir.write("cut.jpg", Bytes(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(cut)));
    const Status s = loadFails(path);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
    if (cut >= 3) {
      EXPECT_TRUE(contains(s.message(), "JPEG"));
    }
  }
}

// ---- Failures before any decoder --------------------------------------------------------

TEST(ImageLoader, MissingFile) {
  ScratchDir dir;
  const std::string path = dir.path("absent.exr");
  const Status s = loadFails(path);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(s.message(), cat("'", path, "': no such file"));
}

TEST(ImageLoader, DirectoryAndEmptyFile) {
  ScratchDir dir;
  const std::string sub = dir.path("sub.png");
  std::filesystem::create_directory(sub);
  Status s = loadFails(sub);
  EXPECT_EQ(s.message(), cat("'", sub, "': is a directory, not an image file"));
  const std::string empty = dir.write("empty.hdr", Bytes{});
  s = loadFails(empty);
  EXPECT_EQ(s.message(), cat("'", empty, "': file is empty"));
}

TEST(ImageLoader, UnknownFormatShowsTheFirstBytes) {
  ScratchDir dir;
  const std::string path = dir.write("image.png", std::string_view("GIF89a\x01\x00\x01\x00", 10));
  const Status s = loadFails(path);
  EXPECT_TRUE(contains(s.message(), "unknown image format"));
  EXPECT_TRUE(contains(s.message(), "47 49 46 38 39 61 01 00"));
  // A near miss of each signature is unknown too.
  for (const Bytes& near : {Bytes{0x76, 0x2f, 0x31, 0x02}, Bytes{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, 0x0b},
                            Bytes{0xff, 0xd8, 0xfe}, Bytes{'#', '!', 'R'}}) {
    EXPECT_TRUE(contains(loadFails(dir.write("near", near)).message(), "unknown image format"));
  }
}

// The format comes from the bytes, not the name.
TEST(ImageLoader, FormatByContentNotName) {
  ScratchDir dir;
  const RgbImage image = loadOk(dir.write("really_a_png.exr", pngBytes(2, 1, 3, {255, 255, 255, 0, 0, 0})));
  ASSERT_EQ(image.width, 2);
  EXPECT_EQ(image.at(0, 0).g, 1.0f);
  EXPECT_EQ(image.at(1, 0).g, 0.0f);
}

TEST(DetectImageFormat, Signatures) {
  const unsigned char exr[] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
  const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const unsigned char jpg[] = {0xff, 0xd8, 0xff, 0xe0};
  const unsigned char hdr[] = {'#', '?', 'R', 'A'};
  EXPECT_EQ(detectImageFormat(exr, sizeof exr), ImageFormat::kOpenExr);
  EXPECT_EQ(detectImageFormat(png, sizeof png), ImageFormat::kPng);
  EXPECT_EQ(detectImageFormat(png, 7), ImageFormat::kUnknown);  // too short to tell
  EXPECT_EQ(detectImageFormat(jpg, sizeof jpg), ImageFormat::kJpeg);
  EXPECT_EQ(detectImageFormat(hdr, sizeof hdr), ImageFormat::kRadianceHdr);
  EXPECT_EQ(detectImageFormat(hdr, 1), ImageFormat::kUnknown);
  EXPECT_EQ(detectImageFormat(exr, 0), ImageFormat::kUnknown);
  EXPECT_STREQ(imageFormatName(ImageFormat::kOpenExr), "OpenEXR");
  EXPECT_STREQ(imageFormatName(ImageFormat::kRadianceHdr), "Radiance HDR");
  EXPECT_STREQ(imageFormatName(ImageFormat::kPng), "PNG");
  EXPECT_STREQ(imageFormatName(ImageFormat::kJpeg), "JPEG");
  EXPECT_STREQ(imageFormatName(ImageFormat::kUnknown), "unknown");
}

TEST(CheckImageSize, Boundaries) {
  EXPECT_TRUE(checkImageSize(1, 1).isOk());
  EXPECT_TRUE(checkImageSize(kMaxImageSide, 1).isOk());
  EXPECT_TRUE(checkImageSize(1, kMaxImageSide).isOk());
  EXPECT_TRUE(checkImageSize(8192, 8192).isOk());  // exactly kMaxImagePixels
  EXPECT_EQ(checkImageSize(0, 5).message(), "image has zero size (0x5)");
  EXPECT_EQ(checkImageSize(5, -1).message(), "image has zero size (5x-1)");
  EXPECT_EQ(checkImageSize(kMaxImageSide + 1, 1).message(),
            "image is too large (32769x1); each side must be at most 32768");
  EXPECT_EQ(checkImageSize(8192, 8193).message(), "image is too large (8192x8193); at most 67108864 pixels");
  EXPECT_EQ(checkImageSize(std::int64_t{1} << 40, std::int64_t{1} << 40).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace prt
