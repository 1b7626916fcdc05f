// Asset decoding and validation of untrusted bytes (layout: docs/asset-format.md).
//
// Order of trust: magic and version first (so a wrong file or a newer format gets its own
// error), then the header checksum before any header field is used, then the table
// checksum before any entry is used, then every entry's bounds against the file, then each
// section's checksum before its payload is interpreted. All offset and size arithmetic is
// done in 64 bits after checks that rule out overflow, so it is also right in wasm, where
// size_t is 32 bits.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "prt/asset.h"
#include "prt/asset_bi_scale.h"
#include "prt/checksum.h"
#include "prt/little_endian.h"
#include "prt/octahedral_normal.h"
#include "prt/transfer_codec.h"
#include "prt/sh_basis.h"

namespace prt {
namespace {

namespace L = asset_layout;

std::string hex32(std::uint32_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s = "0x00000000";
  for (int i = 0; i < 8; ++i) s[9 - i] = kDigits[(v >> (4 * i)) & 0xFu];
  return s;
}

std::string num(std::uint64_t v) { return std::to_string(v); }

struct Entry {
  std::uint32_t index = 0;  // position in the table
  std::uint32_t type = 0, format = 0;
  std::uint64_t offset = 0, size = 0;
  std::uint32_t arg0 = 0, arg1 = 0, arg2 = 0, crc = 0;
};

struct Parsed {
  std::uint16_t major = 0, minor = 0;
  std::uint32_t order = 0, vertexCount = 0, triangleCount = 0, sectionCount = 0;
  std::uint64_t fileSize = 0;
  std::vector<Entry> entries;  // table order
  int positions = -1, normals = -1, indices = -1, albedo = -1, metadata = -1;
  int lighting = -1;  // optional (format 1.1); absent means distant
  int specular = -1;  // required exactly when a matrix section exists (format 1.3)
  // Transfer textures (format 1.4): each required exactly once with a texel pass, else absent.
  int atlasUv = -1, atlases = -1, coverage = -1;
  int texelNormals = -1;  // optional (format 1.6), only with the atlas sections
  // Bi-scale (format 1.7), with a vertex matrix pass: tangents and RTT, and either patch uv or
  // the synthesised id map (placements and id map, with the atlas sections).
  int tangents = -1, patchUv = -1, rtt = -1, placements = -1, idMap = -1;
  bool idMapPerTriangle = false;  // the id map section's arg0
  std::uint64_t texelCount = 0;  // the coverage section's size (1 byte per texel); 0 without one
  std::vector<int> transfer;  // entry indices, table order (vector, matrix and texel passes)
};

// What the small sections hold: the metadata and the lighting.
struct Metadata {
  std::uint64_t samples = 0, seed = 0;
  std::string sampling, name;
  LightingInfo lighting;
};

constexpr std::uint32_t kTypePositions = static_cast<std::uint32_t>(AssetSectionType::kPositions);
constexpr std::uint32_t kTypeNormals = static_cast<std::uint32_t>(AssetSectionType::kNormals);
constexpr std::uint32_t kTypeIndices = static_cast<std::uint32_t>(AssetSectionType::kIndices);
constexpr std::uint32_t kTypeAlbedo = static_cast<std::uint32_t>(AssetSectionType::kAlbedo);
constexpr std::uint32_t kTypeTransfer = static_cast<std::uint32_t>(AssetSectionType::kTransfer);
constexpr std::uint32_t kTypeMetadata = static_cast<std::uint32_t>(AssetSectionType::kMetadata);
constexpr std::uint32_t kTypeLighting = static_cast<std::uint32_t>(AssetSectionType::kLighting);
constexpr std::uint32_t kTypeEncodedTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedTransfer);
constexpr std::uint32_t kTypeMatrixTransfer = static_cast<std::uint32_t>(AssetSectionType::kMatrixTransfer);
constexpr std::uint32_t kTypeEncodedMatrixTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedMatrixTransfer);
constexpr std::uint32_t kTypeSpecular = static_cast<std::uint32_t>(AssetSectionType::kSpecular);
constexpr std::uint32_t kTypeAtlasUv = static_cast<std::uint32_t>(AssetSectionType::kAtlasUv);
constexpr std::uint32_t kTypeAtlases = static_cast<std::uint32_t>(AssetSectionType::kAtlases);
constexpr std::uint32_t kTypeTexelCoverage = static_cast<std::uint32_t>(AssetSectionType::kTexelCoverage);
constexpr std::uint32_t kTypeTexelTransfer = static_cast<std::uint32_t>(AssetSectionType::kTexelTransfer);
constexpr std::uint32_t kTypeEncodedTexelTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedTexelTransfer);
constexpr std::uint32_t kTypeTexelVisibility = static_cast<std::uint32_t>(AssetSectionType::kTexelVisibility);
constexpr std::uint32_t kTypeEncodedTexelVisibility = static_cast<std::uint32_t>(AssetSectionType::kEncodedTexelVisibility);
constexpr std::uint32_t kTypeTexelNormals = static_cast<std::uint32_t>(AssetSectionType::kTexelNormals);
constexpr std::uint32_t kTypeTangents = static_cast<std::uint32_t>(AssetSectionType::kTangents);
constexpr std::uint32_t kTypePatchUv = static_cast<std::uint32_t>(AssetSectionType::kPatchUv);
constexpr std::uint32_t kTypeRtt = static_cast<std::uint32_t>(AssetSectionType::kRtt);
constexpr std::uint32_t kTypePatchPlacements = static_cast<std::uint32_t>(AssetSectionType::kPatchPlacements);
constexpr std::uint32_t kTypeIdMap = static_cast<std::uint32_t>(AssetSectionType::kIdMap);

bool isMatrixType(std::uint32_t type) { return type == kTypeMatrixTransfer || type == kTypeEncodedMatrixTransfer; }
bool isVisibilityType(std::uint32_t type) { return type == kTypeTexelVisibility || type == kTypeEncodedTexelVisibility; }
// Texel passes: vector (15, 16) and visibility (17, 18) sections, one row per texel.
bool isTexelType(std::uint32_t type) {
  return type == kTypeTexelTransfer || type == kTypeEncodedTexelTransfer || isVisibilityType(type);
}
bool isEncodedType(std::uint32_t type) {
  return type == kTypeEncodedTransfer || type == kTypeEncodedMatrixTransfer || type == kTypeEncodedTexelTransfer ||
         type == kTypeEncodedTexelVisibility;
}
TransferForm formOf(std::uint32_t type) {
  return isMatrixType(type) ? TransferForm::kMatrix : isVisibilityType(type) ? TransferForm::kVisibility : TransferForm::kVector;
}
constexpr std::uint32_t kFormatFloat32 = static_cast<std::uint32_t>(AssetElementFormat::kFloat32);
constexpr std::uint32_t kFormatUint32 = static_cast<std::uint32_t>(AssetElementFormat::kUint32);
constexpr std::uint32_t kFormatBytes = static_cast<std::uint32_t>(AssetElementFormat::kBytes);
constexpr std::uint64_t kMetadataFixedBytes = 24;

// "section 3 (indices)", "section 5 (transfer shadowed)", "section 7 (type 99)": every
// error about a section names it by table position and meaning.
std::string sectionLabel(const Entry& e) {
  std::string s = "section " + num(e.index) + " (";
  switch (e.type) {
    case kTypePositions: s += "positions"; break;
    case kTypeNormals: s += "normals"; break;
    case kTypeIndices: s += "indices"; break;
    case kTypeAlbedo: s += "albedo"; break;
    case kTypeTransfer:
    case kTypeEncodedTransfer:
    case kTypeMatrixTransfer:
    case kTypeEncodedMatrixTransfer:
    case kTypeTexelTransfer:
    case kTypeEncodedTexelTransfer:
    case kTypeTexelVisibility:
    case kTypeEncodedTexelVisibility:
      s += isEncodedType(e.type) ? "encoded " : "";
      s += isMatrixType(e.type) ? "matrix " : "";
      s += isTexelType(e.type) ? "texel " : "";
      if (isVisibilityType(e.type)) {  // "texel visibility shadowed"
        s += e.arg0 <= 2 ? std::string("visibility ") + transferKindName(static_cast<TransferKind>(e.arg0))
                         : "visibility kind " + num(e.arg0);
        break;
      }
      s += e.arg0 <= 2 ? std::string("transfer ") + transferKindName(static_cast<TransferKind>(e.arg0))
                       : "transfer kind " + num(e.arg0);
      break;
    case kTypeMetadata: s += "metadata"; break;
    case kTypeLighting: s += "lighting"; break;
    case kTypeSpecular: s += "specular"; break;
    case kTypeAtlasUv: s += "atlas uv"; break;
    case kTypeAtlases: s += "atlases"; break;
    case kTypeTexelCoverage: s += "texel coverage"; break;
    case kTypeTexelNormals: s += "texel normals"; break;
    case kTypeTangents: s += "tangents"; break;
    case kTypePatchUv: s += "patch uv"; break;
    case kTypeRtt: s += "RTT"; break;
    case kTypePatchPlacements: s += "patch placements"; break;
    case kTypeIdMap: s += "id map"; break;
    default: s += "type " + num(e.type); break;
  }
  return s + ")";
}

Status corrupt(std::string message) { return Status::error(StatusCode::kCorrupt, std::move(message)); }

// The bands a transfer section's vectors have: a visibility section's own (arg2), else the header's.
std::uint32_t passOrder(const Entry& e, const Parsed& p) { return isVisibilityType(e.type) ? e.arg2 : p.order; }

// A transfer section's pass without coefficients: kind, channels, bounces (arg2; for a
// visibility section arg2 is its order instead), form, domain.
TransferPass passHeader(const Entry& e) {
  TransferPass t;
  const bool visibility = isVisibilityType(e.type);
  t.kind = static_cast<TransferKind>(e.arg0);
  t.channels = static_cast<int>(e.arg1);
  t.bounces = visibility ? 0 : static_cast<int>(e.arg2);
  t.form = formOf(e.type);
  t.domain = isTexelType(e.type) ? TransferDomain::kTexel : TransferDomain::kVertex;
  t.order = visibility ? static_cast<int>(e.arg2) : 0;
  return t;
}

// Magic, version, header checksum and header fields. Needs only the first 64 bytes.
Status parseHeader(std::span<const std::uint8_t> bytes, Parsed* p) {
  const std::uint8_t* b = bytes.data();
  const std::size_t magicBytes = std::min<std::size_t>(bytes.size(), 4);
  if (magicBytes > 0 && std::memcmp(b, kAssetMagic, magicBytes) != 0) {
    return Status::error(StatusCode::kBadMagic, "not an asset file: it does not start with \"PRTA\"");
  }
  if (bytes.size() < 8) {
    return Status::error(StatusCode::kTruncated, "asset is " + num(bytes.size()) + " bytes, shorter than its " +
                                                     num(kAssetHeaderSize) + "-byte header");
  }
  p->major = readLe16(b + L::kVersionMajor);
  p->minor = readLe16(b + L::kVersionMinor);
  // Checked before the header checksum: another major version may lay its header out
  // differently, and "too new" is the error its reader needs to see.
  if (p->major != kAssetVersionMajor) {
    const std::string theirs = num(p->major) + "." + num(p->minor);
    const std::string ours = num(kAssetVersionMajor) + "." + num(kAssetVersionMinor);
    return Status::error(StatusCode::kBadVersion,
                         p->major > kAssetVersionMajor
                             ? "asset format version " + theirs + " is newer than this reader's " + ours
                             : "asset format version " + theirs + " is older than this reader's " + ours + " and not supported");
  }
  if (bytes.size() < kAssetHeaderSize) {
    return Status::error(StatusCode::kTruncated, "asset is " + num(bytes.size()) + " bytes, shorter than its " +
                                                     num(kAssetHeaderSize) + "-byte header");
  }
  const std::uint32_t storedCrc = readLe32(b + L::kHeaderCrc);
  const std::uint32_t crc = crc32c(bytes.first(L::kHeaderCrc));
  if (storedCrc != crc) {
    return Status::error(StatusCode::kChecksumMismatch,
                         "header checksum " + hex32(storedCrc) + " stored, " + hex32(crc) + " computed");
  }
  const std::uint32_t flags = readLe32(b + L::kFlags);
  if (flags != 0) return corrupt("header flags " + hex32(flags) + " are not defined in format version 1");
  for (std::size_t i = L::kReserved; i < L::kHeaderCrc; ++i) {
    if (b[i] != 0) return corrupt("reserved header byte " + num(i) + " is not zero");
  }
  p->order = readLe32(b + L::kShOrder);
  p->vertexCount = readLe32(b + L::kVertexCount);
  p->triangleCount = readLe32(b + L::kTriangleCount);
  p->sectionCount = readLe32(b + L::kSectionCount);
  p->fileSize = readLe64(b + L::kFileSize);
  if (p->order < static_cast<std::uint32_t>(kMinShOrder) || p->order > static_cast<std::uint32_t>(kMaxShOrder)) {
    return corrupt("header SH order " + num(p->order) + " is outside [" + num(kMinShOrder) + ", " + num(kMaxShOrder) + "]");
  }
  if (p->vertexCount < 1 || p->vertexCount > kMaxAssetVertices) {
    return corrupt("header vertex count " + num(p->vertexCount) + " is outside [1, " + num(kMaxAssetVertices) + "]");
  }
  if (p->triangleCount < 1 || p->triangleCount > kMaxAssetTriangles) {
    return corrupt("header triangle count " + num(p->triangleCount) + " is outside [1, " + num(kMaxAssetTriangles) + "]");
  }
  if (p->sectionCount < 1 || p->sectionCount > kMaxAssetSections) {
    return corrupt("header section count " + num(p->sectionCount) + " is outside [1, " + num(kMaxAssetSections) + "]");
  }
  const std::uint64_t tableEnd = kAssetHeaderSize + static_cast<std::uint64_t>(p->sectionCount) * kAssetSectionEntrySize;
  if (p->fileSize < tableEnd) {
    return corrupt("header file size " + num(p->fileSize) + " is smaller than header and section table (" + num(tableEnd) + " bytes)");
  }
  return Status::ok();
}

// A whole file must be exactly as long as its header says.
Status checkWholeFileSize(std::span<const std::uint8_t> bytes, const Parsed& p) {
  if (bytes.size() < p.fileSize) {
    return Status::error(StatusCode::kTruncated,
                         "asset is " + num(bytes.size()) + " bytes but its header declares " + num(p.fileSize));
  }
  if (bytes.size() > p.fileSize) {
    return corrupt("asset is " + num(bytes.size()) + " bytes but its header declares " + num(p.fileSize) +
                   ": trailing bytes");
  }
  return Status::ok();
}

// Checks one known section's table entry against the header counts; `seen*` detect repeats.
Status checkKnownEntry(const Entry& e, Parsed* p) {
  const std::string label = sectionLabel(e);
  auto expectFormat = [&](std::uint32_t format, const char* name) -> Status {
    if (e.format != format) return corrupt(label + " has element format " + num(e.format) + "; " + name + " expected");
    return Status::ok();
  };
  auto expectNoArgs = [&]() -> Status {
    if (e.arg0 != 0 || e.arg1 != 0 || e.arg2 != 0) return corrupt(label + " has non-zero arguments");
    return Status::ok();
  };
  auto expectSize = [&](std::uint64_t size, const char* how) -> Status {
    if (e.size != size) {
      return corrupt(label + " is " + num(e.size) + " bytes; " + num(size) + " expected (" + how + ")");
    }
    return Status::ok();
  };
  auto once = [&](int* slot) -> Status {
    if (*slot >= 0) return corrupt(label + " repeats section " + num(static_cast<std::uint64_t>(*slot)) + "; it must occur once");
    *slot = static_cast<int>(e.index);
    return Status::ok();
  };
  const std::uint64_t v = p->vertexCount;
  Status s;
  switch (e.type) {
    case kTypePositions:
    case kTypeNormals:
    case kTypeAlbedo:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(v * 12, "12 bytes per vertex")).isOk()) {
        return s;
      }
      return once(e.type == kTypePositions ? &p->positions : e.type == kTypeNormals ? &p->normals : &p->albedo);
    case kTypeIndices:
      if (!(s = expectFormat(kFormatUint32, "uint32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(static_cast<std::uint64_t>(p->triangleCount) * 12, "12 bytes per triangle")).isOk()) {
        return s;
      }
      return once(&p->indices);
    case kTypeMetadata:
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk() || !(s = expectNoArgs()).isOk()) return s;
      if (e.size < kMetadataFixedBytes || e.size > kMetadataFixedBytes + kMaxAssetSamplingBytes + kMaxAssetNameBytes) {
        return corrupt(label + " is " + num(e.size) + " bytes; " + num(kMetadataFixedBytes) + " to " +
                       num(kMetadataFixedBytes + kMaxAssetSamplingBytes + kMaxAssetNameBytes) + " expected");
      }
      return once(&p->metadata);
    case kTypeLighting:
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(kAssetLightingBytes, "model, centre and radius")).isOk()) {
        return s;
      }
      return once(&p->lighting);
    case kTypeSpecular:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(v * kAssetSpecularBytesPerVertex, "f0 r, g, b, f90 and exponent per vertex")).isOk()) {
        return s;
      }
      return once(&p->specular);
    case kTypeAtlasUv:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(v * 8, "u and v per vertex")).isOk()) {
        return s;
      }
      return once(&p->atlasUv);
    case kTypeAtlases:
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk()) return s;
      if (e.arg0 < 1 || e.arg0 > kMaxAssetAtlases) {
        return corrupt(label + " declares " + num(e.arg0) + " atlases; 1 to " + num(kMaxAssetAtlases) + " expected");
      }
      if (e.arg1 != 0 || e.arg2 != 0) return corrupt(label + " has non-zero arguments 1 or 2");
      if (!(s = expectSize(std::uint64_t{e.arg0} * kAssetAtlasEntryBytes, "16 bytes per atlas")).isOk()) return s;
      return once(&p->atlases);
    case kTypeTexelCoverage:
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk() || !(s = expectNoArgs()).isOk()) return s;
      if (e.size < 1 || e.size > kMaxAssetTexels) {
        return corrupt(label + " is " + num(e.size) + " bytes; 1 to " + num(kMaxAssetTexels) + " expected (one per texel)");
      }
      if (Status t = once(&p->coverage); !t.isOk()) return t;
      p->texelCount = e.size;
      return Status::ok();
    case kTypeTexelNormals:
      // Its size depends on the texel count (the coverage section's size): checked in
      // parseTable (checkTexelSections), since the coverage entry may come later in the table.
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk() || !(s = expectNoArgs()).isOk()) return s;
      return once(&p->texelNormals);
    case kTypeTangents:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(v * 12, "12 bytes per vertex")).isOk()) {
        return s;
      }
      return once(&p->tangents);
    case kTypePatchUv:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk() || !(s = expectNoArgs()).isOk() ||
          !(s = expectSize(v * 8, "u and v per vertex")).isOk()) {
        return s;
      }
      return once(&p->patchUv);
    case kTypeRtt:
      // Its contents carry their own shape and checksum (decodeRtt, in validateAll).
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk() || !(s = expectNoArgs()).isOk()) return s;
      return once(&p->rtt);
    case kTypePatchPlacements:
      if (!(s = expectFormat(kFormatFloat32, "float32")).isOk()) return s;
      if (e.arg0 < 1 || e.arg0 > kMaxPatchPlacements) {
        return corrupt(label + " declares " + num(e.arg0) + " placements; 1 to " + num(kMaxPatchPlacements) + " expected");
      }
      if (e.arg1 != 0 || e.arg2 != 0) return corrupt(label + " has non-zero arguments 1 or 2");
      if (!(s = expectSize(std::uint64_t{e.arg0} * kAssetPlacementBytes, "36 bytes per placement")).isOk()) return s;
      return once(&p->placements);
    case kTypeIdMap:
      // Its size depends on the texel or triangle count: checked in checkBiScaleSections.
      if (!(s = expectFormat(kFormatBytes, "bytes")).isOk()) return s;
      if (e.arg0 > 1) return corrupt(label + " has domain " + num(e.arg0) + "; 0 (atlas texels) or 1 (triangles) expected");
      if (e.arg1 != 0 || e.arg2 != 0) return corrupt(label + " has non-zero arguments 1 or 2");
      p->idMapPerTriangle = e.arg0 == 1;
      return once(&p->idMap);
    case kTypeTexelVisibility:
    case kTypeEncodedTexelVisibility: {
      // TPFL glossy visibility (since 1.5): shadowed, one channel, arg2 its own order. A float32
      // section's size depends on the texel count: checked in parseTable (checkTexelSections).
      const bool encoded = e.type == kTypeEncodedTexelVisibility;
      if (!(s = encoded ? expectFormat(kFormatBytes, "bytes") : expectFormat(kFormatFloat32, "float32")).isOk()) return s;
      if (e.arg0 != static_cast<std::uint32_t>(TransferKind::kShadowed)) {
        return corrupt(label + " has transfer kind " + num(e.arg0) + "; visibility sections are shadowed (1)");
      }
      if (e.arg1 != 1) return corrupt(label + " has " + num(e.arg1) + " channels; visibility sections have 1");
      if (e.arg2 < static_cast<std::uint32_t>(kMinVisibilityOrder) || e.arg2 > static_cast<std::uint32_t>(kMaxShOrder)) {
        return corrupt(label + " has visibility order " + num(e.arg2) + "; " + num(kMinVisibilityOrder) + " to " +
                       num(kMaxShOrder) + " expected");
      }
      for (int other : p->transfer) {
        if (isVisibilityType(p->entries[static_cast<std::size_t>(other)].type)) {
          return corrupt(label + " repeats the visibility pass of section " + num(static_cast<std::uint64_t>(other)) +
                         "; at most one is allowed");
        }
      }
      p->transfer.push_back(static_cast<int>(e.index));
      return Status::ok();
    }
    case kTypeTransfer:
    case kTypeEncodedTransfer:
    case kTypeMatrixTransfer:
    case kTypeEncodedMatrixTransfer:
    case kTypeTexelTransfer:
    case kTypeEncodedTexelTransfer: {
      const bool encoded = isEncodedType(e.type), matrix = isMatrixType(e.type), texel = isTexelType(e.type);
      if (!(s = encoded ? expectFormat(kFormatBytes, "bytes") : expectFormat(kFormatFloat32, "float32")).isOk()) return s;
      if (e.arg0 > 2) return corrupt(label + " has unknown transfer kind " + num(e.arg0));
      if (e.arg1 != 1 && e.arg1 != 3) return corrupt(label + " has " + num(e.arg1) + " channels; 1 or 3 expected");
      if (matrix) {
        const std::uint32_t wanted = e.arg0 == static_cast<std::uint32_t>(TransferKind::kInterreflected) ? 3 : 1;
        if (e.arg1 != wanted) return corrupt(label + " has " + num(e.arg1) + " channels; " + num(wanted) + " expected");
        if (p->order > static_cast<std::uint32_t>(kMaxMatrixOrder)) {
          return corrupt(label + ": matrix passes need order <= " + num(kMaxMatrixOrder) + ", the header says " + num(p->order));
        }
      }
      const bool interreflected = e.arg0 == static_cast<std::uint32_t>(TransferKind::kInterreflected);
      if (interreflected ? e.arg2 > kMaxAssetBounces : e.arg2 != 0) {
        return corrupt(label + " has " + num(e.arg2) + " bounces; " +
                       (interreflected ? "at most " + num(kMaxAssetBounces) : std::string("0")) + " expected");
      }
      // v <= 2^28, channels <= 3, order^2 <= 256: the product stays below 2^40. An encoded
      // section's size is its blob's, checked with its contents. A float32 texel section's
      // size depends on the texel count, the coverage section's size: checked in parseTable.
      if (!encoded && !matrix && !texel &&
          !(s = expectSize(v * e.arg1 * static_cast<std::uint64_t>(shCoeffCount(static_cast<int>(p->order))) * 4,
                           "4 bytes per vertex, channel and coefficient"))
               .isOk()) {
        return s;
      }
      // A float32 matrix section's packing depends on the lighting model, a payload checked
      // later (checkMatrixPackings); here its size must be one of the two packings'.
      if (!encoded && matrix) {
        const int order = static_cast<int>(p->order);
        const std::uint64_t sym = v * e.arg1 * matrixEntryCount(order, MatrixPacking::kSymmetric) * 4;
        const std::uint64_t full = v * e.arg1 * matrixEntryCount(order, MatrixPacking::kFull) * 4;
        if (e.size != sym && e.size != full) {
          return corrupt(label + " is " + num(e.size) + " bytes; " + num(sym) + " (symmetric) or " + num(full) +
                         " (full) expected (4 bytes per vertex, channel and packed entry)");
        }
      }
      for (int other : p->transfer) {
        const Entry& o = p->entries[static_cast<std::size_t>(other)];
        if (o.arg0 == e.arg0 && formOf(o.type) == formOf(e.type) && isTexelType(o.type) == texel) {
          return corrupt(label + " repeats the transfer kind of section " + num(static_cast<std::uint64_t>(other)));
        }
      }
      p->transfer.push_back(static_cast<int>(e.index));
      return Status::ok();
    }
    default:
      return Status::ok();  // unknown types are skipped (forward compatibility)
  }
}

// Transfer textures: atlas uv, atlases and coverage exactly when a texel pass exists, and
// float32 texel passes sized by the texel count (the coverage section's size).
Status checkTexelSections(const Parsed& p) {
  bool anyTexel = false;
  for (int t : p.transfer) anyTexel = anyTexel || isTexelType(p.entries[static_cast<std::size_t>(t)].type);
  // The atlases come with a texel pass or a synthesised id map (bi-scale).
  const bool atlasData = anyTexel || (p.idMap >= 0 && !p.idMapPerTriangle);
  const char* needer = anyTexel ? "a texel transfer section" : "an id map";
  const std::pair<int, const char*> sections[] = {{p.atlasUv, "atlas uv"}, {p.atlases, "atlases"}, {p.coverage, "texel coverage"}};
  for (const auto& [slot, name] : sections) {
    if (atlasData && slot < 0) return corrupt(std::string("the asset has ") + needer + " but no " + name + " section");
    if (!atlasData && slot >= 0) {
      return corrupt(sectionLabel(p.entries[static_cast<std::size_t>(slot)]) + " is present without a texel transfer section");
    }
  }
  if (p.texelNormals >= 0) {
    const Entry& e = p.entries[static_cast<std::size_t>(p.texelNormals)];
    if (!anyTexel) return corrupt(sectionLabel(e) + " is present without a texel transfer section");
    // texels <= 2^28: 4 bytes each stays below 2^30.
    if (e.size != p.texelCount * kAssetTexelNormalBytes) {
      return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(p.texelCount * kAssetTexelNormalBytes) +
                     " expected (4 bytes per texel, " + num(p.texelCount) + " texels)");
    }
  }
  for (int t : p.transfer) {
    const Entry& e = p.entries[static_cast<std::size_t>(t)];
    if (e.type == kTypeTexelVisibility) {
      // texels <= 2^28, order^2 <= 256 (the entry check bounded arg2): below 2^40.
      const std::uint64_t want = p.texelCount * static_cast<std::uint64_t>(shCoeffCount(static_cast<int>(e.arg2))) * 4;
      if (e.size != want) {
        return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(want) + " expected (4 bytes per texel and coefficient, " +
                       num(p.texelCount) + " texels, visibility order " + num(e.arg2) + ")");
      }
      continue;
    }
    if (e.type != kTypeTexelTransfer) continue;
    // texels <= 2^28, channels <= 3, order^2 <= 256: below 2^40.
    const std::uint64_t want = p.texelCount * e.arg1 * static_cast<std::uint64_t>(shCoeffCount(static_cast<int>(p.order))) * 4;
    if (e.size != want) {
      return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(want) + " expected (4 bytes per texel, channel and coefficient, " +
                     num(p.texelCount) + " texels)");
    }
  }
  return Status::ok();
}

// Bi-scale: tangents, patch uv and RTT all or none, and only with a vertex matrix pass.
Status checkBiScaleSections(const Parsed& p) {
  const int all[] = {p.tangents, p.patchUv, p.rtt, p.placements, p.idMap};
  if (std::all_of(std::begin(all), std::end(all), [](int slot) { return slot < 0; })) return Status::ok();
  const std::pair<int, const char*> sections[] = {{p.tangents, "tangents"}, {p.rtt, "RTT"}};
  for (const auto& [slot, name] : sections) {
    if (slot < 0) return corrupt(std::string("the asset has bi-scale sections but no ") + name + " section");
  }
  const bool synthesised = p.placements >= 0 || p.idMap >= 0;
  if (synthesised && p.patchUv >= 0) {
    return corrupt("the asset has both a patch uv section and a synthesised id map; one places the RTT");
  }
  if (!synthesised && p.patchUv < 0) return corrupt("the asset has bi-scale sections but no patch uv section");
  if (synthesised) {
    if (p.placements < 0) return corrupt("the asset has an id map but no patch placements section");
    if (p.idMap < 0) return corrupt("the asset has patch placements but no id map section");
    const Entry& e = p.entries[static_cast<std::size_t>(p.idMap)];
    if (p.idMapPerTriangle) {
      if (e.size != 2 * std::uint64_t{p.triangleCount}) {
        return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(2 * std::uint64_t{p.triangleCount}) +
                       " expected (2 bytes per triangle)");
      }
    } else {
      if (p.coverage < 0) return corrupt(sectionLabel(e) + " is present without the atlas sections");
      if (e.size != 2 * p.texelCount) {
        return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(2 * p.texelCount) + " expected (2 bytes per texel, " +
                       num(p.texelCount) + " texels)");
      }
    }
  }
  for (int t : p.transfer) {
    const std::uint32_t type = p.entries[static_cast<std::size_t>(t)].type;
    if (isMatrixType(type)) return Status::ok();
  }
  return corrupt(sectionLabel(p.entries[static_cast<std::size_t>(p.rtt)]) + " is present without a matrix transfer section");
}

// Bi-scale payloads (asset_bi_scale.h's rules): each tangent against its normal (the normals
// section, validated before), each patch coordinate, the RTT against the asset's order.
Status checkTangentsPayload(std::span<const std::uint8_t> payload, const Entry& e, std::span<const std::uint8_t> normals) {
  const std::size_t count = payload.size() / 12;
  for (std::size_t v = 0; v < count; ++v) {
    float t[3], n[3];
    for (int k = 0; k < 3; ++k) {
      t[k] = floatFromBits(readLe32(payload.data() + 12 * v + 4 * k));
      n[k] = floatFromBits(readLe32(normals.data() + 12 * v + 4 * k));
    }
    if (Status s = asset_bi_scale::checkTangent({t[0], t[1], t[2]}, {n[0], n[1], n[2]}, v); !s.isOk()) {
      return corrupt(sectionLabel(e) + ": " + s.message());
    }
  }
  return Status::ok();
}

Status checkPatchUvPayload(std::span<const std::uint8_t> payload, const Entry& e) {
  for (std::size_t i = 0; i < payload.size() / 4; ++i) {
    if (Status s = asset_bi_scale::checkPatchCoordinate(floatFromBits(readLe32(payload.data() + 4 * i)), i); !s.isOk()) {
      return corrupt(sectionLabel(e) + ": " + s.message());
    }
  }
  return Status::ok();
}

Status checkIdMapPayload(std::span<const std::uint8_t> payload, const Entry& e, std::uint32_t placements) {
  for (std::size_t t = 0; t < payload.size() / 2; ++t) {
    if (Status s = asset_bi_scale::checkIdMapEntry(readLe16(payload.data() + 2 * t), placements, t); !s.isOk()) {
      return corrupt(sectionLabel(e) + ": " + s.message());
    }
  }
  return Status::ok();
}

Status checkRttPayload(std::span<const std::uint8_t> payload, const Entry& e, std::uint32_t order) {
  if (Status s = asset_bi_scale::checkRttBytes(payload, static_cast<int>(order)); !s.isOk()) {
    return corrupt(sectionLabel(e) + ": " + s.message());
  }
  return Status::ok();
}

// Section table: checksum, then each entry's bounds, alignment, known-type rules, then
// overlaps and required sections. Entries are checked against the declared file size, so
// this also works on a prefix (peekAssetHeader).
Status parseTable(std::span<const std::uint8_t> bytes, Parsed* p) {
  const std::uint64_t tableBytes = static_cast<std::uint64_t>(p->sectionCount) * kAssetSectionEntrySize;
  const std::uint64_t tableEnd = kAssetHeaderSize + tableBytes;
  if (bytes.size() < tableEnd) {
    return Status::error(StatusCode::kTruncated, "asset is " + num(bytes.size()) + " bytes; its header and section table need " +
                                                     num(tableEnd));
  }
  const auto table = bytes.subspan(kAssetHeaderSize, static_cast<std::size_t>(tableBytes));
  const std::uint32_t storedCrc = readLe32(bytes.data() + L::kTableCrc);
  const std::uint32_t crc = crc32c(table);
  if (storedCrc != crc) {
    return Status::error(StatusCode::kChecksumMismatch,
                         "section table checksum " + hex32(storedCrc) + " stored, " + hex32(crc) + " computed");
  }
  p->entries.resize(p->sectionCount);
  for (std::uint32_t i = 0; i < p->sectionCount; ++i) {
    const std::uint8_t* t = table.data() + static_cast<std::size_t>(i) * kAssetSectionEntrySize;
    Entry& e = p->entries[i];
    e.index = i;
    e.type = readLe32(t + L::kEntryType);
    e.format = readLe32(t + L::kEntryFormat);
    e.offset = readLe64(t + L::kEntryOffset);
    e.size = readLe64(t + L::kEntrySize);
    e.arg0 = readLe32(t + L::kEntryArg0);
    e.arg1 = readLe32(t + L::kEntryArg1);
    e.arg2 = readLe32(t + L::kEntryArg2);
    e.crc = readLe32(t + L::kEntryCrc);
    const std::string label = sectionLabel(e);
    if (e.type == 0) return corrupt(label + ": section type 0 is reserved");
    if (e.offset % kAssetAlignment != 0) {
      return corrupt(label + " offset " + num(e.offset) + " is not a multiple of " + num(kAssetAlignment));
    }
    if (e.offset < tableEnd) {
      return corrupt(label + " offset " + num(e.offset) + " lies inside the header or section table (which end at " +
                     num(tableEnd) + ")");
    }
    // Written as two comparisons so offset + size is never formed: it could wrap.
    if (e.offset > p->fileSize || e.size > p->fileSize - e.offset) {
      return corrupt(label + " (offset " + num(e.offset) + ", " + num(e.size) + " bytes) extends past the end of the " +
                     num(p->fileSize) + "-byte file");
    }
    if (Status s = checkKnownEntry(e, p); !s.isOk()) return s;
  }
  std::vector<const Entry*> sorted;
  sorted.reserve(p->entries.size());
  for (const Entry& e : p->entries) sorted.push_back(&e);
  std::sort(sorted.begin(), sorted.end(), [](const Entry* a, const Entry* b) {
    return a->offset != b->offset ? a->offset < b->offset : a->size < b->size;
  });
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    const Entry& a = *sorted[i - 1];
    const Entry& b = *sorted[i];
    if (a.offset + a.size > b.offset) {  // both within the file: no overflow
      return corrupt(sectionLabel(a) + " and " + sectionLabel(b) + " overlap");
    }
  }
  const std::pair<int, const char*> required[] = {{p->positions, "positions"}, {p->normals, "normals"},
                                                  {p->indices, "indices"},     {p->albedo, "albedo"},
                                                  {p->metadata, "metadata"}};
  for (const auto& [slot, name] : required) {
    if (slot < 0) return corrupt(std::string("the required ") + name + " section is missing");
  }
  if (p->transfer.empty()) return corrupt("the asset has no transfer section");
  // Both glossy forms need the specular materials: matrices per vertex, visibility per texel
  // (interpolated from the vertices').
  bool anyGlossy = false;
  for (int t : p->transfer) {
    const std::uint32_t type = p->entries[static_cast<std::size_t>(t)].type;
    anyGlossy = anyGlossy || isMatrixType(type) || isVisibilityType(type);
  }
  if (anyGlossy && p->specular < 0) return corrupt("the asset has a matrix or visibility transfer section but no specular section");
  if (!anyGlossy && p->specular >= 0) {
    return corrupt(sectionLabel(p->entries[static_cast<std::size_t>(p->specular)]) +
                   " is present without a matrix or visibility transfer section");
  }
  if (Status s = checkBiScaleSections(*p); !s.isOk()) return s;
  return checkTexelSections(*p);
}

// What depends on the lighting model: a float32 matrix section's size must match its
// packing, and a visibility section needs distant lighting (TPFL multiplies V with it).
Status checkMatrixPackings(const Parsed& p, const LightingInfo& lighting) {
  for (int t : p.transfer) {
    const Entry& e = p.entries[static_cast<std::size_t>(t)];
    if (isVisibilityType(e.type) && isLocalLighting(lighting.model)) {
      return corrupt(sectionLabel(e) + " needs distant lighting; the lighting section says " + lightingModelName(lighting.model));
    }
    if (e.type != kTypeMatrixTransfer) continue;
    const MatrixPacking packing = matrixPackingFor(static_cast<TransferKind>(e.arg0), lighting.model);
    const std::uint64_t want = std::uint64_t{p.vertexCount} * e.arg1 * matrixEntryCount(static_cast<int>(p.order), packing) * 4;
    if (e.size != want) {
      return corrupt(sectionLabel(e) + " is " + num(e.size) + " bytes; " + num(want) + " expected (" + matrixPackingName(packing) +
                     " packing under " + lightingModelName(lighting.model) + " lighting)");
    }
  }
  return Status::ok();
}

std::span<const std::uint8_t> payloadOf(std::span<const std::uint8_t> bytes, const Entry& e) {
  return bytes.subspan(static_cast<std::size_t>(e.offset), static_cast<std::size_t>(e.size));
}

Status checkSectionCrc(std::span<const std::uint8_t> bytes, const Entry& e) {
  const std::uint32_t crc = crc32c(payloadOf(bytes, e));
  if (crc != e.crc) {
    return Status::error(StatusCode::kChecksumMismatch,
                         sectionLabel(e) + " checksum " + hex32(e.crc) + " stored, " + hex32(crc) + " computed");
  }
  return Status::ok();
}

// Bytes not covered by the header, the table or a section (alignment padding) must be zero,
// so that every byte of a valid file is pinned by a checksum or by this rule.
Status checkPadding(std::span<const std::uint8_t> bytes, const Parsed& p) {
  std::vector<const Entry*> sorted;
  for (const Entry& e : p.entries) sorted.push_back(&e);
  std::sort(sorted.begin(), sorted.end(), [](const Entry* a, const Entry* b) { return a->offset < b->offset; });
  std::uint64_t cursor = kAssetHeaderSize + static_cast<std::uint64_t>(p.sectionCount) * kAssetSectionEntrySize;
  auto zeroUpTo = [&](std::uint64_t end) -> Status {
    for (std::uint64_t i = cursor; i < end; ++i) {
      if (bytes[static_cast<std::size_t>(i)] != 0) return corrupt("padding byte at offset " + num(i) + " is not zero");
    }
    return Status::ok();
  };
  for (const Entry* e : sorted) {
    if (Status s = zeroUpTo(e->offset); !s.isOk()) return s;
    cursor = std::max(cursor, e->offset + e->size);
  }
  return zeroUpTo(p.fileSize);
}

Status parseMetadata(std::span<const std::uint8_t> payload, const Entry& e, Metadata* m) {
  // The entry check guaranteed 24 <= size <= 24 + 32 + 4096.
  const std::uint8_t* b = payload.data();
  m->samples = readLe64(b);
  m->seed = readLe64(b + 8);
  const std::uint64_t samplingLength = readLe32(b + 16);
  const std::uint64_t nameLength = readLe32(b + 20);
  if (kMetadataFixedBytes + samplingLength + nameLength != payload.size()) {
    return corrupt(sectionLabel(e) + " is " + num(payload.size()) + " bytes but holds a " + num(samplingLength) +
                   "-byte sampling name and a " + num(nameLength) + "-byte asset name after its 24 fixed bytes");
  }
  const char* text = reinterpret_cast<const char*>(b + kMetadataFixedBytes);
  const std::string_view sampling(text, static_cast<std::size_t>(samplingLength));
  const std::string_view name(text + samplingLength, static_cast<std::size_t>(nameLength));
  if (!isValidAssetSamplingName(sampling)) {
    return corrupt(sectionLabel(e) + ": sampling name is not at most " + num(kMaxAssetSamplingBytes) + " characters of [a-z0-9_-]");
  }
  if (!isValidAssetName(name)) {
    return corrupt(sectionLabel(e) + ": asset name is not at most " + num(kMaxAssetNameBytes) +
                   " bytes of UTF-8 without control characters");
  }
  m->sampling.assign(sampling);
  m->name.assign(name);
  return Status::ok();
}

Status parseLighting(std::span<const std::uint8_t> payload, const Entry& e, LightingInfo* out) {
  namespace LL = asset_lighting_layout;
  // The entry check guaranteed the size.
  const std::uint8_t* b = payload.data();
  LightingInfo l;
  l.model = static_cast<LightingModel>(readLe32(b + LL::kModel));
  l.center = {floatFromBits(readLe32(b + LL::kCenterX)), floatFromBits(readLe32(b + LL::kCenterY)),
              floatFromBits(readLe32(b + LL::kCenterZ))};
  l.radius = floatFromBits(readLe32(b + LL::kRadius));
  if (Status s = checkLightingInfo(l); !s.isOk()) return corrupt(sectionLabel(e) + ": " + s.message());
  *out = l;
  return Status::ok();
}

// Finite means the exponent bits are not all ones (which is what NaN and infinity share).
Status checkFloats(std::span<const std::uint8_t> payload, const Entry& e) {
  const std::size_t count = payload.size() / 4;
  const std::uint8_t* b = payload.data();
  for (std::size_t i = 0; i < count; ++i) {
    if ((readLe32(b + 4 * i) & 0x7F800000u) == 0x7F800000u) {
      return corrupt(sectionLabel(e) + ": value " + num(i) + " is not finite");
    }
  }
  return Status::ok();
}

// Raw transfer: finite and within kMaxTransferMagnitude, as every encoded form must be.
Status checkTransferFloats(std::span<const std::uint8_t> payload, const Entry& e) {
  if (Status s = checkFloats(payload, e); !s.isOk()) return s;
  const std::size_t count = payload.size() / 4;
  for (std::size_t i = 0; i < count; ++i) {
    const float x = floatFromBits(readLe32(payload.data() + 4 * i));
    if (x > kMaxTransferMagnitude || x < -kMaxTransferMagnitude) {
      return corrupt(sectionLabel(e) + ": value " + num(i) + " is " + std::to_string(x) +
                     ", beyond the transfer range (65504)");
    }
  }
  return Status::ok();
}

// Specular materials: f0 r, g, b and f90 in [0, 1] and the exponent finite and >= 0, per vertex.
Status checkSpecularPayload(std::span<const std::uint8_t> payload, const Entry& e) {
  constexpr std::size_t kStride = kAssetSpecularBytesPerVertex;
  const std::size_t count = payload.size() / kStride;
  for (std::size_t v = 0; v < count; ++v) {
    for (std::size_t k = 0; k < 5; ++k) {
      const float x = floatFromBits(readLe32(payload.data() + kStride * v + 4 * k));
      const bool ok = k < 4 ? (x >= 0.0f && x <= 1.0f) : (std::isfinite(x) && x >= 0.0f);  // NaN fails both
      if (!ok) {
        const std::string what = k < 3 ? " f0 " + num(k) : " f90";
        return corrupt(sectionLabel(e) + ": vertex " + num(v) + (k < 4 ? what + " is " + std::to_string(x) + ", outside [0, 1]"
                                                                        : " exponent is " + std::to_string(x) + ", not finite and >= 0"));
      }
    }
  }
  return Status::ok();
}

Status checkIndices(std::span<const std::uint8_t> payload, const Entry& e, std::uint32_t vertexCount) {
  const std::size_t count = payload.size() / 4;
  const std::uint8_t* b = payload.data();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t index = readLe32(b + 4 * i);
    if (index >= vertexCount) {
      return corrupt(sectionLabel(e) + ": index " + num(i) + " (triangle " + num(i / 3) + ") is " + num(index) +
                     ", not below the vertex count " + num(vertexCount));
    }
  }
  return Status::ok();
}

// The atlases payload: each atlas's sides in range, the atlases tiling the triangles in order,
// and their texels adding up to the coverage section's size. `out` (may be null) gets them.
Status parseAtlases(std::span<const std::uint8_t> payload, const Entry& e, const Parsed& p, std::vector<TextureAtlas>* out) {
  namespace AL = asset_atlas_layout;
  // The entry check guaranteed size = 16 * arg0 with arg0 <= kMaxAssetAtlases.
  const std::size_t count = payload.size() / kAssetAtlasEntryBytes;
  std::vector<TextureAtlas> atlases(count);
  std::uint64_t next = 0, texels = 0;  // at most 1024 * 2^32 and 1024 * 2^28: no overflow
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* b = payload.data() + kAssetAtlasEntryBytes * i;
    TextureAtlas& a = atlases[i];
    a = {readLe32(b + AL::kWidth), readLe32(b + AL::kHeight), readLe32(b + AL::kFirstTriangle), readLe32(b + AL::kTriangleCount)};
    const std::string label = sectionLabel(e) + ": atlas " + num(i);
    if (a.width < 1 || a.width > kMaxAssetAtlasSize || a.height < 1 || a.height > kMaxAssetAtlasSize) {
      return corrupt(label + " is " + num(a.width) + " x " + num(a.height) + " texels; each side must be 1 to " + num(kMaxAssetAtlasSize));
    }
    if (a.triangleCount < 1) return corrupt(label + " covers no triangles");
    if (a.firstTriangle != next) return corrupt(label + " starts at triangle " + num(a.firstTriangle) + ", expected " + num(next));
    next += a.triangleCount;
    texels += std::uint64_t{a.width} * a.height;
  }
  if (next != p.triangleCount) {
    return corrupt(sectionLabel(e) + ": the atlases cover " + num(next) + " triangles, the header says " + num(p.triangleCount));
  }
  if (texels != p.texelCount) {
    return corrupt(sectionLabel(e) + ": the atlases hold " + num(texels) + " texels, the texel coverage section " + num(p.texelCount));
  }
  if (out != nullptr) *out = std::move(atlases);
  return Status::ok();
}

// Atlas uv: every value finite and in [0, 1] (NaN fails both comparisons).
Status checkAtlasUv(std::span<const std::uint8_t> payload, const Entry& e) {
  const std::size_t count = payload.size() / 4;
  for (std::size_t i = 0; i < count; ++i) {
    const float x = floatFromBits(readLe32(payload.data() + 4 * i));
    if (!(x >= 0.0f && x <= 1.0f)) {
      return corrupt(sectionLabel(e) + ": vertex " + num(i / 2) + (i % 2 ? " v" : " u") + " is " + std::to_string(x) +
                     ", not in [0, 1]");
    }
  }
  return Status::ok();
}

// Texel coverage: every byte a TexelCoverage value.
Status checkCoverage(std::span<const std::uint8_t> payload, const Entry& e) {
  for (std::size_t i = 0; i < payload.size(); ++i) {
    if (payload[i] > static_cast<std::uint8_t>(TexelCoverage::kGutter)) {
      return corrupt(sectionLabel(e) + ": texel " + num(i) + " has coverage " + num(payload[i]) + "; 0, 1 or 2 expected");
    }
  }
  return Status::ok();
}

// Texel normals: no code -32768 (it would decode like -32767: one encoding per normal), and
// (0, 0) at the empty texels of `coverage` (the same texel count: checkTexelSections).
Status checkTexelNormals(std::span<const std::uint8_t> payload, const Entry& e, std::span<const std::uint8_t> coverage) {
  for (std::size_t t = 0; t < coverage.size(); ++t) {
    const std::int16_t x = static_cast<std::int16_t>(readLe16(payload.data() + kAssetTexelNormalBytes * t));
    const std::int16_t y = static_cast<std::int16_t>(readLe16(payload.data() + kAssetTexelNormalBytes * t + 2));
    if (x == kOctahedralInvalidCode || y == kOctahedralInvalidCode) {
      return corrupt(sectionLabel(e) + ": texel " + num(t) + " has the code -32768; -32767 to 32767 expected");
    }
    if (coverage[t] == static_cast<std::uint8_t>(TexelCoverage::kEmpty) && (x != 0 || y != 0)) {
      return corrupt(sectionLabel(e) + ": texel " + num(t) + " is empty in the coverage but holds (" +
                     std::to_string(x) + ", " + std::to_string(y) + "); (0, 0) expected");
    }
  }
  return Status::ok();
}

// Everything decodeAsset checks; afterwards every section may be read without checks.
// An encoded transfer section's blob: its header must describe the asset's pass, and it must
// decode in full (every part's checksum and value). `decoded` (may be null) receives the floats.
// `cpca` (may be null): decode the CPCA parts unexpanded instead (the blob must be CPCA).
// For a matrix section `lighting` gives the packing its blob must have; `cpcaMatrix` (may be
// null) decodes the matrix CPCA parts unexpanded instead.
Status checkEncodedTransfer(std::span<const std::uint8_t> payload, const Entry& e, const Parsed& p, int bands,
                            std::vector<float>* decoded, int* bandsDecoded, CpcaTransfer* cpca = nullptr,
                            const LightingInfo* lighting = nullptr, CpcaMatrixTransfer* cpcaMatrix = nullptr) {
  TransferBlobInfo info;
  if (Status s = readTransferBlobInfo(payload, &info); !s.isOk()) {
    return Status::error(s.code() == StatusCode::kTruncated ? StatusCode::kTruncated : StatusCode::kCorrupt,
                         sectionLabel(e) + ": " + s.message());
  }
  const bool matrix = isMatrixType(e.type);
  if (info.matrix != matrix) {
    return corrupt(sectionLabel(e) + ": its blob holds " + (info.matrix ? "matrices" : "vectors") + ", the section " +
                   (matrix ? "matrices" : "vectors"));
  }
  if (matrix) {
    const MatrixPacking packing = matrixPackingFor(static_cast<TransferKind>(e.arg0), lighting != nullptr ? lighting->model : LightingModel::kDistant);
    if (info.packing != packing) {
      return corrupt(sectionLabel(e) + ": its blob is " + matrixPackingName(info.packing) + ", the pass needs " +
                     matrixPackingName(packing) + " packing");
    }
  }
  // A texel pass's blob has one "vertex" per texel; a visibility blob has the section's order.
  const bool texel = isTexelType(e.type);
  const std::uint64_t rows = texel ? p.texelCount : p.vertexCount;
  const char* rowName = texel ? " texels" : " vertices";
  const std::uint32_t order = passOrder(e, p);
  if (info.order != static_cast<int>(order) || info.channels != static_cast<int>(e.arg1) || info.vertexCount != rows) {
    return corrupt(sectionLabel(e) + ": its blob is order " + num(static_cast<std::uint64_t>(info.order)) + ", " +
                   num(static_cast<std::uint64_t>(info.channels)) + " channels, " + num(info.vertexCount) + " rows; the " +
                   (isVisibilityType(e.type) ? "section" : "asset") + " says order " + num(order) + ", " + num(e.arg1) +
                   " channels, " + num(rows) + rowName);
  }
  const int available = info.bandsAvailable;
  const int want = bands <= 0 ? available : std::min(bands, available);
  if (want < 1) {
    return Status::error(StatusCode::kTruncated, sectionLabel(e) + ": no complete band has arrived");
  }
  std::vector<float> scratch;
  std::vector<float>* out = decoded != nullptr ? decoded : &scratch;
  const bool structured = cpca != nullptr || cpcaMatrix != nullptr;
  Status decodedStatus = cpcaMatrix != nullptr ? decodeCpcaMatrixTransfer(payload, want, cpcaMatrix)
                         : cpca != nullptr     ? decodeCpcaTransfer(payload, want, cpca)
                         : matrix              ? decodeTransferMatrix(payload, want, out)
                                               : decodeTransfer(payload, want, out);
  if (Status s = decodedStatus; !s.isOk()) {
    if (structured && s.code() == StatusCode::kInvalidArgument) return Status::error(s.code(), sectionLabel(e) + ": " + s.message());
    return Status::error(s.code() == StatusCode::kChecksumMismatch ? s.code() : StatusCode::kCorrupt,
                         sectionLabel(e) + ": " + s.message());
  }
  if (bandsDecoded != nullptr) *bandsDecoded = want;
  return Status::ok();
}

Status validateAll(std::span<const std::uint8_t> bytes, Parsed* p, Metadata* m,
                   std::vector<std::vector<float>>* decoded = nullptr) {
  if (Status s = parseHeader(bytes, p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(bytes, *p); !s.isOk()) return s;
  if (Status s = parseTable(bytes, p); !s.isOk()) return s;
  if (decoded != nullptr) decoded->assign(p->transfer.size(), {});
  if (Status s = checkPadding(bytes, *p); !s.isOk()) return s;
  // Every section's checksum, unknown ones included, before any content check: damage
  // reads as damage, not as whatever inconsistency it happens to produce.
  for (const Entry& e : p->entries) {
    if (Status s = checkSectionCrc(bytes, e); !s.isOk()) return s;
  }
  // The lighting first: matrix sections' packing depends on its model.
  if (p->lighting >= 0) {
    const Entry& light = p->entries[static_cast<std::size_t>(p->lighting)];
    if (Status s = parseLighting(payloadOf(bytes, light), light, &m->lighting); !s.isOk()) return s;
  }
  if (Status s = checkMatrixPackings(*p, m->lighting); !s.isOk()) return s;
  for (const Entry& e : p->entries) {
    const auto payload = payloadOf(bytes, e);
    Status s;
    switch (e.type) {
      case kTypePositions:
      case kTypeNormals:
      case kTypeAlbedo: s = checkFloats(payload, e); break;
      case kTypeSpecular: s = checkSpecularPayload(payload, e); break;
      case kTypeTransfer:
      case kTypeMatrixTransfer:
      case kTypeTexelTransfer:
      case kTypeTexelVisibility: s = checkTransferFloats(payload, e); break;
      case kTypeIndices: s = checkIndices(payload, e, p->vertexCount); break;
      case kTypeMetadata: s = parseMetadata(payload, e, m); break;
      case kTypeLighting: break;  // parsed above
      case kTypeAtlasUv: s = checkAtlasUv(payload, e); break;
      case kTypeAtlases: s = parseAtlases(payload, e, *p, nullptr); break;
      case kTypeTexelCoverage: s = checkCoverage(payload, e); break;
      case kTypeTexelNormals: s = checkTexelNormals(payload, e, payloadOf(bytes, p->entries[static_cast<std::size_t>(p->coverage)])); break;
      case kTypeTangents: s = checkTangentsPayload(payload, e, payloadOf(bytes, p->entries[static_cast<std::size_t>(p->normals)])); break;
      case kTypePatchUv: s = checkPatchUvPayload(payload, e); break;
      case kTypeRtt: s = checkRttPayload(payload, e, p->order); break;
      case kTypePatchPlacements: s = checkFloats(payload, e); break;
      case kTypeIdMap: s = checkIdMapPayload(payload, e, p->entries[static_cast<std::size_t>(p->placements)].arg0); break;
      case kTypeEncodedTransfer:
      case kTypeEncodedMatrixTransfer:
      case kTypeEncodedTexelTransfer:
      case kTypeEncodedTexelVisibility: {
        const std::size_t slot = static_cast<std::size_t>(
            std::find(p->transfer.begin(), p->transfer.end(), static_cast<int>(e.index)) - p->transfer.begin());
        if (payload.size() != e.size) return corrupt(sectionLabel(e) + ": size mismatch");
        s = checkEncodedTransfer(payload, e, *p, static_cast<int>(passOrder(e, *p)),
                                 decoded != nullptr ? &(*decoded)[slot] : nullptr, nullptr, nullptr, &m->lighting);
        // The whole section is here: its blob must be exactly the section.
        if (s.isOk()) {
          TransferBlobInfo info;
          if (Status t = readTransferBlobInfo(payload, &info); t.isOk() && info.blobSize != payload.size()) {
            s = corrupt(sectionLabel(e) + ": its blob declares " + num(info.blobSize) + " bytes in a " +
                        num(payload.size()) + "-byte section");
          }
        }
        break;
      }
      default: break;
    }
    if (!s.isOk()) return s;
  }
  return Status::ok();
}

void fillSummary(const Parsed& p, Metadata&& m, AssetSummary* out) {
  AssetSummary s;
  s.versionMajor = p.major;
  s.versionMinor = p.minor;
  s.shOrder = static_cast<int>(p.order);
  s.vertexCount = p.vertexCount;
  s.triangleCount = p.triangleCount;
  s.sectionCount = p.sectionCount;
  s.fileSize = p.fileSize;
  for (int t : p.transfer) {
    const Entry& e = p.entries[static_cast<std::size_t>(t)];
    const bool visibility = isVisibilityType(e.type);  // arg2 is its order, not bounces
    s.passes.push_back({static_cast<TransferKind>(e.arg0), static_cast<int>(e.arg1), visibility ? 0 : static_cast<int>(e.arg2),
                        isEncodedType(e.type), e.size, e.index, formOf(e.type),
                        isTexelType(e.type) ? TransferDomain::kTexel : TransferDomain::kVertex,
                        visibility ? static_cast<int>(e.arg2) : 0});
  }
  s.texelCount = p.texelCount;
  s.samples = m.samples;
  s.seed = m.seed;
  s.sampling = std::move(m.sampling);
  s.name = std::move(m.name);
  s.lighting = m.lighting;
  for (const Entry& e : p.entries) {
    s.sections.push_back({e.type, e.format, e.offset, e.size, e.arg0, e.arg1, e.arg2, e.crc});
  }
  s.tableEnd = kAssetHeaderSize + std::uint64_t{p.sectionCount} * kAssetSectionEntrySize;
  *out = std::move(s);
}

// Copies a validated float payload; memcpy on little-endian hosts, per value otherwise.
void readFloats(std::span<const std::uint8_t> payload, float* dst) {
  const std::size_t count = payload.size() / 4;
  if constexpr (std::endian::native == std::endian::little) {
    if (count > 0) std::memcpy(dst, payload.data(), count * 4);
  } else {
    for (std::size_t i = 0; i < count; ++i) dst[i] = floatFromBits(readLe32(payload.data() + 4 * i));
  }
}

template <typename T>
void readTriples(std::span<const std::uint8_t> payload, std::vector<T>* out) {
  static_assert(sizeof(T) == 3 * sizeof(float) && std::is_trivially_copyable_v<T>, "T must be 3 packed floats");
  out->resize(payload.size() / sizeof(T));
  if constexpr (std::endian::native == std::endian::little) {
    if (!out->empty()) std::memcpy(out->data(), payload.data(), out->size() * sizeof(T));
  } else {
    for (std::size_t i = 0; i < out->size(); ++i) {
      float f[3];
      readFloats(payload.subspan(12 * i, 12), f);
      std::memcpy(&(*out)[i], f, sizeof f);
    }
  }
}

// Copies the three validated atlas sections (they exist: the file has a texel pass) into *out.
void readAtlasSections(std::span<const std::uint8_t> bytes, const Parsed& p, BakedAsset* out) {
  const auto payload = [&](int slot) { return payloadOf(bytes, p.entries[static_cast<std::size_t>(slot)]); };
  const auto uv = payload(p.atlasUv);
  out->atlasUv.resize(uv.size() / 4);
  readFloats(uv, out->atlasUv.data());
  // Validated before: this cannot fail, and *out is all the caller keeps.
  static_cast<void>(parseAtlases(payload(p.atlases), p.entries[static_cast<std::size_t>(p.atlases)], p, &out->atlases).isOk());
  const auto coverage = payload(p.coverage);
  out->texelCoverage.assign(coverage.begin(), coverage.end());
  out->texelNormals.clear();
  if (p.texelNormals >= 0) {
    const auto normals = payload(p.texelNormals);
    out->texelNormals.resize(normals.size() / 2);
    for (std::size_t i = 0; i < out->texelNormals.size(); ++i) {
      out->texelNormals[i] = static_cast<std::int16_t>(readLe16(normals.data() + 2 * i));
    }
  }
}

// Copies the three validated bi-scale sections (they exist) into *out.
void readBiScaleSections(std::span<const std::uint8_t> bytes, const Parsed& p, BakedAsset* out) {
  const auto payload = [&](int slot) { return payloadOf(bytes, p.entries[static_cast<std::size_t>(slot)]); };
  readTriples(payload(p.tangents), &out->tangents);
  out->patchUv.clear();
  out->patchPlacements.clear();
  out->idMap.clear();
  if (p.patchUv >= 0) {
    const auto uv = payload(p.patchUv);
    out->patchUv.resize(uv.size() / 4);
    readFloats(uv, out->patchUv.data());
  } else {
    const auto placements = payload(p.placements);
    out->patchPlacements.resize(placements.size() / kAssetPlacementBytes);
    for (std::size_t k = 0; k < out->patchPlacements.size(); ++k) {
      float f[9];
      readFloats(placements.subspan(kAssetPlacementBytes * k, kAssetPlacementBytes), f);
      out->patchPlacements[k] = {{f[0], f[1], f[2]}, {f[3], f[4], f[5]}, {f[6], f[7], f[8]}};
    }
    const auto ids = payload(p.idMap);
    out->idMap.resize(ids.size() / 2);
    for (std::size_t t = 0; t < out->idMap.size(); ++t) out->idMap[t] = readLe16(ids.data() + 2 * t);
    out->idMapPerTriangle = p.idMapPerTriangle;
  }
  const auto rtt = payload(p.rtt);
  out->rtt.assign(rtt.begin(), rtt.end());
}

void readSpecular(std::span<const std::uint8_t> payload, std::vector<SpecularMaterial>* out) {
  constexpr std::size_t kStride = kAssetSpecularBytesPerVertex;
  out->resize(payload.size() / kStride);
  for (std::size_t v = 0; v < out->size(); ++v) {
    float f[5];
    readFloats(payload.subspan(kStride * v, kStride), f);
    (*out)[v].f0 = {f[0], f[1], f[2]};
    (*out)[v].f90 = f[3];
    (*out)[v].exponent = f[4];
  }
}

}  // namespace

const char* transferKindName(TransferKind kind) {
  switch (kind) {
    case TransferKind::kUnshadowed: return "unshadowed";
    case TransferKind::kShadowed: return "shadowed";
    case TransferKind::kInterreflected: return "interreflected";
  }
  return "unknown";
}

const char* transferFormName(TransferForm form) {
  switch (form) {
    case TransferForm::kVector: return "vector";
    case TransferForm::kMatrix: return "matrix";
    case TransferForm::kVisibility: return "visibility";
  }
  return "unknown";
}

const TransferPass* findPass(const BakedAsset& asset, TransferKind kind) {
  return findPass(asset, kind, TransferForm::kVector);
}

const TransferPass* findPass(const BakedAsset& asset, TransferKind kind, TransferForm form) {
  return findPass(asset, kind, form, TransferDomain::kVertex);
}

const TransferPass* findPass(const BakedAsset& asset, TransferKind kind, TransferForm form, TransferDomain domain) {
  for (const TransferPass& p : asset.passes)
    if (p.kind == kind && p.form == form && p.domain == domain) return &p;
  return nullptr;
}

const char* transferDomainName(TransferDomain domain) {
  switch (domain) {
    case TransferDomain::kVertex: return "vertex";
    case TransferDomain::kTexel: return "texel";
  }
  return "unknown";
}

std::uint64_t assetTexelCount(const BakedAsset& asset) {
  std::uint64_t texels = 0;
  for (const TextureAtlas& a : asset.atlases) texels += std::uint64_t{a.width} * a.height;
  return texels;
}

bool isValidAssetSamplingName(std::string_view sampling) {
  if (sampling.size() > kMaxAssetSamplingBytes) return false;
  for (char ch : sampling) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
    if (!ok) return false;
  }
  return true;
}

bool isValidAssetName(std::string_view name) {
  if (name.size() > kMaxAssetNameBytes) return false;
  // UTF-8 per RFC 3629: shortest form only, no surrogates, nothing above U+10FFFF.
  std::size_t i = 0;
  while (i < name.size()) {
    const auto b0 = static_cast<std::uint8_t>(name[i]);
    if (b0 < 0x80) {
      if (b0 < 0x20 || b0 == 0x7F) return false;  // C0 controls and DEL
      ++i;
      continue;
    }
    std::size_t len = 0;
    std::uint32_t cp = 0, min = 0;
    if ((b0 & 0xE0) == 0xC0) {
      len = 2, cp = b0 & 0x1Fu, min = 0x80;
    } else if ((b0 & 0xF0) == 0xE0) {
      len = 3, cp = b0 & 0x0Fu, min = 0x800;
    } else if ((b0 & 0xF8) == 0xF0) {
      len = 4, cp = b0 & 0x07u, min = 0x10000;
    } else {
      return false;
    }
    if (name.size() - i < len) return false;
    for (std::size_t k = 1; k < len; ++k) {
      const auto b = static_cast<std::uint8_t>(name[i + k]);
      if ((b & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (b & 0x3Fu);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    if (cp >= 0x80 && cp < 0xA0) return false;  // C1 controls
    i += len;
  }
  return true;
}

Status peekAssetHeader(std::span<const std::uint8_t> bytes, AssetSummary* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "peekAssetHeader: out is null");
  Parsed p;
  if (Status s = parseHeader(bytes, &p); !s.isOk()) return s;
  if (Status s = parseTable(bytes, &p); !s.isOk()) return s;
  // The prefix must hold each small section read here; entries are bounded by the declared
  // file size, so offset + size cannot overflow.
  auto inPrefix = [&](const Entry& e, const char* what) -> Status {
    if (e.offset + e.size > bytes.size()) {
      return Status::error(StatusCode::kTruncated, "asset prefix is " + num(bytes.size()) + " bytes; its " + what +
                                                       " section needs " + num(e.offset + e.size));
    }
    return checkSectionCrc(bytes, e);
  };
  Metadata m;
  const Entry& meta = p.entries[static_cast<std::size_t>(p.metadata)];
  if (Status s = inPrefix(meta, "metadata"); !s.isOk()) return s;
  if (Status s = parseMetadata(payloadOf(bytes, meta), meta, &m); !s.isOk()) return s;
  if (p.lighting >= 0) {
    const Entry& light = p.entries[static_cast<std::size_t>(p.lighting)];
    if (Status s = inPrefix(light, "lighting"); !s.isOk()) return s;
    if (Status s = parseLighting(payloadOf(bytes, light), light, &m.lighting); !s.isOk()) return s;
  }
  if (Status s = checkMatrixPackings(p, m.lighting); !s.isOk()) return s;
  fillSummary(p, std::move(m), out);
  return Status::ok();
}

Status verifyAsset(std::span<const std::uint8_t> bytes, AssetSummary* out) {
  Parsed p;
  Metadata m;
  if (Status s = validateAll(bytes, &p, &m); !s.isOk()) return s;
  if (out != nullptr) fillSummary(p, std::move(m), out);
  return Status::ok();
}

Status decodeAsset(std::span<const std::uint8_t> bytes, BakedAsset* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAsset: out is null");
  Parsed p;
  Metadata m;
  std::vector<std::vector<float>> decoded;  // per transfer section, table order; encoded ones only
  if (Status s = validateAll(bytes, &p, &m, &decoded); !s.isOk()) return s;
  BakedAsset a;
  a.shOrder = static_cast<int>(p.order);
  auto payload = [&](int entry) { return payloadOf(bytes, p.entries[static_cast<std::size_t>(entry)]); };
  readTriples(payload(p.positions), &a.positions);
  readTriples(payload(p.normals), &a.normals);
  readTriples(payload(p.albedo), &a.albedo);
  {
    const auto b = payload(p.indices);
    a.indices.resize(b.size() / 4);
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(a.indices.data(), b.data(), b.size());
    } else {
      for (std::size_t i = 0; i < a.indices.size(); ++i) a.indices[i] = readLe32(b.data() + 4 * i);
    }
  }
  for (int t : p.transfer) {
    const Entry& e = p.entries[static_cast<std::size_t>(t)];
    TransferPass pass = passHeader(e);
    if (isEncodedType(e.type)) {
      const std::size_t slot = a.passes.size();
      pass.coeffs = std::move(decoded[slot]);
      const auto blob = payload(t);
      pass.encoded.assign(blob.begin(), blob.end());
    } else {
      pass.coeffs.resize(static_cast<std::size_t>(e.size / 4));
      readFloats(payload(t), pass.coeffs.data());
    }
    a.passes.push_back(std::move(pass));
  }
  if (p.specular >= 0) readSpecular(payload(p.specular), &a.specular);
  if (p.atlases >= 0) readAtlasSections(bytes, p, &a);
  if (p.rtt >= 0) readBiScaleSections(bytes, p, &a);
  a.samples = m.samples;
  a.seed = m.seed;
  a.sampling = std::move(m.sampling);
  a.name = std::move(m.name);
  a.lighting = m.lighting;
  *out = std::move(a);
  return Status::ok();
}

Status decodeAssetGeometry(std::span<const std::uint8_t> file, BakedAsset* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetGeometry: out is null");
  Parsed p;
  if (Status s = parseHeader(file, &p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(file, p); !s.isOk()) return s;
  if (Status s = parseTable(file, &p); !s.isOk()) return s;
  Metadata m;
  for (int slot : {p.positions, p.normals, p.albedo, p.indices, p.metadata, p.lighting}) {
    if (slot < 0) continue;  // only lighting is optional; parseTable required the rest
    const Entry& e = p.entries[static_cast<std::size_t>(slot)];
    if (Status s = checkSectionCrc(file, e); !s.isOk()) return s;
    const auto payload = payloadOf(file, e);
    Status s;
    switch (e.type) {
      case kTypeIndices: s = checkIndices(payload, e, p.vertexCount); break;
      case kTypeMetadata: s = parseMetadata(payload, e, &m); break;
      case kTypeLighting: s = parseLighting(payload, e, &m.lighting); break;
      default: s = checkFloats(payload, e); break;
    }
    if (!s.isOk()) return s;
  }
  BakedAsset a;
  a.shOrder = static_cast<int>(p.order);
  auto payload = [&](int entry) { return payloadOf(file, p.entries[static_cast<std::size_t>(entry)]); };
  readTriples(payload(p.positions), &a.positions);
  readTriples(payload(p.normals), &a.normals);
  readTriples(payload(p.albedo), &a.albedo);
  const auto b = payload(p.indices);
  a.indices.resize(b.size() / 4);
  for (std::size_t i = 0; i < a.indices.size(); ++i) a.indices[i] = readLe32(b.data() + 4 * i);
  a.samples = m.samples;
  a.seed = m.seed;
  a.sampling = std::move(m.sampling);
  a.name = std::move(m.name);
  a.lighting = m.lighting;
  *out = std::move(a);
  return Status::ok();
}

namespace {

// Header and table of a progressive buffer, and the table entry of transfer pass `pass`
// with `bands` (0 = all) in range; `caller` names the function in errors.
Status locatePass(std::span<const std::uint8_t> file, int pass, int bands, const char* caller, Parsed* p, const Entry** entry) {
  if (Status s = parseHeader(file, p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(file, *p); !s.isOk()) return s;
  if (Status s = parseTable(file, p); !s.isOk()) return s;
  if (pass < 0 || static_cast<std::size_t>(pass) >= p->transfer.size()) {
    return Status::error(StatusCode::kInvalidArgument,
                         std::string(caller) + ": pass " + std::to_string(pass) + " of " + std::to_string(p->transfer.size()));
  }
  const Entry& e = p->entries[static_cast<std::size_t>(p->transfer[static_cast<std::size_t>(pass)])];
  // A visibility pass's bands are its own (its order m may exceed the header's n).
  const std::uint32_t order = passOrder(e, *p);
  if (bands < 0 || bands > static_cast<int>(order)) {
    return Status::error(StatusCode::kInvalidArgument, std::string(caller) + ": bands " + std::to_string(bands) +
                                                           " outside 0.." + std::to_string(order));
  }
  *entry = &e;
  return Status::ok();
}

// The lighting a matrix pass's packing and a visibility pass's validity depend on: the
// lighting section (which must have arrived) or distant when the file has none; then the
// float32 matrix sizes and the visibility rule against it (checkMatrixPackings).
Status progressiveLighting(std::span<const std::uint8_t> file, const Parsed& p, LightingInfo* out) {
  *out = LightingInfo{};
  if (p.lighting >= 0) {
    const Entry& e = p.entries[static_cast<std::size_t>(p.lighting)];
    if (Status s = checkSectionCrc(file, e); !s.isOk()) return s;
    if (Status s = parseLighting(payloadOf(file, e), e, out); !s.isOk()) return s;
  }
  return checkMatrixPackings(p, *out);
}

}  // namespace

Status decodeAssetPass(std::span<const std::uint8_t> file, int pass, int bands, TransferPass* out, int* bandsDecoded) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetPass: out is null");
  Parsed p;
  const Entry* entry = nullptr;
  if (Status s = locatePass(file, pass, bands, "decodeAssetPass", &p, &entry); !s.isOk()) return s;
  const Entry& e = *entry;
  const auto payload = payloadOf(file, e);
  TransferPass t = passHeader(e);
  const int order = static_cast<int>(passOrder(e, p));
  int decodedBands = order;
  LightingInfo lighting;
  if (isMatrixType(e.type) || isVisibilityType(e.type)) {  // packing; visibility needs distant lighting
    if (Status s = progressiveLighting(file, p, &lighting); !s.isOk()) return s;
  }
  if (isEncodedType(e.type)) {
    // The blob's own header and part checksums protect a prefix; the section checksum
    // needs the whole section, which a progressive client does not have yet. A matrix
    // pass's prefix holds the order-`bands` leading blocks (the packing's prefix rule).
    if (Status s = checkEncodedTransfer(payload, e, p, bands, &t.coeffs, &decodedBands, nullptr, &lighting); !s.isOk()) return s;
  } else {
    if (bands != 0 && bands != order) {
      // A float32 section is coefficient-interleaved: it cannot be cut into bands.
      return Status::error(StatusCode::kInvalidArgument, sectionLabel(e) + " is float32: only all bands decode");
    }
    if (Status s = checkSectionCrc(file, e); !s.isOk()) return s;
    if (Status s = checkTransferFloats(payload, e); !s.isOk()) return s;
    t.coeffs.resize(static_cast<std::size_t>(e.size / 4));
    readFloats(payload, t.coeffs.data());
  }
  *out = std::move(t);
  if (bandsDecoded != nullptr) *bandsDecoded = decodedBands;
  return Status::ok();
}

Status decodeAssetPassCpca(std::span<const std::uint8_t> file, int pass, int bands, CpcaTransfer* out, TransferPass* info) {
  if (out == nullptr || info == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetPassCpca: out or info is null");
  Parsed p;
  const Entry* entry = nullptr;
  if (Status s = locatePass(file, pass, bands, "decodeAssetPassCpca", &p, &entry); !s.isOk()) return s;
  if (entry->type != kTypeEncodedTransfer && entry->type != kTypeEncodedTexelTransfer &&
      entry->type != kTypeEncodedTexelVisibility) {
    return Status::error(StatusCode::kInvalidArgument,
                         sectionLabel(*entry) + (entry->type == kTypeEncodedMatrixTransfer ? " holds matrices: use decodeAssetPassCpcaMatrix"
                                                                                          : " is float32, not CPCA"));
  }
  if (isVisibilityType(entry->type)) {  // as decodeAssetPass: a visibility pass needs distant lighting
    LightingInfo lighting;
    if (Status s = progressiveLighting(file, p, &lighting); !s.isOk()) return s;
  }
  CpcaTransfer cpca;
  if (Status s = checkEncodedTransfer(payloadOf(file, *entry), *entry, p, bands, nullptr, nullptr, &cpca); !s.isOk()) return s;
  *info = passHeader(*entry);
  *out = std::move(cpca);
  return Status::ok();
}

}  // namespace prt

namespace prt {

Status decodeAssetPassCpcaMatrix(std::span<const std::uint8_t> file, int pass, int bands, CpcaMatrixTransfer* out,
                                 TransferPass* info) {
  if (out == nullptr || info == nullptr) {
    return Status::error(StatusCode::kInvalidArgument, "decodeAssetPassCpcaMatrix: out or info is null");
  }
  Parsed p;
  const Entry* entry = nullptr;
  if (Status s = locatePass(file, pass, bands, "decodeAssetPassCpcaMatrix", &p, &entry); !s.isOk()) return s;
  if (entry->type != kTypeEncodedMatrixTransfer) {
    return Status::error(StatusCode::kInvalidArgument, sectionLabel(*entry) + " is not an encoded matrix pass");
  }
  LightingInfo lighting;
  if (Status s = progressiveLighting(file, p, &lighting); !s.isOk()) return s;
  CpcaMatrixTransfer cpca;
  if (Status s = checkEncodedTransfer(payloadOf(file, *entry), *entry, p, bands, nullptr, nullptr, nullptr, &lighting, &cpca);
      !s.isOk()) {
    return s;
  }
  *info = passHeader(*entry);
  *out = std::move(cpca);
  return Status::ok();
}

Status decodeAssetAtlases(std::span<const std::uint8_t> file, BakedAsset* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetAtlases: out is null");
  Parsed p;
  if (Status s = parseHeader(file, &p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(file, p); !s.isOk()) return s;
  if (Status s = parseTable(file, &p); !s.isOk()) return s;
  BakedAsset a;
  if (p.atlases >= 0) {  // parseTable: then all three exist, with a texel pass
    for (int slot : {p.atlasUv, p.atlases, p.coverage, p.texelNormals}) {
      if (slot < 0) continue;  // the texel normals are optional
      const Entry& e = p.entries[static_cast<std::size_t>(slot)];
      if (Status s = checkSectionCrc(file, e); !s.isOk()) return s;
      const auto payload = payloadOf(file, e);
      Status s = e.type == kTypeAtlasUv   ? checkAtlasUv(payload, e)
                 : e.type == kTypeAtlases ? parseAtlases(payload, e, p, nullptr)
                 : e.type == kTypeTexelNormals
                     ? checkTexelNormals(payload, e, payloadOf(file, p.entries[static_cast<std::size_t>(p.coverage)]))
                     : checkCoverage(payload, e);
      if (!s.isOk()) return s;
    }
    readAtlasSections(file, p, &a);
  }
  out->atlasUv = std::move(a.atlasUv);
  out->atlases = std::move(a.atlases);
  out->texelCoverage = std::move(a.texelCoverage);
  out->texelNormals = std::move(a.texelNormals);
  return Status::ok();
}

Status decodeAssetBiScale(std::span<const std::uint8_t> file, BakedAsset* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetBiScale: out is null");
  Parsed p;
  if (Status s = parseHeader(file, &p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(file, p); !s.isOk()) return s;
  if (Status s = parseTable(file, &p); !s.isOk()) return s;
  BakedAsset a;
  if (p.rtt >= 0) {  // parseTable: then all three exist, with a matrix pass
    // The tangents are checked against the normals: those must have arrived too.
    for (int slot : {p.normals, p.tangents, p.patchUv, p.rtt, p.placements, p.idMap}) {
      if (slot < 0) continue;  // patch uv, or placements and id map
      if (Status s = checkSectionCrc(file, p.entries[static_cast<std::size_t>(slot)]); !s.isOk()) return s;
    }
    const auto payload = [&](int slot) { return payloadOf(file, p.entries[static_cast<std::size_t>(slot)]); };
    const Entry& normals = p.entries[static_cast<std::size_t>(p.normals)];
    PRT_RETURN_IF_ERROR(checkFloats(payload(p.normals), normals));
    PRT_RETURN_IF_ERROR(checkTangentsPayload(payload(p.tangents), p.entries[static_cast<std::size_t>(p.tangents)], payload(p.normals)));
    if (p.patchUv >= 0) {
      PRT_RETURN_IF_ERROR(checkPatchUvPayload(payload(p.patchUv), p.entries[static_cast<std::size_t>(p.patchUv)]));
    } else {
      const Entry& placements = p.entries[static_cast<std::size_t>(p.placements)];
      PRT_RETURN_IF_ERROR(checkFloats(payload(p.placements), placements));
      PRT_RETURN_IF_ERROR(checkIdMapPayload(payload(p.idMap), p.entries[static_cast<std::size_t>(p.idMap)], placements.arg0));
    }
    PRT_RETURN_IF_ERROR(checkRttPayload(payload(p.rtt), p.entries[static_cast<std::size_t>(p.rtt)], p.order));
    readBiScaleSections(file, p, &a);
  }
  out->tangents = std::move(a.tangents);
  out->patchUv = std::move(a.patchUv);
  out->rtt = std::move(a.rtt);
  out->patchPlacements = std::move(a.patchPlacements);
  out->idMap = std::move(a.idMap);
  out->idMapPerTriangle = a.idMapPerTriangle;
  return Status::ok();
}

Status decodeAssetSpecular(std::span<const std::uint8_t> file, std::vector<SpecularMaterial>* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "decodeAssetSpecular: out is null");
  Parsed p;
  if (Status s = parseHeader(file, &p); !s.isOk()) return s;
  if (Status s = checkWholeFileSize(file, p); !s.isOk()) return s;
  if (Status s = parseTable(file, &p); !s.isOk()) return s;
  std::vector<SpecularMaterial> specular;
  if (p.specular >= 0) {
    const Entry& e = p.entries[static_cast<std::size_t>(p.specular)];
    if (Status s = checkSectionCrc(file, e); !s.isOk()) return s;
    if (Status s = checkSpecularPayload(payloadOf(file, e), e); !s.isOk()) return s;
    readSpecular(payloadOf(file, e), &specular);
  }
  *out = std::move(specular);
  return Status::ok();
}

}  // namespace prt
