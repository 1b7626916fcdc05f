#include "cpca_texture.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "client_limits.h"
#include "prt/exit_radiance.h"
#include "prt/sh_basis.h"

namespace prt::web {
namespace {

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

bool consistent(const CpcaTransfer& cpca) {
  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  if ((C != 1 && C != 3) || K == 0 || K > kMaxTransferClusters || cpca.clusterOf.size() != V || cpca.bands.empty() ||
      (cpca.weightBits != 8 && cpca.weightBits != 16)) {
    return false;
  }
  for (std::size_t l = 0; l < cpca.bands.size(); ++l) {
    const CpcaBand& b = cpca.bands[l];
    const std::size_t D = static_cast<std::size_t>(b.dims), N = static_cast<std::size_t>(b.vectors);
    if (b.band != static_cast<int>(l) || D != C * (2 * l + 1) || b.vectors < 0 || N > D || b.means.size() != K * D ||
        b.basis.size() != K * N * D || b.levels.size() != V * N || b.steps.size() != K) {
      return false;
    }
  }
  return std::all_of(cpca.clusterOf.begin(), cpca.clusterOf.end(), [&](std::uint32_t k) { return k < K; });
}

}  // namespace

Status packCpca(const CpcaTransfer& cpca, int maxHeight, CpcaTextures* out) {
  if (!consistent(cpca)) return Status::error(StatusCode::kSizeMismatch, "CPCA transfer arrays disagree with its counts");
  CpcaTextures t;
  t.order = static_cast<int>(cpca.bands.size());
  t.channels = cpca.channels;
  t.clusters = static_cast<int>(cpca.clusterCount);
  t.weightBits = cpca.weightBits;
  t.weightsBefore.assign(1, 0);
  for (const CpcaBand& b : cpca.bands) t.weightsBefore.push_back(t.weightsBefore.back() + b.vectors);
  t.weightCount = t.weightsBefore.back();
  t.weightTexels = std::max(1, (t.weightCount + 3) / 4);
  t.entriesPerCluster = 1 + 4 * t.weightTexels;

  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  const std::size_t E = static_cast<std::size_t>(t.entriesPerCluster), n2 = static_cast<std::size_t>(shCoeffCount(t.order));
  if (Status s = textureRowsFor(V * static_cast<std::size_t>(t.weightTexels), maxHeight, "CPCA weights", &t.weightHeight); !s.isOk()) return s;
  if (Status s = textureRowsFor(K * E, maxHeight, "CPCA cluster table", &t.tableHeight); !s.isOk()) return s;
  t.weightWidth = t.tableWidth = kTransferTextureWidth;

  // Entries as a transfer pass of K * E "vertices": the mean of every band, then each axis
  // times its cluster and band's step, zero outside its band (and for the padding).
  TransferPass entries;
  entries.channels = cpca.channels;
  entries.coeffs.assign(K * E * C * n2, 0.0f);
  for (std::size_t k = 0; k < K; ++k) {
    float* mean = &entries.coeffs[k * E * C * n2];
    std::size_t e = 1;
    for (std::size_t l = 0; l < cpca.bands.size(); ++l) {
      const CpcaBand& b = cpca.bands[l];
      const std::size_t D = static_cast<std::size_t>(b.dims), N = static_cast<std::size_t>(b.vectors), width = 2 * l + 1;
      for (std::size_t d = 0; d < D; ++d) mean[(d / width) * n2 + l * l + d % width] = b.means[k * D + d];
      for (std::size_t j = 0; j < N; ++j, ++e) {
        float* entry = &entries.coeffs[(k * E + e) * C * n2];
        const float* axis = &b.basis[(k * N + j) * D];
        for (std::size_t d = 0; d < D; ++d) entry[(d / width) * n2 + l * l + d % width] = b.steps[k] * axis[d];
      }
    }
  }
  if (Status s = packTransfer(entries, t.order, K * E, maxHeight, &t.entries); !s.isOk()) {
    return invalid("CPCA cluster entries: " + s.message());
  }

  const std::size_t bytesPerLevel = t.weightBits == 8 ? 1 : 2;
  const std::size_t perVertex = static_cast<std::size_t>(t.weightTexels) * 4;
  t.weightData.assign(static_cast<std::size_t>(t.weightWidth) * static_cast<std::size_t>(t.weightHeight) * 4 * bytesPerLevel, 0);
  for (std::size_t v = 0; v < V; ++v) {
    std::size_t e = 0;
    for (const CpcaBand& b : cpca.bands) {
      const std::size_t N = static_cast<std::size_t>(b.vectors);
      for (std::size_t j = 0; j < N; ++j, ++e) {
        const std::int16_t q = b.levels[v * N + j];
        std::uint8_t* dst = &t.weightData[(v * perVertex + e) * bytesPerLevel];
        if (bytesPerLevel == 1) {
          dst[0] = static_cast<std::uint8_t>(static_cast<std::int8_t>(std::clamp<int>(q, -127, 127)));
        } else {
          const auto u = static_cast<std::uint16_t>(q);
          dst[0] = static_cast<std::uint8_t>(u & 0xff);
          dst[1] = static_cast<std::uint8_t>(u >> 8);
        }
      }
    }
  }
  t.clusterOf.resize(V);
  for (std::size_t v = 0; v < V; ++v) t.clusterOf[v] = static_cast<std::uint16_t>(cpca.clusterOf[v]);
  *out = std::move(t);
  return Status::ok();
}

std::vector<float> cpcaRadiance(const CpcaTextures& p, const float* lighting, int displayOrder, const std::vector<float>& albedo) {
  const std::size_t V = p.clusterOf.size(), E = static_cast<std::size_t>(p.entriesPerCluster);
  const std::size_t perChannel = static_cast<std::size_t>(p.entries.texelsPerChannel) * 4;
  const int active = std::clamp(displayOrder, 1, p.order);
  const std::size_t activeCoeffs = static_cast<std::size_t>(active * active);
  // The table pass (prt.vert on the entries, albedo 1): the entries are transfer vectors
  // with a padded stride, so this is the shared exit radiance.
  std::vector<Rgb> rgbLight(activeCoeffs);
  for (std::size_t i = 0; i < activeCoeffs; ++i) rgbLight[i] = {lighting[i], lighting[kMaxClientCoeffs + i], lighting[2 * kMaxClientCoeffs + i]};
  const std::size_t entries = static_cast<std::size_t>(p.clusters) * E;
  std::vector<float> table(entries * 3, 0.0f);
  const std::span<const float> entryTexels(p.entries.texels.data(), entries * static_cast<std::size_t>(p.channels) * perChannel);
  if (!exitRadiance(entryTexels, p.channels, perChannel, {}, rgbLight, table).isOk()) return {};
  // The vertex pass (cpca.vert).
  const std::size_t weights = static_cast<std::size_t>(p.weightsBefore[static_cast<std::size_t>(active)]);
  const std::size_t perVertex = static_cast<std::size_t>(p.weightTexels) * 4, bytesPerLevel = p.weightBits == 8 ? 1 : 2;
  std::vector<float> out(V * 3, 0.0f);
  for (std::size_t v = 0; v < V; ++v) {
    const float* row = &table[static_cast<std::size_t>(p.clusterOf[v]) * E * 3];
    for (int c = 0; c < 3; ++c) {
      float sum = row[c];
      for (std::size_t e = 0; e < weights; ++e) {
        const std::uint8_t* src = &p.weightData[(v * perVertex + e) * bytesPerLevel];
        const int q = bytesPerLevel == 1 ? static_cast<std::int8_t>(src[0])
                                         : static_cast<std::int16_t>(static_cast<std::uint16_t>(src[0] | (src[1] << 8)));
        sum += static_cast<float>(q) * row[3 * (1 + e) + static_cast<std::size_t>(c)];
      }
      out[3 * v + static_cast<std::size_t>(c)] = p.channels == 1 && albedo.size() == 3 * V ? sum * albedo[3 * v + static_cast<std::size_t>(c)] : sum;
    }
  }
  return out;
}

}  // namespace prt::web
