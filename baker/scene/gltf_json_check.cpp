#include "baker/scene/gltf_json_check.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace prt::bake {
namespace {

using Json = nlohmann::json;

Status fail(const std::string& message) { return Status::error(StatusCode::kInvalidArgument, message); }

const char* typeName(const Json& j) {
  if (j.is_object()) return "an object";
  if (j.is_array()) return "an array";
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  return "null";
}

// "mesh 3 ('Wheel')" or "mesh 3".
std::string label(const char* what, std::size_t index, const Json& item) {
  std::string s = std::string(what) + " " + std::to_string(index);
  if (item.is_object()) {
    const auto name = item.find("name");
    if (name != item.end() && name->is_string()) s += " ('" + name->get<std::string>() + "')";
  }
  return s;
}

// A short rendering of a scalar for messages (objects and arrays by their type).
std::string shown(const Json& j) {
  if (j.is_object() || j.is_array()) return typeName(j);
  std::string s = j.dump();
  return s.size() > 40 ? s.substr(0, 40) + "..." : s;
}

// glTF 2.0 says asset.version is a string "2.0"; 1.0 files say "1.0", some the number 1.
Status checkVersion(const Json& root) {
  const auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object()) {
    for (const char* key : {"meshes", "nodes", "accessors"}) {
      const auto it = root.find(key);
      if (it != root.end() && it->is_object()) {
        return fail(std::string("glTF 1.0 is not supported (no asset.version, and '") + key +
                    "' is an object keyed by id, as in glTF 1.0); convert the file to glTF 2.0");
      }
    }
    return Status::ok();  // tinygltf names the missing asset object
  }
  const auto version = asset->find("version");
  if (version == asset->end()) return Status::ok();
  std::string text;
  if (version->is_string()) {
    text = version->get<std::string>();
  } else if (version->is_number()) {
    text = version->dump();
  } else {
    return fail(std::string("asset.version is ") + typeName(*version) + ", not a string like \"2.0\"");
  }
  const std::string major = text.substr(0, text.find('.'));
  if (major == "2") return Status::ok();
  if (major == "1" || major == "0") {
    return fail("glTF 1.0 is not supported (asset.version is " + text + "); convert the file to glTF 2.0");
  }
  return fail("glTF " + text + " is not supported (asset.version is " + text + "; this loader reads glTF 2.0)");
}

Status checkMeshes(const Json& root) {
  const auto meshes = root.find("meshes");
  if (meshes == root.end()) return Status::ok();
  if (!meshes->is_array()) return fail(std::string("'meshes' is ") + typeName(*meshes) + ", not an array");
  for (std::size_t i = 0; i < meshes->size(); ++i) {
    const Json& mesh = (*meshes)[i];
    if (!mesh.is_object()) return fail(label("mesh", i, mesh) + " is " + typeName(mesh) + ", not an object");
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end()) return fail(label("mesh", i, mesh) + " has no 'primitives'");
    if (!primitives->is_array()) {
      return fail(label("mesh", i, mesh) + ": 'primitives' is " + typeName(*primitives) + ", not an array");
    }
  }
  return Status::ok();
}

bool isIndex(const Json& j, std::size_t count) {
  if (!j.is_number_integer() && !j.is_number_unsigned()) return false;
  if (j.is_number_integer() && j.get<std::int64_t>() < 0) return false;
  return j.get<std::uint64_t>() < count;
}

std::size_t arraySize(const Json& root, const char* key) {
  const auto it = root.find(key);
  return it != root.end() && it->is_array() ? it->size() : 0;
}

// The fields that decide the albedo the baker reads.
void checkMaterials(const Json& root, std::vector<std::string>* warnings) {
  const auto materials = root.find("materials");
  if (materials == root.end() || !materials->is_array()) return;
  const std::size_t textureCount = arraySize(root, "textures");
  for (std::size_t i = 0; i < materials->size(); ++i) {
    const Json& m = (*materials)[i];
    const std::string where = label("material", i, m);
    auto warn = [&](const std::string& what) { warnings->push_back(where + ": " + what); };
    if (!m.is_object()) {
      warn(std::string("is ") + typeName(m) + ", not an object: ignored (white albedo)");
      continue;
    }
    const auto pbr = m.find("pbrMetallicRoughness");
    if (pbr == m.end()) continue;
    if (!pbr->is_object()) {
      warn(std::string("pbrMetallicRoughness is ") + typeName(*pbr) + ", not an object: ignored (white albedo)");
      continue;
    }
    const auto factor = pbr->find("baseColorFactor");
    if (factor != pbr->end()) {
      bool ok = factor->is_array() && factor->size() == 4;
      for (std::size_t k = 0; ok && k < 4; ++k) ok = (*factor)[k].is_number() && std::isfinite((*factor)[k].get<double>());
      if (!ok) warn("pbrMetallicRoughness.baseColorFactor is " + shown(*factor) + ", not 4 finite numbers: ignored (white)");
    }
    const auto texture = pbr->find("baseColorTexture");
    if (texture == pbr->end()) continue;
    if (!texture->is_object()) {
      warn(std::string("pbrMetallicRoughness.baseColorTexture is ") + typeName(*texture) + ", not an object: ignored (base colour factor alone)");
      continue;
    }
    const auto index = texture->find("index");
    if (index == texture->end()) {
      warn("pbrMetallicRoughness.baseColorTexture has no index: ignored (base colour factor alone)");
    } else if (!isIndex(*index, textureCount)) {
      warn("pbrMetallicRoughness.baseColorTexture.index " + shown(*index) + " is not a texture of the file (it has " +
           std::to_string(textureCount) + "): ignored (base colour factor alone)");
    }
    const auto extensions = texture->find("extensions");
    if (extensions != texture->end() && extensions->is_object()) {
      const auto transform = extensions->find("KHR_texture_transform");
      if (transform != extensions->end() && !transform->is_object()) {
        warn(std::string("baseColorTexture's KHR_texture_transform is ") + typeName(*transform) + ", not an object: ignored");
      }
    }
  }
}

}  // namespace

Status checkGltfJson(std::string_view json, std::vector<std::string>* warnings) {
  // No exceptions: a syntax error gives a discarded value, which tinygltf then reports.
  const Json root = Json::parse(json.begin(), json.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded() || !root.is_object()) return Status::ok();
  if (Status s = checkVersion(root); !s.isOk()) return s;
  if (Status s = checkMeshes(root); !s.isOk()) return s;
  checkMaterials(root, warnings);
  return Status::ok();
}

}  // namespace prt::bake
