// The glTF loader on valid files written at test time (gltf_test_files.h): buffers as data
// URIs, external files and .glb; node transforms; winding under mirroring; computed
// normals; albedo from factor, vertex colour and texture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "baker/scene/gltf_loader.h"
#include "warning_lines.h"
#include "gltf_test_files.h"

namespace prt::bake {
namespace {

using test::anyContains;
using test::joined;

using test::BufferStorage;
using test::GltfDir;
using test::GltfWriter;

// Counter-clockwise seen from +z.
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
const std::vector<float> kUpNormals = {0, 0, 1, 0, 0, 1, 0, 0, 1};

Vec3 normalize(Vec3 v) { return v * (1.0f / length(v)); }

Vec3 faceNormal(const Scene& s, std::size_t t) {
  const Vec3 a = s.positions[s.indices[3 * t]], b = s.positions[s.indices[3 * t + 1]],
             c = s.positions[s.indices[3 * t + 2]];
  return normalize(cross(b - a, c - a));
}

void expectVec(Vec3 actual, Vec3 expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expectRgb(Rgb actual, Rgb expected, float tolerance = 1e-4f) {
  EXPECT_NEAR(actual.r, expected.r, tolerance);
  EXPECT_NEAR(actual.g, expected.g, tolerance);
  EXPECT_NEAR(actual.b, expected.b, tolerance);
}

Scene loadOk(const std::string& path, std::vector<std::string>* warnings = nullptr) {
  Scene scene;
  std::vector<std::string> local;
  const Status s = loadGltf(path, &scene, warnings ? warnings : &local);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return scene;
}

// Every triangle's winding agrees with its vertices' normals (front faces counter-clockwise).
void expectWindingMatchesNormals(const Scene& s) {
  for (std::size_t t = 0; t < s.indices.size() / 3; ++t) {
    const Vec3 f = faceNormal(s, t);
    for (int k = 0; k < 3; ++k) EXPECT_GT(dot(f, s.normals[s.indices[3 * t + k]]), 0.5f) << "triangle " << t;
  }
}

GltfWriter triangleWriter(bool withNormals = true) {
  GltfWriter w;
  const int pos = w.addFloats(kTriangle, "VEC3");
  std::string attributes = "\"POSITION\":" + std::to_string(pos);
  if (withNormals) attributes += ",\"NORMAL\":" + std::to_string(w.addFloats(kUpNormals, "VEC3"));
  w.addMesh(attributes, w.addIndices({0, 1, 2}));
  return w;
}

void expectUnitTriangle(const Scene& s) {
  ASSERT_EQ(s.positions.size(), 3u);
  ASSERT_EQ(s.indices.size(), 3u);
  expectVec(s.positions[0], {0, 0, 0}, 0);
  expectVec(s.positions[1], {1, 0, 0}, 0);
  expectVec(s.positions[2], {0, 1, 0}, 0);
  EXPECT_EQ(s.indices, (std::vector<std::uint32_t>{0, 1, 2}));
  for (const Vec3& n : s.normals) expectVec(n, {0, 0, 1});
  // glTF's default material is white, and white stays 1 (no cap: a white furnace returns 1).
  for (const Rgb& a : s.albedo) expectRgb(a, {1, 1, 1}, 0);
}

TEST(GltfLoad, TriangleWithDataUriBuffer) {
  GltfDir dir;
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("tri.gltf", triangleWriter().json(BufferStorage::kDataUri)), &warnings);
  expectUnitTriangle(s);
  EXPECT_EQ(s.name, "tri");
  EXPECT_TRUE(warnings.empty()) << joined(warnings);
}

TEST(GltfLoad, TriangleAsGlb) {
  GltfDir dir;
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("tri.glb", triangleWriter().glb()), &warnings);
  expectUnitTriangle(s);
  EXPECT_TRUE(warnings.empty()) << joined(warnings);
}

TEST(GltfLoad, GlbIsRecognisedByMagicNotName) {
  GltfDir dir;
  expectUnitTriangle(loadOk(dir.write("binary-named.gltf", triangleWriter().glb())));
}

TEST(GltfLoad, TriangleWithExternalBuffer) {
  GltfDir dir;
  const GltfWriter w = triangleWriter();
  dir.write("tri.bin", w.bin());
  expectUnitTriangle(loadOk(dir.write("tri.gltf", w.json(BufferStorage::kExternal, "tri.bin"))));
}

TEST(GltfLoad, SceneNameIsUsedWhenPresent) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.scenes = {"{\"name\":\"Kitchen\",\"nodes\":[0]}"};
  EXPECT_EQ(loadOk(dir.write("tri.gltf", w.json(BufferStorage::kDataUri))).name, "Kitchen");
}

TEST(GltfLoad, NodeTrsComposesDownTheHierarchy) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  // Parent translates by +10 x; child scales by 2 then turns 90° about +z.
  const float h = std::sqrt(0.5f);
  w.nodes = {"{\"children\":[1],\"translation\":[10,0,0]}",
             "{\"mesh\":0,\"scale\":[2,2,2],\"rotation\":[0,0," + std::to_string(h) + "," + std::to_string(h) + "]}"};
  const Scene s = loadOk(dir.write("trs.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), 3u);
  expectVec(s.positions[0], {10, 0, 0});
  expectVec(s.positions[1], {10, 2, 0});  // (1,0,0) → (2,0,0) → (0,2,0) → +10 x
  expectVec(s.positions[2], {8, 0, 0});   // (0,1,0) → (0,2,0) → (-2,0,0) → +10 x
  for (const Vec3& n : s.normals) expectVec(n, {0, 0, 1});
  expectWindingMatchesNormals(s);
}

TEST(GltfLoad, NodeMatrixIsColumnMajorAndNormalsUseInverseTranspose) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  // Non-uniform scale (x × 4) and translation (0, 0, 5), column-major.
  w.nodes = {"{\"mesh\":0,\"matrix\":[4,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]}"};
  // A slanted normal shows the inverse-transpose: (1,0,1) under diag(4,1,1) → (1/4,0,1).
  GltfWriter slanted;
  const int pos = slanted.addFloats(kTriangle, "VEC3");
  const int nrm = slanted.addFloats({1, 0, 1, 1, 0, 1, 1, 0, 1}, "VEC3");
  slanted.addMesh("\"POSITION\":" + std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm));
  slanted.nodes = w.nodes;
  const Scene s = loadOk(dir.write("m.gltf", w.json(BufferStorage::kDataUri)));
  expectVec(s.positions[1], {4, 0, 5});
  expectVec(s.positions[2], {0, 1, 5});
  const Scene t = loadOk(dir.write("n.gltf", slanted.json(BufferStorage::kDataUri)));
  expectVec(t.normals[0], normalize({0.25f, 0, 1}));
}

TEST(GltfLoad, WithoutSceneEveryRootNodeIsLoadedOnce) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.scene = -1;
  w.scenes.clear();
  // Node 1 is node 0's child, so only node 0 and node 2 are roots: three instances in all.
  w.nodes = {"{\"mesh\":0,\"children\":[1]}", "{\"mesh\":0,\"translation\":[5,0,0]}",
             "{\"mesh\":0,\"translation\":[0,5,0]}"};
  const Scene s = loadOk(dir.write("roots.gltf", w.json(BufferStorage::kDataUri)));
  EXPECT_EQ(s.positions.size(), 9u);
  EXPECT_EQ(s.indices.size(), 9u);
}

TEST(GltfLoad, MirroringNodeKeepsCounterClockwiseFrontFaces) {
  GltfDir dir;
  for (bool withNormals : {true, false}) {
    for (const char* scale : {"[-1,1,1]", "[1,1,-1]", "[-2,-3,-4]"}) {
      SCOPED_TRACE(std::string(scale) + (withNormals ? " with NORMAL" : " computed normals"));
      GltfWriter w = triangleWriter(withNormals);
      w.nodes = {std::string("{\"mesh\":0,\"scale\":") + scale + "}"};
      const Scene s = loadOk(dir.write("mirror.gltf", w.json(BufferStorage::kDataUri)));
      ASSERT_EQ(s.indices.size(), 3u);
      expectWindingMatchesNormals(s);
    }
  }
  // The mirrored normal itself: z → -z flips (0,0,1) to (0,0,-1).
  GltfWriter w = triangleWriter(true);
  w.nodes = {"{\"mesh\":0,\"scale\":[1,1,-1]}"};
  const Scene s = loadOk(dir.write("mirror.gltf", w.json(BufferStorage::kDataUri)));
  expectVec(s.normals[0], {0, 0, -1});
  expectVec(faceNormal(s, 0), {0, 0, -1});
}

// A cube with 4 vertices per face (24 in all): computed normals are the face normals.
TEST(GltfLoad, ComputedNormalsOfSplitCubeAreFaceNormals) {
  std::vector<float> pos;
  std::vector<std::uint32_t> idx;
  const Vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<Vec3> faceNormals;
  for (int a = 0; a < 3; ++a) {
    for (float sign : {1.0f, -1.0f}) {
      const Vec3 n = axes[a] * sign;
      const Vec3 u = axes[(a + 1) % 3];
      const Vec3 v = cross(n, u);  // u × v = n: corners below run counter-clockwise about n
      const auto base = static_cast<std::uint32_t>(pos.size() / 3);
      for (const Vec3 c : {n - u - v, n + u - v, n + u + v, n - u + v}) pos.insert(pos.end(), {c.x, c.y, c.z});
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      for (int k = 0; k < 4; ++k) faceNormals.push_back(n);
    }
  }
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(pos, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices(idx, 5123));
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("cube.gltf", w.json(BufferStorage::kDataUri)), &warnings);
  ASSERT_EQ(s.normals.size(), 24u);
  for (std::size_t i = 0; i < 24; ++i) expectVec(s.normals[i], faceNormals[i], 1e-6f);
  expectWindingMatchesNormals(s);
  EXPECT_TRUE(anyContains(warnings, "computed smooth")) << joined(warnings);
}

// A welded sphere (one vertex per pole, no seam): computed normals are close to radial.
TEST(GltfLoad, ComputedNormalsOfWeldedSphereAreRadial) {
  const int segments = 32, rings = 16;
  std::vector<float> pos = {0, 1, 0};  // north pole
  for (int j = 1; j < rings; ++j) {
    const double theta = kPi * j / rings;
    for (int i = 0; i < segments; ++i) {
      const double phi = 2 * kPi * i / segments;
      pos.insert(pos.end(), {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                             static_cast<float>(std::sin(theta) * std::sin(phi))});
    }
  }
  pos.insert(pos.end(), {0, -1, 0});  // south pole
  const auto south = static_cast<std::uint32_t>(pos.size() / 3 - 1);
  auto ring = [&](int j, int i) { return static_cast<std::uint32_t>(1 + (j - 1) * segments + (i % segments)); };
  std::vector<std::uint32_t> idx;
  // Outward winding: (north, next, this) etc. — checked against radial directions below.
  for (int i = 0; i < segments; ++i) idx.insert(idx.end(), {0, ring(1, i + 1), ring(1, i)});
  for (int j = 1; j + 1 < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      idx.insert(idx.end(), {ring(j, i), ring(j, i + 1), ring(j + 1, i + 1)});
      idx.insert(idx.end(), {ring(j, i), ring(j + 1, i + 1), ring(j + 1, i)});
    }
  }
  for (int i = 0; i < segments; ++i) idx.insert(idx.end(), {south, ring(rings - 1, i), ring(rings - 1, i + 1)});

  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(pos, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices(idx));
  w.nodes = {"{\"mesh\":0,\"translation\":[3,0,0]}"};
  const Scene s = loadOk(dir.write("sphere.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), pos.size() / 3);
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const Vec3 radial = normalize(s.positions[v] - Vec3{3, 0, 0});
    EXPECT_GT(dot(s.normals[v], radial), 0.999f) << "vertex " << v;
    EXPECT_NEAR(length(s.normals[v]), 1.0f, 1e-5f);
  }
  expectWindingMatchesNormals(s);
}

TEST(GltfLoad, StripsAndFansBecomeCounterClockwiseTriangles) {
  GltfDir dir;
  // Strip v0 v1 v2 v3 and fan v0 v1 v2 v3 over the unit square in z = 0, seen from +z.
  const std::vector<float> strip = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const std::vector<float> fan = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  for (int mode : {5, 6}) {
    SCOPED_TRACE(mode == 5 ? "TRIANGLE_STRIP" : "TRIANGLE_FAN");
    GltfWriter w;
    const int p = w.addFloats(mode == 5 ? strip : fan, "VEC3");
    w.addMesh("\"POSITION\":" + std::to_string(p), -1, mode);
    const Scene s = loadOk(dir.write("strip.gltf", w.json(BufferStorage::kDataUri)));
    ASSERT_EQ(s.indices.size(), 6u);
    for (std::size_t t = 0; t < 2; ++t) expectVec(faceNormal(s, t), {0, 0, 1});
    for (const Vec3& n : s.normals) expectVec(n, {0, 0, 1});
  }
}

TEST(GltfLoad, IndexedStripUsesItsIndices) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 9, 9, 9}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 1, 2, 3}, 5121), 5);
  const Scene s = loadOk(dir.write("strip.gltf", w.json(BufferStorage::kDataUri)));
  EXPECT_EQ(s.indices.size(), 6u);
  EXPECT_EQ(s.positions.size(), 4u);  // vertex 4 is unused and removed
}

TEST(GltfLoad, ByteAndShortIndicesAndNonIndexedPrimitives) {
  GltfDir dir;
  for (int type : {5121, 5123, 5125, 0}) {
    SCOPED_TRACE(type);
    GltfWriter w;
    const int p = w.addFloats(kTriangle, "VEC3");
    w.addMesh("\"POSITION\":" + std::to_string(p), type ? w.addIndices({0, 1, 2}, type) : -1);
    const Scene s = loadOk(dir.write("t.gltf", w.json(BufferStorage::kDataUri)));
    EXPECT_EQ(s.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    expectVec(s.normals[0], {0, 0, 1});
  }
}

TEST(GltfLoad, InterleavedAttributesHonourByteStride) {
  GltfDir dir;
  GltfWriter w;
  // position xyz + normal xyz + 4 bytes of padding per vertex: stride 28.
  std::vector<float> interleaved;
  for (int v = 0; v < 3; ++v) {
    interleaved.insert(interleaved.end(), {kTriangle[3 * v], kTriangle[3 * v + 1], kTriangle[3 * v + 2], 0, 0, 1, -1});
  }
  const int view = w.addView(interleaved.data(), interleaved.size() * sizeof(float), 28);
  const int p = w.addAccessor(view, 5126, 3, "VEC3");
  const int n = w.addAccessor(view, 5126, 3, "VEC3", false, ",\"byteOffset\":12");
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(n));
  expectUnitTriangle(loadOk(dir.write("stride.gltf", w.json(BufferStorage::kDataUri))));
}

TEST(GltfLoad, SparseAccessorsReplaceElements) {
  GltfDir dir;
  GltfWriter w;
  // Dense data with vertex 1 wrong; the sparse part puts it at (1, 0, 0).
  const std::vector<float> dense = {0, 0, 0, 7, 7, 7, 0, 1, 0};
  const std::vector<std::uint32_t> sparseIndex = {1};
  const std::vector<float> sparseValue = {1, 0, 0};
  const int denseView = w.addView(dense.data(), dense.size() * 4);
  const int indexView = w.addView(sparseIndex.data(), 4);
  const int valueView = w.addView(sparseValue.data(), 12);
  const std::string sparse = ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(indexView) +
                             ",\"componentType\":5125},\"values\":{\"bufferView\":" + std::to_string(valueView) + "}}";
  const int p = w.addAccessor(denseView, 5126, 3, "VEC3", false, sparse);
  w.addMesh("\"POSITION\":" + std::to_string(p));
  const Scene s = loadOk(dir.write("sparse.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), 3u);
  expectVec(s.positions[1], {1, 0, 0}, 0);

  // Without a bufferView the dense part is zeros (glTF 2.0 §3.6.2.3).
  GltfWriter z;
  const std::vector<std::uint32_t> two = {1, 2};
  const std::vector<float> values = {1, 0, 0, 0, 1, 0};
  const int iv = z.addView(two.data(), 8);
  const int vv = z.addView(values.data(), 24);
  z.accessors.push_back(
      "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"sparse\":{\"count\":2,\"indices\":{\"bufferView\":" +
      std::to_string(iv) + ",\"componentType\":5125},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}}");
  z.addMesh("\"POSITION\":0");
  expectVec(loadOk(dir.write("zeros.gltf", z.json(BufferStorage::kDataUri))).positions[2], {0, 1, 0}, 0);
}

TEST(GltfLoad, NormalizedIntegerAttributes) {
  GltfDir dir;
  GltfWriter w;
  // Positions as normalised shorts (KHR_mesh_quantization style): 32767 → 1.
  const std::vector<std::int16_t> pos = {0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0};
  const int p = w.addAccessor(w.addView(pos.data(), pos.size() * 2, 8), 5122, 3, "VEC3", true);
  // COLOR_0 as normalised unsigned bytes, VEC4 (alpha ignored).
  const std::vector<std::uint8_t> rgba = {255, 0, 51, 255, 102, 255, 0, 0, 0, 0, 255, 255};
  const int c = w.addAccessor(w.addView(rgba.data(), rgba.size()), 5121, 3, "VEC4", true);
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"COLOR_0\":" + std::to_string(c));
  w.extensionsRequired = {"\"KHR_mesh_quantization\""};
  const Scene s = loadOk(dir.write("quantized.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), 3u);
  expectVec(s.positions[1], {1, 0, 0}, 0);
  expectVec(s.positions[2], {0, 1, 0}, 0);
  expectRgb(s.albedo[0], {1.0f, 0, 0.2f});
  expectRgb(s.albedo[1], {0.4f, 1.0f, 0});
  expectRgb(s.albedo[2], {0, 0, 1.0f});
}

TEST(GltfLoad, AlbedoIsBaseColorFactorTimesVertexColourClamped) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  const int c = w.addFloats({0.5f, 1, 0.2f, 1, 2, 2, 2, 1, -1, 0.5f, 0, 1}, "VEC4");
  w.materials = {"{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1]}}"};
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"COLOR_0\":" + std::to_string(c), -1, 4, 0);
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("colour.gltf", w.json(BufferStorage::kDataUri)), &warnings);
  expectRgb(s.albedo[0], {0.25f, 0.25f, 0.2f});
  expectRgb(s.albedo[1], {1, 0.5f, 1});   // 0.5 x 2 = 1 stays, 1 x 2 is brought into [0, 1]
  expectRgb(s.albedo[2], {0, 0.125f, 0});  // and from -0.5
  for (const Rgb& a : s.albedo) {
    for (float ch : {a.r, a.g, a.b}) {
      EXPECT_GE(ch, 0.0f);
      EXPECT_LE(ch, 1.0f);
    }
  }
  // Not silently: the warning counts the two values it changed (2 and -0.5).
  EXPECT_TRUE(anyContains(warnings, "2 albedo channel values lie outside glTF's [0, 1]")) << joined(warnings);
}

constexpr float kGrey128 = 0.2158605f;  // sRGB 128/255 in linear

// A triangle with the given uvs and a textured material (sampler and extensions optional).
std::string texturedTriangle(const std::vector<float>& uvs, const std::string& sampler,
                             const std::string& textureInfoExtra = "") {
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  const int t = w.addFloats(uvs, "VEC2");
  w.images = {"{\"uri\":\"" + test::twoByTwoPngDataUri() + "\"}"};
  w.textures = {sampler.empty() ? "{\"source\":0}" : "{\"source\":0,\"sampler\":0}"};
  if (!sampler.empty()) w.samplers = {sampler};
  w.materials = {"{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0" + textureInfoExtra + "}}}"};
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"TEXCOORD_0\":" + std::to_string(t), -1, 4, 0);
  return w.json(BufferStorage::kDataUri);
}

TEST(GltfLoad, BaseColorTextureIsSampledAtTexelCentresInLinear) {
  GltfDir dir;
  std::vector<std::string> warnings;
  const Scene s =
      loadOk(dir.write("tex.gltf", texturedTriangle({0.25f, 0.25f, 0.75f, 0.25f, 0.25f, 0.75f}, "")), &warnings);
  EXPECT_FALSE(anyContains(warnings, "image") || anyContains(warnings, "texture")) << joined(warnings);
  expectRgb(s.albedo[0], {kGrey128, kGrey128, kGrey128});
  expectRgb(s.albedo[1], {1.0f, 0, 0});
  expectRgb(s.albedo[2], {0, 1.0f, 0});
  // Half way between the grey and the red texel: the average of linear values.
  const Scene mid = loadOk(dir.write("mid.gltf", texturedTriangle({0.5f, 0.25f, 0.5f, 0.25f, 0.5f, 0.25f}, "")));
  expectRgb(mid.albedo[0], {(kGrey128 + 1) / 2, kGrey128 / 2, kGrey128 / 2});
}

TEST(GltfLoad, SamplerWrapModesAreHonoured) {
  GltfDir dir;
  // u = -0.25 and u = 1.75 on the top row.
  const std::vector<float> uvs = {-0.25f, 0.25f, 1.75f, 0.25f, 0.25f, 0.75f};
  const Rgb grey{kGrey128, kGrey128, kGrey128}, red{1.0f, 0, 0};
  struct Case {
    const char* sampler;
    Rgb first, second;
  };
  const Case cases[] = {
      {"{\"wrapS\":10497,\"wrapT\":10497}", red, red},    // REPEAT: 0.75, 0.75
      {"{\"wrapS\":33071,\"wrapT\":10497}", grey, red},   // CLAMP_TO_EDGE: left, right edge
      {"{\"wrapS\":33648,\"wrapT\":10497}", grey, grey},  // MIRRORED_REPEAT: 0.25, 0.25
      {"{}", red, red},                                   // default REPEAT
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.sampler);
    const Scene s = loadOk(dir.write("wrap.gltf", texturedTriangle(uvs, c.sampler)));
    expectRgb(s.albedo[0], c.first);
    expectRgb(s.albedo[1], c.second);
  }
}

TEST(GltfLoad, TextureTransformExtensionMovesUvs) {
  GltfDir dir;
  const std::string transform = ",\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0]}}";
  const Scene s =
      loadOk(dir.write("xf.gltf", texturedTriangle({0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f}, "", transform)));
  expectRgb(s.albedo[0], {1.0f, 0, 0});  // (0.25, 0.25) + (0.5, 0) is the red texel
}

TEST(GltfLoad, UndecodableTextureIsIgnoredWithAWarning) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  const int t = w.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
  w.images = {"{\"uri\":\"data:image/png;base64,AAAAAAAAAAAAAAAA\"}"};
  w.textures = {"{\"source\":0}"};
  w.materials = {"{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1],\"baseColorTexture\":{\"index\":0}}}"};
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"TEXCOORD_0\":" + std::to_string(t), -1, 4, 0);
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("badtex.gltf", w.json(BufferStorage::kDataUri)), &warnings);
  expectRgb(s.albedo[0], {0.5f, 0.5f, 0.5f});
  EXPECT_TRUE(anyContains(warnings, "image 0")) << joined(warnings);
}

TEST(GltfLoad, UnreferencedVerticesAreRemoved) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats({0, 0, 0, 5, 5, 5, 1, 0, 0, 0, 1, 0}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 2, 3}));
  std::vector<std::string> warnings;
  const Scene s = loadOk(dir.write("unused.gltf", w.json(BufferStorage::kDataUri)), &warnings);
  expectUnitTriangle(s);
  EXPECT_TRUE(anyContains(warnings, "removed 1 vertex")) << joined(warnings);
}

TEST(GltfLoad, EveryMeshInstanceIsFlattened) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.scenes = {"{\"nodes\":[0,1]}"};
  w.nodes = {"{\"mesh\":0}", "{\"mesh\":0,\"translation\":[0,0,-1]}"};
  const Scene s = loadOk(dir.write("two.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), 6u);
  EXPECT_EQ(s.indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
  expectVec(s.positions[3], {0, 0, -1});
}

}  // namespace
}  // namespace prt::bake
