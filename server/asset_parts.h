// Cutting a verified asset file into the contiguous byte ranges ("parts") the server also
// serves on their own, so a browser can fetch an asset piece by piece in its own priority
// order (mesh, then band 0 of a pass, render, then band 1, ...) and a CDN can cache each
// piece under a content-addressed URL (docs/server.md, "Parts").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/asset.h"

namespace prt::serve {

enum class AssetPartKind {
  kHead,              // header, section table and the padding before the first payload
  kSection,           // one section's payload (and the padding after it)
  kTransferHead,      // an encoded-transfer section's blob header and part table
  kTransferClusters,  // an encoded-transfer blob's cluster ids (CPCA)
  kTransferBand,      // one SH band of an encoded-transfer blob
};

// "head" | "section" | "transfer-head" | "transfer-clusters" | "transfer-band".
const char* assetPartKindName(AssetPartKind kind);

struct AssetPart {
  std::uint64_t offset = 0;  // from the start of the file
  std::uint64_t size = 0;    // > 0
  AssetPartKind kind = AssetPartKind::kHead;
  int section = -1;          // index in the section table; -1 for the head
  bool hasPass = false;      // a part of a transfer section (type 5, 8, matrix 9, 10, texel 15-18)...
  TransferKind pass = TransferKind::kUnshadowed;  // ...of this pass (the section's arg0)
  bool matrix = false;       // ...a glossy matrix pass (types 9, 10): listed with "form":"matrix"
  bool visibility = false;   // ...a TPFL texel visibility pass (types 17, 18): "form":"visibility"
  // kTexel for a texel pass's parts (types 15-18) and the atlas sections' (12-14, and the texel
  // normals, 19), which only
  // texel passes need: listed with "domain":"texel" (pass parts otherwise "domain":"vertex").
  TransferDomain domain = TransferDomain::kVertex;
  int band = -1;             // kTransferBand: the SH band l; -1 otherwise
};

// The parts of `file`, whose validated section table is `summary.sections` (verifyAsset),
// in file order. They tile the file exactly: the first starts at 0, each next one where the
// previous ends, the last ends at file.size(). The head runs up to the first payload; each
// section's part runs from its payload to the next payload (padding folded in). An
// encoded-transfer section (type 8, 10, 16 or 18) whose payload is a readable blob of exactly its size
// is cut further at the blob's part boundaries (blob head, clusters, band 0, band 1, ...);
// otherwise it is one section part. Empty ranges (zero-size sections) get no part. Empty
// when the table does not fit `file` (never for a table verifyAsset accepted).
std::vector<AssetPart> cutAssetParts(std::span<const std::uint8_t> file, const AssetSummary& summary);

}  // namespace prt::serve
