// prt_cli_make_texel_asset OUT: writes a small asset with transfer textures (format 1.4) for
// the `prt-bake info` tests, since no bake writes texel passes yet, and prints what it wrote
// as JSON ({"texels", "atlases", "passes": [{kind, domain, encoded}]}) so that the test
// compares `info` with the generator rather than with numbers of its own.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/transfer_codec.h"

namespace {

// A strip of 10 vertices and 8 triangles in two atlases (6x4 for triangles 0-4, 3x2 for 5-7):
// a vertex shadowed pass, a float32 texel shadowed pass, a q16 texel interreflected pass.
prt::Status makeAsset(prt::BakedAsset* out) {
  using namespace prt;
  BakedAsset a;
  a.shOrder = 2;
  const std::uint32_t V = 10, T = 8;
  for (std::uint32_t v = 0; v < V; ++v) {
    const float t = static_cast<float>(v) / static_cast<float>(V - 1);
    a.positions.push_back({t, static_cast<float>(v % 2), 0.0f});
    a.normals.push_back({0.0f, 0.0f, 1.0f});
    a.albedo.push_back({0.8f, 0.8f, 0.8f});
    a.atlasUv.insert(a.atlasUv.end(), {t, static_cast<float>(v % 2)});
  }
  for (std::uint32_t t = 0; t < T; ++t) a.indices.insert(a.indices.end(), {t, t + 1, t + 2});
  a.atlases = {{6, 4, 0, 5}, {3, 2, 5, 3}};
  const std::uint64_t texels = assetTexelCount(a);
  for (std::uint64_t i = 0; i < texels; ++i) a.texelCoverage.push_back(static_cast<std::uint8_t>(i % 3));
  auto pass = [&](TransferKind kind, std::uint64_t rows, TransferDomain domain) {
    TransferPass p;
    p.kind = kind;
    p.channels = kind == TransferKind::kInterreflected ? 3 : 1;
    p.bounces = kind == TransferKind::kInterreflected ? 1 : 0;
    p.domain = domain;
    for (std::uint64_t i = 0; i < rows * static_cast<std::uint64_t>(p.channels) * 4; ++i)
      p.coeffs.push_back(0.5f * std::cos(0.1f * static_cast<float>(i)));
    return p;
  };
  a.passes.push_back(pass(TransferKind::kShadowed, V, TransferDomain::kVertex));
  a.passes.push_back(pass(TransferKind::kShadowed, texels, TransferDomain::kTexel));
  a.passes.push_back(pass(TransferKind::kInterreflected, texels, TransferDomain::kTexel));
  TransferCodecSettings q16;
  if (Status s = parseTransferSetting("q16", TransferCodecSettings{}, &q16); !s.isOk()) return s;
  TransferPass& encoded = a.passes.back();
  if (Status s = encodeTransfer(encoded.coeffs, a.shOrder, encoded.channels, q16, &encoded.encoded); !s.isOk()) return s;
  a.sampling = "hammersley";
  a.name = "texel-fixture";
  *out = std::move(a);
  return Status::ok();
}

std::string describe(const prt::BakedAsset& a) {
  std::string s = "{\"texels\": " + std::to_string(prt::assetTexelCount(a)) + ", \"atlases\": [";
  for (std::size_t i = 0; i < a.atlases.size(); ++i) {
    const prt::TextureAtlas& t = a.atlases[i];
    s += std::string(i ? ", " : "") + "{\"width\": " + std::to_string(t.width) + ", \"height\": " + std::to_string(t.height) +
         ", \"firstTriangle\": " + std::to_string(t.firstTriangle) + ", \"triangleCount\": " + std::to_string(t.triangleCount) + "}";
  }
  s += "], \"passes\": [";
  for (std::size_t i = 0; i < a.passes.size(); ++i) {
    const prt::TransferPass& p = a.passes[i];
    s += std::string(i ? ", " : "") + "{\"kind\": \"" + prt::transferKindName(p.kind) + "\", \"domain\": \"" +
         prt::transferDomainName(p.domain) + "\", \"encoded\": " + (p.encoded.empty() ? "false" : "true") + "}";
  }
  return s + "]}";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: prt_cli_make_texel_asset OUT\n");
    return 2;
  }
  prt::BakedAsset asset;
  std::vector<std::uint8_t> bytes;
  prt::Status s = makeAsset(&asset);
  if (s.isOk()) s = prt::encodeAsset(asset, &bytes);
  if (!s.isOk()) {
    std::fprintf(stderr, "prt_cli_make_texel_asset: %s\n", s.toString().c_str());
    return 1;
  }
  std::ofstream file(argv[1], std::ios::binary);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!file.good()) {
    std::fprintf(stderr, "prt_cli_make_texel_asset: cannot write %s\n", argv[1]);
    return 1;
  }
  std::printf("%s\n", describe(asset).c_str());
  return 0;
}
