// Packs a CPCA matrix pass (prt/transfer_codec.h CpcaMatrixTransfer) for rendering the glossy
// term straight from the compressed form (Sloan et al. 2003 §4.1; docs/web-client.md,
// "Glossy rendering"), and emulates the three glossy shaders on the CPU. GL-free, so the
// arithmetic is tested under Node against prt/glossy_radiance.h.
//
// When the lighting changes (shaders/glossy_table.vert, one point per table texel, then
// shaders/glossy_transfer.vert, one point per vertex and channel; both by transform feedback):
//   table[k][m][c] = A_km,c L_c     (bands^2 values, 4 to an RGBA texel)
//   T_vc           = table[k][0][c] + sum_j level_vj table[k][j][c]   (transferred radiance)
// for every cluster k, matrix m = 0 (the mean) .. N' (basis matrices, their cluster's weight
// step folded in), lighting channel c = r, g, b (A_km,c the channel's matrix, or the one matrix
// of a 1-channel pass for all three) and vertex v of cluster k. Every frame (shaders/glossy.vert):
//   L_c = k_s,c sum_i (g_l(i)(s) T_vc,i) y_i(R),  R = reflect(-v, n) toward the live eye
// with k_s Schlick's term at n.v; the same formula as prt::glossyExitRadiance, reordered by
// linearity (the matrix-vector products are taken before the weighted sum). T is independent
// of the view, so a frame whose lighting did not change (the camera orbiting) costs only the
// last step.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/status.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"
#include "prt/vec3.h"

namespace prt::web {

// Largest glossy order (bands) the shaders take: their arrays hold 64 SH values (y_i(R) and a
// row of the table), the order of the client's lighting (client_limits.h).
inline constexpr int kMaxGlossyOrder = 8;
// Largest N' (basis matrices per cluster) the shaders take: glossy_transfer.vert's loop bound.
// Each costs 3 * ceil(bands^2 / 4) texel fetches per vertex when the lighting changes; the
// codec's searches stay far below.
inline constexpr int kMaxGlossyVectors = 64;

// Floats per vertex in GlossyTextures::specular: f0 r, g, b and the exponent (attribute 5, a
// vec4), then f90 (attribute 6).
inline constexpr std::size_t kGlossySpecularFloats = 5;

struct GlossyTextures {
  int bands = 0;              // order of the packed matrices (the shells decoded so far)
  int channels = 0;           // matrix channels: 1 (shadowed) or 3 (interreflected)
  MatrixPacking packing = MatrixPacking::kFull;
  int clusters = 0;           // K
  int vectors = 0;            // N'
  int weightBits = 8;         // 8: RGBA8I levels; 16: RGBA16I
  int weightTexels = 0;       // ceil(N' / 4) RGBA texels per vertex (at least 1)
  int rowTexels = 0;          // ceil(bands^2 / 4): texels of one matrix row and of one table vector
  int matrixTexels = 0;       // bands^2 * rowTexels texels per matrix
  // Matrices, RGBA32F, kTransferTextureWidth wide: matrix ((k * (1 + N') + m) * channels + c)
  // at texels [that index * matrixTexels, + matrixTexels), expanded from its packing to full
  // rows, row i at texels i * rowTexels .. (4 entries to a texel, zero-padded), so that a row
  // times the lighting is rowTexels vec4 dot products; basis matrices (m >= 1) multiplied by
  // their cluster's weight step.
  int matrixWidth = 0, matrixHeight = 0;
  std::vector<float> matrixData;
  // Integer weight levels, vertex v's N' at texels v * weightTexels .. (4 per texel), int8 or
  // little-endian int16, ready for texImage2D.
  int weightWidth = 0, weightHeight = 0;
  std::vector<std::uint8_t> weightData;
  std::vector<std::uint16_t> clusterOf;  // per vertex (K <= 65536): an integer vertex attribute
  std::vector<float> specular;           // per vertex f0 r, g, b, exponent, f90: a vec4 and a float attribute
  // The per-frame table, RGBA32F: texel ((k * (1 + N') + m) * 3 + c) * rowTexels + t holds rows
  // 4t .. 4t+3 of A_km,c L_c.
  int tableTexels = 0;
  int tableWidth = 0, tableHeight = 0;
  // The transferred radiance, RGBA32F: texel (c * V + v) * rowTexels + t holds rows 4t .. 4t+3
  // of T_vc (channel-major: glossy_transfer.vert runs once per channel over all vertices).
  int transferTexels = 0;
  int transferWidth = 0, transferHeight = 0;
};

// Packs `cpca` (its `bands` decoded shells, 1 .. kMaxGlossyOrder) with one specular material
// per vertex, for a device whose textures hold at most `maxHeight` rows (MAX_TEXTURE_SIZE).
// Errors (kInvalidArgument, kSizeMismatch) name what does not fit or disagrees. Safe on
// untrusted input (every count is checked against the arrays).
Status packGlossy(const CpcaMatrixTransfer& cpca, std::span<const SpecularMaterial> specular, int maxHeight,
                  GlossyTextures* out);

// A plain (float) matrix pass as a trivial CPCA pass the renderer takes: every vertex its own
// cluster (mean = its matrix), no basis matrices. `packed` holds vertexCount * channels *
// matrixEntryCount(bands, packing) floats. kInvalidArgument beyond kMaxTransferClusters vertices.
Status cpcaFromPlainMatrices(std::span<const float> packed, int bands, MatrixPacking packing, int channels,
                             std::uint32_t vertexCount, CpcaMatrixTransfer* out);

// The real-SH recurrence constants (prt/sh_basis.cpp's Lisle & Huang table, normalisation
// folded in) that glossy.vert evaluates y_i(R) with, as its uniforms uShA / uShB take them:
// kMaxGlossyOrder^2 floats each, plus y_00 and the band-1 factor.
struct ShRecurrenceConstants {
  float y00 = 0, k1 = 0;
  float a[kMaxGlossyOrder * kMaxGlossyOrder] = {};
  float b[kMaxGlossyOrder * kMaxGlossyOrder] = {};
};
const ShRecurrenceConstants& shRecurrenceConstants();

// glossy.vert's evaluation of y_i(dir), i < order^2 (order <= kMaxGlossyOrder), unit dir, in
// the shader's order of operations (the same as prt::evalShBasisUnchecked).
void glossyShBasis(int order, Vec3 dir, float* out);

// glossy_table.vert on the CPU: the table (tableTexels * 4 floats) for `lighting` (packLighting
// layout, kPackedLightingFloats floats) at `activeBands` (1 .. packed.bands; rows and columns
// beyond are zero), float, in the shader's order of operations.
std::vector<float> glossyTableCpu(const GlossyTextures& packed, const float* lighting, int activeBands);

// glossy_transfer.vert on the CPU: the transferred radiance (transferTexels * 4 floats) from
// glossyTableCpu's table at `activeBands` (rows beyond are zero, and so is a matte vertex's
// whole T: f0 = f90 = 0, no glossy term), in the shader's order.
std::vector<float> glossyTransferCpu(const GlossyTextures& packed, const std::vector<float>& table, int activeBands);

// glossy.vert's lobeTowardEye on the CPU: gy_i = g_l(i)(s) y_i(R) (i < bands^2; R the mirror
// direction of the view from `position` toward `eye` about the unit normal `n`) and k_s
// (Schlick's term when `fresnel`, else f0) for the specular material `spec`
// (kGlossySpecularFloats floats). False, with gy and k_s zero, for a matte material (f0 = f90 =
// 0) or a vertex at the eye: no glossy term.
bool glossyLobeTowardEye(int bands, const float* spec, Vec3 position, Vec3 n, Vec3 eye, bool fresnel, float* gy, Rgb* ks);

// glossy.vert on the CPU from the transferred radiance: glossy exit radiance toward `eye`, RGB
// per vertex (a vertex at the eye gets 0); Fresnel as in glossyExitRadiance when `fresnel`.
std::vector<float> glossyRadianceCpu(const GlossyTextures& packed, const std::vector<float>& transfer, int activeBands,
                                     std::span<const Vec3> positions, std::span<const Vec3> normals, Vec3 eye,
                                     bool fresnel = true);

}  // namespace prt::web
