// The CPCA parameter search (prt/transfer_codec_cpca.h): cluster counts 1, 2, 4, ... up to
// the limit, for each a few component thresholds kappa, for each the largest step delta
// whose estimated error meets the target; the smallest estimated size wins, and its error
// is then verified on the decoded blob (delta shrinks until it holds).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "transfer_codec_cpca.h"

namespace prt::transfer_codec {
namespace {

// Error goal for the estimates: a little under the target, so the verified error (which
// also sees binary16 axes and float arithmetic) usually passes the first time.
constexpr double kEstimateMargin = 0.97;
constexpr double kKappas[] = {0.0, 0.0625, 0.25, 1.0};
constexpr int kDeltaBisections = 14;
constexpr int kVerifyRetries = 40;

double largestWeight(const CpcaFit& fit) {
  double m = 0.0;
  for (const CpcaBandFit& b : fit.bands) {
    for (float w : b.maxAbsWeight) m = std::max(m, static_cast<double>(w));
  }
  return m;
}

// Largest delta (to within a factor 2^(log2(1e6)/2^kDeltaBisections)) whose estimated
// squared error is at most `goal`; nullopt when even the smallest tried is over it.
std::optional<double> searchDelta(const CpcaFit& fit, double kappa, int weightBits, double goal) {
  auto fits = [&](double delta) {
    return estimateSquaredError(fit, chooseQuantisation(fit, delta, kappa, weightBits), weightBits) <= goal;
  };
  const double hi = 2.0 * largestWeight(fit);
  if (hi == 0.0 || fits(hi)) return hi;
  double lo = hi * 1e-6;
  if (!fits(lo)) return std::nullopt;
  double top = hi;
  for (int i = 0; i < kDeltaBisections; ++i) {
    const double mid = std::sqrt(lo * top);
    (fits(mid) ? lo : top) = mid;
  }
  return lo;
}

struct Candidate {
  double bytes = 0.0;
  double delta = 0.0, kappa = 0.0;
};

double relativeError(std::span<const float> a, std::span<const float> b, double energy, double* maxAbs) {
  double sum = 0.0;
  *maxAbs = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += e * e;
    *maxAbs = std::max(*maxAbs, std::fabs(e));
  }
  return energy > 0.0 ? std::sqrt(sum / energy) : (sum > 0.0 ? INFINITY : 0.0);
}

}  // namespace

Status encodeCpca(std::span<const float> transfer, int order, int channels, const TransferCodecSettings& settings,
                  std::vector<std::uint8_t>* out, TransferEncodeReport* report) {
  const std::size_t vertices = transfer.size() / static_cast<std::size_t>(channels * order * order);
  const int bits = settings.cpcaWeightBits;
  const double target = settings.cpcaTargetError;
  const int maxClusters = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(settings.cpcaMaxClusters), vertices));

  std::optional<CpcaFit> best;
  Candidate bestCandidate;
  int tried = 0, worseInARow = 0, previousClusters = 0;
  double bestFloor = INFINITY;  // smallest relative error seen at the smallest delta, for the error message
  for (int k = 1; k <= maxClusters; k = k >= maxClusters ? maxClusters + 1 : std::min(2 * k, maxClusters)) {
    CpcaFit fit = fitCpca(transfer, order, channels, k, settings.seed);
    if (fit.clusters == previousClusters) break;  // no more distinct points to split
    previousClusters = fit.clusters;
    const double goal = kEstimateMargin * kEstimateMargin * target * target * fit.energy;
    bool improved = false;
    for (double kappa : kKappas) {
      const std::optional<double> delta = searchDelta(fit, kappa, bits, goal);
      ++tried;
      if (!delta) {
        const double floorError = estimateSquaredError(fit, chooseQuantisation(fit, largestWeight(fit) * 2e-6, kappa, bits), bits);
        bestFloor = std::min(bestFloor, std::sqrt(floorError / fit.energy));
        continue;
      }
      const double bytes = estimateCpcaBytes(fit, chooseQuantisation(fit, *delta, kappa, bits), bits);
      if (!best || bytes < bestCandidate.bytes) {
        bestCandidate = {bytes, *delta, kappa};
        improved = true;
      }
    }
    if (improved) best = std::move(fit);
    worseInARow = improved ? 0 : worseInARow + 1;
    if (best && worseInARow >= 2) break;
  }
  if (!best) {
    return Status::error(StatusCode::kInvalidArgument,
                         "CPCA cannot reach the target relative error " + std::to_string(target) + " with " +
                             std::to_string(bits) + "-bit weights (the best found is about " + std::to_string(bestFloor) +
                             "); use 16-bit weights or a larger target");
  }

  BlobHeader header;
  header.encoding = TransferEncoding::kCpca;
  header.weightBits = bits;
  header.order = order;
  header.channels = channels;
  header.vertexCount = static_cast<std::uint32_t>(vertices);
  header.clusterCount = static_cast<std::uint32_t>(best->clusters);
  double delta = bestCandidate.delta;
  std::vector<float> decoded(transfer.size());
  for (int attempt = 0; attempt <= kVerifyRetries; ++attempt, delta *= 0.85) {
    const CpcaQuantisation q = chooseQuantisation(*best, delta, bestCandidate.kappa, bits);
    std::vector<std::uint8_t> blob;
    assembleBlob(header, cpcaParts(*best, q, bits), &blob);
    if (Status s = decodeTransfer(blob, order, decoded); !s.isOk()) {
      return Status::error(StatusCode::kInvalidArgument, "internal error: the CPCA blob does not decode: " + s.toString());
    }
    double maxAbs = 0.0;
    const double rel = relativeError(transfer, decoded, best->energy, &maxAbs);
    if (rel <= target) {
      if (report) {
        report->bytes = blob.size();
        report->clusters = best->clusters;
        report->vectorsPerBand = q.vectors;
        report->relativeError = rel;
        report->maxAbsError = maxAbs;
        report->candidatesTried = tried;
      }
      *out = std::move(blob);
      return Status::ok();
    }
  }
  return Status::error(StatusCode::kInvalidArgument,
                       "CPCA could not verify the target relative error " + std::to_string(target) + " with " +
                           std::to_string(bits) + "-bit weights; use 16-bit weights or a larger target");
}

}  // namespace prt::transfer_codec
