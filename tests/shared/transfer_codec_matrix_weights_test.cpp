// Matrix CPCA with row weights (TransferCodecSettings::cpcaMatrixRowWeights,
// docs/transfer-codec.md "Row weights"): weights of one change nothing, byte for byte; the
// weighted error meets the target, measured here independently; on lobe-like matrices
// (energy in the low rows, detail in the top band) the weighted encode at a target is smaller than
// the unweighted one; the blob keeps the prefix rule; bad weights are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"
#include "matrix_codec_test_util.h"

namespace prt {
namespace {

using namespace codec_test;

int bandOf(std::size_t i) { return static_cast<int>(std::sqrt(static_cast<double>(i) + 0.5)); }

// Lobe-like matrices: per cluster a mean and 2 directions whose entries fall off with both
// indices' bands (smooth transfer: most energy in the low rows and columns), plus 4
// directions living in the top band's rows and columns only (detail that a broad lobe dims),
// plus a little noise in every entry; channels alike but for a gain.
std::vector<float> lobeLikeMatrices(std::size_t V, int order, MatrixPacking packing, int channels, double detail,
                                    std::uint64_t seed) {
  Lcg g{seed};
  const std::size_t n2 = static_cast<std::size_t>(order * order), E = matrixEntryCount(order, packing);
  constexpr int kClusters = 4, kSmooth = 2, kDetail = 4, kShapes = 1 + kSmooth + kDetail;
  std::vector<std::vector<double>> shapes(static_cast<std::size_t>(kClusters * kShapes), std::vector<double>(E, 0.0));
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const bool isDetail = static_cast<int>(s % kShapes) > kSmooth;
    for (std::size_t i = 0; i < n2; ++i)
      for (std::size_t j = 0; j < n2; ++j) {
        if (packing == MatrixPacking::kSymmetric && j > i) continue;
        const bool top = bandOf(i) == order - 1 && bandOf(j) == order - 1;
        const double falloff = 1.0 / ((1.0 + bandOf(i)) * (1.0 + bandOf(i)) * (1.0 + bandOf(j)));
        const double value = isDetail ? (top ? detail * g.gauss() : 0.0) : falloff * g.gauss();
        shapes[s][matrixEntryIndex(i, j, packing)] = value;
      }
  }
  std::vector<float> x(V * static_cast<std::size_t>(channels) * E);
  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t k = v % kClusters;
    double w[kShapes - 1];
    for (double& c : w) c = g.gauss();
    for (int c = 0; c < channels; ++c)
      for (std::size_t e = 0; e < E; ++e) {
        double val = shapes[k * kShapes][e];
        for (int r = 0; r < kShapes - 1; ++r) val += (r < kSmooth ? 0.3 : 1.0) * w[r] * shapes[k * kShapes + 1 + static_cast<std::size_t>(r)][e];
        x[(v * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)) * E + e] =
            static_cast<float>((1.0 + 0.2 * c) * val + 0.002 * g.gauss());
      }
  }
  return x;
}

// A Phong lobe's band scales as row weights (row i of band l gets |g_l(s)|).
std::vector<double> lobeRowWeights(int order, double s) {
  std::vector<double> g(static_cast<std::size_t>(order));
  EXPECT_TRUE(phongLobeBandScales(order, s, g).isOk());
  std::vector<double> w(static_cast<std::size_t>(order * order));
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = std::fabs(g[static_cast<std::size_t>(bandOf(i))]);
  return w;
}

// sqrt(sum over entries of (squared error weighted as the rows weigh it) / same of x): for a
// symmetric entry (i, j), i != j, the two rows' squared weights averaged (the codec's rule).
double weightedError(const std::vector<float>& x, const std::vector<float>& y, int order, MatrixPacking packing,
                     const std::vector<double>& rows) {
  const std::size_t n2 = static_cast<std::size_t>(order * order), E = matrixEntryCount(order, packing);
  std::vector<double> w2(E);
  for (std::size_t i = 0; i < n2; ++i)
    for (std::size_t j = 0; j < n2; ++j) {
      if (packing == MatrixPacking::kSymmetric && j > i) continue;
      w2[matrixEntryIndex(i, j, packing)] = packing == MatrixPacking::kSymmetric ? 0.5 * (rows[i] * rows[i] + rows[j] * rows[j]) : rows[i] * rows[i];
    }
  double num = 0.0, den = 0.0;
  for (std::size_t t = 0; t < x.size(); ++t) {
    const double d = static_cast<double>(y[t]) - x[t];
    num += w2[t % E] * d * d;
    den += w2[t % E] * static_cast<double>(x[t]) * x[t];
  }
  return std::sqrt(num / den);
}

TransferCodecSettings cpca(const char* name) {
  TransferCodecSettings s;
  EXPECT_TRUE(parseTransferSetting(name, {}, &s).isOk()) << name;
  s.cpcaMaxClusters = 16;
  return s;
}

TEST(TransferCodecMatrixWeights, WeightsOfOneWriteTheUnweightedBlobByteForByte) {
  for (MatrixPacking packing : kPackings) {
    for (const char* name : {"cpca8@0.05", "cpca16@0.02"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      const int order = 3, channels = 3;
      const std::vector<float> x = lobeLikeMatrices(400, order, packing, channels, 0.015, 3);
      TransferCodecSettings plain = cpca(name), ones = plain;
      ones.cpcaMatrixRowWeights.assign(static_cast<std::size_t>(order * order), 1.0);
      TransferEncodeReport a, b;
      EXPECT_EQ(encodeOrDie(x, order, packing, channels, plain, &a), encodeOrDie(x, order, packing, channels, ones, &b));
      EXPECT_EQ(a.relativeError, b.relativeError);
      EXPECT_EQ(a.maxAbsError, b.maxAbsError);
    }
  }
}

TEST(TransferCodecMatrixWeights, WeightedEncodeMeetsTheWeightedTargetInFewerBytesOnLobeLikeMatrices) {
  for (MatrixPacking packing : kPackings) {
    for (const char* name : {"cpca8@0.06", "cpca16@0.04"}) {
      SCOPED_TRACE(std::string(name) + " " + matrixPackingName(packing));
      const int order = 4, channels = 3;
      const std::vector<float> x = lobeLikeMatrices(1500, order, packing, channels, 0.015, 11);
      const std::vector<double> rows = lobeRowWeights(order, 3.0);  // g_l = 1, 0.8, 0.5, 0.23
      TransferCodecSettings plain = cpca(name), weighted = plain;
      weighted.cpcaMatrixRowWeights = rows;
      TransferEncodeReport rp, rw;
      const Bytes bp = encodeOrDie(x, order, packing, channels, plain, &rp);
      const Bytes bw = encodeOrDie(x, order, packing, channels, weighted, &rw);
      const std::vector<float> yw = decodeOrDie(bw, order);
      const double e = weightedError(x, yw, order, packing, rows);
      EXPECT_LE(e, weighted.cpcaTargetError);
      EXPECT_NEAR(rw.relativeError, e, 1e-6);
      // The weighted encode needs fewer bytes: the top band's detail, which this lobe sees at
      // g_3^2 = 5% of its energy, needs no basis matrices of its own there.
      EXPECT_LT(bw.size(), bp.size()) << "weighted K " << rw.clusters << " N' " << rw.vectorsPerBand[0] << ", plain K "
                                      << rp.clusters << " N' " << rp.vectorsPerBand[0];
      // Same format: every band prefix decodes as the truncation of the full decode.
      for (int b = 1; b < order; ++b) {
        const std::vector<float> prefix = decodeOrDie(bw, b);
        const std::size_t E = matrixEntryCount(order, packing), Eb = matrixEntryCount(b, packing);
        ASSERT_EQ(prefix.size(), yw.size() / E * Eb);
        for (std::size_t r = 0; r < yw.size() / E; ++r)
          for (std::size_t t = 0; t < Eb; ++t) ASSERT_EQ(prefix[r * Eb + t], yw[r * E + t]) << "band " << b;
      }
    }
  }
}

TEST(TransferCodecMatrixWeights, BadWeightsAreRefusedWithTheirReason) {
  const int order = 2;
  const std::vector<float> x = lobeLikeMatrices(50, order, MatrixPacking::kFull, 1, 0.015, 5);
  Bytes blob;
  const auto refused = [&](TransferCodecSettings s, const char* expect) {
    const Status st = encodeTransferMatrix(x, order, MatrixPacking::kFull, 1, s, &blob);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << expect;
    EXPECT_NE(st.message().find(expect), std::string::npos) << st.message();
  };
  TransferCodecSettings s = cpca("cpca8@0.05");
  s.cpcaMatrixRowWeights = {1.0, 0.5, 0.5};
  refused(s, "3 given for 4 rows");
  s.cpcaMatrixRowWeights = {1.0, 0.5, 0.0, 0.5};
  refused(s, "outside (0, 1]");
  s.cpcaMatrixRowWeights = {1.0, 0.5, 2.0, 0.5};
  refused(s, "outside (0, 1]");
  s.cpcaMatrixRowWeights = {1.0, 0.5, std::nan(""), 0.5};
  refused(s, "outside (0, 1]");
  TransferCodecSettings q8;
  q8.encoding = TransferEncoding::kQuant8;
  q8.cpcaMatrixRowWeights.assign(4, 1.0);
  refused(q8, "matrix CPCA only");
  // A vector transfer has no rows to weight.
  TransferCodecSettings v = cpca("cpca8@0.05");
  v.cpcaMatrixRowWeights.assign(4, 1.0);
  const Status st = encodeTransfer(std::vector<float>(10 * 4, 0.25f), 2, 1, v, &blob);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("matrix CPCA only"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace prt
