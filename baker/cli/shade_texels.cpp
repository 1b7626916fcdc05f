#include "baker/cli/shade_texels.h"

#include <algorithm>
#include <cstddef>

#include "baker/cli/report_failure.h"
#include "baker/texture/asset_texels.h"
#include "native/exit_status.h"
#include "native/json_text.h"
#include "prt/exit_radiance.h"
#include "prt/glossy_radiance.h"
#include "prt/octahedral_normal.h"
#include "prt/sh_basis.h"
#include "prt/sh_triple_product.h"

namespace prt {
namespace {

std::string prefixed(const std::string& path, const Status& s) { return "'" + path + "': " + s.toString(); }

// The transfer order of the product for `order` lighting bands and an order-m visibility:
// at least the lighting's (ShTripleProduct needs it; missing bands are zero), at most
// 2 order - 1 (bands past it do not reach the product's first `order` bands).
int productTransferOrder(int order, int m) { return std::min(std::max(m, order), 2 * order - 1); }

// The shading normal of every texel sample: the asset's stored one where it has texel normals
// (normal maps: the reflection direction and Schlick's n.v follow the bump, as in the client),
// else the interpolated vertex normal. The texel numbering is the asset's (its coverage's).
std::vector<Vec3> texelShadingNormals(const BakedAsset& asset, const std::vector<bake::AtlasTexel>& texels) {
  std::vector<Vec3> normals(texels.size());
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const std::size_t code = 2 * static_cast<std::size_t>(texels[i].index);
    normals[i] = code + 1 < asset.texelNormals.size()
                     ? decodeOctahedralNormal(asset.texelNormals[code], asset.texelNormals[code + 1])
                     : texels[i].normal;
  }
  return normals;
}

// The TPFL glossy term of every texel sample into *out (3 per texel), reflecting about `normals`.
Status tpflTexelRadiance(const BakedAsset& asset, const TexelShade& shade, const std::vector<bake::AtlasTexel>& texels,
                         const std::vector<Vec3>& normals, int order, const std::vector<Rgb>& lighting, std::vector<float>* out) {
  const TransferPass& v = *shade.visibility;
  if (order > kMaxTripleProductOrder) {
    return Status::error(StatusCode::kInvalidArgument, "TPFL glossy shading supports lighting orders up to " +
                                                           std::to_string(kMaxTripleProductOrder) + "; give --order " +
                                                           std::to_string(kMaxTripleProductOrder) + " or less");
  }
  const int t = productTransferOrder(order, v.order);
  ShTripleProduct product;
  PRT_RETURN_IF_ERROR(ShTripleProduct::make(order, t, &product));
  const std::size_t m2 = static_cast<std::size_t>(v.order) * static_cast<std::size_t>(v.order);
  const std::size_t t2 = static_cast<std::size_t>(t) * static_cast<std::size_t>(t), kept = std::min(m2, t2);
  std::vector<float> visibility(texels.size() * t2, 0.0f);
  std::vector<Vec3> positions(texels.size());
  for (std::size_t i = 0; i < texels.size(); ++i) {
    // decodeAsset checked the pass's size against the texel count, and the samples' indices
    // came from the same atlases.
    const std::size_t from = static_cast<std::size_t>(texels[i].index) * m2;
    if (from + m2 > v.coeffs.size()) return Status::error(StatusCode::kCorrupt, "the visibility pass is shorter than its texels");
    std::copy_n(v.coeffs.begin() + static_cast<std::ptrdiff_t>(from), kept, visibility.begin() + static_cast<std::ptrdiff_t>(i * t2));
    positions[i] = texels[i].position;
  }
  std::vector<SpecularMaterial> specular;
  PRT_RETURN_IF_ERROR(bake::assetTexelSpecular(asset, texels, &specular));
  out->assign(3 * texels.size(), 0.0f);
  return tpflGlossyExitRadiance(product, visibility, positions, normals, specular, GlossyView{shade.eye, true}, lighting, *out);
}

// Writes *text to `out` and empties it once it passes 1 MiB, so a large atlas's output
// streams instead of growing one string.
void flushWhenLarge(std::string* text, std::FILE* out) {
  if (text->size() <= (1u << 20)) return;
  std::fputs(text->c_str(), out);
  text->clear();
}

}  // namespace

int printTexels(const BakedAsset& asset, const TexelShade& shade, const std::string& path, const std::string& light,
                int order, const std::vector<Rgb>& lighting, bool json, std::FILE* out, std::FILE* err) {
  const TransferPass& pass = *shade.diffuse;
  std::vector<bake::AtlasTexel> texels;
  if (Status s = bake::assetTexelSamples(asset, &texels); !s.isOk()) {
    return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
  }
  const std::vector<Vec3> shading = texelShadingNormals(asset, texels);
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(asset.shOrder));
  const std::size_t perTexel = n2 * static_cast<std::size_t>(pass.channels);
  std::vector<float> exit(3 * texels.size(), 0.0f);
  if (!shade.glossyOnly) {
    std::vector<float> transfer(texels.size() * perTexel);
    std::vector<Rgb> albedo(texels.size());
    for (std::size_t t = 0; t < texels.size(); ++t) {
      std::copy_n(pass.coeffs.begin() + static_cast<std::ptrdiff_t>(texels[t].index * perTexel), perTexel,
                  transfer.begin() + static_cast<std::ptrdiff_t>(t * perTexel));
      albedo[t] = texels[t].albedo;
    }
    if (Status s = exitRadiance(transfer, pass.channels, n2, albedo, lighting, exit); !s.isOk()) {
      return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
    }
  }
  if (shade.visibility != nullptr) {
    std::vector<float> glossy;
    if (Status s = tpflTexelRadiance(asset, shade, texels, shading, order, lighting, &glossy); !s.isOk()) {
      return reportFailure(err, "shade", Status::error(s.code(), prefixed(path, s)));
    }
    for (std::size_t i = 0; i < exit.size(); ++i) exit[i] += glossy[i];
  }
  std::string text;
  if (json) {
    // "pass" names the diffuse texel pass; the glossy term is always the visibility pass's.
    text = "{\n  \"asset\": " + jsonString(path) + ",\n  \"pass\": \"" + transferKindName(pass.kind) +
           "\",\n  \"domain\": \"texel\",\n  \"order\": " + std::to_string(order) + ",\n  \"light\": " +
           jsonString(light) + ",\n";
    if (shade.visibility) {
      const Vec3 e = shade.eye;
      text += "  \"glossy\": \"visibility\",\n  \"view\": [" + jsonNumber(e.x) + ", " + jsonNumber(e.y) + ", " + jsonNumber(e.z) + "],\n  \"terms\": \"" +
              (shade.glossyOnly ? "glossy" : "diffuse+glossy") + "\",\n  \"visibility_order\": " +
              std::to_string(shade.visibility->order) + ",\n  \"product\": {\"order\": " + std::to_string(order) +
              ", \"transfer_order\": " + std::to_string(productTransferOrder(order, shade.visibility->order)) + "},\n";
    }
    text += "  \"atlases\": [";
    for (std::size_t a = 0; a < asset.atlases.size(); ++a) {
      text += std::string(a ? ", " : "") + "{\"width\": " + std::to_string(asset.atlases[a].width) +
              ", \"height\": " + std::to_string(asset.atlases[a].height) + "}";
    }
    text += "],\n  \"texels\": [\n";
  }
  for (std::size_t t = 0; t < texels.size(); ++t) {
    const bake::AtlasTexel& s = texels[t];
    const float* e = &exit[3 * t];
    if (json) {
      text += "    {\"atlas\": " + std::to_string(s.atlas) + ", \"x\": " + std::to_string(s.x) + ", \"y\": " +
              std::to_string(s.y) + ", \"position\": [" + jsonNumber(s.position.x) + ", " + jsonNumber(s.position.y) +
              ", " + jsonNumber(s.position.z) + "], \"normal\": [" + jsonNumber(s.normal.x) + ", " +
              jsonNumber(s.normal.y) + ", " + jsonNumber(s.normal.z) + "], " +
              (asset.texelNormals.empty() ? std::string()
                                          : "\"shading_normal\": [" + jsonNumber(shading[t].x) + ", " + jsonNumber(shading[t].y) +
                                                ", " + jsonNumber(shading[t].z) + "], ") +
              "\"radiance\": [" + jsonNumber(e[0]) + ", " +
              jsonNumber(e[1]) + ", " + jsonNumber(e[2]) + "]}" + (t + 1 < texels.size() ? ",\n" : "\n");
    } else {
      char line[320];
      std::snprintf(line, sizeof line, "%u %d %d %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g\n", s.atlas, s.x, s.y,
                    static_cast<double>(s.position.x), static_cast<double>(s.position.y),
                    static_cast<double>(s.position.z), static_cast<double>(s.normal.x),
                    static_cast<double>(s.normal.y), static_cast<double>(s.normal.z), static_cast<double>(e[0]),
                    static_cast<double>(e[1]), static_cast<double>(e[2]));
      text += line;
    }
    flushWhenLarge(&text, out);
  }
  if (json) text += "  ]\n}\n";
  std::fputs(text.c_str(), out);
  return kExitOk;
}

}  // namespace prt
