// The transfer codec: compact, band-progressive encodings of per-vertex SH transfer
// (layout [vertex][channel][coefficient], as in prt/asset.h) in a self-contained versioned
// blob. Byte layout, error bounds and the CPCA model: docs/transfer-codec.md.
//
// Encodings: float32 (exact), float16, 16- and 8-bit quantisation with one scale per
// channel and coefficient, and CPCA (clustered principal components, Sloan et al. 2003):
// vertices clustered in transfer space, per band per cluster a mean and principal
// vectors, per vertex a cluster id and quantised weights, the cluster count and vector
// counts chosen to meet a relative-error target at the smallest estimated size.
//
// Band-progressive: the blob is split into parts, one per SH band (plus, for CPCA, one
// holding the cluster ids), each with its own checksum; the first b bands decode without
// the others, as an order-b transfer. Streams are planar and byte-split so that a general
// entropy coder (zstd, brotli, gzip) applied to the blob compresses it well; the codec
// itself does no entropy coding and stays pure (no I/O, no threads), so it builds for wasm.
//
// The decoder treats its input as untrusted: every count, size and checksum is checked
// before use, it never reads outside the input, and its own allocations stay within a
// small multiple of the input size (at most 8x; the output array is the caller's).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "prt/status.h"
#include "prt/transfer_matrix.h"

namespace prt {

enum class TransferEncoding : std::uint8_t {
  kFloat32 = 1,  // IEEE binary32, bit-exact
  kFloat16 = 2,  // IEEE binary16, round to nearest even
  kQuant16 = 3,  // symmetric 16-bit quantisation, a step per channel and coefficient
  kQuant8 = 4,   // symmetric 8-bit quantisation, a step per channel and coefficient
  kCpca = 5,     // clustered PCA, 8- or 16-bit weights
};

// "f32" | "f16" | "q16" | "q8" | "cpca", or "unknown".
const char* transferEncodingName(TransferEncoding encoding);

struct TransferCodecSettings {
  TransferEncoding encoding = TransferEncoding::kFloat16;
  // kCpca only. Bits per stored weight: 8 or 16.
  int cpcaWeightBits = 8;
  // kCpca only. Target relative RMS error of the decoded transfer over all vertices,
  // channels and coefficients: sqrt(sum (x' - x)^2 / sum x^2), in (0, 1).
  double cpcaTargetError = 0.02;
  // kCpca only. Largest cluster count the search tries (1 .. kMaxTransferClusters).
  int cpcaMaxClusters = 256;
  // kCpca only. Seed of k-means++ (the encoding is deterministic for a given seed).
  std::uint64_t seed = 1;
  // Matrix kCpca only (encodeTransferMatrix). The weight w_i > 0 of each matrix row i (the
  // transferred-radiance coefficient l(l+1)+m, order^2 values): the encoder fits and
  // verifies the error of diag(w) M instead of M, i.e. the target and the reported error are
  // sqrt(sum w_i^2 (M' - M)_ij^2 / sum w_i^2 M_ij^2) (docs/transfer-codec.md "Row weights").
  // Empty: unweighted. The blob's format does not change; decoders need not know.
  std::vector<double> cpcaMatrixRowWeights;
  // Matrix kCpca only. Storage of the basis matrices' entries: 16 binary16 (version 1.1's
  // format), or 8: int8 levels with one float32 scale per (cluster, basis matrix, shell),
  // half the bytes, written as version 1.2 (docs/transfer-codec.md "8-bit basis entries").
  // Their rounding is part of the verified error. Setting names "cpca16b8", "cpca8b8".
  // Vector CPCA (encodeTransfer) ignores it: its basis vectors are binary16.
  int cpcaBasisBits = 16;
  // Matrix kCpca only. Largest N', basis matrices per cluster (0 .. 32, the encoder's limit
  // and the default). The client's per-vertex work when the lighting changes is linear in
  // 1 + N', so a renderer-bound user trades bytes (more clusters) for frame time with it
  // (docs/glossy.md). Setting names "cpca16b8n8@0.045": N' <= 8.
  int cpcaMaxVectors = 32;
};

// Parses a setting name: "f32", "f16", "q16", "q8", "cpca8", "cpca16", "cpca8b8",
// "cpca16b8" (8-bit basis entries, matrix transfer only), the CPCA ones optionally with a
// basis limit "n8" (N' <= 8, matrix transfer only) and a target, "cpca16b8n8@0.045". The unspecified fields come from `defaults`.
Status parseTransferSetting(std::string_view text, const TransferCodecSettings& defaults, TransferCodecSettings* out);

// The canonical name of a setting, as parseTransferSetting reads it ("q8", "cpca8@0.02").
std::string transferSettingName(const TransferCodecSettings& settings);

// What encodeTransfer produced, measured by decoding the blob it wrote.
struct TransferEncodeReport {
  std::size_t bytes = 0;            // blob size
  int clusters = 0;                 // CPCA cluster count; 0 for the other encodings
  std::vector<int> vectorsPerBand;  // CPCA principal vectors per band; empty otherwise
  double relativeError = 0.0;       // sqrt(sum (x' - x)^2 / sum x^2) over the whole transfer
  double maxAbsError = 0.0;         // max |x' - x| over the whole transfer
  int candidatesTried = 0;          // CPCA: (cluster count, parameters) candidates evaluated
};

// Largest magnitude of any transfer value an asset may hold, in every encoding (raw float32
// included): readers reject a pass that decodes, or could reconstruct, beyond it, so a
// damaged or hostile file cannot make exit radiance overflow to infinity. Physical transfer
// stays far below: |y_i| <= sqrt((2l+1)/4pi) <= 1.6 for l < 16, a cosine-weighted integral
// of it over a hemisphere is at most that, each bounce (albedo <= 1) adds at most as much
// again, and the paper's local weighting multiplies by at most 20 (docs/spatially-varying.md):
// 1.6 x 20 x (1 + 1024 bounces) < 33,000. It equals float16's largest value, so float16
// passes need no check of their own.
inline constexpr float kMaxTransferMagnitude = 65504.0f;

// Encodes `transfer` (vertexCount * channels * order^2 floats, [vertex][channel][coefficient],
// coefficient index l(l+1)+m) into *out (replaced). order 1..16, channels 1 or 3, 1 ..
// kMaxTransferVertices vertices, every value finite and |x| <= kMaxTransferMagnitude. `report`
// may be null. Errors: kInvalidArgument (bad order, channels, settings, |x| too large, a
// CPCA target that the weight precision cannot reach), kSizeMismatch, kNotFinite.
Status encodeTransfer(std::span<const float> transfer, int order, int channels, const TransferCodecSettings& settings,
                      std::vector<std::uint8_t>* out, TransferEncodeReport* report = nullptr);

// ---- Decoding ---------------------------------------------------------------------------

inline constexpr std::uint32_t kMaxTransferVertices = 1u << 28;
inline constexpr std::uint32_t kMaxTransferClusters = 65536;
inline constexpr std::uint16_t kTransferCodecVersionMajor = 1;
// Minor 1: matrix layout (header bytes 36..39); 2: 8-bit matrix CPCA basis entries (header
// byte 40). Each blob is written with the lowest minor version that holds it: vector blobs
// as 1.0, matrix blobs as 1.1 unless their basis is 8-bit.
inline constexpr std::uint16_t kTransferCodecVersionMinor = 2;

enum class TransferPartType : std::uint16_t {
  kClusters = 1,  // CPCA: the cluster id of every vertex
  kBand = 2,      // one SH band of every vertex (matrix layout: one shell)
  kWeights = 3,   // matrix CPCA: the step per cluster and the weights of every vertex (since 1.1)
};

struct TransferPartInfo {
  TransferPartType type = TransferPartType::kBand;
  int band = 0;              // kBand: l; kClusters: 0
  std::uint64_t offset = 0;  // from the start of the blob
  std::uint64_t size = 0;
  std::uint32_t crc = 0;     // CRC-32C of the part's bytes
};

struct TransferBlobInfo {
  std::uint16_t versionMajor = 0;
  std::uint16_t versionMinor = 0;
  TransferEncoding encoding = TransferEncoding::kFloat32;
  int weightBits = 0;  // CPCA: 8 or 16; 0 otherwise
  int order = 0;
  int channels = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t clusterCount = 0;  // CPCA: >= 1; 0 otherwise
  // 0 for vector transfer; for matrix transfer its packing (prt/transfer_matrix.h), and
  // `vectors` the CPCA basis matrices per cluster (0 otherwise).
  MatrixPacking packing{};
  bool matrix = false;
  int vectors = 0;
  // Matrix CPCA: bits per stored basis entry, 16 (binary16) or 8 (since 1.2); 0 otherwise.
  int basisBits = 0;
  std::uint64_t blobSize = 0;      // as the header declares it
  std::vector<TransferPartInfo> parts;  // in blob order: [clusters,] band 0, band 1, ...
  // How many leading bands have all their parts (and the cluster part) inside the bytes
  // given to readTransferBlobInfo: a prefix of the blob decodes that many bands.
  int bandsAvailable = 0;
};

// Reads and validates the header and the part table (magic, version, checksums, counts,
// the fixed part sequence and contiguous layout up to blobSize). `bytes` may be any prefix
// holding header and table (kTruncated otherwise); part payloads are not checked.
Status readTransferBlobInfo(std::span<const std::uint8_t> bytes, TransferBlobInfo* out);

// Decodes the first `bands` bands (1 .. order) into `out`, which must hold exactly
// vertexCount * channels * bands^2 floats, written [vertex][channel][coefficient] of an
// order-`bands` transfer. `bytes` is the blob or a prefix of it holding those bands' parts
// (bands == order: exactly the whole blob). Checks the checksum and every value of each part
// it uses; on error `out` holds unspecified values. Errors: kTruncated, kBadMagic,
// kBadVersion, kChecksumMismatch, kCorrupt (the message names the part and the problem),
// kInvalidArgument (bands out of range), kSizeMismatch (out). Temporary allocations stay
// below 8x the input size.
Status decodeTransfer(std::span<const std::uint8_t> bytes, int bands, std::span<float> out);

// Same, allocating *out (replaced on success, unchanged on error): vertexCount * channels *
// bands^2 floats, i.e. at most 4 * channels * bands^2 bytes per vertex, and every vertex
// takes at least one byte of the blob. Callers with a memory budget should check
// readTransferBlobInfo first and use the span overload.
Status decodeTransfer(std::span<const std::uint8_t> bytes, int bands, std::vector<float>* out);

// ---- CPCA for direct rendering (Sloan et al. 2003) ---------------------------------------
//
// Exit radiance of vertex v (cluster k) in channel c is sum over bands l of
//   L_l . mean_kl  +  sum_j weight_vlj * (L_l . basis_klj)
// where L_l holds the lighting's band-l coefficients of channel c: per frame the dot
// products are computed once per cluster and band, per vertex n'_l + 1 values are summed.

struct CpcaBand {
  int band = 0;
  int dims = 0;     // channels * (2l+1), index c*(2l+1) + (m+l)
  int vectors = 0;  // n'_l, 0 .. dims
  std::vector<float> means;    // clusterCount * dims
  std::vector<float> basis;    // clusterCount * vectors * dims ([cluster][vector][dim])
  std::vector<float> weights;  // vertexCount * vectors, dequantised: levels[i] * steps[cluster]
  // The stored form of the weights, for renderers that fold the step into the per-cluster
  // constants (web client): weight (v, j) = float(levels[v * vectors + j]) * steps[cluster of v].
  std::vector<float> steps;           // clusterCount
  std::vector<std::int16_t> levels;   // vertexCount * vectors, within +-(2^(weightBits-1) - 1)
};

struct CpcaTransfer {
  int order = 0;     // the blob's order
  int channels = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t clusterCount = 0;
  int weightBits = 8;                    // 8 or 16: the width of the stored levels
  std::vector<std::uint32_t> clusterOf;  // per vertex, < clusterCount
  std::vector<CpcaBand> bands;           // the decoded leading bands
};

// Decodes the cluster part and the first `bands` bands of a CPCA blob without expanding
// them (same checks, errors and prefix rule as decodeTransfer; kInvalidArgument for a
// blob of another encoding). decodeTransfer's result equals cpcaReconstruct of this.
Status decodeCpcaTransfer(std::span<const std::uint8_t> bytes, int bands, CpcaTransfer* out);

// Expands `cpca`'s bands into [vertex][channel][coefficient] floats of an order
// cpca.bands.size() transfer; out.size() must be vertexCount * channels * bands^2.
// x = mean + sum_j w_j basis_j, summed in j order in float (the decoder's exact arithmetic).
Status cpcaReconstruct(const CpcaTransfer& cpca, std::span<float> out);

}  // namespace prt

namespace prt {

// ---- Matrix transfer (glossy PRT; docs/transfer-codec.md "Matrices") ----------------------
//
// Per-vertex packed matrices (prt/transfer_matrix.h), [vertex][channel][packed entry]. Band
// b's part holds "shell" b: the entries of the order-(b+1) prefix beyond the order-b prefix,
// so the first b bands decode as the order-b leading block, exactly the truncation.
//   f32, f16, q16, q8: every shell stored like a vector band (planar, byte-split).
//   CPCA (Sloan et al. 2003 §4.1, over the whole matrix): vertices clustered, per cluster a
//   mean matrix and N' basis matrices spanning every channel and entry, per vertex a cluster
//   id and N' quantised weights; parts [clusters] [weights] [shell 0] [shell 1] ..., shell b
//   holding every cluster's mean and basis entries of that shell. The weights are shared by
//   all shells, so a band prefix reconstructs the leading block exactly.

// Encodes `packed` (vertexCount * channels * matrixEntryCount(order, packing) floats) into
// *out. order 1..kMaxMatrixOrder, channels 1 or 3, values finite and |x| <= kMaxTransferMagnitude.
// CPCA settings as for vectors (target relative RMS error over the whole matrix transfer).
// Bounded memory: temporary allocations stay within a small multiple of the input.
inline constexpr int kMaxMatrixOrder = 8;
Status encodeTransferMatrix(std::span<const float> packed, int order, MatrixPacking packing, int channels,
                            const TransferCodecSettings& settings, std::vector<std::uint8_t>* out,
                            TransferEncodeReport* report = nullptr);

// Decodes the first `bands` bands of a matrix blob into `out`, which must hold exactly
// vertexCount * channels * matrixEntryCount(bands, packing) floats. Same checks, errors and
// prefix rule as decodeTransfer; kInvalidArgument for a vector blob (and decodeTransfer
// returns kInvalidArgument for a matrix blob). Safe on untrusted input.
Status decodeTransferMatrix(std::span<const std::uint8_t> bytes, int bands, std::span<float> out);
Status decodeTransferMatrix(std::span<const std::uint8_t> bytes, int bands, std::vector<float>* out);

// A CPCA matrix blob unexpanded, for rendering from the compressed form (web client):
// exit radiance needs, per frame, every cluster's (1 + vectors) matrices times the lighting,
// then per vertex mean_k L + sum_j w_vj (B_kj L).
struct CpcaMatrixTransfer {
  int order = 0;     // the blob's order
  int bands = 0;     // leading bands decoded: matrices below are order-`bands` blocks
  int channels = 0;
  MatrixPacking packing = MatrixPacking::kFull;
  std::uint32_t vertexCount = 0;
  std::uint32_t clusterCount = 0;
  int weightBits = 8;
  int vectors = 0;                        // N', basis matrices per cluster
  int basisBits = 16;                     // how the blob stored the basis entries (16 or 8); `matrices` holds them decoded
  std::vector<std::uint32_t> clusterOf;   // per vertex, < clusterCount
  std::vector<float> steps;               // per cluster: weight (v, j) = levels[v * vectors + j] * steps[cluster of v]
  std::vector<std::int16_t> levels;       // vertexCount * vectors
  std::vector<float> weights;             // vertexCount * vectors, dequantised
  // [cluster][matrix 0..vectors][channel][packed entry], entry < matrixEntryCount(bands,
  // packing); matrix 0 is the cluster mean, 1..vectors the basis matrices.
  std::vector<float> matrices;
};

// Decodes the cluster and weight parts and the first `bands` shells (0 = every shell that
// has arrived). Same checks as decodeTransferMatrix; decodeTransferMatrix equals
// cpcaMatrixReconstruct of this.
Status decodeCpcaMatrixTransfer(std::span<const std::uint8_t> bytes, int bands, CpcaMatrixTransfer* out);

// Expands to [vertex][channel][packed entry] of order cpca.bands: x = mean + sum_j w_j B_j,
// summed in j order in float. out.size() = vertexCount * channels * matrixEntryCount(bands, packing).
Status cpcaMatrixReconstruct(const CpcaMatrixTransfer& cpca, std::span<float> out);

}  // namespace prt
