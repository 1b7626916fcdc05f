// Raw asset files for the asset tests: little-endian reads and writes, and a file split into
// its header and sections and rebuilt with fresh offsets and checksums in the layout of
// docs/asset-format.md, so a test can craft a file the writer would refuse to produce; and the
// expectations the asset tests share (encodeOrDie, expectError).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/checksum.h"

namespace prt::test {

using Bytes = std::vector<std::uint8_t>;

inline std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
inline std::uint64_t rd64(const Bytes& b, std::size_t at) { return std::uint64_t{rd32(b, at)} | std::uint64_t{rd32(b, at + 4)} << 32; }
inline void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline void wr64(Bytes& b, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (8 * i));
}
inline std::uint32_t bitsOf(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// ---- A file as parts, rebuilt with fresh offsets and checksums (the layout of the document) --

struct RawSection {
  std::uint32_t type = 0, format = 0, arg0 = 0, arg1 = 0, arg2 = 0;
  Bytes payload;
};
struct RawAsset {
  Bytes header;
  std::vector<RawSection> sections;
};

inline std::size_t entryAt(std::size_t i) { return kAssetHeaderSize + i * kAssetSectionEntrySize; }

inline RawAsset split(const Bytes& b) {
  RawAsset r;
  r.header.assign(b.begin(), b.begin() + kAssetHeaderSize);
  for (std::size_t i = 0; i < rd32(b, asset_layout::kSectionCount); ++i) {
    const std::size_t e = entryAt(i);
    RawSection s{rd32(b, e + asset_layout::kEntryType), rd32(b, e + asset_layout::kEntryFormat), rd32(b, e + asset_layout::kEntryArg0),
                 rd32(b, e + asset_layout::kEntryArg1), rd32(b, e + asset_layout::kEntryArg2), {}};
    const auto off = static_cast<std::ptrdiff_t>(rd64(b, e + asset_layout::kEntryOffset));
    const auto size = static_cast<std::ptrdiff_t>(rd64(b, e + asset_layout::kEntrySize));
    s.payload.assign(b.begin() + off, b.begin() + off + size);
    r.sections.push_back(std::move(s));
  }
  return r;
}

inline Bytes build(const RawAsset& r) {
  std::size_t end = kAssetHeaderSize + r.sections.size() * kAssetSectionEntrySize;
  std::vector<std::size_t> offsets;
  for (const RawSection& s : r.sections) {
    offsets.push_back((end + 15) / 16 * 16);
    end = offsets.back() + s.payload.size();
  }
  Bytes b(end, 0);
  std::copy(r.header.begin(), r.header.end(), b.begin());
  wr32(b, asset_layout::kSectionCount, static_cast<std::uint32_t>(r.sections.size()));
  wr64(b, asset_layout::kFileSize, end);
  for (std::size_t i = 0; i < r.sections.size(); ++i) {
    const RawSection& s = r.sections[i];
    std::copy(s.payload.begin(), s.payload.end(), b.begin() + static_cast<std::ptrdiff_t>(offsets[i]));
    const std::size_t e = entryAt(i);
    wr32(b, e + asset_layout::kEntryType, s.type);
    wr32(b, e + asset_layout::kEntryFormat, s.format);
    wr64(b, e + asset_layout::kEntryOffset, offsets[i]);
    wr64(b, e + asset_layout::kEntrySize, s.payload.size());
    wr32(b, e + asset_layout::kEntryArg0, s.arg0);
    wr32(b, e + asset_layout::kEntryArg1, s.arg1);
    wr32(b, e + asset_layout::kEntryArg2, s.arg2);
    wr32(b, e + asset_layout::kEntryCrc, crc32c(s.payload));
  }
  const std::size_t tableBytes = r.sections.size() * kAssetSectionEntrySize;
  wr32(b, asset_layout::kTableCrc, crc32c({b.data() + kAssetHeaderSize, tableBytes}));
  wr32(b, asset_layout::kHeaderCrc, crc32c({b.data(), asset_layout::kHeaderCrc}));
  return b;
}

// ---- Shared expectations -----------------------------------------------------------------

// encodeAsset's bytes, failing the test (and returning them empty) when it refuses.
inline Bytes encodeOrDie(const BakedAsset& a) {
  Bytes out;
  const Status s = encodeAsset(a, &out);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return out;
}

// `s` has `code` and a message containing `fragment`.
inline void expectError(const Status& s, StatusCode code, const std::string& fragment) {
  EXPECT_EQ(s.code(), code) << s.toString();
  EXPECT_NE(s.message().find(fragment), std::string::npos) << "message '" << s.message() << "' lacks '" << fragment << "'";
}

inline RawSection* findSection(RawAsset& r, std::uint32_t type) {
  for (RawSection& s : r.sections)
    if (s.type == type) return &s;
  ADD_FAILURE() << "no section of type " << type;
  return &r.sections.front();
}


}  // namespace prt::test
