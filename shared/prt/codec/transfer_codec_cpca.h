// The CPCA encoder's model (Sloan et al. 2003, per band): one k-means clustering of the
// vertices' whole transfer vectors, then per band and cluster a mean and the principal
// axes of the members' band vectors. Quantisation is set by one step delta for every
// weight (rate-distortion: equal distortion per kept component), raised per cluster and
// band where the weights' range would not fit the weight width; components whose energy
// is below kappa * delta^2 per vertex are dropped. Internal to the codec.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "prt/status.h"
#include "transfer_codec_container.h"

namespace prt::transfer_codec {

struct CpcaBandFit {
  int dims = 0;                        // channels * (2l+1)
  std::vector<float> means;            // clusters * dims, as stored (float)
  std::vector<std::uint16_t> basis;    // clusters * dims * dims: every principal axis, binary16
  std::vector<double> componentEnergy; // dims: sum over clusters of the j-th eigenvalue (scatter)
  std::vector<float> weights;          // vertices * dims: (x - mean) . stored axis j
  std::vector<float> maxAbsWeight;     // clusters * dims: max |weight j| over the members
};

struct CpcaFit {
  int order = 0, channels = 0;
  std::size_t vertices = 0;
  int clusters = 0;
  std::vector<std::uint32_t> clusterOf;
  std::vector<CpcaBandFit> bands;
  double energy = 0.0;  // sum of x^2 over the whole transfer
};

// Clusters `transfer` ([vertex][channel][coefficient]) into at most `clusters` clusters and
// fits every band's per-cluster PCA.
CpcaFit fitCpca(std::span<const float> transfer, int order, int channels, int clusters, std::uint64_t seed);

struct CpcaQuantisation {
  double delta = 0.0;
  std::vector<int> vectors;        // per band: n'_l
  std::vector<float> steps;        // per band, per cluster: [band][cluster]
};

// The quantisation that step `delta` and energy threshold `kappa` give for `weightBits`.
CpcaQuantisation chooseQuantisation(const CpcaFit& fit, double delta, double kappa, int weightBits);

// Squared reconstruction error of `q` over all vertices, computed in weight space (exact
// up to the binary16 rounding of the axes).
double estimateSquaredError(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits);

// Estimated blob size after a general entropy coder (tables raw, streams by entropy).
double estimateCpcaBytes(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits);

// The clusters part and the band parts of `fit` quantised by `q`.
std::vector<PartPayload> cpcaParts(const CpcaFit& fit, const CpcaQuantisation& q, int weightBits);

// Chooses cluster count, delta and kappa: the smallest estimated size whose error meets
// `targetError` (relative RMS), verified by decoding. Writes the blob to *out.
Status encodeCpca(std::span<const float> transfer, int order, int channels, const TransferCodecSettings& settings,
                  std::vector<std::uint8_t>* out, TransferEncodeReport* report);

}  // namespace prt::transfer_codec
