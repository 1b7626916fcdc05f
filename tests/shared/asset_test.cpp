// The asset format (docs/asset-format.md): bit-exact round trips, and a reader that rejects
// every truncation, every single-byte corruption and every crafted inconsistency with a
// named error instead of crashing or reading out of bounds (also run under ASan + UBSan).
//
// The helpers below re-implement the layout from the document (not from asset_writer.cpp)
// so crafted files test the document as much as the code: `build` is an independent writer,
// `reseal` recomputes every checksum after a deliberate edit, so the reader's semantic
// checks are reached rather than stopped at the checksum.
#include "prt/asset.h"
#include "prt/transfer_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "prt/checksum.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"

namespace prt {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// ---- Little-endian access, straight from the document ---------------------------------

std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const Bytes& b, std::size_t at) {
  return static_cast<std::uint64_t>(rd32(b, at)) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32;
}
void wr16(Bytes& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void wr64(Bytes& b, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// IEEE-754 bits of a float (std::bit_cast is missing from Emscripten's libc++).
std::uint32_t bitsOf(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// Header field offsets and entry layout as docs/asset-format.md states them.
constexpr std::size_t kHdrVersionMajor = 4, kHdrVersionMinor = 6, kHdrFlags = 8, kHdrOrder = 12,
                      kHdrVertices = 16, kHdrTriangles = 20, kHdrSections = 24, kHdrTableCrc = 28,
                      kHdrFileSize = 32, kHdrReserved = 40, kHdrCrc = 60, kHeaderBytes = 64, kEntryBytes = 40;
constexpr std::size_t kEType = 0, kEFormat = 4, kEOffset = 8, kESize = 16, kEArg0 = 24, kEArg1 = 28, kEArg2 = 32,
                      kECrc = 36;
constexpr std::uint32_t kPositions = 1, kNormals = 2, kIndices = 3, kAlbedo = 4, kTransfer = 5, kMetadata = 6,
                        kLighting = 7;
// Lighting payload: u32 model, f32 centre x, y, z, f32 radius.
constexpr std::size_t kLightModel = 0, kLightCenter = 4, kLightRadius = 16, kLightBytes = 20;
constexpr std::uint32_t kF32 = 1, kU32 = 2, kRawBytes = 3;

std::size_t entryAt(std::size_t i) { return kHeaderBytes + i * kEntryBytes; }

// Index of the first table entry of `type` (and, for transfer, `kind`).
std::size_t findEntry(const Bytes& b, std::uint32_t type, std::uint32_t kind = 0) {
  const std::uint32_t n = rd32(b, kHdrSections);
  for (std::size_t i = 0; i < n; ++i) {
    if (rd32(b, entryAt(i) + kEType) == type && (type != kTransfer || rd32(b, entryAt(i) + kEArg0) == kind)) return i;
  }
  ADD_FAILURE() << "no section of type " << type;
  return 0;
}
std::size_t payloadOffset(const Bytes& b, std::size_t entry) {
  return static_cast<std::size_t>(rd64(b, entryAt(entry) + kEOffset));
}

// Recomputes every section checksum whose entry lies inside the file, then the table and
// header checksums (the table's only if it fits): the file then passes every checksum
// whatever was edited.
void reseal(Bytes& b) {
  const std::uint32_t n = rd32(b, kHdrSections);
  // 64-bit: n * 40 wraps a 32-bit size_t in wasm for the huge counts tested below.
  const std::uint64_t tableEnd = kHeaderBytes + static_cast<std::uint64_t>(n) * kEntryBytes;
  if (tableEnd <= b.size()) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t off = rd64(b, entryAt(i) + kEOffset), size = rd64(b, entryAt(i) + kESize);
      if (off <= b.size() && size <= b.size() - off) {
        wr32(b, entryAt(i) + kECrc, crc32c({b.data() + off, static_cast<std::size_t>(size)}));
      }
    }
    wr32(b, kHdrTableCrc, crc32c({b.data() + kHeaderBytes, static_cast<std::size_t>(tableEnd) - kHeaderBytes}));
  }
  wr32(b, kHdrCrc, crc32c({b.data(), kHdrCrc}));
}

// A file split into its parts, and an independent writer that lays such parts out as the
// document prescribes (sections in list order, each at the next multiple of 16).
struct RawSection {
  std::uint32_t type = 0, format = 0, arg0 = 0, arg1 = 0, arg2 = 0;
  Bytes payload;
};
struct RawAsset {
  Bytes header;  // the 64 header bytes, of which build() rewrites counts, size and checksums
  std::vector<RawSection> sections;
};

RawAsset split(const Bytes& b) {
  RawAsset r;
  r.header.assign(b.begin(), b.begin() + kHeaderBytes);
  const std::uint32_t n = rd32(b, kHdrSections);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t e = entryAt(i);
    RawSection s{rd32(b, e + kEType), rd32(b, e + kEFormat), rd32(b, e + kEArg0), rd32(b, e + kEArg1), rd32(b, e + kEArg2), {}};
    const std::size_t off = static_cast<std::size_t>(rd64(b, e + kEOffset)), size = static_cast<std::size_t>(rd64(b, e + kESize));
    s.payload.assign(b.begin() + static_cast<std::ptrdiff_t>(off), b.begin() + static_cast<std::ptrdiff_t>(off + size));
    r.sections.push_back(std::move(s));
  }
  return r;
}

Bytes build(const RawAsset& r) {
  const std::size_t n = r.sections.size();
  std::size_t end = kHeaderBytes + n * kEntryBytes;
  std::vector<std::size_t> offsets;
  for (const RawSection& s : r.sections) {
    const std::size_t off = (end + 15) / 16 * 16;
    offsets.push_back(off);
    end = off + s.payload.size();
  }
  Bytes b(end, 0);
  std::copy(r.header.begin(), r.header.end(), b.begin());
  wr32(b, kHdrSections, static_cast<std::uint32_t>(n));
  wr64(b, kHdrFileSize, end);
  for (std::size_t i = 0; i < n; ++i) {
    const RawSection& s = r.sections[i];
    std::copy(s.payload.begin(), s.payload.end(), b.begin() + static_cast<std::ptrdiff_t>(offsets[i]));
    const std::size_t e = entryAt(i);
    wr32(b, e + kEType, s.type);
    wr32(b, e + kEFormat, s.format);
    wr64(b, e + kEOffset, offsets[i]);
    wr64(b, e + kESize, s.payload.size());
    wr32(b, e + kEArg0, s.arg0);
    wr32(b, e + kEArg1, s.arg1);
    wr32(b, e + kEArg2, s.arg2);
  }
  reseal(b);
  return b;
}

// ---- Test assets ----------------------------------------------------------------------

float nextValue(Pcg32& rng) { return (rng.nextFloat() - 0.5f) * 4.0f; }

// A small closed mesh-like asset with every field populated. Awkward float values (negative
// zero, denormals, the largest finite float, the largest transfer value) check that the round trip is bit-exact.
BakedAsset makeAsset(int order, std::size_t vertexCount, std::size_t triangleCount, bool allPasses = true) {
  Pcg32 rng(static_cast<std::uint64_t>(order) * 1000 + vertexCount);
  BakedAsset a;
  a.shOrder = order;
  for (std::size_t v = 0; v < vertexCount; ++v) {
    a.positions.push_back({nextValue(rng), nextValue(rng), nextValue(rng)});
    a.normals.push_back(squareToSphere(rng.nextFloat(), rng.nextFloat()));
    a.albedo.push_back({rng.nextFloat(), rng.nextFloat(), rng.nextFloat()});
  }
  for (std::size_t t = 0; t < triangleCount; ++t)
    for (int k = 0; k < 3; ++k) a.indices.push_back(static_cast<std::uint32_t>((t + static_cast<std::size_t>(k)) % vertexCount));
  const std::size_t n = static_cast<std::size_t>(order) * static_cast<std::size_t>(order);
  const TransferKind kinds[] = {TransferKind::kShadowed, TransferKind::kUnshadowed, TransferKind::kInterreflected};
  for (TransferKind kind : kinds) {
    if (!allPasses && kind != TransferKind::kShadowed) continue;
    TransferPass p;
    p.kind = kind;
    p.channels = kind == TransferKind::kInterreflected ? 3 : 1;
    p.bounces = kind == TransferKind::kInterreflected ? 4 : 0;
    p.coeffs.resize(vertexCount * static_cast<std::size_t>(p.channels) * n);
    for (float& c : p.coeffs) c = nextValue(rng);
    a.passes.push_back(std::move(p));
  }
  a.positions[0].x = -0.0f;
  a.albedo[0].g = 1e-40f;  // denormal
  a.positions.back().y = std::numeric_limits<float>::max();
  a.passes[0].coeffs[0] = -kMaxTransferMagnitude;  // transfer's own limit (transfer_codec.h)
  a.passes[0].coeffs.back() = -std::numeric_limits<float>::denorm_min();
  a.samples = 0x1234567890ULL;  // above 32 bits on purpose
  a.seed = 0xFEDCBA9876543210ULL;
  a.sampling = "stratified";
  a.name = "Cornell box \xC3\xA9t\xC3\xA9 \xE6\x97\xA5\xE6\x9C\xAC \xF0\x9F\x99\x82";  // "été 日本 🙂"
  // Local lighting with awkward values too: negative zero, a denormal, a huge radius.
  a.lighting = {LightingModel::kLocalSpherePaper, {-0.0f, 1e-40f, -3.25f}, 1e30f};
  return a;
}

Bytes encodeOrDie(const BakedAsset& a) {
  Bytes b;
  const Status s = encodeAsset(a, &b);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return b;
}

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectBitEqual(const BakedAsset& a, const BakedAsset& b) {
  EXPECT_EQ(a.shOrder, b.shOrder);
  EXPECT_TRUE(sameBits(a.positions, b.positions));
  EXPECT_TRUE(sameBits(a.normals, b.normals));
  EXPECT_TRUE(sameBits(a.albedo, b.albedo));
  EXPECT_EQ(a.indices, b.indices);
  ASSERT_EQ(a.passes.size(), b.passes.size());
  for (std::size_t i = 0; i < a.passes.size(); ++i) {
    EXPECT_EQ(a.passes[i].kind, b.passes[i].kind);
    EXPECT_EQ(a.passes[i].channels, b.passes[i].channels);
    EXPECT_EQ(a.passes[i].bounces, b.passes[i].bounces);
    EXPECT_TRUE(sameBits(a.passes[i].coeffs, b.passes[i].coeffs)) << "pass " << i;
  }
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.sampling, b.sampling);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.lighting.model, b.lighting.model);
  EXPECT_EQ(bitsOf(a.lighting.center.x), bitsOf(b.lighting.center.x));
  EXPECT_EQ(bitsOf(a.lighting.center.y), bitsOf(b.lighting.center.y));
  EXPECT_EQ(bitsOf(a.lighting.center.z), bitsOf(b.lighting.center.z));
  EXPECT_EQ(bitsOf(a.lighting.radius), bitsOf(b.lighting.radius));
}

Status decode(const Bytes& b, BakedAsset* out = nullptr) {
  BakedAsset scratch;
  return decodeAsset(b, out ? out : &scratch);
}

void expectError(const Status& s, StatusCode code, const char* fragment) {
  EXPECT_FALSE(s.isOk());
  EXPECT_EQ(s.code(), code) << s.toString();
  EXPECT_NE(s.message().find(fragment), std::string::npos) << "message '" << s.message() << "' lacks '" << fragment << "'";
}

// decodeAsset and verifyAsset must agree on every input.
void expectDecodeError(const Bytes& b, StatusCode code, const char* fragment) {
  expectError(decode(b), code, fragment);
  AssetSummary summary;
  expectError(verifyAsset(b, &summary), code, fragment);
}

bool isNamedDecodeError(StatusCode c) {
  return c == StatusCode::kTruncated || c == StatusCode::kBadMagic || c == StatusCode::kBadVersion ||
         c == StatusCode::kChecksumMismatch || c == StatusCode::kCorrupt;
}

// ---- Checksum -------------------------------------------------------------------------

TEST(Checksum, Crc32cMatchesPublishedVectors) {
  const std::string check = "123456789";
  EXPECT_EQ(crc32c({reinterpret_cast<const std::uint8_t*>(check.data()), check.size()}), 0xE3069283u);
  EXPECT_EQ(crc32c({}), 0u);
  // RFC 3720 (iSCSI) appendix B.4.
  Bytes zeros(32, 0), ones(32, 0xFF), up(32), down(32);
  for (std::size_t i = 0; i < 32; ++i) {
    up[i] = static_cast<std::uint8_t>(i);
    down[i] = static_cast<std::uint8_t>(31 - i);
  }
  EXPECT_EQ(crc32c(zeros), 0x8A9136AAu);
  EXPECT_EQ(crc32c(ones), 0x62A8AB43u);
  EXPECT_EQ(crc32c(up), 0x46DD794Eu);
  EXPECT_EQ(crc32c(down), 0x113FDB5Cu);
}

TEST(Checksum, Crc32cContinuesAcrossPiecesAndAlignments) {
  Bytes data(1000);
  Pcg32 rng(7);
  for (auto& x : data) x = static_cast<std::uint8_t>(rng.next());
  const std::uint32_t whole = crc32c(data);
  for (std::size_t cut : {0, 1, 7, 8, 9, 500, 999, 1000}) {
    const std::span<const std::uint8_t> all(data);
    EXPECT_EQ(crc32c(all.subspan(cut), crc32c(all.first(cut))), whole) << cut;
  }
  // Unaligned starts give the same answer as the byte-at-a-time definition.
  for (std::size_t start = 0; start < 9; ++start) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (std::size_t i = start; i < data.size(); ++i) {
      c ^= data[i];
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    }
    EXPECT_EQ(crc32c(std::span<const std::uint8_t>(data).subspan(start)), ~c) << start;
  }
}

// ---- Round trip and layout -------------------------------------------------------------

TEST(Asset, RoundTripIsBitExact) {
  struct Case {
    int order;
    std::size_t vertices, triangles;
    bool allPasses;
  };
  for (const Case& c : {Case{1, 1, 1, true}, Case{2, 4, 2, true}, Case{5, 37, 50, true}, Case{8, 100, 190, false},
                        Case{kMaxShOrder, 9, 3, true}}) {
    const BakedAsset a = makeAsset(c.order, c.vertices, c.triangles, c.allPasses);
    const Bytes bytes = encodeOrDie(a);
    BakedAsset back;
    ASSERT_TRUE(decode(bytes, &back).isOk()) << decode(bytes).toString();
    expectBitEqual(a, back);
    // Re-encoding the decoded asset reproduces the file byte for byte.
    EXPECT_EQ(encodeOrDie(back), bytes);
  }
}

TEST(Asset, EveryLightingModelRoundTrips) {
  for (const LightingInfo& l : {LightingInfo{}, LightingInfo{LightingModel::kLocalSphere, {0.0f, 1.5f, 0.0f}, 3.2f},
                                LightingInfo{LightingModel::kLocalSpherePaper, {-1e6f, 2.5e-3f, 7.0f}, 1e-20f}}) {
    BakedAsset a = makeAsset(3, 5, 4);
    a.lighting = l;
    const Bytes bytes = encodeOrDie(a);
    BakedAsset back;
    ASSERT_TRUE(decode(bytes, &back).isOk()) << lightingModelName(l.model);
    expectBitEqual(a, back);
    AssetSummary peeked, verified;
    ASSERT_TRUE(peekAssetHeader(bytes, &peeked).isOk());
    ASSERT_TRUE(verifyAsset(bytes, &verified).isOk());
    for (const AssetSummary* s : {&peeked, &verified}) {
      EXPECT_EQ(s->lighting.model, l.model);
      EXPECT_EQ(bitsOf(s->lighting.center.y), bitsOf(l.center.y));
      EXPECT_EQ(bitsOf(s->lighting.radius), bitsOf(l.radius));
    }
  }
  EXPECT_STREQ(lightingModelName(LightingModel::kDistant), "distant");
  EXPECT_STREQ(lightingModelName(LightingModel::kLocalSphere), "local-sphere");
  EXPECT_STREQ(lightingModelName(LightingModel::kLocalSpherePaper), "local-sphere-paper");
  EXPECT_STREQ(lightingModelName(static_cast<LightingModel>(3)), "unknown");
  EXPECT_FALSE(isLocalLighting(LightingModel::kDistant));
  EXPECT_TRUE(isLocalLighting(LightingModel::kLocalSphere));
  EXPECT_TRUE(isLocalLighting(LightingModel::kLocalSpherePaper));
}

TEST(Asset, EmptyStringsRoundTrip) {
  BakedAsset a = makeAsset(3, 5, 4);
  a.name.clear();
  a.sampling.clear();
  a.samples = 0;
  a.seed = 0;
  BakedAsset back;
  ASSERT_TRUE(decode(encodeOrDie(a), &back).isOk());
  expectBitEqual(a, back);
}

TEST(Asset, LayoutMatchesTheDocument) {
  const BakedAsset a = makeAsset(3, 5, 4);
  const Bytes b = encodeOrDie(a);
  ASSERT_GE(b.size(), kHeaderBytes);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "PRTA");
  EXPECT_EQ(b[kHdrVersionMajor], 1);
  EXPECT_EQ(b[kHdrVersionMajor + 1], 0);
  EXPECT_EQ(rd32(b, kHdrVersionMinor) & 0xFFFFu, 7u);
  EXPECT_EQ(rd32(b, kHdrFlags), 0u);
  EXPECT_EQ(rd32(b, kHdrOrder), 3u);
  EXPECT_EQ(rd32(b, kHdrVertices), 5u);
  EXPECT_EQ(rd32(b, kHdrTriangles), 4u);
  // metadata, lighting, positions, normals, indices, albedo, 3 passes
  EXPECT_EQ(rd32(b, kHdrSections), 9u);
  EXPECT_EQ(rd64(b, kHdrFileSize), b.size());
  for (std::size_t i = kHdrReserved; i < kHdrCrc; ++i) EXPECT_EQ(b[i], 0) << i;
  EXPECT_EQ(rd32(b, kHdrCrc), crc32c({b.data(), 60}));
  EXPECT_EQ(rd32(b, kHdrTableCrc), crc32c({b.data() + 64, 9 * kEntryBytes}));

  // Metadata comes first, right after the table, so a short prefix holds the name.
  const std::size_t meta = findEntry(b, kMetadata);
  EXPECT_EQ(meta, 0u);
  EXPECT_EQ(payloadOffset(b, meta), (64 + 9 * 40 + 15) / 16 * 16);
  const std::size_t m = payloadOffset(b, meta);
  EXPECT_EQ(rd64(b, m), a.samples);
  EXPECT_EQ(rd64(b, m + 8), a.seed);
  EXPECT_EQ(rd32(b, m + 16), a.sampling.size());
  EXPECT_EQ(rd32(b, m + 20), a.name.size());
  EXPECT_EQ(std::string(b.begin() + static_cast<std::ptrdiff_t>(m + 24), b.begin() + static_cast<std::ptrdiff_t>(m + 24 + a.sampling.size())),
            a.sampling);

  // Lighting second: format bytes, no args, 20 bytes (u32 model, f32 centre x y z, f32 radius).
  const std::size_t light = findEntry(b, kLighting);
  EXPECT_EQ(light, 1u);
  EXPECT_EQ(rd32(b, entryAt(light) + kEFormat), kRawBytes);
  EXPECT_EQ(rd64(b, entryAt(light) + kESize), kLightBytes);
  EXPECT_EQ(rd32(b, entryAt(light) + kEArg0) | rd32(b, entryAt(light) + kEArg1) | rd32(b, entryAt(light) + kEArg2), 0u);
  const std::size_t l = payloadOffset(b, light);
  EXPECT_EQ(l, (m + 24 + a.sampling.size() + a.name.size() + 15) / 16 * 16);
  EXPECT_EQ(rd32(b, l + kLightModel), 2u);
  EXPECT_EQ(rd32(b, l + kLightCenter), bitsOf(a.lighting.center.x));
  EXPECT_EQ(rd32(b, l + kLightCenter + 4), bitsOf(a.lighting.center.y));
  EXPECT_EQ(rd32(b, l + kLightCenter + 8), bitsOf(a.lighting.center.z));
  EXPECT_EQ(rd32(b, l + kLightRadius), bitsOf(a.lighting.radius));

  // Floats are IEEE-754 little-endian; indices uint32 little-endian; transfer [vertex][channel][coefficient].
  const std::size_t pos = payloadOffset(b, findEntry(b, kPositions));
  EXPECT_EQ(rd32(b, pos + 4), bitsOf(a.positions[0].y));
  EXPECT_EQ(rd32(b, pos + 12 * 4 + 8), bitsOf(a.positions[4].z));
  const std::size_t idx = payloadOffset(b, findEntry(b, kIndices));
  EXPECT_EQ(rd32(b, idx + 4 * 7), a.indices[7]);
  const std::size_t ir = findEntry(b, kTransfer, 2);
  EXPECT_EQ(rd32(b, entryAt(ir) + kEArg1), 3u);
  EXPECT_EQ(rd32(b, entryAt(ir) + kEArg2), 4u);
  EXPECT_EQ(rd32(b, entryAt(ir) + kEFormat), kF32);
  const TransferPass* p = findPass(a, TransferKind::kInterreflected);
  ASSERT_NE(p, nullptr);
  const std::size_t vertex = 2, channel = 1, coeff = 5;
  EXPECT_EQ(rd32(b, payloadOffset(b, ir) + 4 * ((vertex * 3 + channel) * 9 + coeff)),
            bitsOf(p->coeffs[(vertex * 3 + channel) * 9 + coeff]));

  // Every section is 16-byte aligned, and its checksum covers exactly its payload.
  for (std::size_t i = 0; i < 9; ++i) {
    const std::uint64_t off = rd64(b, entryAt(i) + kEOffset), size = rd64(b, entryAt(i) + kESize);
    EXPECT_EQ(off % 16, 0u);
    EXPECT_EQ(rd32(b, entryAt(i) + kECrc), crc32c({b.data() + off, static_cast<std::size_t>(size)}));
  }
}

TEST(Asset, MatchesTheWorkedExampleInTheDocument) {
  // docs/asset-format.md, "Worked example": the complete 500-byte file.
  const Bytes expected = {
    0x50, 0x52, 0x54, 0x41, 0x01, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0xdf, 0xa5, 0xcc, 0xf7,
    0xf4, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7a, 0xc5, 0x56, 0x04,
    0x06, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x60, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x26, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x86, 0x00, 0x1d, 0xc3, 0x07, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00,
    0x90, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x14, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x9c, 0x10, 0x21, 0x96,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0xb0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x83, 0xe7, 0x4d, 0x38, 0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0xc0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xda, 0xd3, 0xf3, 0xce,
    0x03, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0xd0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x5d, 0xb5, 0x60, 0x2b, 0x04, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0xe0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0xc2, 0x76, 0x8a,
    0x05, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0xf0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x56, 0xf8, 0x80, 0xd9, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0a, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x68, 0x61, 0x6d, 0x6d, 0x65, 0x72, 0x73, 0x6c,
    0x65, 0x79, 0x74, 0x69, 0x6e, 0x79, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xc0, 0x3f, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0x3e, 0x00, 0x00, 0x00, 0x3e, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x40, 0x3f,
  };
  BakedAsset a;
  a.shOrder = 1;
  a.positions = {{1.0f, 2.0f, 3.0f}};
  a.normals = {{0.0f, 1.0f, 0.0f}};
  a.albedo = {{0.5f, 0.25f, 0.125f}};
  a.indices = {0, 0, 0};
  a.passes = {TransferPass{TransferKind::kShadowed, 1, 0, {0.75f}, {}}};
  a.samples = 1024;
  a.seed = 7;
  a.sampling = "hammersley";
  a.name = "tiny";
  a.lighting = {LightingModel::kLocalSphere, {0.0f, 1.5f, 0.0f}, 4.0f};
  EXPECT_EQ(encodeOrDie(a), expected);
  BakedAsset back;
  ASSERT_TRUE(decode(expected, &back).isOk());
  expectBitEqual(a, back);
}

TEST(Asset, Version10FileWithoutLightingDecodesAsDistant) {
  // The same asset as format 1.0 wrote it (the document's worked example before 1.1): no
  // lighting section. Readers of 1.1 read it as distant lighting.
  const Bytes v10 = {
    0x50, 0x52, 0x54, 0x41, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x00, 0x00, 0x00, 0xdc, 0x3e, 0xfc, 0xc3,
    0xa4, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x64, 0x7c, 0xfe, 0xe0,
    0x06, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00, 0x30, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x26, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x86, 0x00, 0x1d, 0xc3, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0x60, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x83, 0xe7, 0x4d, 0x38,
    0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x70, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0xda, 0xd3, 0xf3, 0xce, 0x03, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00,
    0x80, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x5d, 0xb5, 0x60, 0x2b,
    0x04, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x90, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0c, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x0c, 0xc2, 0x76, 0x8a, 0x05, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    0xa0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x56, 0xf8, 0x80, 0xd9,
    0x00, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x0a, 0x00, 0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 0x68, 0x61, 0x6d, 0x6d, 0x65, 0x72, 0x73, 0x6c,
    0x65, 0x79, 0x74, 0x69, 0x6e, 0x79, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x3f, 0x00, 0x00, 0x80, 0x3e, 0x00, 0x00, 0x00, 0x3e, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x40, 0x3f,
  };
  BakedAsset back;
  const Status s = decode(v10, &back);
  ASSERT_TRUE(s.isOk()) << s.toString();
  EXPECT_EQ(back.lighting.model, LightingModel::kDistant);
  EXPECT_EQ(back.lighting.radius, 0.0f);
  EXPECT_EQ(back.name, "tiny");
  ASSERT_EQ(back.passes.size(), 1u);
  EXPECT_EQ(back.passes[0].coeffs, std::vector<float>{0.75f});
  AssetSummary peeked, verified;
  ASSERT_TRUE(peekAssetHeader(v10, &peeked).isOk());
  ASSERT_TRUE(verifyAsset(v10, &verified).isOk());
  for (const AssetSummary* sum : {&peeked, &verified}) {
    EXPECT_EQ(sum->versionMinor, 0);
    EXPECT_EQ(sum->sectionCount, 6u);
    EXPECT_EQ(sum->lighting.model, LightingModel::kDistant);
  }
  // Re-encoding writes 1.7 with an explicit distant lighting section, one section more.
  const Bytes again = encodeOrDie(back);
  EXPECT_EQ(rd32(again, kHdrSections), 7u);
  EXPECT_EQ(again[kHdrVersionMinor], 7);
  EXPECT_EQ(rd32(again, payloadOffset(again, findEntry(again, kLighting)) + kLightModel), 0u);
}

TEST(Asset, IndependentWriterFromTheDocumentProducesTheSameBytes) {
  const Bytes b = encodeOrDie(makeAsset(4, 11, 9));
  EXPECT_EQ(build(split(b)), b);
}

TEST(Asset, SectionOrderInTheFileDoesNotMatter) {
  const BakedAsset a = makeAsset(4, 11, 9);
  RawAsset r = split(encodeOrDie(a));
  std::reverse(r.sections.begin(), r.sections.end());
  BakedAsset back;
  const Status s = decode(build(r), &back);
  ASSERT_TRUE(s.isOk()) << s.toString();
  // Passes come back in table order, the only order the file has.
  std::reverse(back.passes.begin(), back.passes.end());
  expectBitEqual(a, back);
}

TEST(Asset, PeekAndVerifySummariseWithoutDecoding) {
  const BakedAsset a = makeAsset(5, 20, 30);
  const Bytes b = encodeOrDie(a);
  AssetSummary full, peeked, verified;
  ASSERT_TRUE(peekAssetHeader(b, &full).isOk());
  ASSERT_TRUE(verifyAsset(b, &verified).isOk());
  ASSERT_TRUE(verifyAsset(b, nullptr).isOk());
  for (const AssetSummary* s : {&full, &verified}) {
    EXPECT_EQ(s->versionMajor, 1);
    EXPECT_EQ(s->versionMinor, 7);
    EXPECT_EQ(s->shOrder, 5);
    EXPECT_EQ(s->vertexCount, 20u);
    EXPECT_EQ(s->triangleCount, 30u);
    EXPECT_EQ(s->sectionCount, 9u);
    EXPECT_EQ(s->fileSize, b.size());
    ASSERT_EQ(s->passes.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s->passes[i].kind, a.passes[i].kind);
      EXPECT_EQ(s->passes[i].channels, a.passes[i].channels);
      EXPECT_EQ(s->passes[i].bounces, a.passes[i].bounces);
    }
    EXPECT_EQ(s->samples, a.samples);
    EXPECT_EQ(s->seed, a.seed);
    EXPECT_EQ(s->sampling, a.sampling);
    EXPECT_EQ(s->name, a.name);
    EXPECT_EQ(s->lighting.model, a.lighting.model);
    EXPECT_EQ(bitsOf(s->lighting.center.z), bitsOf(a.lighting.center.z));
    EXPECT_EQ(bitsOf(s->lighting.radius), bitsOf(a.lighting.radius));
  }
  // A prefix that ends with the lighting section (the second) is enough; one byte less is not.
  const std::size_t light = findEntry(b, kLighting);
  const std::size_t needed = payloadOffset(b, light) + static_cast<std::size_t>(rd64(b, entryAt(light) + kESize));
  ASSERT_LT(needed, kAssetPeekPrefixSize);
  ASSERT_TRUE(peekAssetHeader(std::span(b).first(needed), &peeked).isOk());
  EXPECT_EQ(peeked.name, a.name);
  EXPECT_EQ(peeked.lighting.model, a.lighting.model);
  EXPECT_EQ(peeked.fileSize, b.size());  // tells the catalogue how long the file must be
  expectError(peekAssetHeader(std::span(b).first(needed - 1), &peeked), StatusCode::kTruncated, "lighting");
  const std::size_t meta = findEntry(b, kMetadata);
  const std::size_t metaEnd = payloadOffset(b, meta) + static_cast<std::size_t>(rd64(b, entryAt(meta) + kESize));
  expectError(peekAssetHeader(std::span(b).first(metaEnd - 1), &peeked), StatusCode::kTruncated, "metadata");
  // Peek ignores damage outside header, table and metadata; verify does not.
  Bytes damaged = b;
  damaged.back() ^= 0x40;
  EXPECT_TRUE(peekAssetHeader(damaged, &peeked).isOk());
  expectError(verifyAsset(damaged, &verified), StatusCode::kChecksumMismatch, "transfer");
}

// ---- Damage: truncation and single-byte corruption ------------------------------------

TEST(Asset, EveryTruncatedPrefixIsRejected) {
  const Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  for (std::size_t len = 0; len < b.size(); ++len) {
    const Bytes prefix(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(len));
    const Status s = decode(prefix);
    ASSERT_EQ(s.code(), StatusCode::kTruncated) << "length " << len << ": " << s.toString();
    ASSERT_EQ(verifyAsset(prefix, nullptr).code(), StatusCode::kTruncated) << len;
    AssetSummary summary;
    const Status p = peekAssetHeader(prefix, &summary);
    ASSERT_TRUE(p.isOk() || p.code() == StatusCode::kTruncated) << len << ": " << p.toString();
  }
  // Also a larger asset, every prefix through the header and table and a sample beyond.
  const Bytes big = encodeOrDie(makeAsset(6, 300, 400));
  for (std::size_t len = 0; len < big.size(); len += (len < 1024 ? 1 : 997)) {
    ASSERT_EQ(decode(Bytes(big.begin(), big.begin() + static_cast<std::ptrdiff_t>(len))).code(), StatusCode::kTruncated) << len;
  }
}

TEST(Asset, EverySingleByteCorruptionIsRejected) {
  const Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  std::map<StatusCode, int> seen;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (std::uint8_t mask : {0x01, 0x02, 0x10, 0x80, 0xFF, 0x5A}) {
      Bytes c = b;
      c[i] ^= mask;
      const Status s = decode(c);
      ASSERT_FALSE(s.isOk()) << "flipping byte " << i << " with " << int(mask) << " was accepted";
      ASSERT_TRUE(isNamedDecodeError(s.code())) << i << ": " << s.toString();
      ASSERT_EQ(verifyAsset(c, nullptr).code(), s.code()) << i;
      ++seen[s.code()];
    }
  }
  // Most damage is caught by a checksum; magic and version bytes get their own errors,
  // padding bytes (not checksummed) the "not zero" rule.
  EXPECT_GT(seen[StatusCode::kChecksumMismatch], 0);
  EXPECT_GT(seen[StatusCode::kBadMagic], 0);
  EXPECT_GT(seen[StatusCode::kBadVersion], 0);
  EXPECT_GT(seen[StatusCode::kCorrupt], 0);
}

TEST(Asset, SingleByteCorruptionOfALargerAssetIsRejected) {
  const Bytes b = encodeOrDie(makeAsset(5, 60, 80));
  for (std::size_t i = 0; i < b.size(); ++i) {
    Bytes c = b;
    c[i] ^= static_cast<std::uint8_t>(1u << (i % 8));
    ASSERT_FALSE(decode(c).isOk()) << "flipping byte " << i << " was accepted";
  }
}

TEST(Asset, ExtraTrailingBytesAreRejected) {
  Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  b.push_back(0);
  expectDecodeError(b, StatusCode::kCorrupt, "trailing");
}

// ---- Header ---------------------------------------------------------------------------

TEST(Asset, BadMagicIsNamed) {
  Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  b[0] = 'G';
  expectDecodeError(b, StatusCode::kBadMagic, "PRTA");
  expectDecodeError(Bytes{'{', '"'}, StatusCode::kBadMagic, "PRTA");
  expectDecodeError(Bytes{}, StatusCode::kTruncated, "0 bytes");
  expectDecodeError(Bytes{'P', 'R'}, StatusCode::kTruncated, "header");
}

TEST(Asset, FutureAndPastMajorVersionsAreRefusedNamingBoth) {
  Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  wr16(b, kHdrVersionMajor, 2);
  wr16(b, kHdrVersionMinor, 3);
  expectDecodeError(b, StatusCode::kBadVersion, "2.3 is newer than this reader's 1.7");
  AssetSummary s;
  expectError(peekAssetHeader(b, &s), StatusCode::kBadVersion, "2.3");
  // Even a future header we cannot checksum is reported as a version problem, not damage.
  wr16(b, kHdrVersionMajor, 0);
  expectDecodeError(b, StatusCode::kBadVersion, "0.3 is older");
}

TEST(Asset, NewerMinorVersionIsRead) {
  const BakedAsset a = makeAsset(2, 4, 2);
  Bytes b = encodeOrDie(a);
  wr16(b, kHdrVersionMinor, 7);
  reseal(b);
  BakedAsset back;
  ASSERT_TRUE(decode(b, &back).isOk());
  expectBitEqual(a, back);
  AssetSummary s;
  ASSERT_TRUE(verifyAsset(b, &s).isOk());
  EXPECT_EQ(s.versionMinor, 7);
}

TEST(Asset, HeaderFieldsAreRangeChecked) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  auto withHeader = [&](std::size_t field, std::uint32_t value) {
    Bytes b = good;
    wr32(b, field, value);
    reseal(b);
    return b;
  };
  expectDecodeError(withHeader(kHdrFlags, 1), StatusCode::kCorrupt, "flags");
  expectDecodeError(withHeader(kHdrReserved + 8, 0x100), StatusCode::kCorrupt, "reserved");
  expectDecodeError(withHeader(kHdrOrder, 0), StatusCode::kCorrupt, "SH order 0");
  expectDecodeError(withHeader(kHdrOrder, 17), StatusCode::kCorrupt, "SH order 17");
  expectDecodeError(withHeader(kHdrOrder, 3), StatusCode::kCorrupt, "transfer");  // sizes no longer match
  expectDecodeError(withHeader(kHdrVertices, 0), StatusCode::kCorrupt, "vertex count 0");
  expectDecodeError(withHeader(kHdrTriangles, 0), StatusCode::kCorrupt, "triangle count 0");
  expectDecodeError(withHeader(kHdrSections, 0), StatusCode::kCorrupt, "section count 0");
  // A damaged header checksum itself.
  Bytes b = good;
  b[kHdrCrc] ^= 1;
  expectDecodeError(b, StatusCode::kChecksumMismatch, "header checksum");
}

TEST(Asset, HugeCountsCannotOverflowSizeArithmetic) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  auto withHeader = [&](std::size_t field, std::uint32_t value) {
    Bytes b = good;
    wr32(b, field, value);
    reseal(b);
    return b;
  };
  // 0xFFFFFFFF vertices * 3 channels * 256 coefficients * 4 bytes would wrap 32 bits many times.
  expectDecodeError(withHeader(kHdrVertices, 0xFFFFFFFFu), StatusCode::kCorrupt, "vertex count 4294967295");
  expectDecodeError(withHeader(kHdrTriangles, 0x55555556u), StatusCode::kCorrupt, "triangle count");
  expectDecodeError(withHeader(kHdrSections, 0xFFFFFFFFu), StatusCode::kCorrupt, "section count");
  // At the cap the counts are accepted but the sections cannot match them (and nothing is
  // allocated for them).
  expectDecodeError(withHeader(kHdrVertices, kMaxAssetVertices), StatusCode::kCorrupt, "expected");
  // 2^30 triangles * 12 bytes = 3 * 2^32, which wraps to 0 in 32 bits: a 32-bit size check
  // would accept an empty indices section. The cap and 64-bit arithmetic both refuse it.
  Bytes b = withHeader(kHdrTriangles, 1u << 30);
  expectDecodeError(b, StatusCode::kCorrupt, "triangle count");
  // A section table that claims more entries than the declared file size holds.
  expectDecodeError(withHeader(kHdrSections, 1000), StatusCode::kCorrupt, "smaller than header and section table");
  // A file size near 2^64.
  Bytes big = good;
  wr64(big, kHdrFileSize, ~0ull);
  reseal(big);
  expectDecodeError(big, StatusCode::kTruncated, "declares 18446744073709551615");
}

// ---- Section table --------------------------------------------------------------------

Bytes editEntry(const Bytes& good, std::size_t entry, std::size_t field, std::uint64_t value, bool wide = false) {
  Bytes b = good;
  if (wide) {
    wr64(b, entryAt(entry) + field, value);
  } else {
    wr32(b, entryAt(entry) + field, static_cast<std::uint32_t>(value));
  }
  reseal(b);
  return b;
}

TEST(Asset, OverlappingSectionsAreRejected) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t pos = findEntry(good, kPositions), nrm = findEntry(good, kNormals);
  // Normals pointing at the positions (same size, so only the overlap is wrong).
  expectDecodeError(editEntry(good, nrm, kEOffset, rd64(good, entryAt(pos) + kEOffset), true), StatusCode::kCorrupt, "overlap");
  // Normals starting 16 bytes early would cover the last 16 bytes of the positions.
  expectDecodeError(editEntry(good, nrm, kEOffset, rd64(good, entryAt(nrm) + kEOffset) - 16, true), StatusCode::kCorrupt,
                    "overlap");
  // A section placed over the header or table.
  expectDecodeError(editEntry(good, pos, kEOffset, 64, true), StatusCode::kCorrupt, "inside the header");
  expectDecodeError(editEntry(good, pos, kEOffset, 0, true), StatusCode::kCorrupt, "inside the header");
}

TEST(Asset, OffsetsPastTheEndAreRejectedWithoutOverflow) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t idx = findEntry(good, kIndices);
  expectDecodeError(editEntry(good, idx, kEOffset, good.size() + 16 - good.size() % 16, true), StatusCode::kCorrupt, "past the end");
  // offset + size wraps to a small number in 64 bits.
  expectDecodeError(editEntry(good, idx, kEOffset, 0xFFFFFFFFFFFFFFF0ull, true), StatusCode::kCorrupt, "past the end");
  Bytes b = editEntry(good, idx, kEOffset, 0xFFFFFFFFFFFFFFF0ull, true);
  wr64(b, entryAt(idx) + kESize, 0x20);
  reseal(b);
  expectDecodeError(b, StatusCode::kCorrupt, "past the end");
  expectDecodeError(editEntry(good, idx, kESize, ~0ull, true), StatusCode::kCorrupt, "past the end");
  // An unknown section may be skipped, but still not point outside the file.
  RawAsset r = split(good);
  r.sections.push_back({0xBEEF, 7, 0, 0, 0, Bytes(16, 0xAB)});
  Bytes u = build(r);
  const std::size_t last = r.sections.size() - 1;
  wr64(u, entryAt(last) + kEOffset, 1ull << 40);
  reseal(u);
  expectDecodeError(u, StatusCode::kCorrupt, "section 9 (type 48879)");
}

TEST(Asset, MisalignedSectionsAreRejected) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t nrm = findEntry(good, kNormals);
  expectDecodeError(editEntry(good, nrm, kEOffset, rd64(good, entryAt(nrm) + kEOffset) + 4, true), StatusCode::kCorrupt,
                    "multiple of 16");
}

TEST(Asset, SizesMustMatchCountsAndFormats) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t pos = findEntry(good, kPositions), idx = findEntry(good, kIndices), meta = findEntry(good, kMetadata);
  const std::size_t shadowed = findEntry(good, kTransfer, 1), ir = findEntry(good, kTransfer, 2);
  expectDecodeError(editEntry(good, pos, kESize, 36, true), StatusCode::kCorrupt, "section 2 (positions) is 36 bytes; 48 expected");
  expectDecodeError(editEntry(good, idx, kEFormat, kF32), StatusCode::kCorrupt, "element format");
  expectDecodeError(editEntry(good, pos, kEFormat, kU32), StatusCode::kCorrupt, "element format");
  expectDecodeError(editEntry(good, meta, kEFormat, kF32), StatusCode::kCorrupt, "element format");
  expectDecodeError(editEntry(good, pos, kEArg0, 1), StatusCode::kCorrupt, "arguments");
  expectDecodeError(editEntry(good, shadowed, kEArg1, 2), StatusCode::kCorrupt, "2 channels");
  expectDecodeError(editEntry(good, shadowed, kEArg1, 3), StatusCode::kCorrupt, "expected");  // size now wrong
  expectDecodeError(editEntry(good, shadowed, kEArg2, 1), StatusCode::kCorrupt, "bounces");
  expectDecodeError(editEntry(good, ir, kEArg2, kMaxAssetBounces + 1), StatusCode::kCorrupt, "bounces");
  expectDecodeError(editEntry(good, shadowed, kEArg0, 3), StatusCode::kCorrupt, "unknown transfer kind 3");
  expectDecodeError(editEntry(good, meta, kESize, 8, true), StatusCode::kCorrupt, "metadata");
  expectDecodeError(editEntry(good, pos, kEType, 0), StatusCode::kCorrupt, "type 0 is reserved");
}

TEST(Asset, RequiredSectionsMustOccurExactlyOnce) {
  const RawAsset good = split(encodeOrDie(makeAsset(2, 4, 2)));
  for (std::uint32_t type : {kPositions, kNormals, kIndices, kAlbedo, kMetadata}) {
    RawAsset missing = good, twice = good;
    for (std::size_t i = 0; i < good.sections.size(); ++i) {
      if (good.sections[i].type == type) {
        missing.sections.erase(missing.sections.begin() + static_cast<std::ptrdiff_t>(i));
        twice.sections.push_back(good.sections[i]);
        break;
      }
    }
    expectDecodeError(build(missing), StatusCode::kCorrupt, "missing");
    expectDecodeError(build(twice), StatusCode::kCorrupt, "repeats");
  }
  RawAsset noPasses = good;
  std::erase_if(noPasses.sections, [](const RawSection& s) { return s.type == kTransfer; });
  expectDecodeError(build(noPasses), StatusCode::kCorrupt, "no transfer");
}

TEST(Asset, DuplicatePassKindsAreRejected) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  // Unshadowed and shadowed have the same size, so relabelling one is otherwise consistent.
  expectDecodeError(editEntry(good, findEntry(good, kTransfer, 0), kEArg0, 1), StatusCode::kCorrupt,
                    "repeats the transfer kind");
  RawAsset r = split(good);
  r.sections.push_back(r.sections[static_cast<std::size_t>(findEntry(good, kTransfer, 2))]);
  expectDecodeError(build(r), StatusCode::kCorrupt, "repeats the transfer kind");
}

TEST(Asset, UnknownSectionsAreSkipped) {
  const BakedAsset a = makeAsset(3, 6, 5);
  RawAsset r = split(encodeOrDie(a));
  Bytes extra(37);
  for (std::size_t i = 0; i < extra.size(); ++i) extra[i] = static_cast<std::uint8_t>(i * 7 + 1);
  r.sections.insert(r.sections.begin() + 2, RawSection{0x1000, 99, 0xFFFFFFFF, 5, 6, extra});
  r.sections.push_back({77, kRawBytes, 0, 0, 0, {}});  // empty ones too
  const Bytes b = build(r);
  BakedAsset back;
  const Status s = decode(b, &back);
  ASSERT_TRUE(s.isOk()) << s.toString();
  expectBitEqual(a, back);
  AssetSummary summary;
  ASSERT_TRUE(verifyAsset(b, &summary).isOk());
  EXPECT_EQ(summary.sectionCount, 11u);
  EXPECT_EQ(summary.passes.size(), 3u);
  // ...but their checksums are still verified: every byte of a file is protected.
  Bytes damaged = b;
  damaged[static_cast<std::size_t>(rd64(b, entryAt(2) + kEOffset)) + 3] ^= 1;
  expectDecodeError(damaged, StatusCode::kChecksumMismatch, "section 2 (type 4096)");
}

TEST(Asset, PaddingMustBeZero) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  // The byte before the second section is padding (the metadata is 24 + 10 + name bytes).
  const std::size_t meta = findEntry(good, kMetadata);
  const std::size_t metaEnd = payloadOffset(good, meta) + static_cast<std::size_t>(rd64(good, entryAt(meta) + kESize));
  ASSERT_NE(metaEnd % 16, 0u);
  Bytes b = good;
  b[metaEnd] = 1;
  expectDecodeError(b, StatusCode::kCorrupt, ("padding byte at offset " + std::to_string(metaEnd) + " is not zero").c_str());
}

// ---- Section contents (checksums recomputed, so only the content check can object) ----

TEST(Asset, IndexOutOfRangeIsRejected) {
  Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  wr32(b, payloadOffset(b, findEntry(b, kIndices)) + 4 * 5, 4);  // == vertex count
  reseal(b);
  expectDecodeError(b, StatusCode::kCorrupt, "index 5 (triangle 1) is 4, not below the vertex count 4");
  wr32(b, payloadOffset(b, findEntry(b, kIndices)) + 4 * 5, 0xFFFFFFFFu);
  reseal(b);
  expectDecodeError(b, StatusCode::kCorrupt, "4294967295");
}

TEST(Asset, NonFiniteFloatsAreRejectedInEverySection) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  struct Where {
    std::uint32_t type, kind;
    const char* name;
  };
  for (const Where& w : {Where{kPositions, 0, "positions"}, Where{kNormals, 0, "normals"}, Where{kAlbedo, 0, "albedo"},
                         Where{kTransfer, 0, "transfer unshadowed"}, Where{kTransfer, 1, "transfer shadowed"},
                         Where{kTransfer, 2, "transfer interreflected"}}) {
    for (float bad : {kNan, kInf, -kInf}) {
      Bytes b = good;
      wr32(b, payloadOffset(b, findEntry(b, w.type, w.kind)) + 4 * 2, bitsOf(bad));
      reseal(b);
      expectDecodeError(b, StatusCode::kCorrupt, (std::string(w.name) + "): value 2 is not finite").c_str());
    }
  }
  // A signalling NaN with a payload is still NaN.
  Bytes b = good;
  wr32(b, payloadOffset(b, findEntry(b, kPositions)), 0x7F800001u);
  reseal(b);
  expectDecodeError(b, StatusCode::kCorrupt, "not finite");
}

TEST(Asset, MetadataIsValidated) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t m = payloadOffset(good, findEntry(good, kMetadata));
  auto edit = [&](std::size_t at, std::uint8_t value) {
    Bytes b = good;
    b[at] = value;
    reseal(b);
    return b;
  };
  // String lengths that do not add up to the section size.
  expectDecodeError(edit(m + 16, 11), StatusCode::kCorrupt, "sampling name");
  expectDecodeError(edit(m + 20, 0xFF), StatusCode::kCorrupt, "asset name");
  // Bad characters: upper case in sampling, a control character and broken UTF-8 in the name.
  expectDecodeError(edit(m + 24, 'S'), StatusCode::kCorrupt, "[a-z0-9_-]");
  const std::size_t nameAt = m + 24 + rd32(good, m + 16);
  expectDecodeError(edit(nameAt, '\n'), StatusCode::kCorrupt, "UTF-8");
  expectDecodeError(edit(nameAt, 0xC0), StatusCode::kCorrupt, "UTF-8");
  AssetSummary s;
  expectError(peekAssetHeader(edit(nameAt, 0xFF), &s), StatusCode::kCorrupt, "UTF-8");
}

TEST(Asset, LightingIsValidated) {
  const Bytes good = encodeOrDie(makeAsset(2, 4, 2));
  const std::size_t light = findEntry(good, kLighting);
  const std::size_t l = payloadOffset(good, light);
  auto with = [&](std::uint32_t model, const float (&fields)[4]) {
    Bytes b = good;
    wr32(b, l + kLightModel, model);
    for (int i = 0; i < 4; ++i) wr32(b, l + kLightCenter + 4 * static_cast<std::size_t>(i), bitsOf(fields[i]));
    reseal(b);
    return b;
  };
  // The section is well-formed with these; only the values are wrong.
  struct Bad {
    std::uint32_t model;
    float fields[4];  // centre x, y, z, radius
    const char* message;
  };
  const Bad bad[] = {
      {3, {0, 0, 0, 0}, "lighting model 3 is unknown"},
      {0xFFFFFFFFu, {0, 1, 0, 2}, "lighting model 4294967295 is unknown"},
      {1, {kNan, 0, 0, 1}, "local-sphere centre is not finite"},
      {1, {0, kInf, 0, 1}, "local-sphere centre is not finite"},
      {2, {0, 0, -kInf, 1}, "local-sphere-paper centre is not finite"},
      {1, {0, 0, 0, kNan}, "local-sphere radius is not finite"},
      {2, {0, 0, 0, kInf}, "local-sphere-paper radius is not finite"},
      {1, {0, 0, 0, 0}, "radius 0.000000 is not positive"},
      {1, {0, 0, 0, -0.0f}, "is not positive"},
      {2, {1, 2, 3, -2}, "radius -2.000000 is not positive"},
      {0, {0, 0, 0, 1}, "distant has no centre or radius"},
      {0, {0, 1, 0, 0}, "distant has no centre or radius"},
      {0, {-0.0f, 0, 0, 0}, "distant has no centre or radius"},
      {0, {0, 0, 0, kNan}, "distant has no centre or radius"},
  };
  for (const Bad& c : bad) {
    const Bytes b = with(c.model, c.fields);
    expectDecodeError(b, StatusCode::kCorrupt, c.message);
    EXPECT_TRUE(decode(b).message().starts_with("section 1 (lighting): lighting")) << decode(b).message();
    AssetSummary s;
    expectError(peekAssetHeader(b, &s), StatusCode::kCorrupt, c.message);
  }
  // The same values through the encoder are argument errors, not corruption.
  for (const Bad& c : bad) {
    BakedAsset a = makeAsset(2, 4, 2);
    a.lighting = {static_cast<LightingModel>(c.model), {c.fields[0], c.fields[1], c.fields[2]}, c.fields[3]};
    Bytes out;
    const Status st = encodeAsset(a, &out);
    EXPECT_FALSE(st.isOk()) << c.message;
    EXPECT_TRUE(st.code() == StatusCode::kInvalidArgument || st.code() == StatusCode::kNotFinite) << st.toString();
    EXPECT_NE(st.message().find(c.message), std::string::npos) << st.message();
    EXPECT_EQ(checkAsset(a).code(), st.code());
    EXPECT_EQ(checkLightingInfo(a.lighting).code(), st.code());
  }
  // Good values near the edges are accepted.
  for (const float radius : {1e-38f, std::numeric_limits<float>::max()}) {
    const float fields[4] = {-std::numeric_limits<float>::max(), 0.0f, 1e-45f, radius};
    EXPECT_TRUE(decode(with(1, fields)).isOk()) << radius;
  }
  const float zero[4] = {0, 0, 0, 0};
  EXPECT_TRUE(decode(with(0, zero)).isOk());
  // The table entry: format, args, size.
  expectDecodeError(editEntry(good, light, kEFormat, kF32), StatusCode::kCorrupt, "section 1 (lighting) has element format");
  expectDecodeError(editEntry(good, light, kEArg1, 1), StatusCode::kCorrupt, "section 1 (lighting) has non-zero arguments");
  expectDecodeError(editEntry(good, light, kESize, 16, true), StatusCode::kCorrupt, "section 1 (lighting) is 16 bytes; 20 expected");
  expectDecodeError(editEntry(good, light, kESize, 24, true), StatusCode::kCorrupt, "20 expected");
}

TEST(Asset, LightingSectionIsOptionalButAtMostOnce) {
  const BakedAsset a = makeAsset(2, 4, 2);
  const RawAsset good = split(encodeOrDie(a));
  RawAsset missing = good, twice = good;
  std::erase_if(missing.sections, [](const RawSection& s) { return s.type == kLighting; });
  ASSERT_EQ(missing.sections.size(), good.sections.size() - 1);
  BakedAsset back;
  const Bytes noLighting = build(missing);
  ASSERT_TRUE(decode(noLighting, &back).isOk());
  EXPECT_EQ(back.lighting.model, LightingModel::kDistant);
  EXPECT_EQ(back.passes.size(), a.passes.size());
  AssetSummary s;
  ASSERT_TRUE(peekAssetHeader(noLighting, &s).isOk());
  EXPECT_EQ(s.lighting.model, LightingModel::kDistant);
  twice.sections.push_back(good.sections[1]);
  ASSERT_EQ(twice.sections[1].type, kLighting);
  expectDecodeError(build(twice), StatusCode::kCorrupt, "section 9 (lighting) repeats section 1");
  // Damage in the lighting payload is caught by its checksum, by peek as well.
  Bytes damaged = encodeOrDie(a);
  damaged[payloadOffset(damaged, findEntry(damaged, kLighting)) + kLightRadius] ^= 0x01;
  expectDecodeError(damaged, StatusCode::kChecksumMismatch, "section 1 (lighting) checksum");
  expectError(peekAssetHeader(damaged, &s), StatusCode::kChecksumMismatch, "lighting");
}

TEST(Asset, DecodeLeavesOutputUntouchedOnError) {
  Bytes b = encodeOrDie(makeAsset(2, 4, 2));
  b.back() ^= 1;
  BakedAsset out = makeAsset(3, 5, 4);
  const BakedAsset before = out;
  EXPECT_FALSE(decode(b, &out).isOk());
  expectBitEqual(before, out);
  EXPECT_EQ(decodeAsset(b, nullptr).code(), StatusCode::kInvalidArgument);
}

// ---- Encoder validation ---------------------------------------------------------------

TEST(Asset, EncoderRejectsInconsistentInput) {
  const BakedAsset good = makeAsset(3, 5, 4);
  auto expectRejected = [&](const std::function<void(BakedAsset&)>& edit, StatusCode code, const char* fragment) {
    BakedAsset a = good;
    edit(a);
    Bytes out = {1, 2, 3};
    expectError(encodeAsset(a, &out), code, fragment);
    EXPECT_EQ(out, (Bytes{1, 2, 3})) << "output changed on error";
    expectError(checkAsset(a), code, fragment);
  };
  expectRejected([](BakedAsset& a) { a.shOrder = 0; }, StatusCode::kInvalidArgument, "order");
  expectRejected([](BakedAsset& a) { a.shOrder = kMaxShOrder + 1; }, StatusCode::kInvalidArgument, "order");
  expectRejected([](BakedAsset& a) { a.shOrder = 4; }, StatusCode::kSizeMismatch, "coefficients");
  expectRejected([](BakedAsset& a) { a.positions.clear(); a.normals.clear(); a.albedo.clear(); },
                 StatusCode::kInvalidArgument, "0 vertices");
  expectRejected([](BakedAsset& a) { a.normals.pop_back(); }, StatusCode::kSizeMismatch, "normals");
  expectRejected([](BakedAsset& a) { a.albedo.push_back({}); }, StatusCode::kSizeMismatch, "albedos");
  expectRejected([](BakedAsset& a) { a.indices.pop_back(); }, StatusCode::kSizeMismatch, "multiple of 3");
  expectRejected([](BakedAsset& a) { a.indices.clear(); }, StatusCode::kSizeMismatch, "multiple of 3");
  expectRejected([](BakedAsset& a) { a.indices[7] = 5; }, StatusCode::kInvalidArgument, "index 7 is 5");
  expectRejected([](BakedAsset& a) { a.positions[2].y = kNan; }, StatusCode::kNotFinite, "position 2");
  expectRejected([](BakedAsset& a) { a.normals[1].z = kInf; }, StatusCode::kNotFinite, "normal 1");
  expectRejected([](BakedAsset& a) { a.albedo[4].r = -kInf; }, StatusCode::kNotFinite, "albedo 4");
  expectRejected([](BakedAsset& a) { a.passes[2].coeffs[10] = kNan; }, StatusCode::kNotFinite, "coefficient 10");
  expectRejected([](BakedAsset& a) { a.passes.clear(); }, StatusCode::kInvalidArgument, "0 transfer passes");
  expectRejected([](BakedAsset& a) { a.passes[1].kind = TransferKind::kShadowed; }, StatusCode::kInvalidArgument,
                 "repeats the kind");
  expectRejected([](BakedAsset& a) { a.passes[0].kind = static_cast<TransferKind>(7); }, StatusCode::kInvalidArgument,
                 "unknown kind 7");
  expectRejected([](BakedAsset& a) { a.passes[0].channels = 2; }, StatusCode::kInvalidArgument, "2 channels");
  expectRejected([](BakedAsset& a) { a.passes[0].bounces = 1; }, StatusCode::kInvalidArgument, "only interreflection");
  expectRejected([](BakedAsset& a) { a.passes[2].bounces = -1; }, StatusCode::kInvalidArgument, "bounces -1");
  expectRejected([](BakedAsset& a) { a.passes[2].coeffs.pop_back(); }, StatusCode::kSizeMismatch, "coefficients");
  expectRejected([](BakedAsset& a) { a.name = "tab\there"; }, StatusCode::kInvalidArgument, "name");
  expectRejected([](BakedAsset& a) { a.name = std::string(kMaxAssetNameBytes + 1, 'x'); }, StatusCode::kInvalidArgument, "name");
  expectRejected([](BakedAsset& a) { a.sampling = "Hammersley"; }, StatusCode::kInvalidArgument, "sampling");
  Bytes out;
  EXPECT_EQ(encodeAsset(good, nullptr).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(encodeAsset(good, &out).isOk());
}

TEST(Asset, NameValidationFollowsUtf8) {
  EXPECT_TRUE(isValidAssetName(""));
  EXPECT_TRUE(isValidAssetName("Sponza (Crytek) #2"));
  EXPECT_TRUE(isValidAssetName("\xC3\xA9\xE6\x97\xA5\xF0\x9F\x99\x82\xF4\x8F\xBF\xBF"));  // é 日 🙂 U+10FFFF
  EXPECT_TRUE(isValidAssetName(std::string(kMaxAssetNameBytes, 'a')));
  EXPECT_FALSE(isValidAssetName(std::string(kMaxAssetNameBytes + 1, 'a')));
  EXPECT_FALSE(isValidAssetName(std::string("a\0b", 3)));
  EXPECT_FALSE(isValidAssetName("a\x7F"));
  EXPECT_FALSE(isValidAssetName("\xC2\x85"));          // C1 control NEL
  EXPECT_FALSE(isValidAssetName("\xC0\x80"));          // overlong NUL
  EXPECT_FALSE(isValidAssetName("\xE0\x80\xAF"));      // overlong '/'
  EXPECT_FALSE(isValidAssetName("\xED\xA0\x80"));      // surrogate
  EXPECT_FALSE(isValidAssetName("\xF4\x90\x80\x80"));  // above U+10FFFF
  EXPECT_FALSE(isValidAssetName("\xE6\x97"));          // cut short
  EXPECT_FALSE(isValidAssetName("\x80"));              // lone continuation
  EXPECT_FALSE(isValidAssetName("\xF8\x88\x80\x80\x80"));
  EXPECT_TRUE(isValidAssetSamplingName("hammersley"));
  EXPECT_TRUE(isValidAssetSamplingName("stratified"));
  EXPECT_TRUE(isValidAssetSamplingName(""));
  EXPECT_FALSE(isValidAssetSamplingName("a b"));
  EXPECT_FALSE(isValidAssetSamplingName(std::string(kMaxAssetSamplingBytes + 1, 'a')));
}

TEST(Asset, StatusCodesHaveNames) {
  EXPECT_STREQ(statusCodeName(StatusCode::kTruncated), "truncated");
  EXPECT_STREQ(statusCodeName(StatusCode::kBadMagic), "bad magic");
  EXPECT_STREQ(statusCodeName(StatusCode::kBadVersion), "bad version");
  EXPECT_STREQ(statusCodeName(StatusCode::kChecksumMismatch), "checksum mismatch");
  EXPECT_STREQ(statusCodeName(StatusCode::kCorrupt), "corrupt");
  EXPECT_STREQ(transferKindName(TransferKind::kInterreflected), "interreflected");
}

}  // namespace
}  // namespace prt
