#include "glossy_texture.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "client_limits.h"
#include "prt/sh_basis.h"
#include "transfer_texture.h"

namespace prt::web {
namespace {

Status invalid(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }

// K_lm of the real SH without Condon-Shortley phase (prt/sh_basis.cpp's shNorm).
double shNorm(int l, int m) {
  const int am = m < 0 ? -m : m;
  double ratio = 1.0;
  for (int k = l - am + 1; k <= l + am; ++k) ratio /= k;
  const double k2 = (2.0 * l + 1.0) / (4.0 * kPi) * ratio;
  return am == 0 ? std::sqrt(k2) : std::sqrt(2.0 * k2);
}

ShRecurrenceConstants makeConstants() {
  // The same constants, computed the same way (double, then rounded to float), as
  // prt/sh_basis.cpp's RecurrenceTable: the Node test checks the two bases agree bit for bit.
  ShRecurrenceConstants t;
  t.y00 = static_cast<float>(shNorm(0, 0));
  t.k1 = static_cast<float>(shNorm(1, 0));
  for (int l = 2; l < kMaxGlossyOrder; ++l) {
    for (int m = -l; m <= l; ++m) {
      const int am = m < 0 ? -m : m;
      const int i = shIndex(l, m);
      if (am == l) {
        t.a[i] = static_cast<float>((2.0 * l - 1.0) * shNorm(l, m) / shNorm(l - 1, l - 1));
      } else {
        t.a[i] = static_cast<float>((2.0 * l - 1.0) / (l - am) * shNorm(l, m) / shNorm(l - 1, m));
        t.b[i] = am <= l - 2 ? static_cast<float>((l + am - 1.0) / (l - am) * shNorm(l, m) / shNorm(l - 2, m)) : 0.0f;
      }
    }
  }
  return t;
}

int bandOf(int i) {
  int l = 0;
  while ((l + 1) * (l + 1) <= i) ++l;
  return l;
}

int levelAt(const GlossyTextures& p, std::size_t v, int j) {
  const std::size_t index = v * static_cast<std::size_t>(p.weightTexels) * 4 + static_cast<std::size_t>(j);
  if (p.weightBits == 8) return static_cast<std::int8_t>(p.weightData[index]);
  const std::uint8_t* src = &p.weightData[2 * index];
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(src[0] | (src[1] << 8)));
}

}  // namespace

const ShRecurrenceConstants& shRecurrenceConstants() {
  static const ShRecurrenceConstants t = makeConstants();
  return t;
}

void glossyShBasis(int order, Vec3 d, float* out) {
  const ShRecurrenceConstants& t = shRecurrenceConstants();
  out[0] = t.y00;
  if (order == 1) return;
  out[1] = t.k1 * d.y;
  out[2] = t.k1 * d.z;
  out[3] = t.k1 * d.x;
  for (int l = 2; l < order; ++l) {
    const int base = l * (l + 1), base1 = (l - 1) * l, base2 = (l - 2) * (l - 1);
    for (int m = -(l - 2); m <= l - 2; ++m) out[base + m] = t.a[base + m] * d.z * out[base1 + m] - t.b[base + m] * out[base2 + m];
    out[base - (l - 1)] = t.a[base - (l - 1)] * d.z * out[base1 - (l - 1)];
    out[base + (l - 1)] = t.a[base + (l - 1)] * d.z * out[base1 + (l - 1)];
    const float sp = out[base1 + (l - 1)], sn = out[base1 - (l - 1)];
    const float c = t.a[base + l];
    out[base + l] = c * (d.x * sp - d.y * sn);
    out[base - l] = c * (d.y * sp + d.x * sn);
  }
}

Status cpcaFromPlainMatrices(std::span<const float> packed, int bands, MatrixPacking packing, int channels,
                             std::uint32_t vertexCount, CpcaMatrixTransfer* out) {
  if (bands < 1 || bands > kMaxGlossyOrder || (channels != 1 && channels != 3)) return invalid("plain glossy pass: bad bands or channels");
  if (vertexCount == 0 || vertexCount > kMaxTransferClusters) {
    return invalid("plain glossy pass of " + std::to_string(vertexCount) + " vertices: the client renders uncompressed matrices of at most " +
                   std::to_string(kMaxTransferClusters) + " vertices (one cluster each); compress it with CPCA");
  }
  const std::size_t entries = matrixEntryCount(bands, packing);
  if (packed.size() != static_cast<std::size_t>(vertexCount) * static_cast<std::size_t>(channels) * entries) {
    return Status::error(StatusCode::kSizeMismatch, "plain glossy pass: matrix count disagrees with the vertex count");
  }
  CpcaMatrixTransfer t;
  t.order = t.bands = bands;
  t.channels = channels;
  t.packing = packing;
  t.vertexCount = t.clusterCount = vertexCount;
  t.weightBits = 8;
  t.vectors = 0;
  t.clusterOf.resize(vertexCount);
  for (std::uint32_t v = 0; v < vertexCount; ++v) t.clusterOf[v] = v;
  t.steps.assign(vertexCount, 1.0f);
  t.matrices.assign(packed.begin(), packed.end());
  *out = std::move(t);
  return Status::ok();
}

Status packGlossy(const CpcaMatrixTransfer& cpca, std::span<const SpecularMaterial> specular, int maxHeight,
                  GlossyTextures* out) {
  const std::size_t V = cpca.vertexCount, K = cpca.clusterCount, C = static_cast<std::size_t>(cpca.channels);
  const std::size_t N = cpca.vectors < 0 ? 0 : static_cast<std::size_t>(cpca.vectors);
  if (cpca.bands < 1 || cpca.bands > kMaxGlossyOrder) {
    return invalid("glossy pass of " + std::to_string(cpca.bands) + " bands: the client renders 1 .. " +
                   std::to_string(kMaxGlossyOrder));
  }
  if (cpca.vectors < 0 || cpca.vectors > kMaxGlossyVectors) {
    return invalid("glossy pass with " + std::to_string(cpca.vectors) + " basis matrices per cluster: the client takes at most " +
                   std::to_string(kMaxGlossyVectors));
  }
  if (cpca.packing != MatrixPacking::kSymmetric && cpca.packing != MatrixPacking::kFull) return invalid("glossy pass: unknown matrix packing");
  const std::size_t entries = matrixEntryCount(cpca.bands, cpca.packing);
  if ((C != 1 && C != 3) || K == 0 || K > kMaxTransferClusters || (cpca.weightBits != 8 && cpca.weightBits != 16) ||
      cpca.clusterOf.size() != V || cpca.steps.size() != K || cpca.levels.size() != V * N ||
      cpca.matrices.size() != K * (1 + N) * C * entries || specular.size() != V ||
      !std::all_of(cpca.clusterOf.begin(), cpca.clusterOf.end(), [&](std::uint32_t k) { return k < K; })) {
    return Status::error(StatusCode::kSizeMismatch, "glossy CPCA arrays disagree with their counts or the vertex count");
  }
  GlossyTextures t;
  t.bands = cpca.bands;
  t.channels = cpca.channels;
  t.packing = cpca.packing;
  t.clusters = static_cast<int>(K);
  t.vectors = static_cast<int>(N);
  t.weightBits = cpca.weightBits;
  t.weightTexels = std::max<int>(1, static_cast<int>((N + 3) / 4));
  t.rowTexels = texelsForOrder(cpca.bands);
  t.matrixTexels = cpca.bands * cpca.bands * t.rowTexels;
  const std::size_t matrices = K * (1 + N) * C;
  t.tableTexels = static_cast<int>(K * (1 + N) * 3 * static_cast<std::size_t>(t.rowTexels));
  if (Status s = textureRowsFor(matrices * static_cast<std::size_t>(t.matrixTexels), maxHeight, "glossy matrices", &t.matrixHeight); !s.isOk()) return s;
  if (Status s = textureRowsFor(V * static_cast<std::size_t>(t.weightTexels), maxHeight, "glossy weights", &t.weightHeight); !s.isOk()) return s;
  if (Status s = textureRowsFor(static_cast<std::size_t>(t.tableTexels), maxHeight, "glossy cluster table", &t.tableHeight); !s.isOk()) return s;
  t.transferTexels = static_cast<int>(3 * V * static_cast<std::size_t>(t.rowTexels));
  if (Status s = textureRowsFor(static_cast<std::size_t>(t.transferTexels), maxHeight, "glossy transferred radiance", &t.transferHeight);
      !s.isOk()) {
    return s;
  }
  t.matrixWidth = t.weightWidth = t.tableWidth = t.transferWidth = kTransferTextureWidth;

  const std::size_t width = static_cast<std::size_t>(kTransferTextureWidth);
  const std::size_t rows = static_cast<std::size_t>(cpca.bands) * static_cast<std::size_t>(cpca.bands);
  const std::size_t rowFloats = static_cast<std::size_t>(t.rowTexels) * 4;
  t.matrixData.assign(width * static_cast<std::size_t>(t.matrixHeight) * 4, 0.0f);
  for (std::size_t k = 0; k < K; ++k) {
    for (std::size_t m = 0; m <= N; ++m) {
      // The weight step folded into the basis matrices: a vertex stores integer levels only.
      const float scale = m == 0 ? 1.0f : cpca.steps[k];
      for (std::size_t c = 0; c < C; ++c) {
        const std::size_t index = (k * (1 + N) + m) * C + c;
        const float* src = &cpca.matrices[index * entries];
        float* dst = &t.matrixData[index * static_cast<std::size_t>(t.matrixTexels) * 4];
        for (std::size_t i = 0; i < rows; ++i) {
          for (std::size_t j = 0; j < rows; ++j) {
            const float e = src[matrixEntryIndex(i, j, cpca.packing)];
            dst[i * rowFloats + j] = m == 0 ? e : scale * e;
          }
        }
      }
    }
  }
  const std::size_t bytesPerLevel = t.weightBits == 8 ? 1 : 2;
  const std::size_t perVertex = static_cast<std::size_t>(t.weightTexels) * 4;
  t.weightData.assign(width * static_cast<std::size_t>(t.weightHeight) * 4 * bytesPerLevel, 0);
  const int maxLevel = (1 << (t.weightBits - 1)) - 1;
  for (std::size_t v = 0; v < V; ++v) {
    for (std::size_t j = 0; j < N; ++j) {
      const int q = cpca.levels[v * N + j];
      if (q < -maxLevel || q > maxLevel) {
        return Status::error(StatusCode::kCorrupt, "glossy weight level " + std::to_string(q) + " of vertex " + std::to_string(v) +
                                                       " is outside +-" + std::to_string(maxLevel));
      }
      std::uint8_t* dst = &t.weightData[(v * perVertex + j) * bytesPerLevel];
      if (bytesPerLevel == 1) {
        dst[0] = static_cast<std::uint8_t>(static_cast<std::int8_t>(q));
      } else {
        const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(q));
        dst[0] = static_cast<std::uint8_t>(u & 0xff);
        dst[1] = static_cast<std::uint8_t>(u >> 8);
      }
    }
  }
  t.clusterOf.resize(V);
  for (std::size_t v = 0; v < V; ++v) t.clusterOf[v] = static_cast<std::uint16_t>(cpca.clusterOf[v]);
  t.specular.resize(kGlossySpecularFloats * V);
  for (std::size_t v = 0; v < V; ++v) {
    const SpecularMaterial& m = specular[v];
    float* dst = &t.specular[kGlossySpecularFloats * v];
    dst[0] = m.f0.r;
    dst[1] = m.f0.g;
    dst[2] = m.f0.b;
    dst[3] = m.exponent;
    dst[4] = m.f90;
  }
  *out = std::move(t);
  return Status::ok();
}

std::vector<float> glossyTableCpu(const GlossyTextures& p, const float* lighting, int activeBands) {
  const int bands = std::clamp(activeBands, 1, p.bands);
  const int rows = bands * bands, activeTexels = texelsForOrder(bands);
  const std::size_t C = static_cast<std::size_t>(p.channels), rowFloats = static_cast<std::size_t>(p.rowTexels) * 4;
  std::vector<float> table(static_cast<std::size_t>(p.tableTexels) * 4, 0.0f);
  for (int point = 0; point < p.tableTexels; ++point) {
    // glossy_table.vert: gl_VertexID -> (cluster k, matrix m, lighting channel c, texel t).
    const int t = point % p.rowTexels;
    const int c = (point / p.rowTexels) % 3;
    const int km = point / (p.rowTexels * 3);
    const std::size_t matrix = static_cast<std::size_t>(km) * C + (C == 3 ? static_cast<std::size_t>(c) : 0);
    const float* m = &p.matrixData[matrix * static_cast<std::size_t>(p.matrixTexels) * 4];
    const float* light = lighting + c * kMaxClientCoeffs;
    for (int q = 0; q < 4; ++q) {
      const int i = 4 * t + q;
      float acc = 0.0f;
      if (i < rows) {
        for (int u = 0; u < activeTexels; ++u) {
          const float* row = &m[static_cast<std::size_t>(i) * rowFloats + 4 * static_cast<std::size_t>(u)];
          float texel = 0.0f;
          for (int w = 0; w < 4; ++w) texel += 4 * u + w < rows ? row[w] * light[4 * u + w] : 0.0f;
          acc += texel;
        }
      }
      table[static_cast<std::size_t>(point) * 4 + static_cast<std::size_t>(q)] = acc;
    }
  }
  return table;
}

std::vector<float> glossyTransferCpu(const GlossyTextures& p, const std::vector<float>& table, int activeBands) {
  const int activeTexels = texelsForOrder(std::clamp(activeBands, 1, p.bands));
  const std::size_t V = p.clusterOf.size(), N = static_cast<std::size_t>(p.vectors), R = static_cast<std::size_t>(p.rowTexels);
  std::vector<float> transfer(static_cast<std::size_t>(p.transferTexels) * 4, 0.0f);
  if (table.size() != static_cast<std::size_t>(p.tableTexels) * 4 || p.specular.size() != V * kGlossySpecularFloats) return transfer;
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t v = 0; v < V; ++v) {
      // glossy_transfer.vert: the draw of channel c, point v; a matte vertex's T stays 0.
      const float* material = &p.specular[v * kGlossySpecularFloats];
      if (material[0] == 0.0f && material[1] == 0.0f && material[2] == 0.0f && material[4] == 0.0f) continue;
      const std::size_t first = static_cast<std::size_t>(p.clusterOf[v]) * (1 + N);
      for (std::size_t t = 0; t < static_cast<std::size_t>(activeTexels); ++t) {
        const float* mean = &table[((first * 3 + c) * R + t) * 4];
        float tr[4] = {mean[0], mean[1], mean[2], mean[3]};
        for (std::size_t j = 0; j < N; ++j) {
          const float level = static_cast<float>(levelAt(p, v, static_cast<int>(j)));
          const float* axis = &table[(((first + 1 + j) * 3 + c) * R + t) * 4];
          for (int q = 0; q < 4; ++q) tr[q] += level * axis[q];
        }
        std::copy(tr, tr + 4, &transfer[((c * V + v) * R + t) * 4]);
      }
    }
  }
  return transfer;
}

bool glossyLobeTowardEye(int bands, const float* spec, Vec3 position, Vec3 n, Vec3 eye, bool fresnel, float* gy, Rgb* ks) {
  const int rows = bands * bands;
  std::fill(gy, gy + rows, 0.0f);
  *ks = Rgb{0.0f, 0.0f, 0.0f};
  if (spec[4] == 0.0f && spec[0] == 0.0f && spec[1] == 0.0f && spec[2] == 0.0f) return false;
  const Vec3 d = eye - position;
  const float distance = length(d);
  if (!(distance > 0.0f)) return false;
  const Vec3 toEye = d * (1.0f / distance);
  Vec3 r = reflectView(toEye, n);
  const float rl = length(r);
  r = rl > 0.0f ? r * (1.0f / rl) : n;
  float y[kMaxGlossyOrder * kMaxGlossyOrder], g[kMaxGlossyOrder];
  glossyShBasis(bands, r, y);
  phongLobeBandScalesUnchecked(bands, spec[3], g);
  // The lobe's band scales folded into the basis once, as glossy.vert does.
  for (int i = 0; i < rows; ++i) gy[i] = g[bandOf(i)] * y[i];
  *ks = fresnel ? schlickFresnel({spec[0], spec[1], spec[2]}, spec[4], dot(n, toEye)) : Rgb{spec[0], spec[1], spec[2]};
  return true;
}

std::vector<float> glossyRadianceCpu(const GlossyTextures& p, const std::vector<float>& transfer, int activeBands,
                                     std::span<const Vec3> positions, std::span<const Vec3> normals, Vec3 eye, bool fresnel) {
  const int bands = std::clamp(activeBands, 1, p.bands);
  const int rows = bands * bands, activeTexels = texelsForOrder(bands);
  const std::size_t V = p.clusterOf.size(), R = static_cast<std::size_t>(p.rowTexels);
  std::vector<float> out(3 * V, 0.0f);
  if (positions.size() != V || normals.size() != V || transfer.size() != static_cast<std::size_t>(p.transferTexels) * 4) return out;
  float gy[kMaxGlossyOrder * kMaxGlossyOrder];
  for (std::size_t v = 0; v < V; ++v) {
    Rgb ks;
    if (!glossyLobeTowardEye(bands, &p.specular[kGlossySpecularFloats * v], positions[v], normals[v], eye, fresnel, gy, &ks)) continue;
    const float k[3] = {ks.r, ks.g, ks.b};
    for (std::size_t c = 0; c < 3; ++c) {
      float sum = 0.0f;
      for (int t = 0; t < activeTexels; ++t) {
        const float* tr = &transfer[((c * V + v) * R + static_cast<std::size_t>(t)) * 4];
        for (int q = 0; q < 4; ++q) {
          const int i = 4 * t + q;
          if (i < rows) sum += tr[q] * gy[i];
        }
      }
      out[3 * v + c] = k[c] * sum;
    }
  }
  return out;
}

}  // namespace prt::web
