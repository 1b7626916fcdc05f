// The baked-scene asset: what the baker writes, the server serves and the client decodes.
// Byte layout, checksums and compatibility rules: docs/asset-format.md. Encoding and
// decoding work on memory only (the baker writes files, the server and browser fetch
// them), so the same code runs natively and in wasm. The reader treats its input as
// untrusted: every count, offset, size and checksum is checked before anything is read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "prt/glossy_lobe.h"
#include "prt/patch_placement.h"
#include "prt/status.h"
#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"
#include "prt/vec3.h"

namespace prt {

// Which transfer a pass holds (docs/sh-conventions.md, baker/transfer/transfer_bake.h).
enum class TransferKind : std::uint32_t {
  kUnshadowed = 0,
  kShadowed = 1,
  kInterreflected = 2,
};

// "unshadowed" | "shadowed" | "interreflected", or "unknown" for other values.
const char* transferKindName(TransferKind kind);

// Diffuse passes are SH vectors; glossy passes are SH matrices (docs/glossy.md) or, per texel,
// visibility vectors for the triple product (docs/transfer-textures.md, "Glossy by the triple
// product").
enum class TransferForm : std::uint32_t {
  kVector = 0,      // exit radiance = (albedo *) sum_i T_i L_i
  kMatrix = 1,      // transferred incident radiance M L, convolved with the glossy lobe at R
  kVisibility = 2,  // V_k = integral V(x, w) [n.w > 0] y_k(w) dw at its own order (TransferPass::order);
                    // transferred incident radiance P(L) V (prt::tpflGlossyExitRadiance); texel, shadowed, 1 channel
};

// "vector" | "matrix" | "visibility", or "unknown".
const char* transferFormName(TransferForm form);

// Where a pass's transfer lives (docs/transfer-textures.md).
enum class TransferDomain : std::uint32_t {
  kVertex = 0,  // one transfer per vertex, interpolated across each triangle
  kTexel = 1,   // one per texel of the asset's atlases (PRTT), filtered bilinearly at the
                // atlas UV; vector and visibility passes (no matrices)
};

// "vertex" | "texel", or "unknown".
const char* transferDomainName(TransferDomain domain);

struct TransferPass {
  TransferKind kind = TransferKind::kUnshadowed;
  // 1: scalar transfer, exit radiance = albedo * sum_i T_i L_i (unshadowed, shadowed);
  // 3: RGB transfer with albedo folded in, exit radiance_c = sum_i T_ci L_ci (interreflected).
  int channels = 1;
  int bounces = 0;  // interreflection bounces actually gathered; 0 for the other kinds
  // Vectors: vertexCount * channels * order*order floats, [vertex][channel][coefficient].
  // Matrices: vertexCount * channels * matrixEntryCount(order, packing) floats,
  // [vertex][channel][packed entry] (prt/transfer_matrix.h), packing = matrixPackingFor(kind,
  // lighting model). A matrix maps lighting to transferred incident radiance: no albedo, and
  // 1 channel (shadowed: visibility has no colour) or 3 (interreflected: senders' colours).
  std::vector<float> coeffs;
  // When non-empty: the pass as a transfer-codec blob (prt/transfer_codec.h), which the
  // writer stores as a kEncodedTransfer section instead of the floats (coeffs are then
  // ignored by checkAsset/encodeAsset). decodeAsset fills both: coeffs with the blob's
  // full decode, encoded with the blob's bytes.
  std::vector<std::uint8_t> encoded;
  TransferForm form = TransferForm::kVector;  // last, so that {kind, channels, bounces, coeffs} still reads
  // kTexel: coeffs is [texel][channel][coefficient] over every texel of the asset's atlases,
  // atlas after atlas, texel y * width + x within one (BakedAsset::texelCoverage's order),
  // unused texels included (0, or a gutter's dilated value).
  TransferDomain domain = TransferDomain::kVertex;
  // kVisibility: the visibility vector's own bands m (kMinVisibilityOrder..kMaxShOrder; 2n - 1
  // for lighting of order n makes TPFL glossy exact), coeffs [texel][coefficient] with m^2 per
  // texel. 0 for the other forms, whose order is the asset's. Last, like form and domain.
  int order = 0;
};

// The smallest visibility order a pass may have: one band carries no direction at all.
inline constexpr int kMinVisibilityOrder = 2;

// One transfer-texture atlas: a width x height texture covering a contiguous run of the
// asset's triangles (a texture set, PRTT §4.3: one per object or material group).
struct TextureAtlas {
  std::uint32_t width = 0, height = 0;                  // texels, 1..kMaxAssetAtlasSize
  std::uint32_t firstTriangle = 0, triangleCount = 0;  // triangles [first, first + count)
};

// Per-texel coverage values (BakedAsset::texelCoverage).
enum class TexelCoverage : std::uint8_t {
  kEmpty = 0,    // no triangle reaches it and no gutter fill: transfer 0
  kSampled = 1,  // a surface sample was baked here (baker/texture/texel_raster.h)
  kGutter = 2,   // filled by dilation from sampled neighbours, for bilinear filtering
};

// How the transfer is parameterised by the lighting it is multiplied with
// (docs/spatially-varying.md). Every model takes the same lighting vector: the SH of the
// radiance seen from `center`, as a cube map rendered there captures it.
enum class LightingModel : std::uint32_t {
  kDistant = 0,      // lighting at infinity, indexed by direction (Sloan 2002); center/radius unused
  kLocalSphere = 1,  // radiance on the sphere (center, radius), emitted inward as a Lambertian
                     // surface: the area form with cos(theta') (our reading of Fujita & Kanai §3.1)
  kLocalSpherePaper = 2,  // Fujita & Kanai 2004 §3.1 as printed: cos(theta') left out
};

// "distant" | "local-sphere" | "local-sphere-paper", or "unknown" for other values.
const char* lightingModelName(LightingModel model);

struct LightingInfo {
  LightingModel model = LightingModel::kDistant;
  Vec3 center{};       // world units; the point c the client renders its light cube map from
  float radius = 0.0f; // r > 0 for the local models, 0 for distant
};

// True for the local models (kLocalSphere, kLocalSpherePaper).
bool isLocalLighting(LightingModel model);

// How a matrix pass of `kind` is packed under `model`: symmetric for distant unshadowed and
// shadowed matrices (integral V y_i y_j), full otherwise (bounces, and local lighting, whose
// columns are basis functions of the remapped direction).
MatrixPacking matrixPackingFor(TransferKind kind, LightingModel model);

// Ok when `lighting` is valid in an asset: a known model; for the local models a finite
// centre and a finite radius > 0; for distant, centre and radius +0.0 (they mean nothing
// there, and one encoding per meaning keeps files comparable). Errors:
// kInvalidArgument, or kNotFinite for NaN/infinity; the message starts with "lighting".
Status checkLightingInfo(const LightingInfo& lighting);

struct BakedAsset {
  int shOrder = 0;  // kMinShOrder..kMaxShOrder (the baker uses 2..8)
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;         // one per position
  std::vector<Rgb> albedo;           // one per position, linear
  std::vector<std::uint32_t> indices;  // 3 per triangle, each < positions.size()
  std::vector<TransferPass> passes;  // 1..kMaxAssetPasses, at most one per (kind, form, domain); order is kept
  // One per position when the asset has a matrix or visibility pass (the glossy material), else empty.
  std::vector<SpecularMaterial> specular;
  // Bake metadata. samples and seed are 64-bit because the baker's options are
  // (BakeOptions::samples is a size_t, ::seed a uint64_t); narrowing would lose the seed.
  std::uint64_t samples = 0;
  std::uint64_t seed = 0;
  std::string sampling;  // "hammersley" | "stratified" (any isValidAssetSamplingName string)
  std::string name;      // for catalogues and logs (isValidAssetName)
  LightingInfo lighting;  // files without a lighting section decode as distant
  // Transfer textures, all empty unless a pass has domain kTexel (then all required):
  // atlasUv: 2 floats per vertex, u right and v down from the texture's top-left (glTF), in
  // [0, 1]; texel (x, y) of an atlas covers uv in [x, x+1)/width x [y, y+1)/height.
  // atlases: in triangle order, covering every triangle exactly once.
  // texelCoverage: one TexelCoverage per texel of every atlas, atlas after atlas, row-major.
  std::vector<float> atlasUv;
  std::vector<TextureAtlas> atlases;
  std::vector<std::uint8_t> texelCoverage;
  // The shading normal per texel where normal maps turned it (PRTT §6.2), for the glossy term's
  // reflection direction and Schlick's n.v: empty, or 2 per texel (texelCoverage's order),
  // octahedral snorm16 codes (prt/octahedral_normal.h), never -32768, (0, 0) at empty texels.
  // The baker writes it only when some texel's material has a normal map (docs/asset-format.md).
  std::vector<std::int16_t> texelNormals;
  // Bi-scale radiance transfer (Sloan et al. 2003; docs/bi-scale.md), all three empty or all
  // set, and set only with a vertex matrix pass (the macro scale): `rtt` a whole RTT file
  // (prt/rtt.h, decodeRtt) of order <= shOrder; `tangents` one per vertex, unit, orthogonal to
  // the vertex normal (the patch's +x; its +y is cross(normal, tangent)); `patchUv` 2 floats per
  // vertex, the parametric id map: the patch position is fract(patchUv), in patch widths, left
  // unwrapped so it interpolates across a triangle, |value| <= kMaxPatchCoordinate.
  std::vector<std::uint8_t> rtt;
  std::vector<Vec3> tangents;
  std::vector<float> patchUv;
  // Or, instead of patchUv, the synthesised id map (docs/bi-scale.md, "Synthesised id map"):
  // 1..kMaxPatchPlacements placements (finite) and a placement index (< the placement count, or
  // kNoPlacement) per texel of the asset's atlases (texelCoverage's order; the atlas sections
  // then come with it, texel passes or not) or, with idMapPerTriangle, per triangle.
  std::vector<PatchPlacement> patchPlacements;
  std::vector<std::uint16_t> idMap;
  bool idMapPerTriangle = false;
};

// The largest |patch coordinate| an asset may hold: float keeps 2^-11 patch widths there,
// 1/32 of a 64-sample RTT's spacing.
inline constexpr float kMaxPatchCoordinate = 4096.0f;
// How far a bi-scale tangent may be from unit length and from orthogonal to its normal.
inline constexpr float kTangentTolerance = 1e-3f;

// Texels of all atlases together (sum of width x height); 0 without atlases.
std::uint64_t assetTexelCount(const BakedAsset& asset);

// Returns the vector pass of `kind`, or nullptr if the asset has none.
const TransferPass* findPass(const BakedAsset& asset, TransferKind kind);
// Returns the pass of `kind` and `form`, or nullptr.
const TransferPass* findPass(const BakedAsset& asset, TransferKind kind, TransferForm form);
// Returns the pass of `kind`, `form` and `domain`, or nullptr.
const TransferPass* findPass(const BakedAsset& asset, TransferKind kind, TransferForm form, TransferDomain domain);

// ---- Format constants (docs/asset-format.md) -------------------------------------------

inline constexpr std::uint8_t kAssetMagic[4] = {'P', 'R', 'T', 'A'};
inline constexpr std::uint16_t kAssetVersionMajor = 1;  // incompatible layout changes bump this
// New section types bump this (1: lighting, 2: encoded transfer, 3: matrices, specular,
// 4: transfer textures: atlas uv, atlases, texel coverage, texel transfer float32 and encoded,
// 5: texel visibility float32 and encoded, for TPFL glossy, 6: texel normals, 7: bi-scale:
// tangents, patch uv, RTT).
inline constexpr std::uint16_t kAssetVersionMinor = 7;
inline constexpr std::size_t kAssetHeaderSize = 64;
inline constexpr std::size_t kAssetSectionEntrySize = 40;
inline constexpr std::size_t kAssetAlignment = 16;  // every section offset is a multiple of this

// Limits chosen so that every size the reader derives (count * stride) fits in 64 bits
// with room to spare, and so that no field can make a reader allocate absurd memory.
inline constexpr std::uint32_t kMaxAssetVertices = 1u << 28;
inline constexpr std::uint32_t kMaxAssetTriangles = 1u << 28;
inline constexpr std::uint32_t kMaxAssetSections = 1024;
inline constexpr std::uint32_t kMaxAssetBounces = 1024;
inline constexpr std::size_t kMaxAssetNameBytes = 4096;
inline constexpr std::size_t kMaxAssetSamplingBytes = 32;
// A prefix this long always holds the header, table, metadata and lighting of files
// encodeAsset writes (it places those two sections first), which is all peekAssetHeader reads.
inline constexpr std::size_t kAssetPeekPrefixSize = 64 * 1024;

enum class AssetSectionType : std::uint32_t {
  // 0 is reserved: a zeroed table entry is rejected rather than skipped as unknown.
  kPositions = 1,  // float32 x,y,z per vertex
  kNormals = 2,    // float32 x,y,z per vertex
  kIndices = 3,    // uint32 per index, 3 per triangle
  kAlbedo = 4,     // float32 r,g,b per vertex
  kTransfer = 5,   // float32 coefficients; arg0 kind, arg1 channels, arg2 bounces
  kMetadata = 6,   // bytes: samples, seed, sampling, name
  kLighting = 7,   // bytes: lighting model, centre, radius (since 1.1; absent = distant)
  kEncodedTransfer = 8,  // bytes: a transfer codec blob (prt/transfer_codec.h, docs/transfer-codec.md);
                         // arg0 kind, arg1 channels, arg2 bounces, as kTransfer (since 1.2)
  kMatrixTransfer = 9,   // float32 packed matrices (prt/transfer_matrix.h), [vertex][channel][entry];
                         // arg0 kind, arg1 channels, arg2 bounces; packing by matrixPackingFor (since 1.3)
  kEncodedMatrixTransfer = 10,  // bytes: a transfer codec blob of matrix layout; args as kMatrixTransfer (since 1.3)
  kSpecular = 11,        // float32 f0 r, g, b, f90, exponent per vertex; required with a matrix pass (since 1.3)
  // Transfer textures (since 1.4; docs/asset-format.md "Transfer textures"):
  kAtlasUv = 12,         // float32 u, v per vertex; required with a texel pass
  kAtlases = 13,         // bytes: u32 width, height, firstTriangle, triangleCount per atlas; arg0 atlas count
  kTexelCoverage = 14,   // bytes: one TexelCoverage per texel, atlases in order
  kTexelTransfer = 15,   // float32 [texel][channel][coefficient]; args as kTransfer
  kEncodedTexelTransfer = 16,  // bytes: a transfer codec blob with texels as its "vertices"; args as kTransfer
  // TPFL glossy visibility (since 1.5): arg0 kind (shadowed), arg1 channels (1), arg2 its order m.
  kTexelVisibility = 17,         // float32 [texel][coefficient], m^2 per texel; needs specular and the atlases
  kEncodedTexelVisibility = 18,  // bytes: a transfer codec blob of order m, 1 channel, texels as rows
  // Normal-mapped shading normals (since 1.6): 2 snorm16 octahedral codes per texel; only with the atlases.
  kTexelNormals = 19,
  // Bi-scale radiance transfer (since 1.7; docs/asset-format.md "Bi-scale"): all three or none,
  // only with a vertex matrix pass.
  kTangents = 20,  // float32 x, y, z per vertex: unit, orthogonal to the normal
  kPatchUv = 21,   // float32 u, v per vertex: patch coordinates (the parametric id map)
  kRtt = 22,       // bytes: a whole RTT file (prt/rtt.h), its own checksum included
  kPatchPlacements = 23,  // float32 origin, axisU, axisV (9 floats) per placement; arg0 the count
  kIdMap = 24,            // bytes: u16 placement index per atlas texel (arg0 0) or per triangle (arg0 1)
};

// Bytes per texel of the texel normals section: int16 x, y (octahedral, snorm16).
inline constexpr std::size_t kAssetTexelNormalBytes = 4;

// Transfer-texture limits: an atlas side as large as common GPUs' maximum texture size, and
// totals that keep every derived size (texels x channels x coefficients x 4) far from overflow.
inline constexpr std::uint32_t kMaxAssetAtlasSize = 16384;
inline constexpr std::uint32_t kMaxAssetAtlases = 1024;
inline constexpr std::uint64_t kMaxAssetTexels = 1ull << 28;
// At most one pass per (kind, form, domain): 3 vector + 3 matrix vertex passes, 3 texel vector
// passes and the one texel visibility pass (shadowed only).
inline constexpr std::size_t kMaxAssetPasses = 10;

// Bytes per placement of the patch placements section: float32 origin, axisU, axisV.
inline constexpr std::size_t kAssetPlacementBytes = 36;

// Bytes per vertex of the specular section: float32 f0 r, g, b, f90, exponent.
inline constexpr std::size_t kAssetSpecularBytesPerVertex = 20;

// Bytes per atlas of the atlases section, and the u32 fields' offsets in one.
inline constexpr std::size_t kAssetAtlasEntryBytes = 16;
namespace asset_atlas_layout {
inline constexpr std::size_t kWidth = 0;
inline constexpr std::size_t kHeight = 4;
inline constexpr std::size_t kFirstTriangle = 8;
inline constexpr std::size_t kTriangleCount = 12;
}  // namespace asset_atlas_layout

// Size and field offsets of the lighting section's payload (docs/asset-format.md).
inline constexpr std::size_t kAssetLightingBytes = 20;
namespace asset_lighting_layout {
inline constexpr std::size_t kModel = 0;    // u32 LightingModel
inline constexpr std::size_t kCenterX = 4;  // f32
inline constexpr std::size_t kCenterY = 8;  // f32
inline constexpr std::size_t kCenterZ = 12; // f32
inline constexpr std::size_t kRadius = 16;  // f32
}  // namespace asset_lighting_layout

enum class AssetElementFormat : std::uint32_t {
  kFloat32 = 1,  // IEEE-754 binary32, little-endian
  kUint32 = 2,   // little-endian
  kBytes = 3,    // a structure of its own, described with its section type
};

// Byte offsets of the fixed header fields and of the fields inside one section-table entry.
namespace asset_layout {
inline constexpr std::size_t kMagic = 0;           // 4 bytes "PRTA"
inline constexpr std::size_t kVersionMajor = 4;    // u16
inline constexpr std::size_t kVersionMinor = 6;    // u16
inline constexpr std::size_t kFlags = 8;           // u32, 0 in version 1
inline constexpr std::size_t kShOrder = 12;        // u32
inline constexpr std::size_t kVertexCount = 16;    // u32
inline constexpr std::size_t kTriangleCount = 20;  // u32
inline constexpr std::size_t kSectionCount = 24;   // u32
inline constexpr std::size_t kTableCrc = 28;       // u32, CRC-32C of the whole section table
inline constexpr std::size_t kFileSize = 32;       // u64
inline constexpr std::size_t kReserved = 40;       // 20 bytes, 0
inline constexpr std::size_t kHeaderCrc = 60;      // u32, CRC-32C of header bytes 0..59

inline constexpr std::size_t kEntryType = 0;     // u32 AssetSectionType
inline constexpr std::size_t kEntryFormat = 4;   // u32 AssetElementFormat
inline constexpr std::size_t kEntryOffset = 8;   // u64, from the start of the file
inline constexpr std::size_t kEntrySize = 16;    // u64, payload bytes
inline constexpr std::size_t kEntryArg0 = 24;    // u32, meaning depends on the type
inline constexpr std::size_t kEntryArg1 = 28;    // u32
inline constexpr std::size_t kEntryArg2 = 32;    // u32
inline constexpr std::size_t kEntryCrc = 36;     // u32, CRC-32C of the payload
}  // namespace asset_layout

// ---- Validation, encoding, decoding ---------------------------------------------------

// True for names encodeAsset accepts: at most kMaxAssetNameBytes of well-formed UTF-8 with
// no control characters, so a catalogue can put it in JSON or a log line as it is.
bool isValidAssetName(std::string_view name);
// True for at most kMaxAssetSamplingBytes of [a-z0-9_-] (empty allowed): an identifier,
// not free text, so tools can switch on it.
bool isValidAssetSamplingName(std::string_view sampling);

// Ok when `asset` can be encoded: order in range, 1..kMaxAssetVertices vertices with as
// many normals and albedos, 1..kMaxAssetTriangles triangles with every index in range,
// every float finite, 1..kMaxAssetPasses passes of distinct valid (kind, form, domain) with
// channels 1 or 3, bounces 0 except for interreflection, coefficient counts matching, valid
// name and sampling, and valid lighting (checkLightingInfo). With a matrix or visibility pass:
// one specular material per vertex, f0 and f90 in [0, 1] and exponent finite and >= 0;
// without one, no specular materials. Texel passes are vector or visibility form, with
// assetTexelCount as their vertex count; a visibility pass is shadowed, 1 channel, order
// kMinVisibilityOrder..kMaxShOrder with order^2 coefficients per texel (other passes have
// order 0), under distant lighting (TPFL is a product with distant light). With a texel pass: 1..kMaxAssetAtlases atlases of sides 1..kMaxAssetAtlasSize covering the
// triangles contiguously in order, at most kMaxAssetTexels texels, atlasUv 2 per vertex in
// [0, 1], texelCoverage one value (0, 1 or 2) per texel; without one, all three empty.
// texelNormals empty, or (with a texel pass) 2 codes per texel, none -32768, (0, 0) at empty texels.
// rtt, tangents, patchUv, patchPlacements and idMap all empty, or (with a vertex matrix pass)
// an RTT decodeRtt accepts of order <= shOrder, a tangent per vertex within kTangentTolerance
// of unit and orthogonal to its normal, and either 2 patch coordinates per vertex, finite,
// |x| <= kMaxPatchCoordinate, or the synthesised id map: finite placements and one index per
// atlas texel (the atlas data then required even without a texel pass).
Status checkAsset(const BakedAsset& asset);

// Validates `asset` (checkAsset) and replaces *out with its encoding.
Status encodeAsset(const BakedAsset& asset, std::vector<std::uint8_t>* out);

struct AssetPassInfo {
  TransferKind kind = TransferKind::kUnshadowed;
  int channels = 0;
  int bounces = 0;
  bool encoded = false;       // a codec blob (types 8, 10, 16) rather than float32
  std::uint64_t bytes = 0;    // the section's payload size
  std::uint32_t section = 0;  // its index in the section table
  TransferForm form = TransferForm::kVector;
  TransferDomain domain = TransferDomain::kVertex;
  int order = 0;  // kVisibility: the visibility vector's bands (the section's arg2); else 0
};

// One entry of the section table, as validated by the reader (offsets from the file start).
struct AssetSectionInfo {
  std::uint32_t type = 0;    // AssetSectionType value (unknown types included)
  std::uint32_t format = 0;  // AssetElementFormat value
  std::uint64_t offset = 0, size = 0;
  std::uint32_t arg0 = 0, arg1 = 0, arg2 = 0;
  std::uint32_t crc = 0;     // CRC-32C of the payload
};

// What a catalogue needs to list an asset without decoding it.
struct AssetSummary {
  std::uint16_t versionMajor = 0;
  std::uint16_t versionMinor = 0;
  int shOrder = 0;
  std::uint32_t vertexCount = 0;
  std::uint32_t triangleCount = 0;
  std::uint32_t sectionCount = 0;  // including sections of types this reader skips
  std::uint64_t fileSize = 0;      // as the header declares it; compare with the real size
  std::vector<AssetPassInfo> passes;  // in table order
  // Texels of all atlases (the texel coverage section's size, one byte per texel); 0 without
  // texel passes. The atlases themselves: decodeAssetAtlases.
  std::uint64_t texelCount = 0;
  std::uint64_t samples = 0;
  std::uint64_t seed = 0;
  std::string sampling;
  std::string name;
  LightingInfo lighting;  // distant when the file has no lighting section
  std::vector<AssetSectionInfo> sections;  // the whole table, in table order
  std::uint64_t tableEnd = 0;  // end of header + table (before padding): where payloads may start
};

// Reads the header, section table, metadata and (if present) lighting sections and
// validates them (magic, version, checksums of header, table, metadata and lighting, every
// table entry's bounds against the declared file size, alignment, overlaps, required
// sections, sizes against counts) without touching the other sections. `bytes` is the
// whole file or any prefix of it holding those parts (kAssetPeekPrefixSize suffices for
// files encodeAsset wrote); kTruncated when it is too short. Does not check the other sections' checksums or
// contents: use verifyAsset for that.
Status peekAssetHeader(std::span<const std::uint8_t> bytes, AssetSummary* out);

// Validates the whole file as decodeAsset does, every checksum and every value, without
// allocating the arrays. `out` (may be null) receives the summary on success.
Status verifyAsset(std::span<const std::uint8_t> bytes, AssetSummary* out);

// Validates `bytes` (the whole file) completely and decodes it into *out, which is left
// unchanged on error. Errors: kTruncated (file shorter than its structure says), kBadMagic,
// kBadVersion (a major version this reader does not know), kChecksumMismatch, kCorrupt
// (anything else; the message names the section and the problem). Never reads outside
// `bytes`, and allocates no more than about the file's size.
Status decodeAsset(std::span<const std::uint8_t> bytes, BakedAsset* out);

// ---- Progressive decoding (a client that fetches the file piece by piece) ---------------
//
// `file` is a buffer of the declared file size (summary.fileSize, from peekAssetHeader on
// its first bytes) in which only some byte ranges have arrived; the functions below read
// only the ranges they name, check those ranges' checksums and values, and never read
// outside `file`. Safe on untrusted input, like decodeAsset.

// Decodes positions, normals, albedo, indices, metadata and lighting (their sections must
// have arrived) into *out with no passes; out->shOrder is the header's order.
Status decodeAssetGeometry(std::span<const std::uint8_t> file, BakedAsset* out);

// Decodes transfer pass `pass` (an index into AssetSummary::passes, table order) into *out, using only the
// bytes of that pass's section. A float32 section must have arrived whole; an encoded one
// may hold only the codec's header and the parts of its first `bands` bands (the bands the
// caller knows have arrived; 0 = all of them), and decodes as an order-`bands` pass (out->coeffs has
// channels * bands^2 floats per vertex, or per texel for a texel pass, whose texel count is the
// coverage section's size; *bandsDecoded says how many). For a visibility pass `bands` counts
// the vector's own bands (0..out->order, its order m, not the header's): the first b bands of V.
// out->encoded is left empty.
Status decodeAssetPass(std::span<const std::uint8_t> file, int pass, int bands, TransferPass* out, int* bandsDecoded);

// Like decodeAssetPassCpca for an encoded CPCA matrix pass (kEncodedMatrixTransfer): *out gets
// the cluster ids, the per-vertex weights and the first `bands` bands' shells of every
// cluster's mean and basis matrices. Safe on untrusted input.
Status decodeAssetPassCpcaMatrix(std::span<const std::uint8_t> file, int pass, int bands, CpcaMatrixTransfer* out,
                                 TransferPass* info);

// Decodes the atlas uv, atlases, texel coverage and (if the file has one) texel normals
// sections (they must have arrived) into out->atlasUv, out->atlases, out->texelCoverage and
// out->texelNormals, leaving the rest of *out alone; all empty for a file without texel passes,
// texelNormals empty for one without normals. *out is unchanged on error. Safe on untrusted input.
Status decodeAssetAtlases(std::span<const std::uint8_t> file, BakedAsset* out);

// Decodes the bi-scale sections (tangents, patch uv, RTT; they must have arrived) into
// out->tangents, out->patchUv and out->rtt, leaving the rest of *out alone; all empty for a file
// without them. *out is unchanged on error. Safe on untrusted input (the RTT is decoded and
// checked whole: decodeRtt).
Status decodeAssetBiScale(std::span<const std::uint8_t> file, BakedAsset* out);

// Decodes the specular section (it must have arrived) into *out, one per vertex; empty when
// the file has none. Safe on untrusted input.
Status decodeAssetSpecular(std::span<const std::uint8_t> file, std::vector<SpecularMaterial>* out);

// Like decodeAssetPass for an encoded CPCA pass, but unexpanded (for rendering straight from
// the compressed form): *out gets the cluster ids and the first `bands` bands (0 = every band
// that has arrived), *info the pass's kind, channels and bounces (no coefficients).
// kInvalidArgument for a float32 pass or a blob of another encoding. Texel passes (type 16)
// work the same, with one row per texel instead of per vertex, and so does an encoded
// visibility pass (type 18), whose bands are its own (0..m). Safe on untrusted input.
Status decodeAssetPassCpca(std::span<const std::uint8_t> file, int pass, int bands, CpcaTransfer* out, TransferPass* info);

}  // namespace prt
