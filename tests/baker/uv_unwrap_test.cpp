// The atlas generator (baker/unwrap/uv_unwrap.h) with the real Blender: a box without UVs
// gets a valid atlas, byte-identical on a second run; a missing, failing or hanging "Blender"
// and a layout that cannot be valid give errors naming the problem; the scratch directory is
// gone afterwards every time. Seam splitting on its own, without Blender.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "baker/scene/uv_atlas_check.h"
#include "baker/unwrap/seam_split.h"
#include "baker/unwrap/uv_unwrap.h"

namespace prt::bake {
namespace {

namespace fs = std::filesystem;

// A unit box, 8 shared corners, 12 triangles facing out, a colour per vertex to follow.
Scene box() {
  Scene s;
  for (int i = 0; i < 8; ++i) {
    s.positions.push_back({static_cast<float>(i >> 2 & 1), static_cast<float>(i >> 1 & 1), static_cast<float>(i & 1)});
    const Vec3 d = s.positions.back() - Vec3{0.5f, 0.5f, 0.5f};
    s.normals.push_back(d * (1.0f / length(d)));
    s.albedo.push_back({0.1f * static_cast<float>(i), 0.5f, 0.5f});
  }
  s.indices = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
               2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
  s.texcoordAbsent[0] = s.texcoordAbsent[1] = "built in the test";
  s.name = "box";
  return s;
}

// Each test runs with TMPDIR set to a fresh directory of its own, so it can see that the
// generator left nothing behind.
class UvUnwrapTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* info = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    tmp_ = fs::temp_directory_path() / ("prt-uv-unwrap-test-" + std::string(info) + "-" + std::to_string(::getpid()));
    fs::remove_all(tmp_);
    fs::create_directories(tmp_);
    const char* old = std::getenv("TMPDIR");
    if (old != nullptr) oldTmp_ = old;
    hadTmp_ = old != nullptr;
    ::setenv("TMPDIR", tmp_.c_str(), 1);
  }
  void TearDown() override {
    if (hadTmp_) ::setenv("TMPDIR", oldTmp_.c_str(), 1);
    else ::unsetenv("TMPDIR");
    fs::remove_all(tmp_);
  }
  bool scratchLeft() const { return !fs::is_empty(tmp_); }
  // An executable shell script standing in for Blender (a real process, not a mock of our code).
  std::string fakeBlender(const std::string& body) const {
    const fs::path p = tmp_ / "fake-blender";
    std::ofstream(p) << "#!/bin/sh\n" << body << "\n";
    ::chmod(p.c_str(), 0755);
    return p.string();
  }

  fs::path tmp_;
  std::string oldTmp_;
  bool hadTmp_ = false;
};

TEST(SeamSplit, SplitsOnlyWhereCornerUvsDiffer) {
  const Scene s = box();
  // Every corner of triangle t at (t / 12, 0): the two triangles of a face share two vertices
  // but differ in UV, so nothing is shared: 36 vertices; then one face's two triangles agree.
  std::vector<Uv> uvs(s.indices.size());
  for (std::size_t c = 0; c < uvs.size(); ++c) uvs[c] = {static_cast<float>(c / 3) / 12.0f, 0.0f};
  Scene out;
  ASSERT_TRUE(splitSeams(s, uvs, &out).isOk());
  EXPECT_EQ(out.positions.size(), 36u);
  uvs[3] = uvs[0];  // triangle 1's first corner (vertex 0) = triangle 0's first corner
  uvs[4] = uvs[2];  // triangle 1's vertex 3 = triangle 0's vertex 3
  ASSERT_TRUE(splitSeams(s, uvs, &out).isOk());
  EXPECT_EQ(out.positions.size(), 34u);
  ASSERT_EQ(out.texcoord[1].size(), out.positions.size());
  ASSERT_EQ(out.albedo.size(), out.positions.size());
  EXPECT_TRUE(out.texcoordAbsent[1].empty());
  for (std::size_t c = 0; c < s.indices.size(); ++c) {
    const std::uint32_t was = s.indices[c], now = out.indices[c];
    EXPECT_EQ(std::memcmp(&out.positions[now], &s.positions[was], sizeof(Vec3)), 0) << c;
    EXPECT_EQ(out.albedo[now].r, s.albedo[was].r) << c;
    EXPECT_EQ(out.texcoord[1][now].u, uvs[c].u) << c;
  }
  EXPECT_FALSE(splitSeams(s, std::vector<Uv>(5), &out).isOk());
}

TEST_F(UvUnwrapTest, BoxGetsAValidDeterministicAtlas) {
  const Scene s = box();
  UvUnwrapOptions o;
  o.size = 256;
  o.padding = 2;
  Scene first, second;
  UvUnwrapReport r1, r2;
  const Status a = unwrapUvAtlas(s, o, &first, &r1);
  ASSERT_TRUE(a.isOk()) << a.message();
  EXPECT_FALSE(scratchLeft());
  ASSERT_FALSE(r1.attempts.empty());
  for (const UvUnwrapAttempt& t : r1.attempts) {
    std::printf("attempt: margin %.6g, %.2f s: %s\n", t.margin, t.seconds, t.result.c_str());
  }
  EXPECT_EQ(r1.side, 256);
  EXPECT_TRUE(r1.atlas.valid());
  EXPECT_GE(r1.atlas.charts, 1u);
  EXPECT_LE(r1.atlas.charts, 6u);  // at most one island per face of the box
  ASSERT_EQ(first.texcoord[1].size(), first.positions.size());
  EXPECT_GE(first.positions.size(), 14u);  // a box cannot be cut open with fewer
  // The result passes the check on its own, as a glTF set would.
  UvAtlasReport check;
  ASSERT_TRUE(checkUvAtlas(first.positions, first.indices, first.texcoord[1], {256, 256, 2}, "TEXCOORD_1", &check).isOk());
  EXPECT_TRUE(check.valid()) << check.summary();

  const Status b = unwrapUvAtlas(s, o, &second, &r2);
  ASSERT_TRUE(b.isOk()) << b.message();
  ASSERT_EQ(first.texcoord[1].size(), second.texcoord[1].size());
  EXPECT_EQ(std::memcmp(first.texcoord[1].data(), second.texcoord[1].data(), first.texcoord[1].size() * sizeof(Uv)), 0);
  EXPECT_EQ(first.indices, second.indices);
  EXPECT_EQ(r1.attempts.size(), r2.attempts.size());
  EXPECT_FALSE(scratchLeft());
}

TEST_F(UvUnwrapTest, TooSmallAnAtlasFailsWithTheCheck) {
  UvUnwrapOptions o;
  o.size = 6;  // 6 charts with 4 texels of gutter cannot fit 6 texels a side
  o.padding = 4;
  o.maxAttempts = 1;
  Scene out;
  UvUnwrapReport r;
  const Status s = unwrapUvAtlas(box(), o, &out, &r);
  ASSERT_FALSE(s.isOk());
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("is not valid at 6x6, padding 4"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("first: generated atlas: "), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("larger texture size"), std::string::npos) << s.message();
  EXPECT_FALSE(scratchLeft());
}

TEST_F(UvUnwrapTest, MissingBlenderSaysHowToInstallIt) {
  UvUnwrapOptions o;
  o.blender = "/nonexistent/blender";
  Scene out;
  UvUnwrapReport r;
  const Status s = unwrapUvAtlas(box(), o, &out, &r);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_NE(s.message().find("Blender not found"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("/nonexistent/blender"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("apt-get install --no-install-recommends blender"), std::string::npos) << s.message();
  EXPECT_FALSE(scratchLeft());
}

TEST_F(UvUnwrapTest, FailingBlenderIsQuoted) {
  UvUnwrapOptions o;
  o.blender = fakeBlender("echo 'Error: this is not Blender' >&2; exit 9");
  Scene out;
  UvUnwrapReport r;
  const Status s = unwrapUvAtlas(box(), o, &out, &r);
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_NE(s.message().find("exited with status 9"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("Error: this is not Blender"), std::string::npos) << s.message();
  fs::remove(o.blender);
  EXPECT_FALSE(scratchLeft());
}

TEST_F(UvUnwrapTest, HangingBlenderIsKilledAtTheLimit) {
  UvUnwrapOptions o;
  o.blender = fakeBlender("exec sleep 60");
  o.timeoutSeconds = 0.5;
  Scene out;
  UvUnwrapReport r;
  const auto t0 = std::chrono::steady_clock::now();
  const Status s = unwrapUvAtlas(box(), o, &out, &r);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 20.0);
  EXPECT_EQ(s.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(s.message().find("time limit of 0.5 s"), std::string::npos) << s.message();
  fs::remove(o.blender);
  EXPECT_FALSE(scratchLeft());
}

}  // namespace
}  // namespace prt::bake
