// The scene thumbnails without a server: the rasteriser's coverage, depth and Gouraud
// interpolation; the thumbnail of a hand-made asset checked pixel by pixel against the
// exit radiance its own diffuse transfer gives under the default light; damaged bytes;
// the PNG; and one thumbnail per content hash. The served thumbnails are in http_test.cpp.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cmath>
#include <memory>
#include <set>

#include "mesh_raster.h"
#include "prt/exit_radiance.h"
#include "thumbnail.h"
#include "thumbnail_store.h"
#include "thumbnail_view.h"

namespace prt::serve::test {
namespace {

RasterVertex vertex(float x, float y, float depth, Rgb c = {1, 1, 1}) { return {x, y, depth, c}; }

int coveredCount(const RasterTarget& t) {
  int n = 0;
  for (unsigned char c : t.covered) n += c;
  return n;
}

TEST(MeshRaster, SharedEdgesCoverEachPixelCentreExactlyOnce) {
  // A 10 x 10 square from (2, 3) as two triangles; the diagonal passes through pixel centres.
  const RasterVertex a = vertex(2, 3, 1), b = vertex(12, 3, 1), c = vertex(12, 13, 1), d = vertex(2, 13, 1);
  RasterTarget first(16, 16), second(16, 16);
  drawTriangle(first, a, b, c);
  drawTriangle(second, a, c, d);  // the other winding's order: no culling
  int both = 0, either = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 16 + x;
      both += first.covered[i] && second.covered[i];
      either += first.covered[i] || second.covered[i];
      const bool inside = x >= 2 && x < 12 && y >= 3 && y < 13;
      EXPECT_EQ(first.covered[i] || second.covered[i], inside) << x << "," << y;
    }
  }
  EXPECT_EQ(both, 0);
  EXPECT_EQ(either, 100);
}

TEST(MeshRaster, NearestWinsAndColoursInterpolateLinearly) {
  RasterTarget t(20, 20);
  // A far red triangle, then a nearer one with a colour per vertex over part of it.
  drawTriangle(t, vertex(0, 0, 5, {1, 0, 0}), vertex(20, 0, 5, {1, 0, 0}), vertex(0, 20, 5, {1, 0, 0}));
  const RasterVertex p{0, 0, 2, {0, 0, 0}}, q{16, 0, 2, {16, 0, 0}}, r{0, 16, 2, {0, 16, 0}};
  drawTriangle(t, p, q, r);
  // At pixel (3, 5), centre (3.5, 5.5): barycentric weights of q and r are x/16 and y/16, so
  // the colour is (x, y, 0) exactly.
  const Rgb c = t.colour[5 * 20 + 3];
  EXPECT_NEAR(c.r, 3.5f, 1e-5f);
  EXPECT_NEAR(c.g, 5.5f, 1e-5f);
  EXPECT_NEAR(t.depth[5 * 20 + 3], 2.0f, 1e-5f);
  // Drawing the far one again changes nothing where the near one is.
  drawTriangle(t, vertex(0, 0, 5, {1, 0, 0}), vertex(20, 0, 5, {1, 0, 0}), vertex(0, 20, 5, {1, 0, 0}));
  EXPECT_NEAR(t.colour[5 * 20 + 3].r, 3.5f, 1e-5f);
  // Outside the near triangle, the far one shows.
  EXPECT_EQ(t.colour[2 * 20 + 15].r, 1.0f);
}

TEST(MeshRaster, BadTrianglesDrawNothing) {
  RasterTarget t(8, 8);
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  drawTriangle(t, vertex(0, 0, 1), vertex(8, 0, 1), vertex(4, 4, 1, {nan, 0, 0}));
  drawTriangle(t, vertex(0, 0, 1), vertex(inf, 0, 1), vertex(4, 4, 1));
  drawTriangle(t, vertex(0, 0, -1), vertex(8, 0, 1), vertex(0, 8, 1));  // behind the eye
  drawTriangle(t, vertex(0, 0, 1), vertex(4, 4, 1), vertex(8, 8, 1));   // no area
  drawTriangle(t, vertex(-1e9f, -1e9f, 1), vertex(-1e9f + 1, -1e9f, 1), vertex(-1e9f, -1e9f + 1, 1));  // off target
  drawTriangle(t, vertex(1e30f, 1e30f, 1), vertex(3e30f, 1e30f, 1), vertex(1e30f, 3e30f, 1));  // beyond int's range
  EXPECT_EQ(coveredCount(t), 0);
}

// A test asset of separate triangles, each with its own transfer, at order 3. The
// unshadowed pass is all zero, so a thumbnail drawn from it would be black: the
// interreflected pass (RGB) is the one the thumbnail must show.
struct Tri {
  Vec3 p[3];
  float scale[3];  // transfer of each vertex: scale x a fixed direction-dependent vector
};

BakedAsset triangleAsset(const std::vector<Tri>& tris) {
  BakedAsset a;
  a.shOrder = 3;
  a.name = "triangles";
  a.samples = 1;
  a.sampling = "hammersley";
  TransferPass unshadowed, inter;
  unshadowed.kind = TransferKind::kUnshadowed;
  unshadowed.channels = 1;
  inter.kind = TransferKind::kInterreflected;
  inter.channels = 3;
  inter.bounces = 1;
  for (const Tri& t : tris) {
    for (int k = 0; k < 3; ++k) {
      a.indices.push_back(static_cast<std::uint32_t>(a.positions.size()));
      a.positions.push_back(t.p[k]);
      a.normals.push_back({0, 1, 0});
      a.albedo.push_back({0.8f, 0.8f, 0.8f});
      for (int i = 0; i < 9; ++i) unshadowed.coeffs.push_back(0.0f);
      for (int c = 0; c < 3; ++c) {
        // A clamped-cosine-like lobe in bands 0 and 1 about the basis's polar axis, tinted
        // per channel so the channels differ; its exact shape does not matter here.
        const float tint = 0.8f - 0.15f * c;
        const float v[9] = {0.886f * 0.2821f * tint, 0.0f, 1.023f * 0.4886f * tint, 0.0f, 0, 0, 0, 0, 0};
        for (int i = 0; i < 9; ++i) inter.coeffs.push_back(v[i] * t.scale[k]);
      }
    }
  }
  a.passes = {unshadowed, inter};
  return a;
}

std::vector<std::uint8_t> encoded(const BakedAsset& a) {
  std::vector<std::uint8_t> bytes;
  const Status s = encodeAsset(a, &bytes);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return bytes;
}

// Exit radiance of every vertex of `a`'s interreflected pass under the default light.
std::vector<float> expectedRadiance(const BakedAsset& a) {
  const std::vector<Rgb> light = thumbnailLighting(a.shOrder);
  std::vector<float> out(a.positions.size() * 3);
  EXPECT_TRUE(exitRadiance(a.passes[1].coeffs, 3, 9, {}, light, out).isOk());
  return out;
}

TEST(Thumbnail, PixelsAreLitWhereTheDiffuseTransferSaysSo) {
  // Four triangles on the ground plane, apart from each other: bright, dark (transfer 0),
  // dim, and one whose vertices differ (a gradient).
  const std::vector<Tri> tris = {
      {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {1.0f, 1.0f, 1.0f}},
      {{{1.5f, 0, 0}, {2.5f, 0, 0}, {1.5f, 0, 1}}, {0.0f, 0.0f, 0.0f}},
      {{{0, 0, 1.5f}, {1, 0, 1.5f}, {0, 0, 2.5f}}, {0.3f, 0.3f, 0.3f}},
      {{{1.5f, 0, 1.5f}, {2.5f, 0, 1.5f}, {1.5f, 0, 2.5f}}, {0.1f, 1.5f, 0.6f}},
  };
  const BakedAsset asset = triangleAsset(tris);
  const std::vector<std::uint8_t> bytes = encoded(asset);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(bytes, &summary).isOk());
  EXPECT_EQ(thumbnailPass(summary), 1);  // interreflected before unshadowed
  ThumbnailImage img;
  const Status s = renderThumbnail(bytes, summary, &img);
  ASSERT_TRUE(s.isOk()) << s.toString();
  ASSERT_EQ(img.width, kThumbnailWidth);
  ASSERT_EQ(img.height, kThumbnailHeight);
  ASSERT_EQ(img.rgba.size(), static_cast<std::size_t>(kThumbnailWidth) * kThumbnailHeight * 4);

  const std::vector<float> radiance = expectedRadiance(asset);
  const int ss = kThumbnailSupersample;
  const ThumbnailCamera cam = frameThumbnail(asset.positions, kThumbnailWidth * ss, kThumbnailHeight * ss);
  const auto pixel = [&](int x, int y) { return &img.rgba[(static_cast<std::size_t>(y) * img.width + x) * 4]; };
  for (std::size_t t = 0; t < tris.size(); ++t) {
    RasterVertex v[3];
    for (int k = 0; k < 3; ++k) v[k] = cam.project(asset.positions[t * 3 + k]);
    // The thumbnail pixel holding the centroid (far from every edge: all its samples hit).
    const double cx = (v[0].x + v[1].x + v[2].x) / 3.0, cy = (v[0].y + v[1].y + v[2].y) / 3.0;
    const int px = static_cast<int>(cx / ss), py = static_cast<int>(cy / ss);
    // The mean of a linear function over the pixel's symmetric samples is its value at the
    // pixel's centre: the barycentric blend of the vertices' radiance there.
    const double sx = (px + 0.5) * ss, sy = (py + 0.5) * ss;
    const auto area = [](double ax, double ay, double bx, double by, double qx, double qy) {
      return (bx - ax) * (qy - ay) - (by - ay) * (qx - ax);
    };
    const double whole = area(v[0].x, v[0].y, v[1].x, v[1].y, v[2].x, v[2].y);
    const double w[3] = {area(v[1].x, v[1].y, v[2].x, v[2].y, sx, sy) / whole, area(v[2].x, v[2].y, v[0].x, v[0].y, sx, sy) / whole,
                         area(v[0].x, v[0].y, v[1].x, v[1].y, sx, sy) / whole};
    for (double wk : w) ASSERT_GT(wk, 0.1) << "triangle " << t << " is too small in the thumbnail to test";
    const std::uint8_t* p = pixel(px, py);
    EXPECT_EQ(p[3], 255) << "triangle " << t;
    for (int c = 0; c < 3; ++c) {
      double expected = 0;
      for (int k = 0; k < 3; ++k) expected += w[k] * radiance[(t * 3 + k) * 3 + c];
      EXPECT_NEAR(p[c], toneMap8(static_cast<float>(expected)), 1) << "triangle " << t << " channel " << c << " radiance " << expected;
    }
    if (t == 1) {
      EXPECT_EQ(p[0] + p[1] + p[2], 0);  // no transfer: black, but covered
    }
    if (t == 0) {
      EXPECT_GT(p[1], 150);  // lit: the light is not too dim to see
    }
  }
  // The corners show no geometry: transparent.
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{kThumbnailWidth - 1, 0}, std::pair{0, kThumbnailHeight - 1}}) {
    EXPECT_EQ(pixel(x, y)[3], 0) << x << "," << y;
  }
  // Framed: the geometry reaches within the margin of two opposite sides and no closer.
  int minX = img.width, maxX = -1, minY = img.height, maxY = -1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (pixel(x, y)[3] > 0) minX = std::min(minX, x), maxX = std::max(maxX, x), minY = std::min(minY, y), maxY = std::max(maxY, y);
  const int marginX = static_cast<int>(kThumbnailMargin * kThumbnailWidth), marginY = static_cast<int>(kThumbnailMargin * kThumbnailHeight);
  EXPECT_GE(minX, marginX - 1);
  EXPECT_GE(minY, marginY - 1);
  EXPECT_LE(maxX, kThumbnailWidth - marginX);
  EXPECT_LE(maxY, kThumbnailHeight - marginY);
  EXPECT_TRUE(minX <= marginX + 1 || minY <= marginY + 1) << "not framed tightly: " << minX << "," << minY;
}

TEST(Thumbnail, ToneMapIsThePagesAcesAndSrgb) {
  EXPECT_EQ(toneMap8(0.0f), 0);
  EXPECT_EQ(toneMap8(-3.0f), 0);
  EXPECT_EQ(toneMap8(std::nanf("")), 0);
  EXPECT_EQ(toneMap8(std::numeric_limits<float>::infinity()), 255);
  // ACES fit at 0.18: 0.18 (2.51 0.18 + 0.03) / (0.18 (2.43 0.18 + 0.59) + 0.14) = 0.2669...;
  // sRGB 0.5533..., x 255 = 141.1.
  EXPECT_EQ(toneMap8(0.18f), 141);
  EXPECT_EQ(toneMap8(100.0f), 255);
}

TEST(Thumbnail, DamagedBytesGiveAnErrorNotACrash) {
  const BakedAsset asset = triangleAsset({{{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {1, 1, 1}}});
  std::vector<std::uint8_t> bytes = encoded(asset);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(bytes, &summary).isOk());
  ThumbnailImage img;
  // The summary of the good file with bytes that no longer match it: cut short, and flipped.
  const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
  EXPECT_FALSE(renderThumbnail(cut, summary, &img).isOk());
  EXPECT_FALSE(renderThumbnail({}, summary, &img).isOk());
  for (std::size_t i = 64; i < bytes.size(); i += 97) {
    std::vector<std::uint8_t> flipped = bytes;
    flipped[i] ^= 0x5a;
    (void)renderThumbnail(flipped, summary, &img);  // any outcome but a crash (ASan watches)
  }
  // No vertex vector pass to draw from (only a matrix pass listed): an error.
  AssetSummary matrixOnly = summary;
  for (AssetPassInfo& p : matrixOnly.passes) p.form = TransferForm::kMatrix;
  EXPECT_EQ(thumbnailPass(matrixOnly), -1);
  const Status s = renderThumbnail(bytes, matrixOnly, &img);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.toString();
}

TEST(Thumbnail, PngDecodesToTheRenderedPixels) {
  const BakedAsset asset = triangleAsset({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 1}}, {1, 0.2f, 0.6f}}});
  const std::vector<std::uint8_t> bytes = encoded(asset);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(bytes, &summary).isOk());
  std::string png;
  ASSERT_TRUE(makeThumbnailPng(bytes, summary, &png).isOk());
  int w = 0, h = 0, n = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> decoded(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), static_cast<int>(png.size()), &w, &h, &n, 4), stbi_image_free);
  ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
  EXPECT_EQ(w, kThumbnailWidth);
  EXPECT_EQ(h, kThumbnailHeight);
  EXPECT_EQ(n, 4);
  ThumbnailImage img;
  ASSERT_TRUE(renderThumbnail(bytes, summary, &img).isOk());
  EXPECT_TRUE(std::equal(img.rgba.begin(), img.rgba.end(), decoded.get()));
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < img.rgba.size(); i += 4) colours.insert(img.rgba[i] | img.rgba[i + 1] << 8 | img.rgba[i + 2] << 16 | std::uint32_t{img.rgba[i + 3]} << 24);
  EXPECT_GT(colours.size(), 20u) << "a gradient triangle over a transparent background";
}

TEST(Thumbnail, OnePerContentHash) {
  const BakedAsset asset = triangleAsset({{{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {1, 1, 1}}});
  const std::vector<std::uint8_t> bytes = encoded(asset);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(bytes, &summary).isOk());
  ThumbnailPool pool({});
  const auto first = pool.thumbnailFor("0123456789abcdef", bytes, summary, "a.prt");
  ASSERT_TRUE(first && first->resource);
  EXPECT_TRUE(first->url.starts_with(kThumbnailPrefix) && first->url.ends_with(".png")) << first->url;
  EXPECT_EQ(first->resource->contentType, "image/png");
  EXPECT_EQ(first->resource->cacheControl, "public, max-age=31536000, immutable");
  // The same hash again is not drawn again: no bytes, the same thumbnail.
  EXPECT_EQ(pool.thumbnailFor("0123456789abcdef", {}, summary, "b.prt"), first);
  // A later refresh starting from what this one made reuses it too.
  ThumbnailPool next({{"0123456789abcdef", first}});
  EXPECT_EQ(next.thumbnailFor("0123456789abcdef", {}, summary, "a.prt"), first);
  // Bytes that cannot be drawn: a record without URL (logged), remembered like a success.
  const auto failed = pool.thumbnailFor("fedcba9876543210", {}, summary, "c.prt");
  ASSERT_TRUE(failed);
  EXPECT_TRUE(failed->url.empty());
  EXPECT_EQ(failed->resource, nullptr);
  EXPECT_EQ(pool.thumbnailFor("fedcba9876543210", bytes, summary, "c.prt"), failed);
}

}  // namespace
}  // namespace prt::serve::test
