// The glTF loader on a corpus of malformed and unsupported files, written at test time:
// each must give an error whose message names the problem (or, for recoverable content, a
// scene and a warning) and never read out of bounds (the sanitizer build runs these too).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

using test::kTriangle;
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// Loading `path` fails with a message containing `fragment` and the file name, and leaves
// the scene empty.
void expectLoadError(const std::string& path, const std::string& fragment,
                     StatusCode code = StatusCode::kInvalidArgument) {
  Scene scene;
  scene.name = "stale";
  scene.positions.push_back({1, 2, 3});
  std::vector<std::string> warnings;
  const Status s = loadGltf(path, &scene, &warnings);
  ASSERT_FALSE(s.isOk()) << "loaded " << path;
  EXPECT_EQ(s.code(), code) << s.toString();
  EXPECT_NE(s.message().find(fragment), std::string::npos)
      << "message '" << s.message() << "' lacks '" << fragment << "'";
  EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
  EXPECT_TRUE(scene.positions.empty() && scene.indices.empty() && scene.name.empty());
}

Scene expectLoadWithWarning(const std::string& path, const std::string& fragment) {
  Scene scene;
  std::vector<std::string> warnings;
  const Status s = loadGltf(path, &scene, &warnings);
  EXPECT_TRUE(s.isOk()) << s.toString();
  EXPECT_TRUE(anyContains(warnings, fragment)) << "no warning with '" << fragment << "' in:" << joined(warnings);
  return scene;
}

GltfWriter triangleWriter() {
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 1, 2}));
  return w;
}

TEST(GltfMalformed, MissingFile) {
  GltfDir dir;
  expectLoadError(dir.path("nowhere.gltf"), "no such file", StatusCode::kNotFound);
}

TEST(GltfMalformed, EmptyFile) {
  GltfDir dir;
  expectLoadError(dir.write("empty.gltf", std::string()), "empty");
}

TEST(GltfMalformed, NotJson) {
  GltfDir dir;
  expectLoadError(dir.write("text.gltf", std::string("this is not json at all")), "JSON");
  expectLoadError(dir.write("broken.gltf", std::string("{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [")),
                  "glTF parser");
  expectLoadError(dir.write("array.gltf", std::string("[1, 2, 3]")), "JSON");
}

TEST(GltfMalformed, MissingAssetVersion) {
  GltfDir dir;
  expectLoadError(dir.write("noasset.gltf", std::string("{\"meshes\":[]}")), "asset");
}

TEST(GltfMalformed, TruncatedGlb) {
  GltfDir dir;
  const std::vector<std::uint8_t> glb = triangleWriter().glb();
  // Cut inside the header, inside the JSON chunk, inside the BIN chunk header and payload.
  for (std::size_t keep :
       {std::size_t{9}, std::size_t{40}, glb.size() - triangleWriter().bin().size() - 4, glb.size() - 3}) {
    SCOPED_TRACE(keep);
    expectLoadError(
        dir.write("cut.glb", std::vector<std::uint8_t>(glb.begin(), glb.begin() + static_cast<std::ptrdiff_t>(keep))),
        "truncated");
  }
}

TEST(GltfMalformed, GlbWithBadMagic) {
  GltfDir dir;
  std::vector<std::uint8_t> glb = triangleWriter().glb();
  glb[3] = 'X';
  expectLoadError(dir.write("magic.glb", glb), "magic");
}

TEST(GltfMalformed, GlbWithWrongVersionOrChunkLength) {
  GltfDir dir;
  std::vector<std::uint8_t> glb = triangleWriter().glb();
  std::vector<std::uint8_t> v1 = glb;
  v1[4] = 1;
  expectLoadError(dir.write("v1.glb", v1), "version 1");
  // The BIN chunk claims 4 bytes more than the file holds (tinygltf alone would read 8
  // bytes past the end here).
  std::vector<std::uint8_t> longBin = glb;
  const std::size_t binHeader = glb.size() - triangleWriter().bin().size() - 8;
  longBin[binHeader] = static_cast<std::uint8_t>(longBin[binHeader] + 4);
  expectLoadError(dir.write("longbin.glb", longBin), "truncated");
}

TEST(GltfMalformed, MissingExternalBufferNamesTheUri) {
  GltfDir dir;
  expectLoadError(dir.write("nobin.gltf", triangleWriter().json(BufferStorage::kExternal, "missing-buffer.bin")),
                  "missing-buffer.bin");
}

TEST(GltfMalformed, ExternalBufferShorterThanDeclared) {
  GltfDir dir;
  const GltfWriter w = triangleWriter();
  std::vector<std::uint8_t> bin = w.bin();
  bin.resize(bin.size() - 8);
  dir.write("short.bin", bin);
  expectLoadError(dir.write("short.gltf", w.json(BufferStorage::kExternal, "short.bin")), "short.bin");
}

TEST(GltfMalformed, AccessorPastTheEndOfItsBufferView) {
  GltfDir dir;
  GltfWriter w;
  const int view = w.addView(kTriangle.data(), kTriangle.size() * 4);
  const int p = w.addAccessor(view, 5126, 4, "VEC3");  // 4 vertices, data for 3
  w.addMesh("\"POSITION\":" + std::to_string(p));
  expectLoadError(dir.write("past.gltf", w.json(BufferStorage::kDataUri)), "past the end");

  GltfWriter offset;
  const int v2 = offset.addView(kTriangle.data(), kTriangle.size() * 4);
  offset.addAccessor(v2, 5126, 3, "VEC3", false, ",\"byteOffset\":4");
  offset.addMesh("\"POSITION\":0");
  expectLoadError(dir.write("offset.gltf", offset.json(BufferStorage::kDataUri)), "past the end");

  // A huge byteOffset must not wrap around.
  GltfWriter huge;
  const int v3 = huge.addView(kTriangle.data(), kTriangle.size() * 4);
  huge.addAccessor(v3, 5126, 3, "VEC3", false, ",\"byteOffset\":18446744073709551600");
  huge.addMesh("\"POSITION\":0");
  expectLoadError(dir.write("huge.gltf", huge.json(BufferStorage::kDataUri)), "past the end");
}

TEST(GltfMalformed, BufferViewPastTheEndOfItsBuffer) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.bufferViews[0] = "{\"buffer\":0,\"byteOffset\":20,\"byteLength\":36}";  // the buffer has 48 bytes
  expectLoadError(dir.write("view.gltf", w.json(BufferStorage::kDataUri)), "past the end of buffer");
}

TEST(GltfMalformed, StrideSmallerThanElement) {
  GltfDir dir;
  GltfWriter w;
  const int view = w.addView(kTriangle.data(), kTriangle.size() * 4, 8);
  w.addAccessor(view, 5126, 3, "VEC3");
  w.addMesh("\"POSITION\":0");
  expectLoadError(dir.write("stride.gltf", w.json(BufferStorage::kDataUri)), "byteStride 8");
}

TEST(GltfMalformed, IndexOutOfRange) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 1, 7}, 5123));
  expectLoadError(dir.write("index.gltf", w.json(BufferStorage::kDataUri)), "out of range");
}

TEST(GltfMalformed, IndicesOfWrongType) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  const int i = w.addFloats({0, 1, 2}, "SCALAR");  // float indices
  w.addMesh("\"POSITION\":" + std::to_string(p), i);
  expectLoadError(dir.write("floatidx.gltf", w.json(BufferStorage::kDataUri)), "indices");
}

TEST(GltfMalformed, AttributeCountsDisagree) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  const int n = w.addFloats({0, 0, 1, 0, 0, 1}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p) + ",\"NORMAL\":" + std::to_string(n));
  expectLoadError(dir.write("counts.gltf", w.json(BufferStorage::kDataUri)), "NORMAL");
}

TEST(GltfMalformed, PositionOfWrongType) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats({0, 0, 1, 0, 0, 1}, "VEC2");
  w.addMesh("\"POSITION\":" + std::to_string(p));
  expectLoadError(dir.write("vec2.gltf", w.json(BufferStorage::kDataUri)), "POSITION");
}

TEST(GltfMalformed, SparseIndexOutOfRange) {
  GltfDir dir;
  GltfWriter w;
  const std::vector<std::uint32_t> index = {9};
  const std::vector<float> value = {1, 0, 0};
  const int dense = w.addView(kTriangle.data(), 36);
  const int iv = w.addView(index.data(), 4);
  const int vv = w.addView(value.data(), 12);
  w.addAccessor(dense, 5126, 3, "VEC3", false,
                ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":" + std::to_string(iv) +
                    ",\"componentType\":5125},\"values\":{\"bufferView\":" + std::to_string(vv) + "}}");
  w.addMesh("\"POSITION\":0");
  expectLoadError(dir.write("sparse.gltf", w.json(BufferStorage::kDataUri)), "sparse index 9");
}

TEST(GltfMalformed, PointsOnlyMeshIsAnError) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), -1, 0);
  expectLoadError(dir.write("points.gltf", w.json(BufferStorage::kDataUri)), "POINTS");
}

TEST(GltfMalformed, PointsAndLinesBesideTrianglesAreSkippedWithWarnings) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.addMesh("\"POSITION\":0", -1, 0);  // POINTS
  w.addMesh("\"POSITION\":0", -1, 3);  // LINE_STRIP
  w.scenes = {"{\"nodes\":[0,1,2]}"};
  w.nodes = {"{\"mesh\":0}", "{\"mesh\":1}", "{\"mesh\":2}"};
  const std::string path = dir.write("mixed.gltf", w.json(BufferStorage::kDataUri));
  const Scene s = expectLoadWithWarning(path, "POINTS");
  EXPECT_EQ(s.indices.size(), 3u);
  expectLoadWithWarning(path, "LINES");
}

TEST(GltfMalformed, UnknownPrimitiveMode) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), -1, 9);
  expectLoadError(dir.write("mode.gltf", w.json(BufferStorage::kDataUri)), "mode 9");
}

TEST(GltfMalformed, DracoRequiredIsRejectedByName) {
  GltfDir dir;
  // As Draco files are: accessors without bufferViews, geometry in the extension.
  GltfWriter w;
  w.extensionsRequired = {"\"KHR_draco_mesh_compression\""};
  w.addView(kTriangle.data(), 36);
  w.accessors = {"{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}",
                 "{\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}"};
  w.meshes = {
      "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"extensions\":{\"KHR_draco_mesh_compression\":"
      "{\"bufferView\":0,\"attributes\":{\"POSITION\":0}}}}]}"};
  expectLoadError(dir.write("draco.gltf", w.json(BufferStorage::kDataUri)), "KHR_draco_mesh_compression");
  // Required even though an uncompressed copy is present: still rejected, by name.
  GltfWriter fallback = triangleWriter();
  fallback.extensionsRequired = {"\"KHR_draco_mesh_compression\""};
  expectLoadError(dir.write("draco2.glb", fallback.glb()), "KHR_draco_mesh_compression");
  // Used but not required, with no uncompressed data: also an error naming it.
  GltfWriter optional = w;
  optional.extensionsRequired.clear();
  optional.accessors = {"{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}"};
  optional.meshes = {
      "{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"extensions\":{\"KHR_draco_mesh_compression\":"
      "{\"bufferView\":0,\"attributes\":{\"POSITION\":0}}}}]}"};
  expectLoadError(dir.write("draco3.gltf", optional.json(BufferStorage::kDataUri)), "KHR_draco_mesh_compression");
}

TEST(GltfMalformed, OtherRequiredExtensionIsNamed) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.extensionsRequired = {"\"EXT_made_up_extension\""};
  expectLoadError(dir.write("ext.gltf", w.json(BufferStorage::kDataUri)), "EXT_made_up_extension");
}

TEST(GltfMalformed, NanPositionsDropTheirTrianglesWithAWarning) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, kNan, 0, 0}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 1, 2, 0, 3, 2}));
  const Scene s = expectLoadWithWarning(dir.write("nan.gltf", w.json(BufferStorage::kDataUri)), "non-finite");
  EXPECT_EQ(s.indices.size(), 3u);
  EXPECT_EQ(s.positions.size(), 3u);
  for (const Vec3& p3 : s.positions) EXPECT_TRUE(isFinite(p3));
}

TEST(GltfMalformed, ZeroAreaTrianglesAreDroppedWithAWarning) {
  GltfDir dir;
  GltfWriter w;
  // Triangle 2 repeats an index; triangle 3 is collinear.
  const int p = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), w.addIndices({0, 1, 2, 0, 1, 1, 0, 1, 3}));
  const Scene s =
      expectLoadWithWarning(dir.write("zero.gltf", w.json(BufferStorage::kDataUri)), "2 zero-area triangles");
  EXPECT_EQ(s.indices.size(), 3u);
}

TEST(GltfMalformed, OnlyDegenerateTrianglesIsAnError) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats({0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p));
  expectLoadError(dir.write("line.gltf", w.json(BufferStorage::kDataUri)), "zero area");
}

TEST(GltfMalformed, EmptySceneHasNoTriangles) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  w.scenes = {"{\"nodes\":[]}"};
  expectLoadError(dir.write("emptyscene.gltf", w.json(BufferStorage::kDataUri)), "no triangles");
  GltfWriter nothing;
  nothing.nodes.clear();
  nothing.scenes.clear();
  nothing.scene = -1;
  expectLoadError(dir.write("nothing.gltf", nothing.json(BufferStorage::kDataUri)), "no triangles");
}

TEST(GltfMalformed, BadNodeReferences) {
  GltfDir dir;
  GltfWriter cycle = triangleWriter();
  cycle.nodes = {"{\"mesh\":0,\"children\":[1]}", "{\"children\":[0]}"};
  expectLoadError(dir.write("cycle.gltf", cycle.json(BufferStorage::kDataUri)), "reached twice");
  GltfWriter noMesh = triangleWriter();
  noMesh.nodes = {"{\"mesh\":4}"};
  expectLoadError(dir.write("nomesh.gltf", noMesh.json(BufferStorage::kDataUri)), "mesh 4");
  GltfWriter noChild = triangleWriter();
  noChild.nodes = {"{\"mesh\":0,\"children\":[12]}"};
  expectLoadError(dir.write("nochild.gltf", noChild.json(BufferStorage::kDataUri)), "node 12");
  GltfWriter badMatrix = triangleWriter();
  badMatrix.nodes = {"{\"mesh\":0,\"matrix\":[1,0,0]}"};
  expectLoadError(dir.write("matrix.gltf", badMatrix.json(BufferStorage::kDataUri)), "matrix");
  GltfWriter badScene = triangleWriter();
  badScene.scene = 3;
  expectLoadError(dir.write("scene.gltf", badScene.json(BufferStorage::kDataUri)), "scene 3");
}

TEST(GltfMalformed, TooManyVerticesIsRejectedBeforeReading) {
  GltfDir dir;
  GltfWriter w;
  const int view = w.addView(kTriangle.data(), 36);
  w.addAccessor(view, 5126, kMaxSceneVertices + 1, "VEC3");
  w.addMesh("\"POSITION\":0");
  expectLoadError(dir.write("big.gltf", w.json(BufferStorage::kDataUri)), "limit");
}

TEST(GltfMalformed, MissingMaterialOrTexture) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(p), -1, 4, 2);
  expectLoadError(dir.write("mat.gltf", w.json(BufferStorage::kDataUri)), "material 2");
  GltfWriter t;
  const int q = t.addFloats(kTriangle, "VEC3");
  t.materials = {"{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":5}}}"};
  t.addMesh("\"POSITION\":" + std::to_string(q), -1, 4, 0);
  expectLoadError(dir.write("tex.gltf", t.json(BufferStorage::kDataUri)), "texture 5");
}

TEST(GltfMalformed, MissingTexCoordIgnoresTextureWithAWarning) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  w.images = {"{\"uri\":\"" + test::twoByTwoPngDataUri() + "\"}"};
  w.textures = {"{\"source\":0}"};
  w.materials = {
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1],\"baseColorTexture\":{\"index\":0,\"texCoord\":1}"
      "}}"};
  w.addMesh("\"POSITION\":" + std::to_string(p), -1, 4, 0);
  const Scene s = expectLoadWithWarning(dir.write("nouv.gltf", w.json(BufferStorage::kDataUri)), "TEXCOORD_1");
  ASSERT_FALSE(s.albedo.empty());
  EXPECT_FLOAT_EQ(s.albedo[0].g, 0.5f);
}

TEST(GltfMalformed, GlbImageBufferViewPastTheBuffer) {
  GltfDir dir;
  GltfWriter w = triangleWriter();
  // bufferView 2 claims 4 KiB of a 48-byte buffer: tinygltf passes it to the image decoder
  // unchecked, so the loader's decoder must catch it.
  w.bufferViews.push_back("{\"buffer\":0,\"byteOffset\":0,\"byteLength\":4096}");
  w.images = {"{\"bufferView\":2,\"mimeType\":\"image/png\"}"};
  expectLoadError(dir.write("img.glb", w.glb()), "image 0");
}

TEST(GltfMalformed, DirectoryInsteadOfFile) {
  GltfDir dir;
  expectLoadError(dir.path(""), "regular file");
}

}  // namespace
}  // namespace prt::bake
