// Normal maps in the texel bake (PRTT §6.2; docs/transfer-textures.md, "Normal maps"): the
// loader's normalTexture, TANGENT and mirrored nodes, computed tangents, the decode, and a
// flat normal-mapped quad against the finely tessellated bumpy surface it stands for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "baker/gltf_test_files.h"
#include "baker/scene/gltf_loader.h"
#include "baker/scene/mesh_tangents.h"
#include "baker/scene/normal_map.h"
#include "baker/transfer/texel_bake.h"
#include "baker/transfer/transfer_bake.h"
#include "prt/octahedral_normal.h"
#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"

namespace prt::bake {
namespace {

constexpr double kPi = 3.14159265358979323846;

unsigned char encode(float c) { return static_cast<unsigned char>(std::lround((c + 1.0f) * 0.5f * 255.0f)); }

// The tangent-space normal every test map below stores: tilted towards +x and +y.
const Vec3 kTilt = [] {
  const Vec3 t{0.3f, 0.2f, 0.9327379f};
  return t * (1.0f / length(t));
}();

// The unit square in the z = 0 plane facing +z (u along +x, glTF's v down the image: v = 1 - y),
// with a 2 x 2 normal map of kTilt, under a node scaled by (sx, 1, 1); with `tangent`, its
// TANGENT is (1, 0, 0, 1) (the true one: +u is +x, the map's up is +y).
std::string tiltedSquareGltf(float sx, bool tangent) {
  test::GltfWriter w;
  const int position = w.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
  const int normal = w.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int uv = w.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
  const int indices = w.addIndices({0, 1, 2, 0, 2, 3});
  std::string attributes = "\"POSITION\":" + std::to_string(position) + ",\"NORMAL\":" + std::to_string(normal) +
                           ",\"TEXCOORD_0\":" + std::to_string(uv);
  if (tangent) attributes += ",\"TANGENT\":" + std::to_string(w.addFloats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1}, "VEC4"));
  w.addMesh(attributes, indices, 4, 0);
  w.materials = {"{\"normalTexture\":{\"index\":0}}"};
  w.textures = {"{\"source\":0}"};
  const unsigned char r = encode(kTilt.x), g = encode(kTilt.y), b = encode(kTilt.z);
  const unsigned char pixels[] = {r, g, b, r, g, b, r, g, b, r, g, b};
  w.images = {"{\"uri\":\"" + test::rgbPngDataUri(2, 2, pixels) + "\"}"};
  w.nodes = {"{\"mesh\":0,\"scale\":[" + std::to_string(sx) + ",1,1]}"};
  return w.json(test::BufferStorage::kDataUri);
}

// The shading normal at the square's centre.
Vec3 centreShadingNormal(const Scene& s) {
  const std::array<std::uint32_t, 3> corners{s.indices[0], s.indices[1], s.indices[2]};
  // The centre is the midpoint of the diagonal 0-2 of the first triangle in either winding.
  std::array<float, 3> bary{};
  for (int k = 0; k < 3; ++k) {
    const Vec3 p = s.positions[corners[k]];
    const bool onDiagonal = std::abs(std::abs(p.x) - std::abs(p.y)) < 1e-6f;  // (0,0) or (±1,1)
    bary[k] = onDiagonal ? 0.5f : 0.0f;
  }
  return shadingNormalAt(s, corners, bary, {0, 0, 1});
}

TEST(NormalMaps, LoaderReadsNormalTextureAndMirrorsItWithTheNode) {
  test::GltfDir dir;
  for (const bool tangent : {true, false}) {
    SCOPED_TRACE(tangent ? "TANGENT in the file" : "tangents computed");
    Scene plain, mirrored;
    std::vector<std::string> warnings;
    ASSERT_TRUE(loadGltf(dir.write("plain.gltf", tiltedSquareGltf(1.0f, tangent)), &plain, &warnings).isOk());
    ASSERT_TRUE(loadGltf(dir.write("mirrored.gltf", tiltedSquareGltf(-1.0f, tangent)), &mirrored, &warnings).isOk());
    ASSERT_EQ(plain.normalMaps.size(), 1u);
    ASSERT_EQ(plain.normalMapOf.size(), plain.positions.size());
    for (std::int32_t m : plain.normalMapOf) EXPECT_EQ(m, 0);
    EXPECT_TRUE(checkNormalMaps(plain).isOk());
    EXPECT_TRUE(checkNormalMaps(mirrored).isOk());
    // Texture space +x is +u = +x and +y is up the image = +y: the tilt lands unchanged.
    const Vec3 a = centreShadingNormal(plain);
    EXPECT_NEAR(a.x, kTilt.x, 0.01f);
    EXPECT_NEAR(a.y, kTilt.y, 0.01f);
    EXPECT_NEAR(a.z, kTilt.z, 0.01f);
    // Mirrored in x, the surface's bump must be the mirror image: x negated, y and z kept.
    const Vec3 b = centreShadingNormal(mirrored);
    EXPECT_NEAR(b.x, -kTilt.x, 0.01f);
    EXPECT_NEAR(b.y, kTilt.y, 0.01f);
    EXPECT_NEAR(b.z, kTilt.z, 0.01f);
    bool saidComputed = false;
    for (const std::string& line : warnings) saidComputed = saidComputed || line.find("computed tangents") != std::string::npos;
    EXPECT_EQ(saidComputed, !tangent);
  }
}

TEST(NormalMaps, ComputedTangentsFollowTheTextureCoordinates) {
  // One triangle in the y = 0 plane facing +y; u along +x, v along +z (down the image).
  const std::vector<Vec3> positions{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};
  const std::vector<Vec3> normals(3, Vec3{0, 1, 0});
  const std::vector<std::uint32_t> indices{0, 1, 2};
  const std::vector<std::uint8_t> all(3, 1);
  std::vector<Tangent> t;
  EXPECT_EQ(computeVertexTangents(positions, normals, std::vector<Uv>{{0, 0}, {0, 1}, {1, 0}}, indices, all, &t), 0u);
  for (const Tangent& x : t) {
    EXPECT_NEAR(x.direction.x, 1.0f, 1e-6f);
    // bitangent = up the image = -z = handedness cross(+y, +x) = handedness (-z).
    EXPECT_EQ(x.handedness, 1.0f);
  }
  // u mirrored: the tangent turns to -x, the bitangent stays -z, so the handedness flips.
  EXPECT_EQ(computeVertexTangents(positions, normals, std::vector<Uv>{{1, 0}, {1, 1}, {0, 0}}, indices, all, &t), 0u);
  for (const Tangent& x : t) {
    EXPECT_NEAR(x.direction.x, -1.0f, 1e-6f);
    EXPECT_EQ(x.handedness, -1.0f);
  }
  // All UVs equal: no direction, a fallback orthogonal to the normal, counted.
  EXPECT_EQ(computeVertexTangents(positions, normals, std::vector<Uv>(3, Uv{0.5f, 0.5f}), indices, all, &t), 3u);
  for (const Tangent& x : t) {
    EXPECT_NEAR(dot(x.direction, normals[0]), 0.0f, 1e-6f);
    EXPECT_NEAR(length(x.direction), 1.0f, 1e-6f);
  }
}

TEST(NormalMaps, DecodeAppliesScaleAndFallsBackOnDegenerateInput) {
  NormalMap map;
  ASSERT_TRUE(textureFromUnorm8(1, 1, 3, std::vector<unsigned char>{encode(kTilt.x), encode(kTilt.y), encode(kTilt.z)},
                                &map.texture)
                  .isOk());
  const Vec3 n{0, 1, 0};
  const Tangent t{{1, 0, 0}, 1.0f};  // bitangent cross(+y, +x) = -z
  const Vec3 m = normalMapped(map, {0.5f, 0.5f}, n, t);
  EXPECT_NEAR(m.x, kTilt.x, 0.01f);
  EXPECT_NEAR(m.z, -kTilt.y, 0.01f);
  EXPECT_NEAR(m.y, kTilt.z, 0.01f);
  map.scale = 0.0f;  // glTF: scale 0 flattens the map
  const Vec3 flat = normalMapped(map, {0.5f, 0.5f}, n, t);
  EXPECT_NEAR(flat.y, 1.0f, 1e-6f);
  // A tangent along the normal has no frame: the vertex normal is kept.
  map.scale = 1.0f;
  const Vec3 kept = normalMapped(map, {0.5f, 0.5f}, n, Tangent{{0, 1, 0}, 1.0f});
  EXPECT_EQ(kept.y, 1.0f);
}

TEST(NormalMaps, CheckRejectsInconsistentScenes) {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  s.indices = {0, 2, 1};
  EXPECT_TRUE(checkNormalMaps(s).isOk());
  s.normalMaps.resize(1);
  ASSERT_TRUE(textureFromUnorm8(1, 1, 3, std::vector<unsigned char>{128, 128, 255}, &s.normalMaps[0].texture).isOk());
  s.normalMapOf = {0, 0};
  EXPECT_NE(checkNormalMaps(s).message().find("one per vertex"), std::string::npos);
  s.normalMapOf = {0, 0, 1};
  s.normalMapUv.resize(3);
  s.tangents.resize(3);
  EXPECT_NE(checkNormalMaps(s).message().find("normal map 1"), std::string::npos);
  s.normalMapOf = {0, 0, -1};
  EXPECT_NE(checkNormalMaps(s).message().find("different normal maps"), std::string::npos);
  s.normalMapOf = {0, 0, 0};
  EXPECT_TRUE(checkNormalMaps(s).isOk());
  s.normalMaps[0].texture.rgb.clear();
  EXPECT_NE(checkNormalMaps(s).message().find("no valid texels"), std::string::npos);
}

// ---- a flat quad with a bump map against the bumpy surface itself

// h(x, z) = A sin(k x) sin(k z) over [-1, 1]^2: 4 periods a side, slopes up to A k = 0.3.
constexpr double kWave = 4.0 * kPi;
constexpr double kAmplitude = 0.3 / kWave;
Vec3 bumpNormal(double x, double z) {
  const double hx = kAmplitude * kWave * std::cos(kWave * x) * std::sin(kWave * z);
  const double hz = kAmplitude * kWave * std::sin(kWave * x) * std::cos(kWave * z);
  const double len = std::sqrt(hx * hx + 1.0 + hz * hz);
  return {static_cast<float>(-hx / len), static_cast<float>(1.0 / len), static_cast<float>(-hz / len)};
}

constexpr int kTexels = 64;  // atlas side; the tessellated reference has a vertex at each texel centre
double texelCentre(int i) { return -1.0 + 2.0 * (i + 0.5) / kTexels; }

// The quad [-1, 1]^2 at y = 0 facing +y, uv (0, 0) at (-1, -1), u along +x, v along +z; with
// `mapSide` > 0, a normal map of that side storing bumpNormal in the frame its computed
// tangents give (+x; up the image = -z).
Scene flatQuad(int mapSide) {
  Scene s;
  s.positions = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  s.normals.assign(4, Vec3{0, 1, 0});
  s.albedo.assign(4, Rgb{1, 1, 1});
  s.texcoord[0] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  s.indices = {0, 2, 1, 0, 3, 2};
  if (mapSide > 0) {
    std::vector<unsigned char> bytes;
    for (int y = 0; y < mapSide; ++y) {
      for (int x = 0; x < mapSide; ++x) {
        const Vec3 n = bumpNormal(-1.0 + 2.0 * (x + 0.5) / mapSide, -1.0 + 2.0 * (y + 0.5) / mapSide);
        for (float c : {n.x, -n.z, n.y}) bytes.push_back(encode(c));
      }
    }
    s.normalMaps.resize(1);
    EXPECT_TRUE(textureFromUnorm8(mapSide, mapSide, 3, bytes, &s.normalMaps[0].texture).isOk());
    s.normalMapOf.assign(4, 0);
    s.normalMapUv = s.texcoord[0];
    computeVertexTangents(s.positions, s.normals, s.normalMapUv, s.indices, std::vector<std::uint8_t>(4, 1),
                          &s.tangents);
  }
  return s;
}

// The bumpy surface itself, a vertex at every texel centre with its analytic normal.
Scene tessellatedBumps() {
  Scene s;
  for (int j = 0; j < kTexels; ++j) {
    for (int i = 0; i < kTexels; ++i) {
      const double x = texelCentre(i), z = texelCentre(j);
      s.positions.push_back({static_cast<float>(x),
                             static_cast<float>(kAmplitude * std::sin(kWave * x) * std::sin(kWave * z)),
                             static_cast<float>(z)});
      s.normals.push_back(bumpNormal(x, z));
      s.albedo.push_back({1, 1, 1});
    }
  }
  for (int j = 0; j + 1 < kTexels; ++j) {
    for (int i = 0; i + 1 < kTexels; ++i) {
      const std::uint32_t a = j * kTexels + i, b = a + 1, c = a + kTexels, d = c + 1;
      for (std::uint32_t v : {a, c, b, b, c, d}) s.indices.push_back(v);
    }
  }
  return s;
}

TEST(NormalMaps, FlatNormalMappedQuadLightsLikeTheTessellatedBumpySurface) {
  BakeOptions o;
  o.order = 4;
  o.samples = 4096;
  o.threads = 2;
  o.interreflection = false;
  const int n2 = shCoeffCount(o.order);
  // A disc light of 30 degrees radius, 40 degrees from the zenith.
  std::vector<float> zonal(o.order), light(n2);
  ASSERT_TRUE(zonalCircularLight(o.order, static_cast<float>(30.0 * kPi / 180.0), 1.0f, zonal).isOk());
  const float s40 = std::sin(40.0f * 3.14159265f / 180.0f), c40 = std::cos(40.0f * 3.14159265f / 180.0f);
  ASSERT_TRUE(placeZonal(o.order, zonal, Vec3{s40 * 0.7071068f, c40, s40 * 0.7071068f}, light).isOk());
  auto exit = [&](const float* t) {
    double e = 0.0;
    for (int i = 0; i < n2; ++i) e += double{t[i]} * light[i];
    return e;
  };

  BakeResult reference;
  ASSERT_TRUE(bakeTransfer(tessellatedBumps(), o, &reference).isOk());
  const std::vector<TextureAtlas> atlas{{kTexels, kTexels, 0, 2}};
  TexelBakeOptions texel;
  texel.transfer = o;
  double mappedSq = 0.0, flatSq = 0.0, variationSq = 0.0, mean = 0.0, mappedWorst = 0.0;
  TexelBakeResult mapped, flat;
  const Scene mappedQuad = flatQuad(256), flatOnly = flatQuad(0);
  ASSERT_TRUE(bakeTexelTransfer(mappedQuad, mappedQuad.texcoord[0], atlas, texel, &mapped).isOk());
  ASSERT_TRUE(bakeTexelTransfer(flatOnly, flatOnly.texcoord[0], atlas, texel, &flat).isOk());
  EXPECT_EQ(mapped.normalMappedTexels, static_cast<std::size_t>(kTexels * kTexels));
  EXPECT_EQ(flat.normalMappedTexels, 0u);
  const std::size_t count = static_cast<std::size_t>(kTexels) * kTexels;
  // The shading normals the asset stores (format 1.6, texel normals): a code pair per texel,
  // each decoding to the analytic bump normal at the texel within the 8-bit map's quantisation
  // and its bilinear read; none for the quad without a map.
  ASSERT_EQ(mapped.normals.size(), 2 * count);
  EXPECT_TRUE(flat.normals.empty());
  double worstDegrees = 0.0;
  for (std::size_t t = 0; t < count; ++t) {
    const Vec3 want = bumpNormal(texelCentre(static_cast<int>(t % kTexels)), texelCentre(static_cast<int>(t / kTexels)));
    const Vec3 got = decodeOctahedralNormal(mapped.normals[2 * t], mapped.normals[2 * t + 1]);
    worstDegrees = std::max(worstDegrees, std::acos(std::min(1.0, static_cast<double>(dot(want, got)))) * 180.0 / kPi);
  }
  std::printf("stored texel normals: worst %.3f degrees from the analytic bump normal\n", worstDegrees);
  EXPECT_LT(worstDegrees, 1.0);
  for (std::size_t t = 0; t < count; ++t) mean += exit(&reference.shadowed[t * n2]) / count;
  for (std::size_t t = 0; t < count; ++t) {
    // Texel (x, y) and reference vertex j * kTexels + i sit at the same (x, z).
    const double ref = exit(&reference.shadowed[t * n2]);
    const double m = exit(&mapped.shadowed[t * n2]) - ref, f = exit(&flat.shadowed[t * n2]) - ref;
    mappedSq += m * m;
    flatSq += f * f;
    variationSq += (ref - mean) * (ref - mean);
    mappedWorst = std::max(mappedWorst, std::abs(m));
  }
  const double mappedRms = std::sqrt(mappedSq / count), flatRms = std::sqrt(flatSq / count);
  const double variationRms = std::sqrt(variationSq / count);
  std::printf("normal-mapped quad vs tessellated bumps: rms %.5f (worst %.5f), flat quad rms %.5f, "
              "the bumps' own rms variation %.5f, mean %.5f\n",
              mappedRms, mappedWorst, flatRms, variationRms, mean);
  // The flat quad misses the bumps' shading entirely: its error is their whole variation.
  EXPECT_GT(flatRms, 0.8 * variationRms);
  // The normal map reproduces it, up to the bumps' own self-shadowing and the 8-bit map.
  EXPECT_LT(mappedRms, 0.05 * variationRms);  // measured 0.019
  EXPECT_LT(mappedWorst, 0.02 * mean);  // measured 0.0067
}

}  // namespace
}  // namespace prt::bake
