#include "asset_parts.h"

#include <algorithm>

#include "prt/transfer_codec.h"

namespace prt::serve {
namespace {

constexpr std::uint32_t kTypeTransfer = static_cast<std::uint32_t>(AssetSectionType::kTransfer);
constexpr std::uint32_t kTypeEncodedTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedTransfer);
constexpr std::uint32_t kTypeMatrixTransfer = static_cast<std::uint32_t>(AssetSectionType::kMatrixTransfer);
constexpr std::uint32_t kTypeEncodedMatrixTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedMatrixTransfer);
constexpr std::uint32_t kTypeAtlasUv = static_cast<std::uint32_t>(AssetSectionType::kAtlasUv);
constexpr std::uint32_t kTypeTexelCoverage = static_cast<std::uint32_t>(AssetSectionType::kTexelCoverage);
constexpr std::uint32_t kTypeTexelNormals = static_cast<std::uint32_t>(AssetSectionType::kTexelNormals);
constexpr std::uint32_t kTypeTexelTransfer = static_cast<std::uint32_t>(AssetSectionType::kTexelTransfer);
constexpr std::uint32_t kTypeEncodedTexelTransfer = static_cast<std::uint32_t>(AssetSectionType::kEncodedTexelTransfer);
constexpr std::uint32_t kTypeTexelVisibility = static_cast<std::uint32_t>(AssetSectionType::kTexelVisibility);
constexpr std::uint32_t kTypeEncodedTexelVisibility = static_cast<std::uint32_t>(AssetSectionType::kEncodedTexelVisibility);

bool isEncodedTransfer(std::uint32_t type) {
  return type == kTypeEncodedTransfer || type == kTypeEncodedMatrixTransfer || type == kTypeEncodedTexelTransfer ||
         type == kTypeEncodedTexelVisibility;
}

AssetPart sectionPart(std::uint64_t begin, std::uint64_t end, AssetPartKind kind, int section,
                      const AssetSectionInfo& info) {
  AssetPart p;
  p.offset = begin;
  p.size = end - begin;
  p.kind = kind;
  p.section = section;
  p.matrix = info.type == kTypeMatrixTransfer || info.type == kTypeEncodedMatrixTransfer;
  p.visibility = info.type == kTypeTexelVisibility || info.type == kTypeEncodedTexelVisibility;
  const bool texelPass = info.type == kTypeTexelTransfer || info.type == kTypeEncodedTexelTransfer || p.visibility;
  p.hasPass = info.type == kTypeTransfer || info.type == kTypeEncodedTransfer || p.matrix || texelPass;
  p.pass = p.hasPass ? static_cast<TransferKind>(info.arg0) : TransferKind::kUnshadowed;
  // The texel normals (19) go with the atlas sections: only texel passes use them.
  const bool atlasSection = (info.type >= kTypeAtlasUv && info.type <= kTypeTexelCoverage) || info.type == kTypeTexelNormals;
  p.domain = texelPass || atlasSection ? TransferDomain::kTexel : TransferDomain::kVertex;
  return p;
}

// Cuts the encoded-transfer section `index` ([begin, end) with its padding) at its blob's
// part boundaries into *out; false (nothing added) when the payload is not a whole,
// readable blob, so the caller keeps the section in one piece.
bool cutEncodedTransfer(std::span<const std::uint8_t> file, const AssetSectionInfo& info, int index,
                        std::uint64_t end, std::vector<AssetPart>* out) {
  const std::span<const std::uint8_t> payload = file.subspan(info.offset, info.size);
  TransferBlobInfo blob;
  if (!readTransferBlobInfo(payload, &blob).isOk() || blob.blobSize != info.size || blob.parts.empty() ||
      blob.bandsAvailable != blob.order) {
    return false;
  }
  std::vector<AssetPart> parts;
  std::uint64_t at = info.offset;
  auto add = [&](std::uint64_t next, AssetPartKind kind, int band) {
    if (next == at) return;  // an empty blob part: nothing to fetch
    AssetPart p = sectionPart(at, next, kind, index, info);
    p.band = band;
    parts.push_back(p);
    at = next;
  };
  add(info.offset + blob.parts.front().offset, AssetPartKind::kTransferHead, -1);
  for (std::size_t i = 0; i < blob.parts.size(); ++i) {
    const TransferPartInfo& tp = blob.parts[i];
    const bool last = i + 1 == blob.parts.size();
    // The padding after the blob goes with its last part, so the parts tile the file.
    const std::uint64_t next = last ? end : info.offset + tp.offset + tp.size;
    if (tp.type != TransferPartType::kBand) {  // cluster ids (and a matrix blob's weights): needed before any band
      add(next, AssetPartKind::kTransferClusters, -1);
    } else {
      add(next, AssetPartKind::kTransferBand, tp.band);
    }
  }
  out->insert(out->end(), parts.begin(), parts.end());
  return true;
}

}  // namespace

const char* assetPartKindName(AssetPartKind kind) {
  switch (kind) {
    case AssetPartKind::kHead: return "head";
    case AssetPartKind::kSection: return "section";
    case AssetPartKind::kTransferHead: return "transfer-head";
    case AssetPartKind::kTransferClusters: return "transfer-clusters";
    case AssetPartKind::kTransferBand: return "transfer-band";
  }
  return "unknown";
}

std::vector<AssetPart> cutAssetParts(std::span<const std::uint8_t> file, const AssetSummary& summary) {
  const std::vector<AssetSectionInfo>& sections = summary.sections;
  if (sections.empty()) return {};
  std::vector<int> order(sections.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  // By offset; a zero-size section sharing an offset with another comes first, so the
  // range it gets is empty instead of swallowing its neighbour.
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const AssetSectionInfo& x = sections[static_cast<std::size_t>(a)];
    const AssetSectionInfo& y = sections[static_cast<std::size_t>(b)];
    return x.offset != y.offset ? x.offset < y.offset : x.size < y.size;
  });
  const std::uint64_t fileSize = file.size();
  std::uint64_t previousEnd = summary.tableEnd;
  for (const int i : order) {
    const AssetSectionInfo& s = sections[static_cast<std::size_t>(i)];
    if (s.offset < previousEnd || s.size > fileSize || s.offset > fileSize - s.size) return {};
    previousEnd = s.offset + s.size;
  }

  std::vector<AssetPart> parts;
  AssetPart head;
  head.size = sections[static_cast<std::size_t>(order.front())].offset;
  if (head.size == 0) return {};
  parts.push_back(head);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const int index = order[k];
    const AssetSectionInfo& s = sections[static_cast<std::size_t>(index)];
    const std::uint64_t end = k + 1 < order.size() ? sections[static_cast<std::size_t>(order[k + 1])].offset : fileSize;
    if (end == s.offset) continue;
    // A glossy matrix blob is cut like a vector one (its shells are its bands; the weights
    // part goes with the clusters, as the client needs both before any shell), and so is a
    // texel pass's (its rows are texels).
    if (isEncodedTransfer(s.type) && s.size > 0 && cutEncodedTransfer(file, s, index, end, &parts)) continue;
    parts.push_back(sectionPart(s.offset, end, AssetPartKind::kSection, index, s));
  }
  return parts;
}

}  // namespace prt::serve
