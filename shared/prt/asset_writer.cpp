// Asset validation and encoding (layout: docs/asset-format.md).
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include "prt/asset.h"
#include "prt/asset_bi_scale.h"
#include "prt/checksum.h"
#include "prt/little_endian.h"
#include "prt/octahedral_normal.h"
#include "prt/sh_basis.h"
#include "prt/transfer_codec.h"

namespace prt {
namespace {

namespace L = asset_layout;

// Everything is written in little-endian order (prt/little_endian.h), so the encoding does
// not depend on the host; bulk copies below are only taken where the host is little-endian.

// Writes `count` floats; memcpy is the same bytes on a little-endian host, per-value
// stores are the portable fallback.
void putFloats(std::uint8_t* p, const float* src, std::size_t count) {
  if constexpr (std::endian::native == std::endian::little) {
    if (count > 0) std::memcpy(p, src, count * sizeof(float));
  } else {
    for (std::size_t i = 0; i < count; ++i) writeLe32(p + 4 * i, floatBits(src[i]));
  }
}

// Vec3 and Rgb are three packed floats, so their arrays are float arrays for the copy.
template <typename T>
void putTriples(std::uint8_t* p, const std::vector<T>& v) {
  static_assert(sizeof(T) == 3 * sizeof(float) && std::is_trivially_copyable_v<T>, "T must be 3 packed floats");
  if constexpr (std::endian::native == std::endian::little) {
    if (!v.empty()) std::memcpy(p, v.data(), v.size() * sizeof(T));
  } else {
    for (std::size_t i = 0; i < v.size(); ++i) {
      float f[3];
      std::memcpy(f, &v[i], sizeof f);
      putFloats(p + 12 * i, f, 3);
    }
  }
}

bool finite3(Vec3 v) { return isFinite(v); }
bool finite3(Rgb c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

template <typename T>
Status checkTriples(const std::vector<T>& v, const char* what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!finite3(v[i])) {
      return Status::error(StatusCode::kNotFinite, std::string(what) + " " + std::to_string(i) + " is not finite");
    }
  }
  return Status::ok();
}

// One material per vertex exactly when a glossy pass (matrix, or texel visibility) needs it
// (prt/asset.h).
Status checkSpecular(const std::vector<SpecularMaterial>& specular, bool anyGlossy, std::size_t vertexCount) {
  if (!anyGlossy) {
    if (specular.empty()) return Status::ok();
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(specular.size()) +
                                                           " specular materials but no matrix or visibility pass; they are kept only with one");
  }
  if (specular.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(specular.size()) + " specular materials for " +
                                                        std::to_string(vertexCount) +
                                                        " vertices; a matrix or visibility pass needs one per vertex");
  }
  for (std::size_t i = 0; i < specular.size(); ++i) {
    const SpecularMaterial& m = specular[i];
    const float f0[4] = {m.f0.r, m.f0.g, m.f0.b, m.f90};
    for (int k = 0; k < 4; ++k) {
      const char* what = k < 3 ? "f0" : "f90";
      if (!std::isfinite(f0[k])) {
        return Status::error(StatusCode::kNotFinite, "specular material " + std::to_string(i) + " has a non-finite " + what);
      }
      if (f0[k] < 0.0f || f0[k] > 1.0f) {
        return Status::error(StatusCode::kInvalidArgument, "specular material " + std::to_string(i) + " has " + what + " " +
                                                               std::to_string(f0[k]) + ", outside [0, 1]");
      }
    }
    if (!std::isfinite(m.exponent)) {
      return Status::error(StatusCode::kNotFinite, "specular material " + std::to_string(i) + " has a non-finite exponent");
    }
    if (m.exponent < 0.0f) {
      return Status::error(StatusCode::kInvalidArgument, "specular material " + std::to_string(i) + " has exponent " +
                                                             std::to_string(m.exponent) + "; it must be >= 0");
    }
  }
  return Status::ok();
}

bool isKnownKind(TransferKind kind) { return static_cast<std::uint32_t>(kind) <= 2; }

// The bi-scale sections (prt/asset.h): all or none, only with a vertex matrix pass, each value
// by asset_bi_scale's rules.
Status checkBiScale(const BakedAsset& asset) {
  const std::size_t vertexCount = asset.positions.size();
  if (asset.rtt.empty()) {
    if (asset.tangents.empty() && asset.patchUv.empty() && asset.patchPlacements.empty() && asset.idMap.empty()) return Status::ok();
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(asset.tangents.size()) + " tangents, " +
                                                           std::to_string(asset.patchUv.size()) + " patch uv floats, " +
                                                           std::to_string(asset.patchPlacements.size()) + " placements and " +
                                                           std::to_string(asset.idMap.size()) +
                                                           " id map texels but no RTT; they are kept only with one");
  }
  const bool synthesised = !asset.patchPlacements.empty() || !asset.idMap.empty();
  if (synthesised && !asset.patchUv.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "asset has both patch uv (the parametric id map) and a synthesised id map; one places the RTT");
  }
  bool matrix = false;
  for (const TransferPass& pass : asset.passes) {
    matrix = matrix || (pass.form == TransferForm::kMatrix && pass.domain == TransferDomain::kVertex);
  }
  if (!matrix) {
    return Status::error(StatusCode::kInvalidArgument, "asset has an RTT but no vertex matrix pass (bi-scale's macro scale)");
  }
  if (asset.tangents.size() != vertexCount || (!synthesised && asset.patchUv.size() != 2 * vertexCount)) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.tangents.size()) + " tangents and " +
                                                        std::to_string(asset.patchUv.size()) + " patch uv floats for " +
                                                        std::to_string(vertexCount) + " vertices; bi-scale needs 1 and 2 per vertex");
  }
  if (synthesised) {
    if (asset.patchPlacements.empty() || asset.patchPlacements.size() > kMaxPatchPlacements) {
      return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(asset.patchPlacements.size()) +
                                                             " patch placements; a synthesised id map needs 1 to " +
                                                             std::to_string(kMaxPatchPlacements));
    }
    const std::size_t want = asset.idMapPerTriangle ? asset.indices.size() / 3 : assetTexelCount(asset);
    const char* what = asset.idMapPerTriangle ? " triangles" : " atlas texels";
    if (asset.idMap.size() != want) {
      return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.idMap.size()) + " id map entries for " +
                                                          std::to_string(want) + what + "; one each is needed");
    }
    for (std::size_t i = 0; i < asset.patchPlacements.size(); ++i) {
      const PatchPlacement& q = asset.patchPlacements[i];
      PRT_RETURN_IF_ERROR(asset_bi_scale::checkPlacement({q.origin.x, q.origin.y, q.origin.z, q.axisU.x, q.axisU.y, q.axisU.z, q.axisV.x,
                                                          q.axisV.y, q.axisV.z},
                                                         i));
    }
    for (std::size_t t = 0; t < asset.idMap.size(); ++t) {
      PRT_RETURN_IF_ERROR(asset_bi_scale::checkIdMapEntry(asset.idMap[t], asset.patchPlacements.size(), t));
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    PRT_RETURN_IF_ERROR(asset_bi_scale::checkTangent(asset.tangents[v], asset.normals[v], v));
  }
  for (std::size_t i = 0; i < asset.patchUv.size(); ++i) {
    PRT_RETURN_IF_ERROR(asset_bi_scale::checkPatchCoordinate(asset.patchUv[i], i));
  }
  return asset_bi_scale::checkRttBytes(asset.rtt, asset.shOrder);
}

bool hasTexelPass(const BakedAsset& asset) {
  for (const TransferPass& pass : asset.passes)
    if (pass.domain == TransferDomain::kTexel) return true;
  return false;
}

// Without a texel pass the atlas data would be dead weight that no reader uses: refuse it
// rather than silently drop it.
Status checkNoAtlasData(const BakedAsset& asset) {
  const auto refuse = [](std::size_t count, const char* what) {
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(count) + " " + what +
                                                           " but no texel pass; they are kept only with one");
  };
  if (!asset.atlases.empty()) return refuse(asset.atlases.size(), "atlases");
  if (!asset.atlasUv.empty()) return refuse(asset.atlasUv.size(), "atlas uv floats");
  if (!asset.texelCoverage.empty()) return refuse(asset.texelCoverage.size(), "texel coverage values");
  if (!asset.texelNormals.empty()) return refuse(asset.texelNormals.size(), "texel normal codes");
  return Status::ok();
}

// The atlases tile the triangles in order: each starts where the previous ended, the
// first at 0, the last ends at the triangle count (prt/asset.h).
Status checkAtlasList(const std::vector<TextureAtlas>& atlases, std::uint64_t triangleCount) {
  if (atlases.empty() || atlases.size() > kMaxAssetAtlases) {
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(atlases.size()) + " atlases; a texel pass needs 1 to " +
                                                           std::to_string(kMaxAssetAtlases));
  }
  std::uint64_t next = 0, texels = 0;
  for (std::size_t i = 0; i < atlases.size(); ++i) {
    const TextureAtlas& a = atlases[i];
    const std::string label = "atlas " + std::to_string(i);
    if (a.width < 1 || a.width > kMaxAssetAtlasSize || a.height < 1 || a.height > kMaxAssetAtlasSize) {
      return Status::error(StatusCode::kInvalidArgument, label + " is " + std::to_string(a.width) + " x " + std::to_string(a.height) +
                                                             " texels; each side must be 1 to " + std::to_string(kMaxAssetAtlasSize));
    }
    if (a.triangleCount < 1) return Status::error(StatusCode::kInvalidArgument, label + " covers no triangles; at least 1 is needed");
    if (a.firstTriangle != next) {
      return Status::error(StatusCode::kInvalidArgument, label + " starts at triangle " + std::to_string(a.firstTriangle) + ", expected " +
                                                             std::to_string(next) + " (atlases cover the triangles in order)");
    }
    next += a.triangleCount;
    if (next > triangleCount) {
      return Status::error(StatusCode::kInvalidArgument, label + " ends at triangle " + std::to_string(next) + ", past the " +
                                                             std::to_string(triangleCount) + " triangles");
    }
    texels += std::uint64_t{a.width} * a.height;
  }
  if (next != triangleCount) {
    return Status::error(StatusCode::kInvalidArgument, "the atlases cover " + std::to_string(next) + " of the " +
                                                           std::to_string(triangleCount) + " triangles; they must cover all");
  }
  if (texels > kMaxAssetTexels) {
    return Status::error(StatusCode::kInvalidArgument, "the atlases hold " + std::to_string(texels) + " texels; at most " +
                                                           std::to_string(kMaxAssetTexels) + " are allowed");
  }
  return Status::ok();
}

// The optional texel normals: none, or 2 codes per texel (coverage checked), never -32768
// (one encoding per normal), (0, 0) where the texel is empty, as the reader demands.
Status checkTexelNormalCodes(const BakedAsset& asset) {
  if (asset.texelNormals.empty()) return Status::ok();
  if (asset.texelNormals.size() != 2 * asset.texelCoverage.size()) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.texelNormals.size()) +
                                                        " texel normal codes for " + std::to_string(asset.texelCoverage.size()) +
                                                        " texels; two per texel are needed");
  }
  for (std::size_t t = 0; t < asset.texelCoverage.size(); ++t) {
    const std::int16_t x = asset.texelNormals[2 * t], y = asset.texelNormals[2 * t + 1];
    if (x == kOctahedralInvalidCode || y == kOctahedralInvalidCode) {
      return Status::error(StatusCode::kInvalidArgument, "texel normal " + std::to_string(t) + " has the code -32768; -32767 to 32767 expected");
    }
    if (asset.texelCoverage[t] == static_cast<std::uint8_t>(TexelCoverage::kEmpty) && (x != 0 || y != 0)) {
      return Status::error(StatusCode::kInvalidArgument, "texel normal " + std::to_string(t) + " is (" + std::to_string(x) + ", " +
                                                             std::to_string(y) + ") at an empty texel; (0, 0) expected");
    }
  }
  return Status::ok();
}

// With a texel pass: the atlases, a uv per vertex in [0, 1] and a coverage value per texel.
Status checkAtlasData(const BakedAsset& asset) {
  const std::uint64_t vertexCount = asset.positions.size();
  if (Status s = checkAtlasList(asset.atlases, asset.indices.size() / 3); !s.isOk()) return s;
  if (asset.atlasUv.size() != 2 * vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.atlasUv.size()) + " atlas uv floats for " +
                                                        std::to_string(vertexCount) + " vertices; a texel pass needs 2 per vertex");
  }
  for (std::size_t i = 0; i < asset.atlasUv.size(); ++i) {
    const float x = asset.atlasUv[i];
    const std::string what = "atlas uv of vertex " + std::to_string(i / 2) + (i % 2 ? " (v)" : " (u)");
    if (!std::isfinite(x)) return Status::error(StatusCode::kNotFinite, what + " is not finite");
    if (x < 0.0f || x > 1.0f) {
      return Status::error(StatusCode::kInvalidArgument, what + " is " + std::to_string(x) + ", outside [0, 1]");
    }
  }
  const std::uint64_t texels = assetTexelCount(asset);
  if (asset.texelCoverage.size() != texels) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.texelCoverage.size()) +
                                                        " texel coverage values for " + std::to_string(texels) +
                                                        " texels; one per texel is needed");
  }
  for (std::size_t i = 0; i < asset.texelCoverage.size(); ++i) {
    if (asset.texelCoverage[i] > static_cast<std::uint8_t>(TexelCoverage::kGutter)) {
      return Status::error(StatusCode::kInvalidArgument, "texel coverage " + std::to_string(i) + " is " +
                                                             std::to_string(asset.texelCoverage[i]) + "; 0 (empty), 1 (sampled) or 2 (gutter) expected");
    }
  }
  return checkTexelNormalCodes(asset);
}

// A texel visibility pass (TPFL glossy): shadowed, one channel, no bounces, its own order, and
// distant lighting, since TPFL multiplies it with the distant light (docs/asset-format.md).
Status checkVisibilityPass(const TransferPass& pass, const std::string& named, LightingModel model) {
  if (pass.domain != TransferDomain::kTexel) {
    return Status::error(StatusCode::kInvalidArgument, named + ": visibility passes are texel passes only");
  }
  if (pass.kind != TransferKind::kShadowed) {
    return Status::error(StatusCode::kInvalidArgument, named + ": visibility passes are shadowed (V(x, w) is the shadow test)");
  }
  if (pass.channels != 1) {
    return Status::error(StatusCode::kInvalidArgument, named + " has " + std::to_string(pass.channels) +
                                                           " channels; visibility passes have 1 (visibility has no colour)");
  }
  if (pass.order < kMinVisibilityOrder || pass.order > kMaxShOrder) {
    return Status::error(StatusCode::kInvalidArgument, named + " has order " + std::to_string(pass.order) + "; " +
                                                           std::to_string(kMinVisibilityOrder) + " to " +
                                                           std::to_string(kMaxShOrder) + " are allowed");
  }
  if (isLocalLighting(model)) {
    return Status::error(StatusCode::kInvalidArgument, named + ": visibility passes need distant lighting, the asset is " +
                                                           lightingModelName(model));
  }
  return Status::ok();
}

// One section as laid out: table entry fields plus where its payload comes from.
struct PlannedSection {
  AssetSectionType type;
  AssetElementFormat format;
  std::uint32_t arg0 = 0, arg1 = 0, arg2 = 0;
  std::uint64_t size = 0;
  std::uint64_t offset = 0;
  const TransferPass* pass = nullptr;  // for the transfer sections (5, 8, 9, 10, 15 to 18)
};

std::uint64_t alignUp(std::uint64_t v) { return (v + (kAssetAlignment - 1)) & ~static_cast<std::uint64_t>(kAssetAlignment - 1); }

}  // namespace

Status checkAsset(const BakedAsset& asset) {
  if (Status s = checkShOrder(asset.shOrder); !s.isOk()) return Status::error(s.code(), "asset: " + s.message());
  const std::size_t vertexCount = asset.positions.size();
  if (vertexCount < 1 || vertexCount > kMaxAssetVertices) {
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(vertexCount) +
                                                           " vertices; 1 to " + std::to_string(kMaxAssetVertices) + " are allowed");
  }
  if (asset.normals.size() != vertexCount || asset.albedo.size() != vertexCount) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(vertexCount) + " positions, " +
                                                        std::to_string(asset.normals.size()) + " normals and " +
                                                        std::to_string(asset.albedo.size()) + " albedos; all must be equal");
  }
  if (asset.indices.size() % 3 != 0 || asset.indices.empty() || asset.indices.size() / 3 > kMaxAssetTriangles) {
    return Status::error(StatusCode::kSizeMismatch, "asset has " + std::to_string(asset.indices.size()) +
                                                        " indices; a positive multiple of 3, at most 3*" +
                                                        std::to_string(kMaxAssetTriangles) + ", is needed");
  }
  for (std::size_t i = 0; i < asset.indices.size(); ++i) {
    if (asset.indices[i] >= vertexCount) {
      return Status::error(StatusCode::kInvalidArgument, "index " + std::to_string(i) + " is " + std::to_string(asset.indices[i]) +
                                                             ", not below the vertex count " + std::to_string(vertexCount));
    }
  }
  if (Status s = checkTriples(asset.positions, "position"); !s.isOk()) return s;
  if (Status s = checkTriples(asset.normals, "normal"); !s.isOk()) return s;
  if (Status s = checkTriples(asset.albedo, "albedo"); !s.isOk()) return s;

  if (asset.passes.empty() || asset.passes.size() > kMaxAssetPasses) {
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(asset.passes.size()) +
                                                           " transfer passes; 1 to " + std::to_string(kMaxAssetPasses) + " are needed");
  }
  // The atlases first: a texel pass's size depends on their texel count.
  // The atlases come with a texel pass or with a synthesised id map (bi-scale); texel normals
  // only with a texel pass.
  const bool anyTexel = hasTexelPass(asset);
  const bool texelIdMap = !asset.idMap.empty() && !asset.idMapPerTriangle;
  if (Status s = anyTexel || texelIdMap ? checkAtlasData(asset) : checkNoAtlasData(asset); !s.isOk()) return s;
  if (!anyTexel && !asset.texelNormals.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "asset has " + std::to_string(asset.texelNormals.size()) +
                                                           " texel normal codes but no texel pass; they are kept only with one");
  }
  const std::uint64_t texelCount = assetTexelCount(asset);
  bool anyGlossy = false;  // a matrix or visibility pass: the specular materials are needed
  const std::uint64_t coeffsPerChannel = static_cast<std::uint64_t>(shCoeffCount(asset.shOrder));
  for (std::size_t p = 0; p < asset.passes.size(); ++p) {
    const TransferPass& pass = asset.passes[p];
    const std::string label = "transfer pass " + std::to_string(p);
    if (!isKnownKind(pass.kind)) {
      return Status::error(StatusCode::kInvalidArgument,
                           label + " has unknown kind " + std::to_string(static_cast<std::uint32_t>(pass.kind)));
    }
    if (pass.form != TransferForm::kVector && pass.form != TransferForm::kMatrix && pass.form != TransferForm::kVisibility) {
      return Status::error(StatusCode::kInvalidArgument,
                           label + " has unknown form " + std::to_string(static_cast<std::uint32_t>(pass.form)));
    }
    if (pass.domain != TransferDomain::kVertex && pass.domain != TransferDomain::kTexel) {
      return Status::error(StatusCode::kInvalidArgument,
                           label + " has unknown domain " + std::to_string(static_cast<std::uint32_t>(pass.domain)));
    }
    const bool matrix = pass.form == TransferForm::kMatrix;
    const bool visibility = pass.form == TransferForm::kVisibility;
    const bool texel = pass.domain == TransferDomain::kTexel;
    anyGlossy = anyGlossy || matrix || visibility;
    const std::string named = label + " (" + (texel ? "texel " : "") + (matrix ? "matrix " : "") +
                              (visibility ? "visibility " : "") + transferKindName(pass.kind) + ")";
    if (texel && matrix) {
      return Status::error(StatusCode::kInvalidArgument,
                           named + ": texel passes are vector or visibility form (glossy texels are visibility vectors, not matrices)");
    }
    if (visibility) {
      if (Status s = checkVisibilityPass(pass, named, asset.lighting.model); !s.isOk()) return s;
    } else if (pass.order != 0) {
      return Status::error(StatusCode::kInvalidArgument, named + " has order " + std::to_string(pass.order) +
                                                             "; only visibility passes have their own order (0 otherwise)");
    }
    // The bands this pass's vectors have: a visibility pass's own, else the asset's.
    const int passOrder = visibility ? pass.order : asset.shOrder;
    for (std::size_t q = 0; q < p; ++q) {
      if (asset.passes[q].kind == pass.kind && asset.passes[q].form == pass.form && asset.passes[q].domain == pass.domain) {
        return Status::error(StatusCode::kInvalidArgument, named + " repeats the kind of pass " + std::to_string(q) +
                                                               "; at most one per kind, form and domain");
      }
    }
    // A texel pass is a vertex pass whose "vertices" are the atlases' texels.
    const std::uint64_t rows = texel ? texelCount : vertexCount;
    const char* rowName = texel ? "texels" : "vertices";
    if (pass.channels != 1 && pass.channels != 3) {
      return Status::error(StatusCode::kInvalidArgument,
                           named + " has " + std::to_string(pass.channels) + " channels; 1 or 3 are allowed");
    }
    if (matrix) {
      // Visibility has no colour; bounces carry the senders' colours (prt/asset.h).
      const int wanted = pass.kind == TransferKind::kInterreflected ? 3 : 1;
      if (pass.channels != wanted) {
        return Status::error(StatusCode::kInvalidArgument, named + " has " + std::to_string(pass.channels) + " channels; " +
                                                               transferKindName(pass.kind) + " matrix passes have " +
                                                               std::to_string(wanted));
      }
      if (asset.shOrder > kMaxMatrixOrder) {
        return Status::error(StatusCode::kInvalidArgument, named + ": matrix passes need order <= " +
                                                               std::to_string(kMaxMatrixOrder) + ", the asset is order " +
                                                               std::to_string(asset.shOrder));
      }
    }
    const MatrixPacking packing = matrixPackingFor(pass.kind, asset.lighting.model);
    const bool interreflected = pass.kind == TransferKind::kInterreflected;
    if (interreflected ? (pass.bounces < 0 || pass.bounces > static_cast<int>(kMaxAssetBounces)) : pass.bounces != 0) {
      return Status::error(StatusCode::kInvalidArgument,
                           named + " has bounces " + std::to_string(pass.bounces) +
                               (interreflected ? "; 0 to " + std::to_string(kMaxAssetBounces) + " are allowed"
                                               : "; only interreflection has bounces"));
    }
    if (!pass.encoded.empty()) {
      // The blob is the pass: its header must describe this asset's pass. Its payload was
      // produced by encodeTransfer and is checked in full by every reader.
      TransferBlobInfo info;
      if (Status s = readTransferBlobInfo(pass.encoded, &info); !s.isOk()) {
        return Status::error(StatusCode::kInvalidArgument, named + " encoded blob: " + s.message());
      }
      if (info.matrix != matrix || (matrix && info.packing != packing)) {
        return Status::error(StatusCode::kInvalidArgument,
                             named + " encoded blob holds " + (info.matrix ? std::string(matrixPackingName(info.packing)) + " matrices" : "vectors") +
                                 "; the pass needs " + (matrix ? std::string(matrixPackingName(packing)) + " matrices" : "vectors"));
      }
      if (info.order != passOrder || info.channels != pass.channels || info.vertexCount != rows ||
          info.blobSize != pass.encoded.size()) {
        return Status::error(StatusCode::kSizeMismatch,
                             named + " encoded blob is order " + std::to_string(info.order) + ", " +
                                 std::to_string(info.channels) + " channels, " + std::to_string(info.vertexCount) +
                                 " rows, " + std::to_string(info.blobSize) + " bytes declared of " +
                                 std::to_string(pass.encoded.size()) + "; the " + (visibility ? "pass" : "asset") +
                                 " needs order " + std::to_string(passOrder) + ", " + std::to_string(pass.channels) + " channels, " +
                                 std::to_string(rows) + " " + rowName);
      }
      continue;
    }
    const std::uint64_t perChannel = matrix       ? matrixEntryCount(asset.shOrder, packing)
                                     : visibility ? static_cast<std::uint64_t>(shCoeffCount(pass.order))
                                                  : coeffsPerChannel;
    const std::uint64_t expected = rows * static_cast<std::uint64_t>(pass.channels) * perChannel;
    if (pass.coeffs.size() != expected) {
      return Status::error(StatusCode::kSizeMismatch,
                           named + " has " + std::to_string(pass.coeffs.size()) + " coefficients, " + std::to_string(expected) +
                               (matrix       ? " expected (vertices * channels * " + std::to_string(perChannel) + " " +
                                                   matrixPackingName(packing) + " packed entries)"
                                : visibility ? " expected (texels * the pass's order^2)"
                                             : " expected (" + std::string(rowName) + " * channels * order^2)"));
    }
    for (std::size_t i = 0; i < pass.coeffs.size(); ++i) {
      if (!std::isfinite(pass.coeffs[i])) {
        return Status::error(StatusCode::kNotFinite, named + " coefficient " + std::to_string(i) + " is not finite");
      }
      if (std::fabs(pass.coeffs[i]) > kMaxTransferMagnitude) {
        return Status::error(StatusCode::kInvalidArgument, named + " coefficient " + std::to_string(i) + " is " +
                                                               std::to_string(pass.coeffs[i]) + ", beyond the transfer range (65504)");
      }
    }
  }
  if (Status st = checkSpecular(asset.specular, anyGlossy, vertexCount); !st.isOk()) return st;
  if (Status st = checkBiScale(asset); !st.isOk()) return st;
  if (!isValidAssetName(asset.name)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "asset name must be at most " + std::to_string(kMaxAssetNameBytes) +
                             " bytes of UTF-8 without control characters");
  }
  if (!isValidAssetSamplingName(asset.sampling)) {
    return Status::error(StatusCode::kInvalidArgument, "asset sampling '" + asset.sampling + "' must be at most " +
                                                           std::to_string(kMaxAssetSamplingBytes) + " characters of [a-z0-9_-]");
  }
  return checkLightingInfo(asset.lighting);
}

Status encodeAsset(const BakedAsset& asset, std::vector<std::uint8_t>* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "encodeAsset: out is null");
  if (Status s = checkAsset(asset); !s.isOk()) return s;

  const std::uint64_t vertexCount = asset.positions.size();
  const std::uint64_t triangleCount = asset.indices.size() / 3;
  const std::uint64_t coeffsPerChannel = static_cast<std::uint64_t>(shCoeffCount(asset.shOrder));

  // Metadata and lighting first: they are tiny and hold what a catalogue lists, so it can
  // read a short prefix. Lighting is written even when distant, so every file says which
  // model its transfer belongs to.
  std::vector<PlannedSection> sections;
  sections.push_back({AssetSectionType::kMetadata, AssetElementFormat::kBytes, 0, 0, 0,
                      24 + asset.sampling.size() + asset.name.size(), 0, nullptr});
  sections.push_back({AssetSectionType::kLighting, AssetElementFormat::kBytes, 0, 0, 0, kAssetLightingBytes, 0, nullptr});
  sections.push_back({AssetSectionType::kPositions, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 12, 0, nullptr});
  sections.push_back({AssetSectionType::kNormals, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 12, 0, nullptr});
  sections.push_back({AssetSectionType::kIndices, AssetElementFormat::kUint32, 0, 0, 0, triangleCount * 12, 0, nullptr});
  sections.push_back({AssetSectionType::kAlbedo, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 12, 0, nullptr});
  // The specular materials before the passes: a progressive client needs them with the
  // first glossy shell. Only glossy assets have them, so other files keep their layout.
  if (!asset.specular.empty()) {
    sections.push_back({AssetSectionType::kSpecular, AssetElementFormat::kFloat32, 0, 0, 0,
                        vertexCount * kAssetSpecularBytesPerVertex, 0, nullptr});
  }
  // The atlas sections before the passes: a client needs them before any texel pass is of
  // use. Only assets with texel passes have them, so other files keep their layout.
  if (!asset.atlases.empty()) {
    sections.push_back({AssetSectionType::kAtlasUv, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 8, 0, nullptr});
    sections.push_back({AssetSectionType::kAtlases, AssetElementFormat::kBytes, static_cast<std::uint32_t>(asset.atlases.size()), 0, 0,
                        asset.atlases.size() * kAssetAtlasEntryBytes, 0, nullptr});
    sections.push_back({AssetSectionType::kTexelCoverage, AssetElementFormat::kBytes, 0, 0, 0, asset.texelCoverage.size(), 0, nullptr});
    // With the atlases, before the passes: the glossy term reads them from its first band.
    if (!asset.texelNormals.empty()) {
      sections.push_back({AssetSectionType::kTexelNormals, AssetElementFormat::kBytes, 0, 0, 0,
                          asset.texelNormals.size() / 2 * kAssetTexelNormalBytes, 0, nullptr});
    }
  }
  // The bi-scale sections before the passes too: the client draws bi-scale from the first
  // glossy shell on. Only bi-scale assets have them, so other files keep their layout.
  if (!asset.rtt.empty()) {
    sections.push_back({AssetSectionType::kTangents, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 12, 0, nullptr});
    if (!asset.patchUv.empty()) {
      sections.push_back({AssetSectionType::kPatchUv, AssetElementFormat::kFloat32, 0, 0, 0, vertexCount * 8, 0, nullptr});
    } else {
      sections.push_back({AssetSectionType::kPatchPlacements, AssetElementFormat::kFloat32,
                          static_cast<std::uint32_t>(asset.patchPlacements.size()), 0, 0,
                          asset.patchPlacements.size() * kAssetPlacementBytes, 0, nullptr});
      sections.push_back({AssetSectionType::kIdMap, AssetElementFormat::kBytes, asset.idMapPerTriangle ? 1u : 0u, 0, 0,
                          asset.idMap.size() * 2, 0, nullptr});
    }
    sections.push_back({AssetSectionType::kRtt, AssetElementFormat::kBytes, 0, 0, 0, asset.rtt.size(), 0, nullptr});
  }
  const std::uint64_t texelCount = assetTexelCount(asset);
  for (const TransferPass& pass : asset.passes) {
    const bool matrix = pass.form == TransferForm::kMatrix;
    const bool visibility = pass.form == TransferForm::kVisibility;  // texel domain (checkAsset)
    const bool texel = pass.domain == TransferDomain::kTexel;        // vector or visibility form (checkAsset)
    // A visibility section's arg2 is its order; the other passes' is their bounces.
    const std::uint32_t arg2 = static_cast<std::uint32_t>(visibility ? pass.order : pass.bounces);
    if (!pass.encoded.empty()) {
      sections.push_back({visibility ? AssetSectionType::kEncodedTexelVisibility
                          : texel    ? AssetSectionType::kEncodedTexelTransfer
                          : matrix   ? AssetSectionType::kEncodedMatrixTransfer
                                     : AssetSectionType::kEncodedTransfer,
                          AssetElementFormat::kBytes, static_cast<std::uint32_t>(pass.kind),
                          static_cast<std::uint32_t>(pass.channels), arg2, pass.encoded.size(), 0, &pass});
      continue;
    }
    const std::uint64_t perChannel = matrix       ? matrixEntryCount(asset.shOrder, matrixPackingFor(pass.kind, asset.lighting.model))
                                     : visibility ? static_cast<std::uint64_t>(shCoeffCount(pass.order))
                                                  : coeffsPerChannel;
    sections.push_back({visibility ? AssetSectionType::kTexelVisibility
                        : texel    ? AssetSectionType::kTexelTransfer
                        : matrix   ? AssetSectionType::kMatrixTransfer
                                   : AssetSectionType::kTransfer,
                        AssetElementFormat::kFloat32, static_cast<std::uint32_t>(pass.kind),
                        static_cast<std::uint32_t>(pass.channels), arg2,
                        (texel ? texelCount : vertexCount) * static_cast<std::uint64_t>(pass.channels) * perChannel * 4, 0, &pass});
  }

  const std::uint64_t tableEnd = kAssetHeaderSize + sections.size() * kAssetSectionEntrySize;
  std::uint64_t end = tableEnd;
  for (PlannedSection& s : sections) {
    s.offset = alignUp(end);
    end = s.offset + s.size;
  }
  const std::uint64_t fileSize = end;
  // Matters in wasm, where size_t is 32 bits: refuse rather than wrap.
  if (fileSize > std::numeric_limits<std::size_t>::max() || fileSize > out->max_size()) {
    return Status::error(StatusCode::kInvalidArgument,
                         "encoded asset would be " + std::to_string(fileSize) + " bytes, too large for this platform");
  }

  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(fileSize), 0);
  std::uint8_t* base = bytes.data();
  for (std::size_t i = 0; i < sections.size(); ++i) {
    const PlannedSection& s = sections[i];
    std::uint8_t* p = base + s.offset;
    switch (s.type) {
      case AssetSectionType::kMetadata:
        writeLe64(p, asset.samples);
        writeLe64(p + 8, asset.seed);
        writeLe32(p + 16, static_cast<std::uint32_t>(asset.sampling.size()));
        writeLe32(p + 20, static_cast<std::uint32_t>(asset.name.size()));
        if (!asset.sampling.empty()) std::memcpy(p + 24, asset.sampling.data(), asset.sampling.size());
        if (!asset.name.empty()) std::memcpy(p + 24 + asset.sampling.size(), asset.name.data(), asset.name.size());
        break;
      case AssetSectionType::kLighting: {
        namespace LL = asset_lighting_layout;
        writeLe32(p + LL::kModel, static_cast<std::uint32_t>(asset.lighting.model));
        static_assert(LL::kCenterY == LL::kCenterX + 4 && LL::kCenterZ == LL::kCenterX + 8 && LL::kRadius == LL::kCenterX + 12,
                      "centre and radius are four consecutive floats");
        const float fields[4] = {asset.lighting.center.x, asset.lighting.center.y, asset.lighting.center.z,
                                 asset.lighting.radius};
        putFloats(p + LL::kCenterX, fields, 4);
        break;
      }
      case AssetSectionType::kPositions: putTriples(p, asset.positions); break;
      case AssetSectionType::kNormals: putTriples(p, asset.normals); break;
      case AssetSectionType::kAlbedo: putTriples(p, asset.albedo); break;
      case AssetSectionType::kIndices:
        if constexpr (std::endian::native == std::endian::little) {
          std::memcpy(p, asset.indices.data(), asset.indices.size() * 4);
        } else {
          for (std::size_t k = 0; k < asset.indices.size(); ++k) writeLe32(p + 4 * k, asset.indices[k]);
        }
        break;
      case AssetSectionType::kTransfer:
      case AssetSectionType::kMatrixTransfer:
      case AssetSectionType::kTexelTransfer:
      case AssetSectionType::kTexelVisibility: putFloats(p, s.pass->coeffs.data(), s.pass->coeffs.size()); break;
      case AssetSectionType::kEncodedTransfer:
      case AssetSectionType::kEncodedMatrixTransfer:
      case AssetSectionType::kEncodedTexelTransfer:
      case AssetSectionType::kEncodedTexelVisibility: std::memcpy(p, s.pass->encoded.data(), s.pass->encoded.size()); break;
      case AssetSectionType::kAtlasUv: putFloats(p, asset.atlasUv.data(), asset.atlasUv.size()); break;
      case AssetSectionType::kAtlases:
        for (std::size_t a = 0; a < asset.atlases.size(); ++a) {
          namespace AL = asset_atlas_layout;
          const TextureAtlas& atlas = asset.atlases[a];
          std::uint8_t* q = p + kAssetAtlasEntryBytes * a;
          writeLe32(q + AL::kWidth, atlas.width);
          writeLe32(q + AL::kHeight, atlas.height);
          writeLe32(q + AL::kFirstTriangle, atlas.firstTriangle);
          writeLe32(q + AL::kTriangleCount, atlas.triangleCount);
        }
        break;
      case AssetSectionType::kTexelCoverage: std::memcpy(p, asset.texelCoverage.data(), asset.texelCoverage.size()); break;
      case AssetSectionType::kTangents: putTriples(p, asset.tangents); break;
      case AssetSectionType::kPatchUv: putFloats(p, asset.patchUv.data(), asset.patchUv.size()); break;
      case AssetSectionType::kRtt: std::memcpy(p, asset.rtt.data(), asset.rtt.size()); break;
      case AssetSectionType::kPatchPlacements:
        for (std::size_t k = 0; k < asset.patchPlacements.size(); ++k) {
          const PatchPlacement& q = asset.patchPlacements[k];
          const float f[9] = {q.origin.x, q.origin.y, q.origin.z, q.axisU.x, q.axisU.y, q.axisU.z, q.axisV.x, q.axisV.y, q.axisV.z};
          putFloats(p + kAssetPlacementBytes * k, f, 9);
        }
        break;
      case AssetSectionType::kIdMap:
        for (std::size_t k = 0; k < asset.idMap.size(); ++k) writeLe16(p + 2 * k, asset.idMap[k]);
        break;
      case AssetSectionType::kTexelNormals:
        for (std::size_t k = 0; k < asset.texelNormals.size(); ++k) {
          writeLe16(p + 2 * k, static_cast<std::uint16_t>(asset.texelNormals[k]));
        }
        break;
      case AssetSectionType::kSpecular:
        for (std::size_t v = 0; v < asset.specular.size(); ++v) {
          const SpecularMaterial& m = asset.specular[v];
          const float f[5] = {m.f0.r, m.f0.g, m.f0.b, m.f90, m.exponent};
          putFloats(p + kAssetSpecularBytesPerVertex * v, f, 5);
        }
        break;
    }
    std::uint8_t* e = base + kAssetHeaderSize + i * kAssetSectionEntrySize;
    writeLe32(e + L::kEntryType, static_cast<std::uint32_t>(s.type));
    writeLe32(e + L::kEntryFormat, static_cast<std::uint32_t>(s.format));
    writeLe64(e + L::kEntryOffset, s.offset);
    writeLe64(e + L::kEntrySize, s.size);
    writeLe32(e + L::kEntryArg0, s.arg0);
    writeLe32(e + L::kEntryArg1, s.arg1);
    writeLe32(e + L::kEntryArg2, s.arg2);
    writeLe32(e + L::kEntryCrc, crc32c({p, static_cast<std::size_t>(s.size)}));
  }

  std::memcpy(base + L::kMagic, kAssetMagic, 4);
  writeLe16(base + L::kVersionMajor, kAssetVersionMajor);
  // Always the current minor version (1.5): older readers skip the section types they do
  // not know, so a glossy or texel file still shows them its vertex diffuse passes (a file
  // with a visibility pass but no matrix pass they reject: its specular section has no
  // matrix section they know, docs/asset-format.md "Versioning").
  writeLe16(base + L::kVersionMinor, kAssetVersionMinor);
  writeLe32(base + L::kFlags, 0);
  writeLe32(base + L::kShOrder, static_cast<std::uint32_t>(asset.shOrder));
  writeLe32(base + L::kVertexCount, static_cast<std::uint32_t>(vertexCount));
  writeLe32(base + L::kTriangleCount, static_cast<std::uint32_t>(triangleCount));
  writeLe32(base + L::kSectionCount, static_cast<std::uint32_t>(sections.size()));
  writeLe32(base + L::kTableCrc, crc32c({base + kAssetHeaderSize, static_cast<std::size_t>(tableEnd - kAssetHeaderSize)}));
  writeLe64(base + L::kFileSize, fileSize);
  writeLe32(base + L::kHeaderCrc, crc32c({base, L::kHeaderCrc}));

  *out = std::move(bytes);
  return Status::ok();
}

}  // namespace prt
