// Writes the small images the prt-bake CLI tests read, at test time, so no binary fixture
// lives in the repository. Usage: prt_cli_make_fixtures OUTPUT_DIR
//
// Known answers (order-n SH of radiance L, i = l(l+1)+m, +y up):
//   constant 1        -> c0 = 2 sqrt(pi) = 3.5449077, every other coefficient 0
//   1 above horizon   -> c0 = sqrt(pi) = 1.7724539, c1 (y) = sqrt(3 pi)/2 = 1.5349900
//   sRGB 128 (PNG)    -> linear 0.21586050, c0 = 0.76520
//   sRGB 188 (JPEG)   -> linear 0.50288862, c0 = 1.78268
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <ImfRgbaFile.h>
#include <stb_image_write.h>

namespace {

using Fill = std::function<void(int x, int y, float rgb[3])>;

std::string g_dir;

std::string at(const char* name) { return g_dir + "/" + name; }

void writeExr(const char* name, int w, int h, Imf::Compression compression, const Fill& fill) {
  std::vector<Imf::Rgba> px(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float c[3];
      fill(x, y, c);
      px[static_cast<std::size_t>(y) * w + x] = Imf::Rgba(c[0], c[1], c[2], 1.0f);
    }
  }
  Imf::RgbaOutputFile file(at(name).c_str(), Imf::Header(w, h, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, compression),
                           Imf::WRITE_RGB);
  file.setFrameBuffer(px.data(), 1, static_cast<std::size_t>(w));
  file.writePixels(h);
}

std::vector<float> floats(int w, int h, const Fill& fill) {
  std::vector<float> px(static_cast<std::size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) fill(x, y, &px[(static_cast<std::size_t>(y) * w + x) * 3]);
  return px;
}

// `fill` gives 8-bit code values in [0, 255] (sRGB-encoded, as the files store them).
std::vector<unsigned char> bytes(int w, int h, const Fill& fill) {
  std::vector<unsigned char> out;
  for (float v : floats(w, h, fill)) out.push_back(static_cast<unsigned char>(v));
  return out;
}

bool writePng(const char* name, int w, int h, const Fill& fill) {
  const std::vector<unsigned char> px = bytes(w, h, fill);
  return stbi_write_png(at(name).c_str(), w, h, 3, px.data(), w * 3) != 0;
}

bool writeJpg(const char* name, int w, int h, const Fill& fill) {
  const std::vector<unsigned char> px = bytes(w, h, fill);
  return stbi_write_jpg(at(name).c_str(), w, h, 3, px.data(), 100) != 0;
}

bool writeHdr(const char* name, int w, int h, const Fill& fill) {
  const std::vector<float> px = floats(w, h, fill);
  return stbi_write_hdr(at(name).c_str(), w, h, 3, px.data()) != 0;
}

// An EXR whose display window is wider than prt::kMaxImageSide but stores a single pixel:
// a tiny file that declares an oversized image.
void writeWideExr(const char* name) {
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(39999, 1));
  const Imath::Box2i data(Imath::V2i(0, 0), Imath::V2i(0, 0));
  Imf::RgbaOutputFile file(at(name).c_str(), Imf::Header(display, data), Imf::WRITE_RGB);
  Imf::Rgba px(1.0f, 1.0f, 1.0f, 1.0f);
  file.setFrameBuffer(&px, 1, 1);
  file.writePixels(1);
}

std::uint32_t crc32(const unsigned char* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void put32(std::vector<unsigned char>& v, std::uint32_t x) {
  for (int s = 24; s >= 0; s -= 8) v.push_back(static_cast<unsigned char>(x >> s));
}

// A PNG with a well-formed header claiming w x h and an IEND, but no pixel data: lets the
// tests reach the loader's size checks without a multi-gigabyte file.
bool writePngHeaderOnly(const char* name, std::uint32_t w, std::uint32_t h) {
  std::vector<unsigned char> f = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  auto chunk = [&f](const char* type, const std::vector<unsigned char>& data) {
    put32(f, static_cast<std::uint32_t>(data.size()));
    const std::size_t start = f.size();
    f.insert(f.end(), type, type + 4);
    f.insert(f.end(), data.begin(), data.end());
    put32(f, crc32(&f[start], f.size() - start));
  };
  std::vector<unsigned char> ihdr;
  put32(ihdr, w);
  put32(ihdr, h);
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, no filter, no interlace
  chunk("IHDR", ihdr);
  chunk("IEND", {});
  std::ofstream out(at(name), std::ios::binary);
  out.write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size()));
  return static_cast<bool>(out);
}

// Deterministic noise in [0, 1) so truncation lands in data that does not compress away.
float noise(int x, int y, int c) {
  std::uint32_t s = static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u ^
                    static_cast<std::uint32_t>(c) * 83492791u;
  s ^= s >> 13;
  s *= 0x5bd1e995u;
  s ^= s >> 15;
  return static_cast<float>(s & 0xffffu) / 65536.0f;
}

Fill constant(float v) {
  return [v](int, int, float c[3]) { c[0] = c[1] = c[2] = v; };
}

// `v` in the top half of the rows (above the horizon of an equirect), 0 below.
Fill topHalf(int h, float v) {
  return [h, v](int, int y, float c[3]) { c[0] = c[1] = c[2] = (y < h / 2 ? v : 0.0f); };
}

Fill noiseFill(float scale) {
  return [scale](int x, int y, float c[3]) {
    for (int k = 0; k < 3; ++k) c[k] = noise(x, y, k) * scale;
  };
}

bool run() {
  std::filesystem::create_directories(g_dir);
  // OpenEXR in several compressions, DWAB (lossy, what blender-data ships) included.
  writeExr("const1_zip.exr", 64, 32, Imf::ZIP_COMPRESSION, constant(1.0f));
  writeExr("const1_dwab.exr", 64, 32, Imf::DWAB_COMPRESSION, constant(1.0f));
  writeExr("const1_piz.exr", 64, 32, Imf::PIZ_COMPRESSION, constant(1.0f));
  writeExr("top_bright.exr", 64, 32, Imf::ZIP_COMPRESSION, topHalf(32, 1.0f));
  writeExr("const1_angular.exr", 64, 64, Imf::ZIP_COMPRESSION, constant(1.0f));
  writeExr("const1_cross.exr", 64, 48, Imf::ZIP_COMPRESSION, constant(1.0f));
  writeExr("noise.exr", 64, 32, Imf::NO_COMPRESSION, noiseFill(4.0f));
  writeExr("noise_zip.exr", 64, 32, Imf::ZIP_COMPRESSION, noiseFill(4.0f));
  writeExr("nan.exr", 64, 32, Imf::ZIP_COMPRESSION, [](int x, int y, float c[3]) {
    c[0] = c[1] = c[2] = (x == 5 && y == 7) ? std::numeric_limits<float>::quiet_NaN() : 1.0f;
  });
  writeWideExr("wide.exr");

  bool ok = true;
  ok &= writeHdr("const1.hdr", 64, 32, constant(1.0f));
  ok &= writeHdr("top_bright.hdr", 64, 32, topHalf(32, 1.0f));
  ok &= writeHdr("noise.hdr", 64, 32, noiseFill(4.0f));
  ok &= writePng("const1.png", 64, 32, constant(255.0f));
  ok &= writePng("gray128.png", 64, 32, constant(128.0f));
  ok &= writePng("top_bright.png", 64, 32, topHalf(32, 255.0f));
  ok &= writePng("const1_vcross.png", 48, 64, constant(255.0f));
  ok &= writePng("odd_aspect.png", 50, 30, constant(255.0f));
  ok &= writePng("noise.png", 64, 32, noiseFill(256.0f));
  ok &= writeJpg("gray188.jpg", 64, 32, constant(188.0f));
  ok &= writeJpg("noise.jpg", 64, 32, noiseFill(256.0f));
  ok &= writePngHeaderOnly("wide.png", 40000, 1);
  ok &= writePngHeaderOnly("zero.png", 0, 16);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  g_dir = argv[1];
  try {
    if (!run()) {
      std::fprintf(stderr, "make_fixtures: stb_image_write failed to write into %s\n", argv[1]);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_fixtures: %s\n", e.what());
    return 1;
  }
  std::printf("fixtures written to %s\n", argv[1]);
  return 0;
}
