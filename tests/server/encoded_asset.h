// Assets holding encoded-transfer sections (type 8, a transfer-codec blob), written by
// the tests themselves: encodeAsset writes the rest, and the sections are appended with a
// re-laid-out header and table as docs/asset-format.md specifies.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/asset.h"

namespace prt::serve::test {

struct ExtraSection {
  AssetSectionType type = AssetSectionType::kEncodedTransfer;
  std::uint32_t args[3] = {0, 0, 0};
  std::vector<std::uint8_t> payload;
};

// `asset` (a file encodeAsset wrote) with `extra` appended: every payload at the next
// multiple of 16 after the enlarged table, minor version 2, table and header checksums
// recomputed. `table` (may be null) receives the section table written, so a test can use
// it without a reader (which rejects the damaged sections some tests append). Throws
// std::runtime_error if `asset` cannot be read.
std::vector<std::uint8_t> appendSections(const std::vector<std::uint8_t>& asset, const std::vector<ExtraSection>& extra,
                                         std::vector<AssetSectionInfo>* table = nullptr);

struct EncodedTransferAsset {
  std::vector<std::uint8_t> bytes;  // the asset file
  std::vector<std::uint8_t> cpcaBlob;   // interreflected, 3 channels, CPCA (a clusters part)
  std::vector<std::uint8_t> quantBlob;  // shadowed, 1 channel, q8 (no clusters part)
  int order = 0;
};

// A valid asset of `vertices` vertices and SH order `order` with a plain unshadowed
// transfer section (type 5) and two encoded-transfer sections: interreflected as a CPCA
// blob, shadowed as a q8 blob. Throws std::runtime_error on an encoder failure.
EncodedTransferAsset makeEncodedTransferAsset(int vertices, int order, std::uint32_t seed);

struct TexelTransferAsset {
  std::vector<std::uint8_t> bytes;   // the asset file (format 1.4, written by encodeAsset)
  std::vector<std::uint8_t> blob;    // its texel shadowed pass: q8, one codec "vertex" per texel
  std::vector<std::uint8_t> visibilityBlob;  // withVisibility: the visibility pass, q8
  std::vector<TextureAtlas> atlases;
  int order = 0;
};

// makeAssetBytes' strip of `vertices` vertices with its vertex passes, plus transfer
// textures: two atlases (the first half of the triangles in a 16 x 8 atlas, the rest in
// 8 x 8), atlas uv and coverage, and a texel shadowed pass encoded q8; withVisibility adds a
// TPFL visibility pass of order 2 order - 1, encoded q8, and the specular materials it needs
// (format 1.5). Throws std::runtime_error on an encoder failure.
TexelTransferAsset makeTexelTransferAsset(int vertices, int order, std::uint32_t seed, bool withVisibility = false);

}  // namespace prt::serve::test
