// The glossy material inputs: the loader's metallic-roughness and KHR_materials_specular
// factors per vertex, and the split of base colour into diffuse and specular parts
// (docs/glossy.md), each against values worked out by hand from the glTF spec.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "baker/scene/default_scene.h"
#include "baker/scene/glossy_materials.h"
#include "baker/scene/gltf_loader.h"
#include "gltf_test_files.h"

namespace prt::bake {
namespace {

using test::BufferStorage;
using test::GltfDir;
using test::GltfWriter;

using test::kTriangle;

Scene loadTriangleWithMaterial(const std::string& material, std::vector<std::string>* warnings = nullptr) {
  GltfDir dir;
  GltfWriter w;
  const int p = w.addFloats(kTriangle, "VEC3");
  if (!material.empty()) w.materials = {material};
  w.addMesh("\"POSITION\":" + std::to_string(p), -1, 4, material.empty() ? -1 : 0);
  Scene s;
  const Status st = loadGltf(dir.write("m.gltf", w.json(BufferStorage::kDataUri)), &s, warnings);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return s;
}

TEST(GlossyMaterials, LoaderReadsMetallicRoughnessFactors) {
  const Scene s = loadTriangleWithMaterial(
      "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1],\"metallicFactor\":0.25,\"roughnessFactor\":0.6}}");
  ASSERT_EQ(s.pbr.size(), 3u);
  for (const PbrVertex& m : s.pbr) {
    EXPECT_FLOAT_EQ(m.metallic, 0.25f);
    EXPECT_FLOAT_EQ(m.roughness, 0.6f);
    EXPECT_FLOAT_EQ(m.dielectricF0.g, 0.04f);
  }
}

TEST(GlossyMaterials, GltfDefaultsAreARoughMetal) {
  // glTF 2.0: no material, or a material without factors, is metallic 1 and roughness 1.
  for (const std::string& material : {std::string(), std::string("{}")}) {
    const Scene s = loadTriangleWithMaterial(material);
    ASSERT_EQ(s.pbr.size(), 3u);
    EXPECT_FLOAT_EQ(s.pbr[0].metallic, 1.0f);
    EXPECT_FLOAT_EQ(s.pbr[0].roughness, 1.0f);
  }
}

TEST(GlossyMaterials, KhrMaterialsSpecularScalesDielectricF0) {
  const Scene s = loadTriangleWithMaterial(
      "{\"pbrMetallicRoughness\":{\"metallicFactor\":0},\"extensions\":{\"KHR_materials_specular\":"
      "{\"specularFactor\":0.5,\"specularColorFactor\":[1,2,40]}}}");
  ASSERT_EQ(s.pbr.size(), 3u);
  EXPECT_FLOAT_EQ(s.pbr[0].dielectricF0.r, 0.02f);  // 0.04 x 1 x 0.5
  EXPECT_FLOAT_EQ(s.pbr[0].dielectricF0.g, 0.04f);  // 0.04 x 2 x 0.5
  EXPECT_FLOAT_EQ(s.pbr[0].dielectricF0.b, 0.5f);   // min(0.04 x 40, 1) x 0.5
  EXPECT_FLOAT_EQ(s.pbr[0].dielectricF90, 0.5f);
  const Scene none = loadTriangleWithMaterial(
      "{\"pbrMetallicRoughness\":{\"metallicFactor\":0},\"extensions\":{\"KHR_materials_specular\":{\"specularFactor\":0}}}");
  EXPECT_FLOAT_EQ(none.pbr[0].dielectricF0.r, 0.0f);
  EXPECT_FLOAT_EQ(none.pbr[0].dielectricF90, 0.0f);
}

TEST(GlossyMaterials, OutOfRangeFactorsAreBroughtInWithAWarning) {
  std::vector<std::string> warnings;
  const Scene s = loadTriangleWithMaterial("{\"pbrMetallicRoughness\":{\"metallicFactor\":1.5,\"roughnessFactor\":-2}}", &warnings);
  EXPECT_FLOAT_EQ(s.pbr[0].metallic, 1.0f);
  EXPECT_FLOAT_EQ(s.pbr[0].roughness, 0.0f);
  bool found = false;
  for (const std::string& w : warnings) found = found || w.find("2 metallic, roughness or specular factors lie") != std::string::npos;
  EXPECT_TRUE(found);
}

TEST(GlossyMaterials, SplitsBaseColourIntoDiffuseAndSpecular) {
  Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.normals.assign(3, Vec3{0, 0, 1});
  s.albedo = {{0.8f, 0.4f, 0.2f}, {0.8f, 0.4f, 0.2f}, {0.5f, 0.5f, 0.5f}};
  s.pbr = {PbrVertex{0.0f, 1.0f, {0.04f, 0.04f, 0.04f}}, PbrVertex{1.0f, 0.5f, {0.04f, 0.04f, 0.04f}},
           PbrVertex{0.5f, 0.0f, {0.0f, 0.0f, 0.0f}, 0.0f}};
  ASSERT_TRUE(applyGlossyMaterials({}, &s).isOk());
  // Dielectric: the base colour stays diffuse, f0 = 0.04, roughness 1 -> s = 0.
  EXPECT_FLOAT_EQ(s.albedo[0].r, 0.8f);
  EXPECT_FLOAT_EQ(s.specular[0].f0.g, 0.04f);
  EXPECT_FLOAT_EQ(s.specular[0].exponent, 0.0f);
  // Metal: no diffuse part, f0 = base colour, roughness 0.5 -> alpha 0.25 -> (2/0.0625 - 2)/4 = 7.5.
  EXPECT_FLOAT_EQ(s.albedo[1].g, 0.0f);
  EXPECT_FLOAT_EQ(s.specular[1].f0.r, 0.8f);
  EXPECT_FLOAT_EQ(s.specular[1].exponent, 7.5f);
  // Half metal, no dielectric specular, a mirror: half the colour each way, s at the cap.
  EXPECT_FLOAT_EQ(s.albedo[2].b, 0.25f);
  EXPECT_FLOAT_EQ(s.specular[2].f0.b, 0.25f);
  EXPECT_FLOAT_EQ(s.specular[2].f90, 0.5f);  // (1 - 0.5) x 0 + 0.5
  EXPECT_FLOAT_EQ(s.specular[1].f90, 1.0f);
  EXPECT_FLOAT_EQ(s.specular[2].exponent, static_cast<float>(kDefaultMaxSpecularExponent));
}

TEST(GlossyMaterials, FixedExponentAndErrors) {
  Scene s;
  s.positions = {{0, 0, 0}};
  s.normals = {{0, 0, 1}};
  s.albedo = {{1, 1, 1}};
  GlossyMaterialOptions o;
  o.exponent = 12.0;
  ASSERT_TRUE(applyGlossyMaterials(o, &s).isOk());  // empty pbr: a rough dielectric
  EXPECT_FLOAT_EQ(s.specular[0].exponent, 12.0f);
  EXPECT_FLOAT_EQ(s.specular[0].f0.r, 0.04f);
  o.exponent = -1.0;
  EXPECT_FALSE(applyGlossyMaterials(o, &s).isOk());
  o.exponent = NAN;
  EXPECT_FALSE(applyGlossyMaterials(o, &s).isOk());
  s.pbr = {PbrVertex{}, PbrVertex{}};
  EXPECT_FALSE(applyGlossyMaterials({}, &s).isOk());
}

TEST(GlossyMaterials, DefaultSceneHasMatteRoomAndGlossyObjects) {
  Scene s = makeDefaultScene();
  ASSERT_EQ(s.pbr.size(), s.positions.size());
  ASSERT_TRUE(applyGlossyMaterials({}, &s).isOk());
  std::size_t matte = 0, glossy = 0, metal = 0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const SpecularMaterial& m = s.specular[v];
    if (m.f0.r == 0.0f && m.f0.g == 0.0f && m.f0.b == 0.0f && m.f90 == 0.0f) ++matte;
    else if (s.albedo[v].r == 0.0f) ++metal;
    else ++glossy;
  }
  EXPECT_GT(matte, s.positions.size() / 2);  // floor, walls, boxes
  EXPECT_GT(glossy, 1000u);                  // the sphere: 64 x 32 grid
  EXPECT_GT(metal, 1000u);                   // the torus: 64 x 24 grid
}

}  // namespace
}  // namespace prt::bake
