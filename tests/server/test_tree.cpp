#include "test_tree.h"

#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "prt/asset.h"

namespace prt::serve::test {

namespace fs = std::filesystem;

std::vector<std::uint8_t> makeAssetBytes(int vertices, int order, std::uint32_t seed, const std::string& name,
                                         const LightingInfo& lighting) {
  BakedAsset a;
  a.shOrder = order;
  a.name = name;
  a.lighting = lighting;
  a.samples = 64;
  a.seed = seed;
  a.sampling = "hammersley";
  for (int v = 0; v < vertices; ++v) {
    const float t = static_cast<float>(v) * 0.01f;
    a.positions.push_back({t, static_cast<float>(v % 2), std::sin(t)});
    a.normals.push_back({0.0f, 1.0f, 0.0f});
    a.albedo.push_back({0.5f, 0.25f, 0.125f});
  }
  for (int v = 0; v + 2 < vertices; ++v) {
    a.indices.insert(a.indices.end(), {static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(v + 1),
                                       static_cast<std::uint32_t>(v + 2)});
  }
  const int n2 = order * order;
  for (const auto& [kind, channels] : {std::pair{TransferKind::kUnshadowed, 1}, std::pair{TransferKind::kInterreflected, 3}}) {
    TransferPass p;
    p.kind = kind;
    p.channels = channels;
    p.bounces = kind == TransferKind::kInterreflected ? 2 : 0;
    for (int v = 0; v < vertices; ++v) {
      for (int c = 0; c < channels * n2; ++c) {
        // Rounded to 1/256: real transfer is smooth, and the encodings need something to find.
        const double x = std::sin(0.001 * v * (c + 1) + seed) / (1 + c);
        p.coeffs.push_back(static_cast<float>(std::round(x * 256.0) / 256.0));
      }
    }
    a.passes.push_back(std::move(p));
  }
  std::vector<std::uint8_t> out;
  if (Status s = encodeAsset(a, &out); !s.isOk()) throw std::runtime_error("encodeAsset: " + s.toString());
  return out;
}

std::string makeRgbeImage(int width, int height, float r, float g, float b) {
  std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
  const float m = std::max({r, g, b});
  int e = 0;
  const float scale = std::frexp(m, &e) * 256.0f / m;
  const char pixel[4] = {static_cast<char>(static_cast<int>(r * scale)), static_cast<char>(static_cast<int>(g * scale)),
                         static_cast<char>(static_cast<int>(b * scale)), static_cast<char>(e + 128)};
  // Flat (not run-length encoded) scanlines: valid for any width.
  for (int i = 0; i < width * height; ++i) out.append(pixel, 4);
  return out;
}

void writeFile(const std::string& path, const std::string& bytes) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path);
}

void writeFile(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  writeFile(path, std::string(bytes.begin(), bytes.end()));
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

namespace {

// Removes the trees at exit. A function-local static made on the first tree, so it is
// destroyed after anything built later (the shared server is stopped before its tree goes).
struct TreeJanitor {
  std::vector<std::string> dirs;
  ~TreeJanitor() {
    if (std::getenv("PRT_KEEP_TEST_TREES")) return;
    std::error_code ec;
    for (const std::string& d : dirs) fs::remove_all(d, ec);
  }
};

TreeJanitor& janitor() {
  static TreeJanitor j;
  return j;
}

}  // namespace

TestTree makeTestTree(const std::string& parent) {
  janitor();
  fs::create_directories(parent);
  std::string pattern = parent + "/tree-XXXXXX";
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed under " + parent);
  TestTree t;
  t.dir = pattern;
  janitor().dirs.push_back(t.dir);
  t.root = t.dir + "/root";
  t.web = t.dir + "/web";
  t.outside = t.dir + "/outside";

  t.room = makeAssetBytes(6000, 4, 1, "test room");
  t.small = makeAssetBytes(3, 1, 2, "tiny", {LightingModel::kLocalSphere, {0.5f, 1.25f, -2.0f}, 3.5f});
  writeFile(t.root + "/room.prt", t.room);
  writeFile(t.root + "/sub/small.prt", t.small);
  std::vector<std::uint8_t> corrupt = t.room;
  corrupt[corrupt.size() / 2] ^= 0x40;  // inside a transfer section: its checksum fails
  writeFile(t.root + "/corrupt.prt", corrupt);
  writeFile(t.root + "/truncated.prt", std::vector<std::uint8_t>(t.room.begin(), t.room.begin() + 5000));
  writeFile(t.root + "/notes.txt", std::string("not an asset\n"));
  writeFile(t.root + "/sky.hdr", makeRgbeImage(64, 32, 0.5f, 0.75f, 1.0f));
  writeFile(t.root + "/bad.hdr", std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 9999999 +X 9999999\n"));
  // Unusable maps whose loader messages name the file by its absolute path (OpenEXR's own
  // text repeats it): the server must not pass those paths on.
  writeFile(t.root + "/damaged.exr", std::string("v/1\x01 not really an OpenEXR file, only its magic number"));
  writeFile(t.root + "/sub/notimage.exr", std::string("hello"));
  const fs::path exr = PRT_BLENDER_STUDIO_EXR;
  std::error_code ec;
  if (fs::exists(exr, ec)) {
    fs::copy_file(exr, t.root + "/studio.exr", ec);
    t.hasExr = !ec;
  }

  writeFile(t.outside + "/secret.txt", std::string("top secret\n"));
  writeFile(t.outside + "/secret.prt", t.small);
  fs::create_symlink("../outside/secret.prt", t.root + "/escape.prt");
  fs::create_symlink("../outside", t.root + "/outdir");

  writeFile(t.web + "/index.html", std::string("<!doctype html><title>prt</title><p>hello</p>\n"));
  writeFile(t.web + "/app.js", std::string("export const answer = 42;\n"));
  writeFile(t.web + "/module.mjs", std::string("export default 1;\n"));
  writeFile(t.web + "/core.wasm", std::string("\0asm\1\0\0\0", 8));
  writeFile(t.web + "/style.css", std::string("body { margin: 0 }\n"));
  writeFile(t.web + "/data.json", std::string("{\"a\": 1}\n"));
  writeFile(t.web + "/logo.png", std::string("\x89PNG\r\n\x1a\n", 8));
  writeFile(t.web + "/icon.svg", std::string("<svg xmlns=\"http://www.w3.org/2000/svg\"/>\n"));
  writeFile(t.web + "/blob.xyz", std::string("opaque\n"));
  writeFile(t.web + "/docs/index.html", std::string("<p>docs</p>\n"));
  writeFile(t.web + "/.env", std::string("PASSWORD=hunter2\n"));
  for (int i = 0; i < 4000; ++i) t.bigJs += "console.log('line " + std::to_string(i % 50) + "');\n";
  writeFile(t.web + "/big.js", t.bigJs);
  t.huge.resize(24u << 20);
  std::uint64_t x = 0x9e3779b97f4a7c15ULL;
  for (char& c : t.huge) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;  // xorshift64: incompressible, reproducible
    c = static_cast<char>(x);
  }
  writeFile(t.web + "/huge.bin", t.huge);
  fs::create_symlink("../outside/secret.txt", t.web + "/leak.txt");
  fs::create_symlink("../outside", t.web + "/leakdir");
  fs::create_symlink("index.html", t.web + "/alias.html");
  return t;
}

}  // namespace prt::serve::test
