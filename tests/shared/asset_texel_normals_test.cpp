// Asset format 1.6's texel normals (docs/asset-format.md, type 19): the octahedral snorm16
// codec (prt/octahedral_normal.h) and its stated worst-case error, the section's round trip,
// checkAsset's and the reader's rules, the documented bytes, and every cut and byte flip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/octahedral_normal.h"
#include "prt/sampling.h"
#include "shared/asset_raw_file.h"

namespace prt {
namespace {

using namespace prt::test;  // NOLINT: the raw-file helpers

constexpr std::uint32_t kTypeTexelTransfer = 15, kTypeTexelNormals = 19;

double angleDegrees(Vec3 a, Vec3 b) {
  // atan2 of |a x b| and a.b: accurate for tiny angles, where acos of a dot near 1 is not.
  const double cx = double{a.y} * b.z - double{a.z} * b.y, cy = double{a.z} * b.x - double{a.x} * b.z,
               cz = double{a.x} * b.y - double{a.y} * b.x;
  const double d = double{a.x} * b.x + double{a.y} * b.y + double{a.z} * b.z;
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), d) * 180.0 / kPi;
}

Vec3 unit(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  return {static_cast<float>(x / l), static_cast<float>(y / l), static_cast<float>(z / l)};
}

// ---- The codec ------------------------------------------------------------------------------

TEST(OctahedralNormal, AxesAreExactAndDegenerateInputsGivePlusZ) {
  const Vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3 a : axes) {
    const auto c = encodeOctahedralNormal(a);
    const Vec3 d = decodeOctahedralNormal(c[0], c[1]);
    EXPECT_EQ(d.x, a.x) << a.x << " " << a.y << " " << a.z;
    EXPECT_EQ(d.y, a.y);
    EXPECT_EQ(d.z, a.z);
  }
  EXPECT_EQ(encodeOctahedralNormal({0, 0, 1}), (std::array<std::int16_t, 2>{0, 0}));
  EXPECT_EQ(encodeOctahedralNormal({0, 0, 0}), (std::array<std::int16_t, 2>{0, 0}));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(encodeOctahedralNormal({nan, 0, 1}), (std::array<std::int16_t, 2>{0, 0}));
  EXPECT_EQ(encodeOctahedralNormal({inf, 0, 0}), (std::array<std::int16_t, 2>{0, 0}));
  // Unnormalised input encodes its direction; -32768 reads as -32767 (GL's snorm rule).
  EXPECT_EQ(encodeOctahedralNormal({0, 3, 0}), encodeOctahedralNormal({0, 1, 0}));
  const Vec3 a = decodeOctahedralNormal(-32768, 100), b = decodeOctahedralNormal(-32767, 100);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
}

// The documented worst case holds over a dense sweep (uniform directions, and directions
// hugging the fold z = 0 and the octahedron's edges, where the map stretches most), it is
// tight (the sweep reaches at least 80 % of it), and no code is ever -32768.
TEST(OctahedralNormal, WorstCaseErrorIsTheDocumentedOne) {
  double worst = 0.0;
  auto check = [&](Vec3 n) {
    const auto c = encodeOctahedralNormal(n);
    ASSERT_NE(c[0], kOctahedralInvalidCode);
    ASSERT_NE(c[1], kOctahedralInvalidCode);
    const Vec3 d = decodeOctahedralNormal(c[0], c[1]);
    ASSERT_NEAR(length(d), 1.0f, 1e-6f);
    worst = std::max(worst, angleDegrees(n, d));
  };
  Pcg32 rng(7);
  for (int i = 0; i < 400000; ++i) check(squareToSphere(rng.nextFloat(), rng.nextFloat()));
  for (int i = 0; i < 100000; ++i) {
    const double phi = 2.0 * kPi * rng.nextFloat(), z = 1e-3 * (2.0 * rng.nextFloat() - 1.0);
    check(unit(std::cos(phi), std::sin(phi), z));                       // around the fold
    check(unit(1e-3 * (2.0 * rng.nextFloat() - 1.0), std::cos(phi), std::sin(phi)));  // around x = 0
  }
  EXPECT_LE(worst, kOctahedralMaxErrorDegrees);
  EXPECT_GE(worst, 0.8 * kOctahedralMaxErrorDegrees) << "the documented bound is loose: measured " << worst;
  std::printf("octahedral snorm16: worst angular error %.6f degrees\n", worst);
}

// ---- The section ----------------------------------------------------------------------------

// Two triangles in one 3 x 2 atlas (coverage sampled, sampled, gutter, empty, sampled,
// gutter), a float32 texel shadowed pass and, with `normals`, a normal per non-empty texel.
BakedAsset normalAsset(bool normals) {
  BakedAsset a;
  a.shOrder = 2;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
  a.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  a.albedo = {{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}};
  a.indices = {0, 2, 1, 1, 2, 3};
  a.atlasUv = {0, 0, 1, 0, 0, 1, 1, 1};
  a.atlases = {{3, 2, 0, 2}};
  a.texelCoverage = {1, 1, 2, 0, 1, 2};
  TransferPass p;
  p.kind = TransferKind::kShadowed;
  p.channels = 1;
  p.domain = TransferDomain::kTexel;
  for (int t = 0; t < 6; ++t) p.coeffs.insert(p.coeffs.end(), {0.5f, 0.0f, 0.25f * static_cast<float>(t), 0.0f});
  a.passes.push_back(p);
  a.sampling = "hammersley";
  a.name = "normals";
  if (normals) {
    const Vec3 n[6] = {unit(0, 1, 0), unit(0.3, 1, 0), unit(-0.2, 1, 0.4), {0, 0, 1}, unit(0, -1, 0.01), unit(1, 0.2, -0.3)};
    for (int t = 0; t < 6; ++t) {
      const auto c = a.texelCoverage[static_cast<std::size_t>(t)] == 0 ? std::array<std::int16_t, 2>{0, 0} : encodeOctahedralNormal(n[t]);
      a.texelNormals.insert(a.texelNormals.end(), {c[0], c[1]});
    }
  }
  return a;
}

// decodeAsset, verifyAsset and (for the atlas sections' own checks) decodeAssetAtlases agree.
void expectCorrupt(const Bytes& file, const std::string& fragment) {
  BakedAsset out;
  expectError(decodeAsset(file, &out), StatusCode::kCorrupt, fragment);
  AssetSummary summary;
  expectError(verifyAsset(file, &summary), StatusCode::kCorrupt, fragment);
  expectError(decodeAssetAtlases(file, &out), StatusCode::kCorrupt, fragment);
}

TEST(AssetTexelNormals, RoundTripAndOnlyWrittenWhenPresent) {
  const BakedAsset a = normalAsset(true);
  const Bytes file = encodeOrDie(a);
  EXPECT_EQ(rd32(file, asset_layout::kVersionMinor) & 0xffff, 7u);
  BakedAsset out;
  ASSERT_TRUE(decodeAsset(file, &out).isOk());
  EXPECT_EQ(out.texelNormals, a.texelNormals);
  BakedAsset atlases;
  ASSERT_TRUE(decodeAssetAtlases(file, &atlases).isOk());
  EXPECT_EQ(atlases.texelNormals, a.texelNormals);
  EXPECT_EQ(atlases.texelCoverage, a.texelCoverage);
  Bytes again;
  ASSERT_TRUE(encodeAsset(out, &again).isOk());
  EXPECT_EQ(again, file);
  // The section: after the coverage, type 19, bytes, no args, 4 bytes per texel.
  const RawAsset raw = split(file);
  ASSERT_EQ(raw.sections.size(), 11u);  // metadata, lighting, 4 geometry, uv, atlases, coverage, normals, pass
  const RawSection& s = raw.sections[9];
  EXPECT_EQ(s.type, kTypeTexelNormals);
  EXPECT_EQ(s.format, 3u);
  EXPECT_EQ(s.arg0 | s.arg1 | s.arg2, 0u);
  ASSERT_EQ(s.payload.size(), 24u);
  // Texel 3 is empty: (0, 0); texel 0 is +y, whose octahedral code is (0, 32767): 00 00 ff 7f.
  EXPECT_EQ(Bytes(s.payload.begin() + 12, s.payload.begin() + 16), (Bytes{0, 0, 0, 0}));
  EXPECT_EQ(Bytes(s.payload.begin(), s.payload.begin() + 4), (Bytes{0x00, 0x00, 0xff, 0x7f}));

  // Without normals: no section, and the file is the 1.5 layout.
  const Bytes plain = encodeOrDie(normalAsset(false));
  for (const RawSection& r : split(plain).sections) EXPECT_NE(r.type, kTypeTexelNormals);
  ASSERT_TRUE(decodeAsset(plain, &out).isOk());
  EXPECT_TRUE(out.texelNormals.empty());
}

TEST(AssetTexelNormals, CheckAssetRefusesBrokenNormals) {
  auto refused = [](const BakedAsset& a, StatusCode code, const std::string& fragment) {
    Bytes out;
    expectError(encodeAsset(a, &out), code, fragment);
  };
  BakedAsset a = normalAsset(true);
  a.texelNormals.pop_back();
  refused(a, StatusCode::kSizeMismatch, "11 texel normal codes for 6 texels");
  a = normalAsset(true);
  a.texelNormals[9] = kOctahedralInvalidCode;
  refused(a, StatusCode::kInvalidArgument, "texel normal 4 has the code -32768");
  a = normalAsset(true);
  a.texelNormals[7] = 1;
  refused(a, StatusCode::kInvalidArgument, "texel normal 3 is (0, 1) at an empty texel");
  // Normals need a texel pass (and with it the atlases).
  a = normalAsset(true);
  a.passes[0].domain = TransferDomain::kVertex;
  a.passes[0].coeffs.resize(4 * 4);
  a.atlases.clear();
  a.atlasUv.clear();
  a.texelCoverage.clear();
  refused(a, StatusCode::kInvalidArgument, "12 texel normal codes but no texel pass");
}

TEST(AssetTexelNormals, ReaderRefusesCraftedNormals) {
  const Bytes file = encodeOrDie(normalAsset(true));
  const RawAsset good = split(file);
  ASSERT_EQ(build(good), file) << "the test's builder lays files out as the writer does";
  RawAsset r = good;
  findSection(r, kTypeTexelNormals)->payload.resize(20);
  expectCorrupt(build(r), "section 9 (texel normals) is 20 bytes; 24 expected (4 bytes per texel, 6 texels)");
  r = good;
  findSection(r, kTypeTexelNormals)->format = 1;
  expectCorrupt(build(r), "(texel normals) has element format 1");
  r = good;
  findSection(r, kTypeTexelNormals)->arg1 = 2;
  expectCorrupt(build(r), "(texel normals) has non-zero arguments");
  r = good;
  r.sections.push_back(*findSection(r, kTypeTexelNormals));
  expectCorrupt(build(r), "(texel normals) repeats section 9");
  r = good;
  Bytes& p = findSection(r, kTypeTexelNormals)->payload;
  p[4 * 4 + 2] = 0x00;  // texel 4's y: 0x8000 = -32768
  p[4 * 4 + 3] = 0x80;
  expectCorrupt(build(r), "section 9 (texel normals): texel 4 has the code -32768");
  r = good;
  findSection(r, kTypeTexelNormals)->payload[3 * 4] = 1;  // texel 3 is empty
  expectCorrupt(build(r), "texel 3 is empty in the coverage but holds (1, 0); (0, 0) expected");
  // The texel pass turned into an unknown type beside a vertex pass: normals without a texel
  // pass (the atlas sections, checked first, are refused for the same reason).
  r = good;
  findSection(r, kTypeTexelTransfer)->type = 99;
  r.sections.push_back({5, 1, 1, 1, 0, Bytes(4 * 4 * 4, 0)});  // shadowed, 4 vertices x 4 coefficients
  expectCorrupt(build(r), "is present without a texel transfer section");
  // Without the atlas sections the normals are the first to be refused.
  r.sections.erase(r.sections.begin() + 6, r.sections.begin() + 9);  // atlas uv, atlases, coverage
  expectCorrupt(build(r), "(texel normals) is present without a texel transfer section");
  // A 1.5 reader's view: a type it does not know is skipped; this reader knows 19 and holds it
  // to its rules, while an unknown 99 is still skipped.
  r = good;
  r.sections.push_back({99, 3, 0, 0, 0, {1, 2, 3}});
  BakedAsset out;
  EXPECT_TRUE(decodeAsset(build(r), &out).isOk());
}

TEST(AssetTexelNormals, EveryPrefixAndByteFlipIsRejected) {
  const Bytes file = encodeOrDie(normalAsset(true));
  for (std::size_t cut = 0; cut < file.size(); ++cut) {
    const std::span<const std::uint8_t> prefix = std::span<const std::uint8_t>(file).first(cut);
    BakedAsset out;
    ASSERT_FALSE(decodeAsset(prefix, &out).isOk()) << "prefix " << cut;
    ASSERT_FALSE(decodeAssetAtlases(prefix, &out).isOk()) << "prefix " << cut;
  }
  for (std::size_t i = 0; i < file.size(); ++i) {
    for (std::uint8_t flip : {std::uint8_t{0x01}, std::uint8_t{0x80}}) {
      Bytes damaged = file;
      damaged[i] ^= flip;
      BakedAsset out;
      ASSERT_FALSE(decodeAsset(damaged, &out).isOk()) << "byte " << i;
      ASSERT_FALSE(verifyAsset(damaged, nullptr).isOk()) << "byte " << i;
    }
  }
}

}  // namespace
}  // namespace prt
