// Matrix transfer in the codec (prt/transfer_codec.h, docs/transfer-codec.md "Matrices"):
// round trips within each encoding's bound, the band-prefix rule (the first b bands decode
// bit for bit as the order-b leading blocks of the full decode), CPCA on low-rank and on
// visibility-like matrices against the target, the unexpanded CPCA form against the
// expanded one, the layout refusals, sizes by formula, and every truncation and byte flip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/checksum.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"
#include "matrix_codec_test_util.h"

namespace prt {
namespace {

using namespace codec_test;

TransferCodecSettings setting(const char* name) {
  TransferCodecSettings s;
  EXPECT_TRUE(parseTransferSetting(name, {}, &s).isOk()) << name;
  return s;
}

std::size_t entries(int order, MatrixPacking packing) { return matrixEntryCount(order, packing); }

// Random matrices of mixed magnitudes (so the float encodings see several exponents).
std::vector<float> randomMatrices(std::size_t V, int order, MatrixPacking packing, int channels, std::uint64_t seed) {
  Lcg g{seed};
  std::vector<float> x(V * static_cast<std::size_t>(channels) * entries(order, packing));
  for (float& v : x) v = static_cast<float>((g.next() - 0.5) * std::pow(10.0, 3.0 * g.next() - 2.0));
  return x;
}

// Clusters of a mean plus `rank` random directions with small noise: CPCA's own model.
std::vector<float> lowRankMatrices(std::size_t V, std::size_t D, int clusters, int rank, double noise, std::uint64_t seed) {
  Lcg g{seed};
  std::vector<std::vector<double>> means(static_cast<std::size_t>(clusters), std::vector<double>(D));
  std::vector<std::vector<double>> dirs(static_cast<std::size_t>(clusters * rank), std::vector<double>(D));
  for (auto& m : means)
    for (double& v : m) v = g.gauss();
  for (auto& d : dirs)
    for (double& v : d) v = g.gauss() / std::sqrt(static_cast<double>(D));
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

// Visibility-like: the unshadowed/shadowed matrix of a vertex whose visible set is the
// hemisphere about its normal minus a cap of "occluder" about a second direction, by
// quadrature over a fixed direction set: M_ij = sum_k V(w_k) y_i(w_k) y_j(w_k) 4pi/n.
std::vector<float> visibilityMatrices(std::size_t V, int order, MatrixPacking packing) {
  DirectionSet dirs;
  EXPECT_TRUE(hammersleySphere(2048, &dirs).isOk());
  const std::size_t n2 = static_cast<std::size_t>(order * order), E = entries(order, packing);
  std::vector<float> ys(dirs.size() * n2);
  for (std::size_t k = 0; k < dirs.size(); ++k) evalShBasisUnchecked(order, dirs.at(k), &ys[k * n2]);
  std::vector<float> x(V * E);
  for (std::size_t v = 0; v < V; ++v) {
    // Normals along a spiral over the sphere; the occluder leans 60 degrees off the normal.
    const double t = (static_cast<double>(v) + 0.5) / static_cast<double>(V);
    const double z = 1.0 - 2.0 * t, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.399963 * static_cast<double>(v);
    const double nx = r * std::cos(phi), ny = r * std::sin(phi), nz = z;
    const double ox = 0.5 * nx + 0.866 * (-ny), oy = 0.5 * ny + 0.866 * nx, oz = 0.5 * nz;
    std::vector<double> m(n2 * n2, 0.0);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      const double dn = dirs.x[k] * nx + dirs.y[k] * ny + dirs.z[k] * nz;
      const double dd = dirs.x[k] * ox + dirs.y[k] * oy + dirs.z[k] * oz;
      if (dn <= 0.0 || dd > 0.8) continue;
      const float* y = &ys[k * n2];
      for (std::size_t i = 0; i < n2; ++i)
        for (std::size_t j = 0; j < n2; ++j) m[i * n2 + j] += static_cast<double>(y[i]) * y[j] * dirs.weight;
    }
    for (std::size_t i = 0; i < n2; ++i)
      for (std::size_t j = 0; j < n2; ++j) {
        if (packing == MatrixPacking::kSymmetric && j > i) continue;
        x[v * E + matrixEntryIndex(i, j, packing)] = static_cast<float>(m[i * n2 + j]);
      }
  }
  return x;
}

double relError(const std::vector<float>& a, const std::vector<float>& b) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += (static_cast<double>(a[i]) - b[i]) * (static_cast<double>(a[i]) - b[i]);
    den += static_cast<double>(a[i]) * a[i];
  }
  return std::sqrt(num / den);
}

// The order-`bands` leading blocks of [vertex][channel][entry] matrices of order `order`.
std::vector<float> truncate(const std::vector<float>& x, int order, int bands, MatrixPacking packing, int channels) {
  const std::size_t E = entries(order, packing), Eb = entries(bands, packing);
  const std::size_t rows = x.size() / E;
  std::vector<float> out(rows * Eb);
  for (std::size_t r = 0; r < rows; ++r) std::copy_n(&x[r * E], Eb, &out[r * Eb]);
  (void)channels;
  return out;
}

std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const Bytes& b, std::size_t at) { return rd32(b, at) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32; }
void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Recomputes part, table and header checksums (layout: docs/transfer-codec.md), so that a
// deliberate edit reaches the content checks.
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

TEST(TransferCodecMatrix, PerEntryEncodingsRoundTripWithinTheirBounds) {
  for (MatrixPacking packing : kPackings) {
    for (int channels : {1, 3}) {
      for (int order : {1, 2, 4}) {
        const std::vector<float> x = randomMatrices(37, order, packing, channels, 11u + static_cast<unsigned>(order));
        double maxAbs = 0.0;
        for (float v : x) maxAbs = std::max(maxAbs, std::fabs(static_cast<double>(v)));
        for (const char* name : {"f32", "f16", "q16", "q8"}) {
          SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing) + " order " + std::to_string(order) + " channels " +
                       std::to_string(channels));
          TransferEncodeReport report;
          const Bytes blob = encodeOrDie(x, order, packing, channels, setting(name), &report);
          const std::vector<float> y = decodeOrDie(blob, order);
          ASSERT_EQ(y.size(), x.size());
          EXPECT_EQ(report.bytes, blob.size());
          double worst = 0.0;
          for (std::size_t i = 0; i < x.size(); ++i) {
            const double e = std::fabs(static_cast<double>(y[i]) - x[i]);
            worst = std::max(worst, e);
            const std::string n = name;
            if (n == "f32") {
              ASSERT_EQ(y[i], x[i]);
            } else if (n == "f16") {
              // Round to nearest binary16: half an ulp, 2^-11 relative (2^-25 absolute below normals).
              ASSERT_LE(e, std::fabs(static_cast<double>(x[i])) * 0x1.0p-11 + 0x1.0p-25);
            } else {
              // Half a step; the step of a stream is at most max|x| / Q (rounded up by a float ulp).
              const double Q = n == "q16" ? 32767.0 : 127.0;
              ASSERT_LE(e, maxAbs / Q * 0.5 * (1.0 + 1e-6));
            }
          }
          EXPECT_NEAR(report.maxAbsError, worst, 1e-12 + worst * 1e-9);
        }
      }
    }
  }
}

TEST(TransferCodecMatrix, BlobInfoRecordsTheLayoutAndVectorBlobsStayVersionOneZero) {
  const std::vector<float> x = randomMatrices(5, 3, MatrixPacking::kFull, 3, 3);
  const Bytes blob = encodeOrDie(x, 3, MatrixPacking::kFull, 3, setting("q8"));
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  EXPECT_TRUE(info.matrix);
  EXPECT_EQ(info.packing, MatrixPacking::kFull);
  EXPECT_EQ(info.vectors, 0);
  EXPECT_EQ(info.versionMinor, 1);
  EXPECT_EQ(info.order, 3);
  EXPECT_EQ(info.channels, 3);
  EXPECT_EQ(info.vertexCount, 5u);
  ASSERT_EQ(info.parts.size(), 3u);
  EXPECT_EQ(blob[36], 1);  // layout: matrix
  EXPECT_EQ(blob[37], 2);  // packing: full

  // A vector blob is still written as 1.0 with bytes 36..43 zero: old readers read it.
  std::vector<float> vec(4 * 9, 0.25f);
  Bytes vblob;
  ASSERT_TRUE(encodeTransfer(vec, 3, 1, setting("f16"), &vblob).isOk());
  EXPECT_EQ(vblob[6], 0);
  EXPECT_EQ(vblob[7], 0);
  for (std::size_t i = 36; i < 44; ++i) EXPECT_EQ(vblob[i], 0) << i;
  TransferBlobInfo vinfo;
  ASSERT_TRUE(readTransferBlobInfo(vblob, &vinfo).isOk());
  EXPECT_FALSE(vinfo.matrix);

  // Each decoder refuses the other layout with kInvalidArgument.
  std::vector<float> out;
  EXPECT_EQ(decodeTransfer(blob, 3, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decodeTransferMatrix(vblob, 3, &out).code(), StatusCode::kInvalidArgument);
  CpcaMatrixTransfer cm;
  EXPECT_EQ(decodeCpcaMatrixTransfer(blob, 3, &cm).code(), StatusCode::kInvalidArgument);
  // And the CPCA forms: a matrix CPCA blob is not vector CPCA, nor the other way round.
  TransferCodecSettings cpca = setting("cpca16@0.05");
  cpca.cpcaMaxClusters = 2;
  const Bytes mcpca = encodeOrDie(x, 3, MatrixPacking::kFull, 3, cpca);
  CpcaTransfer vc;
  EXPECT_EQ(decodeCpcaTransfer(mcpca, 3, &vc).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decodeTransfer(mcpca, 3, &out).code(), StatusCode::kInvalidArgument);
  Bytes vcpca;
  ASSERT_TRUE(encodeTransfer(vec, 3, 1, cpca, &vcpca).isOk());
  EXPECT_EQ(decodeCpcaMatrixTransfer(vcpca, 3, &cm).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decodeTransferMatrix(vcpca, 3, &out).code(), StatusCode::kInvalidArgument);
}

TEST(TransferCodecMatrix, SizesFollowTheDocumentedFormula) {
  // Per shell: streams = channels * shell entries; f32/f16 write a filter byte and V values
  // per stream, q16/q8 a 4-byte step too. Plus the 48-byte header and 24 bytes per part.
  const std::size_t V = 13;
  for (MatrixPacking packing : kPackings) {
    for (int channels : {1, 3}) {
      const int order = 3;
      const std::vector<float> x = randomMatrices(V, order, packing, channels, 5);
      for (auto [name, width, stepBytes] : {std::tuple{"f32", 4, 0}, std::tuple{"f16", 2, 0}, std::tuple{"q16", 2, 4}, std::tuple{"q8", 1, 4}}) {
        std::size_t want = 48 + 24 * static_cast<std::size_t>(order);
        for (int b = 0; b < order; ++b) {
          const std::size_t streams = static_cast<std::size_t>(channels) * (entries(b + 1, packing) - entries(b, packing));
          want += streams * (1 + V * static_cast<std::size_t>(width) + static_cast<std::size_t>(stepBytes));
        }
        EXPECT_EQ(encodeOrDie(x, order, packing, channels, setting(name)).size(), want) << name;
      }
    }
  }
}

TEST(TransferCodecMatrix, BandPrefixDecodesExactlyTheLeadingBlocks) {
  for (MatrixPacking packing : kPackings) {
    const int order = 4, channels = 3;
    const std::vector<float> x = lowRankMatrices(90, channels * entries(order, packing), 3, 4, 0.01, 21);
    for (const char* name : {"f32", "f16", "q8", "cpca16@0.05", "cpca8@0.1"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      TransferCodecSettings s = setting(name);
      s.cpcaMaxClusters = 8;
      const Bytes blob = encodeOrDie(x, order, packing, channels, s);
      const std::vector<float> full = decodeOrDie(blob, order);
      TransferBlobInfo info;
      ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
      for (int b = 1; b <= order; ++b) {
        // Bit for bit: the truncation of the full decode, from the whole blob and from the
        // shortest prefix holding b bands.
        const std::vector<float> expect = truncate(full, order, b, packing, channels);
        EXPECT_EQ(decodeOrDie(blob, b), expect) << "bands " << b;
        const TransferPartInfo& last = info.parts[info.parts.size() - static_cast<std::size_t>(order - b) - 1];
        const Bytes prefix(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(last.offset + last.size));
        TransferBlobInfo pinfo;
        ASSERT_TRUE(readTransferBlobInfo(prefix, &pinfo).isOk());
        EXPECT_EQ(pinfo.bandsAvailable, b);
        EXPECT_EQ(decodeOrDie(prefix, b), expect) << "prefix, bands " << b;
        std::vector<float> out;
        if (b < order) {
          EXPECT_EQ(decodeTransferMatrix(prefix, b + 1, &out).code(), StatusCode::kTruncated);
        }
        if (std::string(name) == "f32") {
          EXPECT_EQ(expect, truncate(x, order, b, packing, channels));
        }
      }
    }
  }
}

TEST(TransferCodecMatrix, CpcaMeetsTheTargetOnLowRankMatrices) {
  struct Case {
    MatrixPacking packing;
    int order, channels;
  };
  for (const Case c : {Case{MatrixPacking::kFull, 3, 1}, Case{MatrixPacking::kSymmetric, 3, 3}, Case{MatrixPacking::kFull, 2, 3}}) {
    const std::size_t D = static_cast<std::size_t>(c.channels) * entries(c.order, c.packing);
    const std::vector<float> x = lowRankMatrices(600, D, 4, 3, 0.003, 7);
    for (const char* name : {"cpca8@0.05", "cpca16@0.02", "cpca16@0.005"}) {
      SCOPED_TRACE(std::string(name) + " D " + std::to_string(D));
      TransferCodecSettings s = setting(name);
      s.cpcaMaxClusters = 16;
      TransferEncodeReport report;
      const Bytes blob = encodeOrDie(x, c.order, c.packing, c.channels, s, &report);
      const std::vector<float> y = decodeOrDie(blob, c.order);
      const double e = relError(x, y);
      EXPECT_LE(e, s.cpcaTargetError);
      EXPECT_NEAR(report.relativeError, e, 1e-9);
      EXPECT_EQ(report.bytes, blob.size());
      ASSERT_EQ(report.vectorsPerBand.size(), 1u);
      TransferBlobInfo info;
      ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
      EXPECT_EQ(info.vectors, report.vectorsPerBand[0]);
      EXPECT_EQ(static_cast<int>(info.clusterCount), report.clusters);
      EXPECT_EQ(info.parts.size(), static_cast<std::size_t>(c.order) + 2);
      // Four clusters of rank 3 are the model: 4 * (1 + 3) = 16 matrices describe it (fewer
      // clusters with more vectors span it too, and can be smaller with few vertices). The
      // search must not store much more than that, and must beat float16 by far.
      EXPECT_LE(report.clusters * (1 + report.vectorsPerBand[0]), 16 + 4)
          << report.clusters << " clusters, " << report.vectorsPerBand[0] << " vectors";
      const Bytes f16 = encodeOrDie(x, c.order, c.packing, c.channels, setting("f16"));
      EXPECT_LT(blob.size() * 3, f16.size());
    }
  }
}

TEST(TransferCodecMatrix, CpcaMeetsTheTargetOnVisibilityLikeMatrices) {
  for (MatrixPacking packing : kPackings) {
    const int order = 3;
    const std::vector<float> x = visibilityMatrices(400, order, packing);
    for (const char* name : {"cpca8@0.05", "cpca16@0.02"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      TransferCodecSettings s = setting(name);
      s.cpcaMaxClusters = 32;
      TransferEncodeReport report;
      const Bytes blob = encodeOrDie(x, order, packing, 1, s, &report);
      const std::vector<float> y = decodeOrDie(blob, order);
      EXPECT_LE(relError(x, y), s.cpcaTargetError);
      double maxAbs = 0.0;
      for (std::size_t i = 0; i < x.size(); ++i) maxAbs = std::max(maxAbs, std::fabs(static_cast<double>(y[i]) - x[i]));
      EXPECT_NEAR(report.maxAbsError, maxAbs, 1e-9);
      const Bytes f16 = encodeOrDie(x, order, packing, 1, setting("f16"));
      EXPECT_LT(blob.size(), f16.size());
    }
  }
}

TEST(TransferCodecMatrix, UnexpandedCpcaReconstructsToTheDecode) {
  const int order = 3;
  for (MatrixPacking packing : kPackings) {
    const std::vector<float> x = lowRankMatrices(200, 3 * entries(order, packing), 5, 4, 0.01, 3);
    TransferCodecSettings s = setting("cpca8@0.05");
    s.cpcaMaxClusters = 8;
    const Bytes blob = encodeOrDie(x, order, packing, 3, s);
    for (int b = 1; b <= order; ++b) {
      CpcaMatrixTransfer cpca;
      ASSERT_TRUE(decodeCpcaMatrixTransfer(blob, b, &cpca).isOk());
      EXPECT_EQ(cpca.bands, b);
      EXPECT_EQ(cpca.order, order);
      EXPECT_EQ(cpca.packing, packing);
      const std::size_t N = static_cast<std::size_t>(cpca.vectors);
      ASSERT_EQ(cpca.matrices.size(), cpca.clusterCount * (N + 1) * 3 * entries(b, packing));
      // The stored form: weights are levels times the cluster's step, levels within +-127.
      for (std::size_t v = 0; v < cpca.vertexCount; ++v)
        for (std::size_t j = 0; j < N; ++j) {
          ASSERT_EQ(cpca.weights[v * N + j], static_cast<float>(cpca.levels[v * N + j]) * cpca.steps[cpca.clusterOf[v]]);
          ASSERT_LE(std::abs(cpca.levels[v * N + j]), 127);
        }
      // Independent expansion: mean + sum_j w_j B_j in j order, in float.
      std::vector<float> mine(cpca.vertexCount * 3 * entries(b, packing));
      const std::size_t D = 3 * entries(b, packing);
      for (std::size_t v = 0; v < cpca.vertexCount; ++v) {
        const float* m = &cpca.matrices[cpca.clusterOf[v] * (N + 1) * D];
        for (std::size_t i = 0; i < D; ++i) {
          float acc = m[i];
          for (std::size_t j = 0; j < N; ++j) acc += cpca.weights[v * N + j] * m[(j + 1) * D + i];
          mine[v * D + i] = acc;
        }
      }
      std::vector<float> expanded(mine.size());
      ASSERT_TRUE(cpcaMatrixReconstruct(cpca, expanded).isOk());
      EXPECT_EQ(expanded, mine);
      EXPECT_EQ(decodeOrDie(blob, b), mine);
    }
    CpcaMatrixTransfer all;
    ASSERT_TRUE(decodeCpcaMatrixTransfer(blob, 0, &all).isOk());
    EXPECT_EQ(all.bands, order);
    std::vector<float> wrongSize(3);
    EXPECT_EQ(cpcaMatrixReconstruct(all, wrongSize).code(), StatusCode::kSizeMismatch);
  }
}

TEST(TransferCodecMatrix, CpcaIsDeterministicForASeed) {
  const std::vector<float> x = lowRankMatrices(150, 45, 3, 3, 0.01, 9);
  TransferCodecSettings s = setting("cpca8@0.05");
  EXPECT_EQ(encodeOrDie(x, 3, MatrixPacking::kSymmetric, 1, s), encodeOrDie(x, 3, MatrixPacking::kSymmetric, 1, s));
}

// Degenerate inputs: all zero, all equal, one vertex. CPCA stores them exactly (the means
// carry everything; no basis matrix is needed).
TEST(TransferCodecMatrix, CpcaHandlesDegenerateTransfer) {
  for (std::size_t V : {std::size_t{1}, std::size_t{50}}) {
    for (float value : {0.0f, 0.375f}) {
      const std::vector<float> x(V * 3 * entries(2, MatrixPacking::kFull), value);
      TransferEncodeReport report;
      const Bytes blob = encodeOrDie(x, 2, MatrixPacking::kFull, 3, setting("cpca8@0.02"), &report);
      EXPECT_EQ(decodeOrDie(blob, 2), x) << V << " vertices of " << value;
      EXPECT_EQ(report.relativeError, 0.0);
      EXPECT_EQ(report.clusters, 1);
      ASSERT_EQ(report.vectorsPerBand.size(), 1u);
      EXPECT_EQ(report.vectorsPerBand[0], 0);
    }
  }
}

TEST(TransferCodecMatrix, BadInputIsRefusedWithItsReason) {
  Bytes blob;
  const std::vector<float> x(2 * entries(2, MatrixPacking::kFull), 0.5f);
  EXPECT_EQ(encodeTransferMatrix(x, 9, MatrixPacking::kFull, 1, setting("f32"), &blob).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransferMatrix(x, 2, MatrixPacking::kFull, 2, setting("f32"), &blob).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransferMatrix(x, 2, static_cast<MatrixPacking>(7), 1, setting("f32"), &blob).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransferMatrix(x, 2, MatrixPacking::kSymmetric, 1, setting("f32"), &blob).code(), StatusCode::kSizeMismatch);
  std::vector<float> bad = x;
  bad[3] = std::nanf("");
  EXPECT_EQ(encodeTransferMatrix(bad, 2, MatrixPacking::kFull, 1, setting("f32"), &blob).code(), StatusCode::kNotFinite);
  bad[3] = 70000.0f;
  const Status s = encodeTransferMatrix(bad, 2, MatrixPacking::kFull, 1, setting("f16"), &blob);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("65504"), std::string::npos) << s.message();
}

// Every byte matters: each cut and each flipped byte of a blob of every encoding is refused.
TEST(TransferCodecMatrix, EveryTruncationAndByteFlipIsRejected) {
  for (MatrixPacking packing : kPackings) {
    const int order = 2;
    const std::vector<float> x = lowRankMatrices(12, 3 * entries(order, packing), 2, 2, 0.01, 17);
    for (const char* name : {"f32", "f16", "q16", "q8", "cpca8@0.1", "cpca16@0.02"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      TransferCodecSettings s = setting(name);
      s.cpcaMaxClusters = 4;
      const Bytes blob = encodeOrDie(x, order, packing, 3, s);
      std::vector<float> out;
      for (std::size_t n = 0; n < blob.size(); ++n) {
        const Bytes cut(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(n));
        ASSERT_FALSE(decodeTransferMatrix(cut, order, &out).isOk()) << "prefix " << n;
      }
      for (std::size_t i = 0; i < blob.size(); ++i) {
        Bytes bad = blob;
        bad[i] ^= 0x5a;
        ASSERT_FALSE(decodeTransferMatrix(bad, order, &out).isOk()) << "byte " << i;
        CpcaMatrixTransfer cm;
        if (s.encoding == TransferEncoding::kCpca) {
          ASSERT_FALSE(decodeCpcaMatrixTransfer(bad, order, &cm).isOk()) << "byte " << i;
        }
      }
    }
  }
}

// Edits with resealed checksums reach the content checks, which name the problem.
TEST(TransferCodecMatrix, CraftedHeaderAndContentErrorsAreNamed) {
  const int order = 2;
  const std::vector<float> x = lowRankMatrices(20, entries(order, MatrixPacking::kSymmetric), 2, 2, 0.01, 5);
  TransferCodecSettings s = setting("cpca8@0.05");
  s.cpcaMaxClusters = 2;
  const Bytes blob = encodeOrDie(x, order, MatrixPacking::kSymmetric, 1, s);
  auto expectCorrupt = [&](Bytes b, const char* needle) {
    reseal(b);
    std::vector<float> out;
    const Status st = decodeTransferMatrix(b, order, &out);
    EXPECT_EQ(st.code(), StatusCode::kCorrupt) << needle << ": " << st.toString();
    EXPECT_NE(st.message().find(needle), std::string::npos) << st.message();
  };
  Bytes b = blob;
  b[36] = 2;
  expectCorrupt(b, "layout 2");
  b = blob;
  b[37] = 3;
  expectCorrupt(b, "matrix packing 3");
  b = blob;
  b[38] = 0xff;
  b[39] = 0xff;
  expectCorrupt(b, "vector count 65535 exceeds");
  b = blob;
  b[6] = 0;  // a 1.0 header cannot say "matrix"
  expectCorrupt(b, "reserved header byte 36");
  b = blob;
  b[10] = 9;  // order above kMaxMatrixOrder
  expectCorrupt(b, "outside 1..8 for matrix transfer");
  // The weights part: a level beyond +-127.
  TransferBlobInfo info;
  ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
  ASSERT_GT(info.vectors, 0);
  b = blob;
  const std::size_t weights = static_cast<std::size_t>(info.parts[1].offset);
  const std::size_t firstLevel = weights + 4 * info.clusterCount + static_cast<std::size_t>(info.vectors);
  b[weights + 4 * info.clusterCount] = 0;  // filter none, so the byte is the zig-zag code itself
  b[firstLevel] = 0xff;                    // zig-zag 255 = -128
  expectCorrupt(b, "outside +-127");
  // A shell's mean that is not finite.
  b = blob;
  wr32(b, static_cast<std::size_t>(info.parts[2].offset), 0x7f800000u);
  expectCorrupt(b, "not finite or beyond the transfer range");
}


// The basis limit ("n<N>" in a setting's name, TransferCodecSettings::cpcaMaxVectors): the
// encoder keeps at most N' basis matrices per cluster and reaches its target with more
// clusters instead, or says that the limit is what stops it.
TEST(TransferCodecMatrix, CpcaBasisLimitCapsTheVectorsAndNamesItselfWhenItStops) {
  TransferCodecSettings parsed;
  ASSERT_TRUE(parseTransferSetting("cpca16b8n8@0.045", {}, &parsed).isOk());
  EXPECT_EQ(parsed.cpcaMaxVectors, 8);
  EXPECT_EQ(parsed.cpcaBasisBits, 8);
  EXPECT_EQ(transferSettingName(parsed), "cpca16b8n8@0.045");
  EXPECT_EQ(transferSettingName(setting("cpca16@0.02")), "cpca16@0.02");  // no limit: no suffix
  for (const char* bad : {"cpca16n33", "cpca16n", "cpca16nx", "cpca8b8n-1", "cpca16n123", "cpca16b8x@0.1"}) {
    TransferCodecSettings s;
    EXPECT_FALSE(parseTransferSetting(bad, {}, &s).isOk()) << bad;
  }

  const int order = 3, channels = 1;
  const std::size_t D = entries(order, MatrixPacking::kFull);
  const std::vector<float> x = lowRankMatrices(600, D, 4, 2, 0.003, 7);
  TransferCodecSettings free = setting("cpca16@0.05"), capped = setting("cpca16n1@0.05");
  free.cpcaMaxClusters = capped.cpcaMaxClusters = 256;
  TransferEncodeReport freeReport, cappedReport;
  (void)encodeOrDie(x, order, MatrixPacking::kFull, channels, free, &freeReport);
  const Bytes blob = encodeOrDie(x, order, MatrixPacking::kFull, channels, capped, &cappedReport);
  ASSERT_EQ(cappedReport.vectorsPerBand.size(), 1u);
  EXPECT_GT(freeReport.vectorsPerBand[0], 1);  // without the limit the search wants more
  EXPECT_LE(cappedReport.vectorsPerBand[0], 1);
  EXPECT_LE(relError(x, decodeOrDie(blob, order)), capped.cpcaTargetError);

  TransferCodecSettings stuck = setting("cpca16n0@0.02");
  stuck.cpcaMaxClusters = 1;
  Bytes out;
  const Status st = encodeTransferMatrix(x, order, MatrixPacking::kFull, channels, stuck, &out);
  ASSERT_FALSE(st.isOk());
  EXPECT_NE(st.message().find("at most 0 basis matrices"), std::string::npos) << st.toString();
  EXPECT_NE(st.message().find("a larger basis limit"), std::string::npos) << st.toString();
}

}  // namespace
}  // namespace prt
