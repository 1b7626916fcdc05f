// TEXCOORD_0/1 as the glTF loader reads them for the atlas choice (scene.h): accessor types
// per glTF 2.0 (float, normalised unsigned byte/short; more with KHR_mesh_quantization), a set
// missing from one primitive dropped with the reason; and the atlas check over the
// assimp-testmodels glTF 2.0 corpus without a crash (docs/transfer-textures.md lists the results).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "baker/scene/gltf_loader.h"
#include "baker/scene/uv_atlas_choice.h"
#include "gltf_test_files.h"
#include "warning_lines.h"

namespace prt::bake {
namespace {

using test::BufferStorage;
using test::GltfDir;
using test::GltfWriter;

using test::kTriangle;

// A triangle whose TEXCOORD_0 is normalised unsigned short and TEXCOORD_1 float.
GltfWriter texturedTriangle(int uv1ComponentType = 5126, bool uv1Normalized = false) {
  GltfWriter w;
  const int pos = w.addFloats(kTriangle, "VEC3");
  const std::uint16_t uv0[6] = {0, 0, 65535, 0, 0, 32768};
  const int t0 = w.addAccessor(w.addView(uv0, sizeof uv0), 5123, 3, "VEC2", true);
  int t1 = -1;
  if (uv1ComponentType == 5126) {
    t1 = w.addFloats({0.25f, 0.5f, 0.75f, 0.5f, 0.25f, 1.0f}, "VEC2");
  } else {
    const std::uint16_t raw[6] = {0, 0, 1, 0, 0, 1};
    t1 = w.addAccessor(w.addView(raw, sizeof raw), uv1ComponentType, 3, "VEC2", uv1Normalized);
  }
  w.addMesh("\"POSITION\":" + std::to_string(pos) + ",\"TEXCOORD_0\":" + std::to_string(t0) +
                ",\"TEXCOORD_1\":" + std::to_string(t1),
            w.addIndices({0, 1, 2}));
  return w;
}

Scene load(const std::string& path) {
  Scene scene;
  const Status s = loadGltf(path, &scene, nullptr);
  EXPECT_TRUE(s.isOk()) << s.message();
  return scene;
}

TEST(GltfTexcoords, BothSetsAreRead) {
  GltfDir dir;
  const Scene s = load(dir.write("uv.gltf", texturedTriangle().json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.texcoord[0].size(), 3u);
  ASSERT_EQ(s.texcoord[1].size(), 3u);
  EXPECT_TRUE(s.texcoordAbsent[0].empty()) << s.texcoordAbsent[0];
  EXPECT_FLOAT_EQ(s.texcoord[0][1].u, 1.0f);
  EXPECT_NEAR(s.texcoord[0][2].v, 32768.0f / 65535.0f, 1e-7);
  EXPECT_FLOAT_EQ(s.texcoord[1][2].u, 0.25f);
  EXPECT_FLOAT_EQ(s.texcoord[1][2].v, 1.0f);
}

TEST(GltfTexcoords, TypeGltfForbidsIsDroppedWithTheReason) {
  GltfDir dir;
  // Unnormalised unsigned short needs KHR_mesh_quantization.
  const Scene s = load(dir.write("uv.gltf", texturedTriangle(5123, false).json(BufferStorage::kDataUri)));
  EXPECT_EQ(s.texcoord[0].size(), 3u);
  EXPECT_TRUE(s.texcoord[1].empty());
  EXPECT_NE(s.texcoordAbsent[1].find("component type 5123"), std::string::npos) << s.texcoordAbsent[1];
  EXPECT_NE(s.texcoordAbsent[1].find("mesh 0 primitive 0"), std::string::npos) << s.texcoordAbsent[1];

  GltfWriter quantized = texturedTriangle(5123, false);
  quantized.extensionsRequired = {"\"KHR_mesh_quantization\""};
  const Scene q = load(dir.write("q.gltf", quantized.json(BufferStorage::kDataUri)));
  ASSERT_EQ(q.texcoord[1].size(), 3u) << q.texcoordAbsent[1];
  EXPECT_FLOAT_EQ(q.texcoord[1][1].u, 1.0f);
}

TEST(GltfTexcoords, SetMissingFromOnePrimitiveIsDropped) {
  GltfDir dir;
  GltfWriter w = texturedTriangle();
  const int pos = w.addFloats({0, 0, 1, 1, 0, 1, 0, 1, 1}, "VEC3");
  w.addMesh("\"POSITION\":" + std::to_string(pos));
  w.nodes = {"{\"mesh\":0}", "{\"mesh\":1}"};
  w.scenes = {"{\"nodes\":[0,1]}"};
  const Scene s = load(dir.write("two.gltf", w.json(BufferStorage::kDataUri)));
  ASSERT_EQ(s.positions.size(), 6u);
  for (int set = 0; set < 2; ++set) {
    EXPECT_TRUE(s.texcoord[set].empty());
    EXPECT_NE(s.texcoordAbsent[set].find("mesh 1 primitive 0: no TEXCOORD_" + std::to_string(set)), std::string::npos)
        << s.texcoordAbsent[set];
  }
}

// Every glTF 2.0 file of assimp-testmodels that loads goes through the choice; the line per
// file is what docs/transfer-textures.md records.
TEST(GltfTexcoords, CorpusRunsThroughTheAtlasCheck) {
  std::vector<std::string> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(std::string(PRT_ASSIMP_MODELS_DIR) + "/glTF2", ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::string ext = it->path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(it->path().string());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 40u) << "assimp-testmodels not found";
  int checked = 0, withUvs = 0, valid = 0;
  for (const std::string& path : files) {
    Scene scene;
    if (!loadGltf(path, &scene, nullptr).isOk()) continue;
    ++checked;
    if (!scene.texcoord[0].empty() || !scene.texcoord[1].empty()) ++withUvs;
    UvAtlasChoice choice;
    const Status s = chooseUvAtlas(scene, {1024, 1024, 2}, &choice);
    ASSERT_TRUE(s.isOk()) << path << ": " << s.message();
    ASSERT_EQ(choice.rejected.size(), choice.texcoord == 1 ? 0u : choice.texcoord == 0 ? 1u : 2u) << path;
    if (choice.texcoord >= 0) ++valid;
    std::string line = path.substr(std::string(PRT_ASSIMP_MODELS_DIR).size() + 1) + " | " +
                       std::to_string(scene.indices.size() / 3) + " | ";
    line += choice.texcoord >= 0 ? "TEXCOORD_" + std::to_string(choice.texcoord) + ": " + choice.report.summary()
                                 : std::string("generate");
    for (const std::string& r : choice.rejected) line += " | " + r;
    std::printf("uv-corpus: %s\n", line.c_str());
    // Two files whose verdict is known: a box with a one-chart TEXCOORD_1, and a box whose
    // TEXCOORD_0 tiles its texture (u up to 6).
    if (path.ends_with("BoxTexcoords-glTF/boxTexcoords.gltf")) {
      EXPECT_EQ(choice.texcoord, 1) << line;
      EXPECT_EQ(choice.report.charts, 1u) << line;
    }
    if (path.ends_with("BoxTextured-glTF/BoxTextured.gltf")) {
      EXPECT_EQ(choice.texcoord, -1) << line;
      EXPECT_NE(line.find("TEXCOORD_0: 10 triangles outside [0, 1]"), std::string::npos) << line;
    }
  }
  std::printf("uv-corpus: %d loaded, %d with UVs, %d with a valid atlas\n", checked, withUvs, valid);
  EXPECT_GE(checked, 25);
  EXPECT_GT(withUvs, 0);
}

}  // namespace
}  // namespace prt::bake
