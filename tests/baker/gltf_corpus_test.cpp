// The glTF loader on a corpus of real files made by other tools: Debian's assimp-testmodels
// (glTF 1.0 and 2.0, valid and malformed; installed by scripts/install-deps.sh). Each file
// loads, or fails with a message that names the problem and the file; glTF 1.0 is named as
// such, wrongly typed fields are named in an error or a warning.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "baker/scene/gltf_loader.h"
#include "warning_lines.h"

namespace prt::bake {
namespace {

using test::anyContains;
using test::joined;

const std::string kModels = PRT_ASSIMP_MODELS_DIR;

std::vector<std::string> corpus() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const char* dir : {"/glTF", "/glTF2"}) {
    for (auto it = std::filesystem::recursive_directory_iterator(kModels + dir, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
      const std::string ext = it->path().extension().string();
      if (ext == ".gltf" || ext == ".glb") files.push_back(it->path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(GltfCorpus, EveryFileLoadsOrFailsNamingItself) {
  const std::vector<std::string> files = corpus();
  // Fails rather than skips without the package: the install script installs it.
  ASSERT_GE(files.size(), 50u) << "assimp-testmodels not found under " << kModels;
  int loaded = 0;
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    Scene scene;
    std::vector<std::string> warnings;
    const Status s = loadGltf(path, &scene, &warnings);
    if (s.isOk()) {
      ++loaded;
      EXPECT_FALSE(scene.positions.empty());
      EXPECT_EQ(scene.positions.size(), scene.albedo.size());
    } else {
      EXPECT_NE(s.message().find("'" + path + "'"), std::string::npos) << s.message();
      EXPECT_TRUE(scene.positions.empty());
      // None of the messages that misled users before.
      EXPECT_EQ(s.message().find("'asset' object not found"), std::string::npos) << s.message();
    }
  }
  EXPECT_GE(loaded, 25) << "most of the glTF 2.0 corpus is valid";
}

TEST(GltfCorpus, GltfOneFilesAreNamedAsSuch) {
  const char* files[] = {
      "/glTF/BoxTextured-glTF/BoxTextured.gltf",           "/glTF/BoxTextured-glTF-Embedded/BoxTextured.gltf",
      "/glTF/BoxTextured-glTF-MaterialsCommon/BoxTextured.gltf", "/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
      "/glTF/IncorrectVertexArrays/Cube_v1.gltf",          "/glTF/TwoBoxes/TwoBoxes.gltf",
  };
  for (const char* file : files) {
    SCOPED_TRACE(file);
    Scene scene;
    const Status s = loadGltf(kModels + file, &scene, nullptr);
    ASSERT_FALSE(s.isOk());
    EXPECT_NE(s.message().find("glTF 1.0 is not supported (asset.version is 1"), std::string::npos) << s.message();
    EXPECT_NE(s.message().find("convert the file to glTF 2.0"), std::string::npos) << s.message();
  }
}

TEST(GltfCorpus, WronglyTypedFieldsAreNamed) {
  const std::string dir = kModels + "/glTF2/wrongTypes/";
  Scene scene;
  std::vector<std::string> warnings;
  // `primitives` given as an object: an error naming the mesh and the field.
  Status s = loadGltf(dir + "badArray.gltf", &scene, &warnings);
  ASSERT_FALSE(s.isOk());
  EXPECT_NE(s.message().find("mesh 0 ('Mesh'): 'primitives' is an object, not an array"), std::string::npos) << s.message();

  // Invalid material fields bake, with a warning naming the material and the field.
  struct Case {
    const char* file;
    const char* warning;
  };
  const Case cases[] = {
      {"badObject.gltf", "material 0 ('Texture'): pbrMetallicRoughness is an array, not an object"},
      {"badUint.gltf", "material 0 ('Texture'): pbrMetallicRoughness.baseColorTexture.index -1 is not a texture"},
      {"badExtension.gltf", "material 0 ('Texture'): baseColorTexture's KHR_texture_transform is a string"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    warnings.clear();
    s = loadGltf(dir + c.file, &scene, &warnings);
    if (!s.isOk()) {
      // tinygltf may refuse the file itself; then the error must still name it.
      EXPECT_NE(s.message().find(c.file), std::string::npos) << s.message();
      continue;
    }
    EXPECT_TRUE(anyContains(warnings, c.warning)) << joined(warnings);
  }
}

}  // namespace
}  // namespace prt::bake
