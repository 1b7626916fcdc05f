// 8-bit basis entries of matrix CPCA (docs/transfer-codec.md "8-bit basis entries", version
// 1.2): the verified error meets the target (plain and row-weighted, measured here), the
// stored levels and scales as the page lays them out (read here byte by byte), the band
// prefix rule, blobs built by hand from the page in both the 1.1 (binary16) and the 1.2
// layout, every truncation and byte flip rejected, crafted errors named, and the settings
// (which vector CPCA reads as its binary16 form).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "prt/checksum.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"
#include "matrix_codec_test_util.h"

namespace prt {
namespace {

using namespace codec_test;

// Clusters of a mean plus `rank` random directions with small noise (CPCA's own model); the
// entries fall off with the row's band, as smooth transfer's do, so shells differ in scale.
std::vector<float> lowRankMatrices(std::size_t V, int order, MatrixPacking packing, int channels, int clusters, int rank,
                                   double noise, std::uint64_t seed) {
  Lcg g{seed};
  const std::size_t E = matrixEntryCount(order, packing), D = static_cast<std::size_t>(channels) * E;
  const std::size_t n2 = static_cast<std::size_t>(order * order);
  std::vector<double> falloff(E, 1.0);
  for (std::size_t i = 0; i < n2; ++i)
    for (std::size_t j = 0; j < n2; ++j) {
      if (packing == MatrixPacking::kSymmetric && j > i) continue;
      falloff[matrixEntryIndex(i, j, packing)] = 1.0 / (1.0 + std::sqrt(static_cast<double>(i)));
    }
  std::vector<std::vector<double>> means(static_cast<std::size_t>(clusters), std::vector<double>(D));
  std::vector<std::vector<double>> dirs(static_cast<std::size_t>(clusters * rank), std::vector<double>(D));
  for (auto& m : means)
    for (std::size_t d = 0; d < D; ++d) m[d] = g.gauss() * falloff[d % E];
  for (auto& dir : dirs)
    for (std::size_t d = 0; d < D; ++d) dir[d] = g.gauss() * falloff[d % E] / std::sqrt(static_cast<double>(D));
  std::vector<float> x(V * D);
  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t k = v % static_cast<std::size_t>(clusters);
    std::vector<double> w(static_cast<std::size_t>(rank));
    for (double& c : w) c = 2.0 * g.gauss();
    for (std::size_t d = 0; d < D; ++d) {
      double val = means[k][d] + noise * g.gauss();
      for (int r = 0; r < rank; ++r) val += w[static_cast<std::size_t>(r)] * dirs[k * static_cast<std::size_t>(rank) + static_cast<std::size_t>(r)][d];
      x[v * D + d] = static_cast<float>(val);
    }
  }
  return x;
}

// Relative RMS error of y against x, each entry's squared error weighted by w2[entry % E]
// (all ones: the plain metric).
double weightedError(const std::vector<float>& x, const std::vector<float>& y, const std::vector<double>& w2) {
  double num = 0.0, den = 0.0;
  for (std::size_t t = 0; t < x.size(); ++t) {
    const double d = static_cast<double>(y[t]) - x[t];
    num += w2[t % w2.size()] * d * d;
    den += w2[t % w2.size()] * static_cast<double>(x[t]) * x[t];
  }
  return std::sqrt(num / den);
}

TransferCodecSettings setting(const char* name, int maxClusters = 8) {
  TransferCodecSettings s;
  EXPECT_TRUE(parseTransferSetting(name, {}, &s).isOk()) << name;
  s.cpcaMaxClusters = maxClusters;
  return s;
}

std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const Bytes& b, std::size_t at) { return rd32(b, at) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32; }
float rdF32(const Bytes& b, std::size_t at) {
  const std::uint32_t u = rd32(b, at);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}
void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void wrF32(Bytes& b, std::size_t at, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  wr32(b, at, u);
}
void put16(Bytes& b, std::uint32_t v) {
  for (int i = 0; i < 2; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put32(Bytes& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put64(Bytes& b, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void putF32(Bytes& b, float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  put32(b, u);
}

// Recomputes part, table and header checksums (docs/transfer-codec.md "Container"), so that
// a deliberate edit reaches the content checks.
void reseal(Bytes& b) {
  const std::uint64_t parts = rd32(b, 20), tableEnd = 48 + 24 * parts;
  for (std::uint64_t i = 0; i < parts; ++i) {
    const std::size_t e = 48 + 24 * static_cast<std::size_t>(i);
    const std::uint64_t off = rd64(b, e + 8), size = rd64(b, e + 16);
    wr32(b, e + 4, crc32c({b.data() + off, static_cast<std::size_t>(size)}));
  }
  wr32(b, 32, crc32c({b.data() + 48, static_cast<std::size_t>(tableEnd) - 48}));
  wr32(b, 44, crc32c({b.data(), 44}));
}

// Reads shell `band` of an 8-bit-basis blob as the page lays it out (means, K * N' scales,
// K * N' * C * S int8 levels) and checks it against the unexpanded decode: every basis entry
// is float(level) * scale, every level within +-127, and each nonzero scale is tight (some
// level of its cluster, basis matrix and shell reaches 127; a zero scale has only zeros).
void expectShellAsDocumented(const Bytes& blob, const TransferBlobInfo& info, const CpcaMatrixTransfer& cpca, int band) {
  const std::size_t K = info.clusterCount, N = static_cast<std::size_t>(info.vectors), C = static_cast<std::size_t>(info.channels);
  const std::size_t first = matrixEntryCount(band, info.packing), S = matrixEntryCount(band + 1, info.packing) - first;
  const std::size_t Eb = matrixEntryCount(cpca.bands, info.packing);
  const TransferPartInfo& part = info.parts[static_cast<std::size_t>(band) + 2];
  ASSERT_EQ(part.size, K * C * S * (4 + N) + 4 * K * N) << "shell " << band;
  const std::size_t scales = static_cast<std::size_t>(part.offset) + 4 * K * C * S, levels = scales + 4 * K * N;
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t j = 0; j < N; ++j) {
      const float scale = rdF32(blob, scales + 4 * (k * N + j));
      ASSERT_TRUE(std::isfinite(scale) && scale >= 0.0f);
      int largest = 0;
      for (std::size_t c = 0; c < C; ++c)
        for (std::size_t e = 0; e < S; ++e) {
          const int q = static_cast<std::int8_t>(blob[levels + ((k * N + j) * C + c) * S + e]);
          ASSERT_GE(q, -127);
          largest = std::max(largest, std::abs(q));
          const float decoded = cpca.matrices[((k * (N + 1) + j + 1) * C + c) * Eb + first + e];
          ASSERT_EQ(decoded, static_cast<float>(q) * scale) << "cluster " << k << " basis " << j << " shell " << band;
        }
      EXPECT_EQ(largest, scale > 0.0f ? 127 : 0) << "cluster " << k << " basis " << j << " shell " << band;
    }
}

TEST(TransferCodecMatrixBasis8, MeetsTheTargetWithLevelsAndScalesAsDocumented) {
  for (MatrixPacking packing : kPackings) {
    const int order = 3, channels = 3;
    const std::vector<float> x = lowRankMatrices(600, order, packing, channels, 4, 4, 0.003, 7);
    for (const char* name : {"cpca8b8@0.05", "cpca16b8@0.02", "cpca16b8@0.01"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      const TransferCodecSettings s = setting(name, 16);
      TransferEncodeReport report;
      const Bytes blob = encodeOrDie(x, order, packing, channels, s, &report);
      const std::vector<float> y = decodeOrDie(blob, order);
      const double e = weightedError(x, y, {1.0});
      EXPECT_LE(e, s.cpcaTargetError);
      EXPECT_NEAR(report.relativeError, e, 1e-9);
      EXPECT_EQ(report.bytes, blob.size());
      TransferBlobInfo info;
      ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
      EXPECT_EQ(info.versionMinor, 2);
      EXPECT_EQ(info.basisBits, 8);
      EXPECT_EQ(blob[40], 8);
      ASSERT_GT(info.vectors, 0);
      CpcaMatrixTransfer cpca;
      ASSERT_TRUE(decodeCpcaMatrixTransfer(blob, order, &cpca).isOk());
      EXPECT_EQ(cpca.basisBits, 8);
      for (int b = 0; b < order; ++b) expectShellAsDocumented(blob, info, cpca, b);
      // Half the basis bytes: smaller than the binary16 blob at the same target.
      TransferCodecSettings s16 = s;
      s16.cpcaBasisBits = 16;
      const Bytes b16 = encodeOrDie(x, order, packing, channels, s16);
      EXPECT_LT(blob.size(), b16.size());
      TransferBlobInfo info16;
      ASSERT_TRUE(readTransferBlobInfo(b16, &info16).isOk());
      EXPECT_EQ(info16.versionMinor, 1);  // a binary16 blob stays 1.1, byte 40 zero
      EXPECT_EQ(info16.basisBits, 16);
      EXPECT_EQ(b16[40], 0);
    }
  }
}

TEST(TransferCodecMatrixBasis8, RowWeightedEncodeMeetsTheWeightedTarget) {
  const int order = 3, channels = 3;
  const MatrixPacking packing = MatrixPacking::kFull;
  const std::vector<float> x = lowRankMatrices(800, order, packing, channels, 4, 5, 0.004, 13);
  TransferCodecSettings s = setting("cpca16b8@0.03", 16);
  s.cpcaMatrixRowWeights = {1.0, 0.8, 0.8, 0.8, 0.4, 0.4, 0.4, 0.4, 0.4};
  const std::size_t E = matrixEntryCount(order, packing);
  std::vector<double> w2(E);
  for (std::size_t i = 0; i < 9; ++i)
    for (std::size_t j = 0; j < 9; ++j) w2[matrixEntryIndex(i, j, packing)] = s.cpcaMatrixRowWeights[i] * s.cpcaMatrixRowWeights[i];
  TransferEncodeReport report;
  const Bytes blob = encodeOrDie(x, order, packing, channels, s, &report);
  const double e = weightedError(x, decodeOrDie(blob, order), w2);
  EXPECT_LE(e, s.cpcaTargetError);
  EXPECT_NEAR(report.relativeError, e, 1e-6);
}

TEST(TransferCodecMatrixBasis8, BandPrefixDecodesExactlyTheLeadingBlocks) {
  for (MatrixPacking packing : kPackings) {
    const int order = 4, channels = 3;
    const std::vector<float> x = lowRankMatrices(90, order, packing, channels, 3, 4, 0.01, 21);
    for (const char* name : {"cpca16b8@0.05", "cpca8b8@0.1"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      const Bytes blob = encodeOrDie(x, order, packing, channels, setting(name));
      const std::vector<float> full = decodeOrDie(blob, order);
      TransferBlobInfo info;
      ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
      const std::size_t E = matrixEntryCount(order, packing), rows = full.size() / E;
      for (int b = 1; b <= order; ++b) {
        const std::size_t Eb = matrixEntryCount(b, packing);
        std::vector<float> expect(rows * Eb);
        for (std::size_t r = 0; r < rows; ++r) std::copy_n(&full[r * E], Eb, &expect[r * Eb]);
        const TransferPartInfo& last = info.parts[static_cast<std::size_t>(b) + 1];
        const Bytes prefix(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(last.offset + last.size));
        EXPECT_EQ(decodeOrDie(blob, b), expect) << "bands " << b;
        EXPECT_EQ(decodeOrDie(prefix, b), expect) << "prefix, bands " << b;
        CpcaMatrixTransfer cpca;
        ASSERT_TRUE(decodeCpcaMatrixTransfer(prefix, 0, &cpca).isOk());
        EXPECT_EQ(cpca.bands, b);
        std::vector<float> expanded(expect.size());
        ASSERT_TRUE(cpcaMatrixReconstruct(cpca, expanded).isOk());
        EXPECT_EQ(expanded, expect) << "unexpanded prefix, bands " << b;
      }
    }
  }
}

// Blobs written by hand from docs/transfer-codec.md: order 1, full packing, 1 channel, 2
// vertices, 1 cluster, 1 basis matrix, 8-bit weights (levels 2 and -3, step 0.5), mean 1.25,
// basis entry 0.5: as 1.1 (binary16 0x3800) and as 1.2 (scale 0.25, level 2). Both decode
// to 1.25 + 2 * 0.5 * 0.5 = 1.75 and 1.25 - 3 * 0.5 * 0.5 = 0.5. The 1.1 blob is what this
// codec wrote before 1.2 existed: older blobs keep decoding.
Bytes handBuiltBlob(bool basis8) {
  Bytes clusters = {0, 0, 0};  // stream group: filter 0, zig-zag ids 0, 0
  Bytes weights;
  putF32(weights, 0.5f);
  weights.insert(weights.end(), {0, 4, 5});  // filter 0, zig-zag(2) = 4, zig-zag(-3) = 5
  Bytes shell;
  putF32(shell, 1.25f);
  if (basis8) {
    putF32(shell, 0.25f);
    shell.push_back(2);
  } else {
    put16(shell, 0x3800);
  }
  const std::vector<std::pair<std::uint16_t, const Bytes*>> parts = {{1, &clusters}, {3, &weights}, {2, &shell}};
  const std::uint64_t tableEnd = 48 + 24 * parts.size();
  const std::uint64_t total = tableEnd + clusters.size() + weights.size() + shell.size();
  Bytes b = {'P', 'R', 'T', 'T'};
  put16(b, 1);
  put16(b, basis8 ? 2 : 1);
  b.insert(b.end(), {5, 8, 1, 1});  // cpca, 8-bit weights, order 1, 1 channel
  put32(b, 2);                      // vertices
  put32(b, 1);                      // clusters
  put32(b, 3);                      // parts
  put64(b, total);
  put32(b, 0);                      // table CRC (reseal)
  b.insert(b.end(), {1, 2});        // matrix layout, full packing
  put16(b, 1);                      // N'
  b.insert(b.end(), {static_cast<std::uint8_t>(basis8 ? 8 : 0), 0, 0, 0});
  put32(b, 0);                      // header CRC (reseal)
  std::uint64_t offset = tableEnd;
  for (const auto& [type, payload] : parts) {
    put16(b, type);
    put16(b, 0);
    put32(b, 0);
    put64(b, offset);
    put64(b, payload->size());
    offset += payload->size();
  }
  for (const auto& part : parts) b.insert(b.end(), part.second->begin(), part.second->end());
  reseal(b);
  return b;
}

TEST(TransferCodecMatrixBasis8, HandBuiltBlobsOfBothVersionsDecode) {
  for (bool basis8 : {false, true}) {
    SCOPED_TRACE(basis8 ? "1.2, 8-bit basis" : "1.1, binary16 basis");
    const Bytes blob = handBuiltBlob(basis8);
    TransferBlobInfo info;
    ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
    EXPECT_EQ(info.basisBits, basis8 ? 8 : 16);
    EXPECT_EQ(decodeOrDie(blob, 1), (std::vector<float>{1.75f, 0.5f}));
    CpcaMatrixTransfer cpca;
    ASSERT_TRUE(decodeCpcaMatrixTransfer(blob, 1, &cpca).isOk());
    EXPECT_EQ(cpca.basisBits, basis8 ? 8 : 16);
    EXPECT_EQ(cpca.matrices, (std::vector<float>{1.25f, 0.5f}));
  }
}

TEST(TransferCodecMatrixBasis8, EveryTruncationAndByteFlipIsRejected) {
  for (MatrixPacking packing : kPackings) {
    const int order = 2;
    const std::vector<float> x = lowRankMatrices(12, order, packing, 3, 2, 2, 0.01, 17);
    for (const char* name : {"cpca8b8@0.1", "cpca16b8@0.02"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      const Bytes blob = encodeOrDie(x, order, packing, 3, setting(name, 4));
      std::vector<float> out;
      CpcaMatrixTransfer cm;
      for (std::size_t n = 0; n < blob.size(); ++n) {
        const Bytes cut(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(n));
        ASSERT_FALSE(decodeTransferMatrix(cut, order, &out).isOk()) << "prefix " << n;
        ASSERT_FALSE(decodeCpcaMatrixTransfer(cut, order, &cm).isOk()) << "prefix " << n;
      }
      for (std::size_t i = 0; i < blob.size(); ++i) {
        Bytes bad = blob;
        bad[i] ^= 0x5a;
        ASSERT_FALSE(decodeTransferMatrix(bad, order, &out).isOk()) << "byte " << i;
        ASSERT_FALSE(decodeCpcaMatrixTransfer(bad, order, &cm).isOk()) << "byte " << i;
      }
    }
  }
}

// Edits with resealed checksums reach the content checks, which name the problem.
TEST(TransferCodecMatrixBasis8, CraftedHeaderAndContentErrorsAreNamed) {
  const int order = 2;
  const std::vector<float> x = lowRankMatrices(40, order, MatrixPacking::kFull, 1, 2, 2, 0.01, 5);
  const Bytes blob = encodeOrDie(x, order, MatrixPacking::kFull, 1, setting("cpca16b8@0.05", 2));
  auto expectCorrupt = [&](Bytes b, const std::string& needle) {
    reseal(b);
    std::vector<float> out;
    const Status st = decodeTransferMatrix(b, order, &out);
    EXPECT_EQ(st.code(), StatusCode::kCorrupt) << needle << ": " << st.toString();
    EXPECT_NE(st.message().find(needle), std::string::npos) << st.message();
  };
  Bytes b = blob;
  b[6] = 1;  // a 1.1 header cannot say "8-bit basis"
  expectCorrupt(b, "basis bits 8 (expected 0, or 8 for matrix CPCA since version 1.2)");
  b = blob;
  b[40] = 16;
  expectCorrupt(b, "basis bits 16");
  b = blob;
  b[41] = 1;
  expectCorrupt(b, "reserved header byte 41");
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  ASSERT_GT(info.vectors, 0);
  const std::size_t K = info.clusterCount, N = static_cast<std::size_t>(info.vectors);
  // Shell 1 (15 entries): means, then the scales, then the levels.
  const std::size_t shell = static_cast<std::size_t>(info.parts[3].offset), S = 15;
  const std::size_t scales = shell + 4 * K * S, levels = scales + 4 * K * N;
  b = blob;
  b[levels] = 0x80;  // -128
  expectCorrupt(b, "level -128, outside +-127");
  b = blob;
  wr32(b, scales, 0x7fc00000u);  // NaN
  expectCorrupt(b, "basis scale of cluster 0, basis matrix 0 is nan");
  b = blob;
  wrF32(b, scales, -0.5f);
  expectCorrupt(b, "expected a finite step >= 0");
  b = blob;
  wrF32(b, scales, 600.0f);  // 127 levels of 600 pass 65504
  expectCorrupt(b, "reach beyond the transfer range");
  // Each value in range, their combination not: a basis entry near 65504 (scale 515, level
  // 127) times a weight of more than one (step 1, the cluster's levels as encoded) is
  // refused before anything is expanded.
  b = blob;
  const std::size_t weights = static_cast<std::size_t>(info.parts[1].offset);
  for (std::size_t k = 0; k < K; ++k) wrF32(b, weights + 4 * k, 1.0f);
  for (std::size_t k = 0; k < K; ++k)
    for (std::size_t j = 0; j < N; ++j) {
      wrF32(b, scales + 4 * (k * N + j), 515.0f);
      for (std::size_t e = 0; e < S; ++e) b[levels + (k * N + j) * S + e] = 127;
    }
  expectCorrupt(b, "can reconstruct values up to");
  CpcaMatrixTransfer cm;
  reseal(b);
  EXPECT_EQ(decodeCpcaMatrixTransfer(b, order, &cm).code(), StatusCode::kCorrupt);
}

TEST(TransferCodecMatrixBasis8, SettingsNameTheBasisWidth) {
  for (const char* name : {"cpca16b8@0.04", "cpca8b8@0.05", "cpca16@0.04", "cpca8@0.05"}) {
    const TransferCodecSettings s = setting(name);
    EXPECT_EQ(s.cpcaBasisBits, std::string(name).find("b8") != std::string::npos ? 8 : 16) << name;
    EXPECT_EQ(s.cpcaWeightBits, std::string(name).starts_with("cpca16") ? 16 : 8) << name;
    EXPECT_EQ(transferSettingName(s), name);
  }
  // The name decides the basis width, whatever the defaults said.
  TransferCodecSettings defaults, s;
  defaults.cpcaBasisBits = 8;
  ASSERT_TRUE(parseTransferSetting("cpca16@0.04", defaults, &s).isOk());
  EXPECT_EQ(s.cpcaBasisBits, 16);
  // 8-bit basis entries are matrix CPCA's: vector CPCA writes the binary16 blob of the same
  // setting without them, byte for byte (so one setting serves an asset's vector and matrix
  // passes). Other widths do not exist.
  Lcg g{31};
  std::vector<float> vec(40 * 9);
  for (float& v : vec) v = static_cast<float>(g.gauss());
  Bytes blob, blob16;
  ASSERT_TRUE(encodeTransfer(vec, 3, 1, setting("cpca16b8@0.05"), &blob).isOk());
  ASSERT_TRUE(encodeTransfer(vec, 3, 1, setting("cpca16@0.05"), &blob16).isOk());
  EXPECT_EQ(blob, blob16);
  TransferCodecSettings odd = setting("cpca16@0.05");
  odd.cpcaBasisBits = 12;
  const Status st = encodeTransferMatrix(std::vector<float>(20 * 16, 0.25f), 2, MatrixPacking::kFull, 1, odd, &blob);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("basis bits is 12"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace prt
