#include "baker/scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <initializer_list>
#include <map>
#include <new>
#include <set>

#include "baker/scene/gltf_accessor.h"
#include "baker/scene/gltf_json_check.h"
#include "baker/scene/gltf_texture.h"
#include "baker/scene/mesh_cleanup.h"
#include "baker/scene/mesh_normals.h"
#include "baker/scene/mesh_tangents.h"
#include "native/file_io.h"
#include "prt/checksum.h"

namespace prt::bake {
namespace {

Status fail(const std::string& message) { return Status::error(StatusCode::kInvalidArgument, message); }

// tinygltf reports several problems as newline-separated lines; Status messages are one line.
std::string oneLine(const std::string& text) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
    start = end + 1;
  }
  return out;
}

std::string plural(std::size_t n, const char* singular, const char* pluralForm) {
  return std::to_string(n) + " " + (n == 1 ? singular : pluralForm);
}

// ---- the file and its container -------------------------------------------------------

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;  // little-endian host, as gltf_accessor.cpp asserts
}

// Checks the binary glTF header and chunk table before tinygltf sees them: tinygltf 2.7
// reads the BIN chunk's 8-byte header without counting it against the file length, so a
// file truncated there would be read past its end. Sets *length to the declared length.
Status checkGlbContainer(const std::vector<unsigned char>& bytes, std::size_t* length,
                         std::vector<std::string>* notes) {
  const std::size_t size = bytes.size();
  if (size < 12)
    return fail("truncated binary glTF: the 12-byte header is cut off (" + std::to_string(size) + " bytes)");
  const std::uint32_t version = readU32(bytes, 4);
  if (version != 2) return fail("binary glTF version " + std::to_string(version) + " is not supported (only 2)");
  const std::uint64_t declared = readU32(bytes, 8);
  if (declared > size) {
    return fail("truncated binary glTF: the header declares " + std::to_string(declared) + " bytes, the file has " +
                std::to_string(size));
  }
  if (declared < size)
    notes->push_back(std::to_string(size - declared) + " bytes after the end of the binary glTF ignored");
  std::uint64_t at = 12;
  for (int chunk = 0; at < declared; ++chunk) {
    const char* name = chunk == 0 ? "JSON" : "BIN";
    if (declared - at < 8) return fail(std::string("truncated binary glTF: the ") + name + " chunk header is cut off");
    const std::uint64_t chunkLength = readU32(bytes, static_cast<std::size_t>(at));
    const std::uint32_t type = readU32(bytes, static_cast<std::size_t>(at + 4));
    if (chunk == 0 && type != 0x4E4F534Au) return fail("binary glTF: the first chunk is not JSON");
    if (chunkLength > declared - at - 8) {
      return fail(std::string("truncated binary glTF: the ") + name + " chunk of " + std::to_string(chunkLength) +
                  " bytes runs past the end of the file");
    }
    at += 8 + chunkLength;
  }
  if (at == 12) return fail("truncated binary glTF: no JSON chunk");
  *length = static_cast<std::size_t>(declared);
  return Status::ok();
}

bool hasGlbMagic(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

bool looksLikeJsonObject(const std::vector<unsigned char>& bytes) {
  std::size_t i = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;  // UTF-8 BOM
  while (i < bytes.size() && std::isspace(bytes[i])) ++i;
  return i < bytes.size() && bytes[i] == '{';
}

bool isSupportedRequiredExtension(const std::string& name) {
  return std::find(std::begin(kSupportedRequiredExtensions), std::end(kSupportedRequiredExtensions), name) !=
         std::end(kSupportedRequiredExtensions);
}

Status unsupportedExtension(const std::string& name) {
  std::string message = "requires the glTF extension " + name + ", which this loader does not support";
  if (name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression") {
    message += " (compressed geometry: decompress the file first)";
  }
  return fail(message);
}

// Finds extensionsRequired in raw JSON text. Used only when tinygltf has rejected the
// file, to report the real cause: Draco files, for one, fail tinygltf's accessor checks
// before their extension list could be looked at.
std::vector<std::string> scanRequiredExtensions(const std::string& json) {
  std::vector<std::string> names;
  const std::string key = "\"extensionsRequired\"";
  std::size_t at = json.find(key);
  if (at == std::string::npos) return names;
  at = json.find('[', at + key.size());
  const std::size_t end = at == std::string::npos ? at : json.find(']', at);
  if (end == std::string::npos) return names;
  for (std::size_t q = json.find('"', at); q != std::string::npos && q < end; q = json.find('"', q + 1)) {
    const std::size_t close = json.find('"', q + 1);
    if (close == std::string::npos || close > end) break;
    names.push_back(json.substr(q + 1, close - q - 1));
    q = close;
  }
  return names;
}

// ---- materials --------------------------------------------------------------------------

// KHR_texture_transform: uv' = T · R · S · uv as a 2×3 matrix.
struct UvTransform {
  double m[2][3] = {{1, 0, 0}, {0, 1, 0}};
  void apply(float u, float v, float* outU, float* outV) const {
    *outU = static_cast<float>(m[0][0] * u + m[0][1] * v + m[0][2]);
    *outV = static_cast<float>(m[1][0] * u + m[1][1] * v + m[1][2]);
  }
};

struct BaseColor {
  Rgb factor{1, 1, 1};
  const LinearTexture* texture = nullptr;  // null: factor only
  WrapMode wrapS = WrapMode::kRepeat;
  WrapMode wrapT = WrapMode::kRepeat;
  int texCoord = 0;
  UvTransform uv;
  PbrVertex pbr;  // the material's metallic-roughness part (factors; textures are not sampled)
  // normalTexture: an index into the builder's normal maps (-1: none), its texture
  // coordinate set and KHR_texture_transform.
  int normalMap = -1;
  int normalTexCoord = 0;
  UvTransform normalUv;
};

double numberOr(const tinygltf::Value& v, double fallback) { return v.IsNumber() ? v.GetNumberAsDouble() : fallback; }

// Reads KHR_texture_transform from a textureInfo's extensions (rotation is
// counter-clockwise in uv space, per the extension).
void readTextureTransform(const tinygltf::ExtensionMap& extensions, UvTransform* uv, int* texCoordOut) {
  const auto it = extensions.find("KHR_texture_transform");
  if (it == extensions.end() || !it->second.IsObject()) return;
  const tinygltf::Value& ext = it->second;
  double offset[2] = {0, 0}, scale[2] = {1, 1};
  const tinygltf::Value& o = ext.Get("offset");
  const tinygltf::Value& s = ext.Get("scale");
  for (int i = 0; i < 2; ++i) {
    if (o.IsArray() && o.ArrayLen() == 2) offset[i] = numberOr(o.Get(i), offset[i]);
    if (s.IsArray() && s.ArrayLen() == 2) scale[i] = numberOr(s.Get(i), scale[i]);
  }
  const double rotation = numberOr(ext.Get("rotation"), 0.0);
  const double c = std::cos(rotation), sn = std::sin(rotation);
  uv->m[0][0] = c * scale[0];
  uv->m[0][1] = sn * scale[1];
  uv->m[0][2] = offset[0];
  uv->m[1][0] = -sn * scale[0];
  uv->m[1][1] = c * scale[1];
  uv->m[1][2] = offset[1];
  const tinygltf::Value& texCoord = ext.Get("texCoord");
  if (texCoord.IsInt()) *texCoordOut = texCoord.GetNumberAsInt();
}

// glTF's albedo range, [0, 1]; albedo 1 stays 1 (a white furnace must return its light).
// Counts the values it had to change. NaN becomes 0.
float albedoInRange(float v, std::size_t* outOfRange) {
  if (v >= 0.0f && v <= 1.0f) return v;
  ++*outOfRange;
  return v > 1.0f ? 1.0f : 0.0f;
}

// ---- node transforms --------------------------------------------------------------------

bool allFinite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// ---- the builder ------------------------------------------------------------------------

struct Counters {
  std::size_t pointPrimitives = 0;
  std::size_t linePrimitives = 0;
  std::size_t noPositionPrimitives = 0;
  std::size_t trianglePrimitives = 0;
  std::size_t primitivesWithoutNormals = 0;
  std::size_t unusableNormals = 0;
  std::size_t trailingIndices = 0;
  std::size_t skinnedNodes = 0;
  std::size_t morphedPrimitives = 0;
  std::size_t nonOpaquePrimitives = 0;
  std::size_t unnormalisedRotations = 0;
  std::size_t albedoOutOfRange = 0;  // channel values, before removal of unused vertices
  std::size_t materialOutOfRange = 0;  // metallic, roughness and specular factors outside [0, 1]
  std::size_t unusableTangents = 0;    // TANGENT values zero or non-finite (computed instead)
};

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const ImageDecodeLog& log) : model_(model), log_(log) {}

  Status addDefaultScene();
  Status finish(const std::string& fallbackName, Scene* out, std::vector<std::string>* warnings);

 private:
  Status localTransform(int nodeIndex, glm::dmat4* out);
  Status addMesh(int meshIndex, const glm::dmat4& world);
  Status addPrimitive(int meshIndex, int primitiveIndex, const glm::dmat4& world);
  Status baseColorFor(int materialIndex, BaseColor* out);
  void addTexcoords(const tinygltf::Primitive& prim, const std::string& label, std::size_t vertexCount);
  void readMetallicRoughness(const tinygltf::Material& material, const std::string& label, PbrVertex* out);
  void addNormalMapVertex(const BaseColor& base, const FloatElements& uv, const FloatElements& tangent, std::size_t v,
                          const glm::dmat3& linear, bool mirrored);
  const LinearTexture* textureFor(int textureIndex, const std::string& user, BaseColor* out);
  void readWrapModes(int textureIndex, WrapMode* wrapS, WrapMode* wrapT);
  int normalMapFor(const tinygltf::NormalTextureInfo& info, const std::string& user);
  std::string meshLabel(int meshIndex) const;

  const tinygltf::Model& model_;
  const ImageDecodeLog& log_;
  std::string sceneName_;

  // The soup under construction; needsNormal marks vertices whose normal is computed.
  std::vector<Vec3> positions_;
  std::vector<Vec3> normals_;
  std::vector<Rgb> albedo_;
  std::vector<PbrVertex> pbr_;
  std::vector<std::uint8_t> needsNormal_;
  std::vector<std::uint32_t> indices_;
  std::vector<std::uint32_t> triangleObject_;  // per triangle, into objectNames_ (scene.h)
  std::vector<std::string> objectNames_;
  // TEXCOORD_0/1 of every vertex so far; a set is dropped (cleared, with the reason) at the
  // first triangle primitive that lacks it or stores it in a type glTF does not allow.
  std::vector<Uv> texcoord_[2];
  std::string texcoordAbsent_[2];
  // Normal maps (scene.h): per vertex the map (-1: none), its uv and tangent; needsTangent_
  // marks normal-mapped vertices whose primitive has no TANGENT.
  std::vector<NormalMap> normalMaps_;
  std::map<std::pair<int, float>, int> normalMapIndex_;  // (texture, scale) -> normalMaps_ index
  std::vector<std::int32_t> normalMapOf_;
  std::vector<Uv> normalMapUv_;
  std::vector<Tangent> tangents_;
  std::vector<std::uint8_t> needsTangent_;

  Counters counters_;
  std::set<std::string> notes_;            // one-off warnings (textures, materials), deduplicated
  std::map<int, LinearTexture> textures_;  // by image index; empty: could not be used
};

std::string SceneBuilder::meshLabel(int meshIndex) const {
  std::string s = "mesh " + std::to_string(meshIndex);
  const std::string& name = model_.meshes[static_cast<std::size_t>(meshIndex)].name;
  if (!name.empty()) s += " ('" + name + "')";
  return s;
}

Status SceneBuilder::addDefaultScene() {
  const std::size_t nodeCount = model_.nodes.size();
  std::vector<int> roots;
  if (model_.defaultScene >= 0) {
    if (static_cast<std::size_t>(model_.defaultScene) >= model_.scenes.size()) {
      return fail("the default scene " + std::to_string(model_.defaultScene) + " does not exist");
    }
    const tinygltf::Scene& scene = model_.scenes[static_cast<std::size_t>(model_.defaultScene)];
    roots = scene.nodes;
    sceneName_ = scene.name;
  } else {
    // No `scene`: every node that is nobody's child is a root.
    std::vector<std::uint8_t> isChild(nodeCount, 0);
    for (std::size_t n = 0; n < nodeCount; ++n) {
      for (int child : model_.nodes[n].children) {
        if (child < 0 || static_cast<std::size_t>(child) >= nodeCount) {
          return fail("node " + std::to_string(n) + " has child " + std::to_string(child) + ", which does not exist");
        }
        isChild[static_cast<std::size_t>(child)] = 1;
      }
    }
    for (std::size_t n = 0; n < nodeCount; ++n) {
      if (!isChild[n]) roots.push_back(static_cast<int>(n));
    }
  }

  // Depth-first with an explicit stack: a hostile file can nest nodes deeper than the
  // call stack would survive. Each node may be reached once; a second visit means a cycle
  // or a shared child, which glTF forbids (nodes form disjoint trees).
  struct Pending {
    int node;
    int parent;  // -1 for a root
    glm::dmat4 parentWorld;
  };
  std::vector<Pending> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, glm::dmat4(1.0)});
  std::vector<std::uint8_t> visited(nodeCount, 0);
  while (!stack.empty()) {
    const Pending item = stack.back();
    stack.pop_back();
    if (item.node < 0 || static_cast<std::size_t>(item.node) >= nodeCount) {
      const std::string referrer = item.parent < 0 ? "the scene" : "node " + std::to_string(item.parent);
      return fail(referrer + " refers to node " + std::to_string(item.node) + ", which does not exist");
    }
    const auto index = static_cast<std::size_t>(item.node);
    if (visited[index]) {
      return fail(
          "node " + std::to_string(item.node) +
          " is reached twice: glTF requires the node hierarchy to be disjoint trees (a cycle or a shared child)");
    }
    visited[index] = 1;
    glm::dmat4 local;
    if (Status s = localTransform(item.node, &local); !s.isOk()) return s;
    const glm::dmat4 world = item.parentWorld * local;
    const tinygltf::Node& node = model_.nodes[index];
    if (node.skin >= 0) ++counters_.skinnedNodes;
    if (node.mesh >= 0 || node.mesh < -1) {
      if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
        return fail("node " + std::to_string(item.node) + " refers to mesh " + std::to_string(node.mesh) +
                    ", which does not exist");
      }
      // Each node's instance of a mesh is an object of its own (scene.h): instances share UVs.
      std::string object = "node " + std::to_string(item.node);
      if (!node.name.empty()) object += " ('" + node.name + "')";
      objectNames_.push_back(object + ", " + meshLabel(node.mesh));
      if (Status s = addMesh(node.mesh, world); !s.isOk()) return s;
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, item.node, world});
  }
  return Status::ok();
}

Status SceneBuilder::localTransform(int nodeIndex, glm::dmat4* out) {
  const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
  const std::string label = "node " + std::to_string(nodeIndex);
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16)
      return fail(label + ": matrix has " + std::to_string(node.matrix.size()) + " numbers, not 16");
    *out = glm::make_mat4(node.matrix.data());  // column-major in glTF and in GLM
  } else {
    if (!node.translation.empty() && node.translation.size() != 3)
      return fail(label + ": translation must have 3 numbers");
    if (!node.rotation.empty() && node.rotation.size() != 4) return fail(label + ": rotation must have 4 numbers");
    if (!node.scale.empty() && node.scale.size() != 3) return fail(label + ": scale must have 3 numbers");
    glm::dvec3 t(0.0), s(1.0);
    glm::dquat q(1.0, 0.0, 0.0, 0.0);
    if (!node.translation.empty()) t = glm::make_vec3(node.translation.data());
    if (!node.scale.empty()) s = glm::make_vec3(node.scale.data());
    if (!node.rotation.empty()) {
      const std::vector<double>& r = node.rotation;
      q = glm::dquat(r[3], r[0], r[1], r[2]);  // glTF stores x, y, z, w; GLM's constructor takes w first
      const double len = glm::length(q);
      if (!(len > 0.0) || !std::isfinite(len))
        return fail(label + ": rotation quaternion has zero or non-finite length");
      if (std::abs(len - 1.0) > 1e-3) ++counters_.unnormalisedRotations;
      q = q / len;
    }
    *out = glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(q) * glm::scale(glm::dmat4(1.0), s);
  }
  if (!allFinite(*out)) return fail(label + ": transform has non-finite values");
  return Status::ok();
}

Status SceneBuilder::addMesh(int meshIndex, const glm::dmat4& world) {
  const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    if (Status s = addPrimitive(meshIndex, static_cast<int>(p), world); !s.isOk()) return s;
  }
  return Status::ok();
}

void SceneBuilder::readWrapModes(int textureIndex, WrapMode* wrapS, WrapMode* wrapT) {
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(textureIndex)];
  if (texture.sampler >= 0 && static_cast<std::size_t>(texture.sampler) < model_.samplers.size()) {
    const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(texture.sampler)];
    const bool knownS = wrapModeFromGltf(sampler.wrapS, wrapS);
    const bool knownT = wrapModeFromGltf(sampler.wrapT, wrapT);
    if (!knownS || !knownT) {
      notes_.insert("sampler " + std::to_string(texture.sampler) + ": unknown wrap mode, REPEAT used");
    }
  } else if (texture.sampler != -1) {
    notes_.insert("texture " + std::to_string(textureIndex) + ": sampler " + std::to_string(texture.sampler) +
                  " does not exist, REPEAT used");
  }
}

// The normal map of a normalTexture, decoded once per (texture, scale); -1 (with a note)
// when its image cannot be used: the surface is then baked with its vertex normals.
int SceneBuilder::normalMapFor(const tinygltf::NormalTextureInfo& info, const std::string& user) {
  const auto key = std::make_pair(info.index, static_cast<float>(info.scale));
  if (const auto it = normalMapIndex_.find(key); it != normalMapIndex_.end()) return it->second;
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
  NormalMap map;
  map.scale = static_cast<float>(info.scale);
  readWrapModes(info.index, &map.wrapS, &map.wrapT);
  int result = -1;
  if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size()) {
    notes_.insert(user + " uses texture " + std::to_string(info.index) +
                  ", which has no image this loader can decode; normalTexture ignored");
  } else if (!std::isfinite(map.scale)) {
    notes_.insert(user + ": normalTexture scale is not finite; normalTexture ignored");
  } else {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(texture.source)];
    if (image.image.empty()) {
      const auto failure = log_.failures.find(texture.source);
      notes_.insert("image " + std::to_string(texture.source) + ": " +
                    (failure != log_.failures.end() ? failure->second : std::string("not loaded (missing file?)")) +
                    "; normalTexture ignored");
    } else if (image.bits != 8 ||
               !textureFromUnorm8(image.width, image.height, image.component, image.image, &map.texture).isOk()) {
      notes_.insert("image " + std::to_string(texture.source) + ": unexpected pixel layout; normalTexture ignored");
    } else {
      result = static_cast<int>(normalMaps_.size());
      normalMaps_.push_back(std::move(map));
    }
  }
  normalMapIndex_.emplace(key, result);
  return result;
}

const LinearTexture* SceneBuilder::textureFor(int textureIndex, const std::string& user, BaseColor* out) {
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(textureIndex)];
  const std::string label = "texture " + std::to_string(textureIndex);
  readWrapModes(textureIndex, &out->wrapS, &out->wrapT);
  if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= model_.images.size()) {
    notes_.insert(user + " uses " + label + ", which has no image this loader can decode; baseColorTexture ignored");
    return nullptr;
  }
  auto it = textures_.find(texture.source);
  if (it == textures_.end()) {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(texture.source)];
    LinearTexture linear;
    if (image.image.empty()) {
      const auto failure = log_.failures.find(texture.source);
      const std::string why = failure != log_.failures.end() ? failure->second : "not loaded (missing file?)";
      notes_.insert("image " + std::to_string(texture.source) +
                    (image.uri.rfind("data:", 0) == 0 || image.uri.empty() ? "" : " ('" + image.uri + "')") + ": " +
                    why + "; baseColorTexture ignored");
    } else if (image.bits != 8 ||
               !linearTextureFromSrgb8(image.width, image.height, image.component, image.image, &linear).isOk()) {
      notes_.insert("image " + std::to_string(texture.source) + ": unexpected pixel layout; baseColorTexture ignored");
      linear = LinearTexture();
    }
    it = textures_.emplace(texture.source, std::move(linear)).first;
  }
  return it->second.rgb.empty() ? nullptr : &it->second;
}

// The vertex's normal-map entries: the map, its uv (texture transform applied) and the
// tangent, TANGENT transformed like a surface direction (a mirroring transform flips the
// handedness: cross(n, t) turns with it, the bitangent must not) or marked for computing.
void SceneBuilder::addNormalMapVertex(const BaseColor& base, const FloatElements& uv, const FloatElements& tangent,
                                      std::size_t v, const glm::dmat3& linear, bool mirrored) {
  normalMapOf_.push_back(base.normalMap);
  Uv mapped;
  if (base.normalMap >= 0) base.normalUv.apply(uv.values[2 * v], uv.values[2 * v + 1], &mapped.u, &mapped.v);
  normalMapUv_.push_back(mapped);
  Tangent t;
  bool usable = false;
  if (base.normalMap >= 0 && !tangent.values.empty()) {
    const float* q = &tangent.values[4 * v];
    const glm::dvec3 w = linear * glm::dvec3(q[0], q[1], q[2]);
    const double len = glm::length(w);
    if (len > 1e-20 && std::isfinite(len) && std::isfinite(q[3])) {
      t.direction = {static_cast<float>(w.x / len), static_cast<float>(w.y / len), static_cast<float>(w.z / len)};
      t.handedness = (q[3] < 0.0f) != mirrored ? -1.0f : 1.0f;
      usable = true;
    } else {
      ++counters_.unusableTangents;
    }
  }
  tangents_.push_back(t);
  needsTangent_.push_back(base.normalMap >= 0 && !usable ? 1 : 0);
}

void SceneBuilder::readMetallicRoughness(const tinygltf::Material& material, const std::string& label, PbrVertex* out) {
  const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
  std::size_t& bad = counters_.materialOutOfRange;
  out->metallic = albedoInRange(static_cast<float>(pbr.metallicFactor), &bad);
  out->roughness = albedoInRange(static_cast<float>(pbr.roughnessFactor), &bad);
  if (pbr.metallicRoughnessTexture.index >= 0) {
    notes_.insert(label + ": metallicRoughnessTexture not sampled; metallicFactor and roughnessFactor are used");
  }
  // KHR_materials_specular: dielectric f0 = min(0.04 x specularColorFactor, 1) x specularFactor.
  const auto it = material.extensions.find("KHR_materials_specular");
  if (it == material.extensions.end() || !it->second.IsObject()) return;
  const tinygltf::Value& ext = it->second;
  const float factor = albedoInRange(static_cast<float>(numberOr(ext.Get("specularFactor"), 1.0)), &bad);
  double color[3] = {1.0, 1.0, 1.0};
  const tinygltf::Value& c = ext.Get("specularColorFactor");
  if (c.IsArray() && c.ArrayLen() == 3) {
    for (int i = 0; i < 3; ++i) color[i] = std::max(0.0, numberOr(c.Get(i), 1.0));
  }
  auto f0 = [&](double k) { return static_cast<float>(std::min(0.04 * k, 1.0)) * factor; };
  out->dielectricF0 = {f0(color[0]), f0(color[1]), f0(color[2])};
  out->dielectricF90 = factor;
  if (ext.Has("specularTexture") || ext.Has("specularColorTexture")) {
    notes_.insert(label + ": KHR_materials_specular textures not sampled; its factors are used");
  }
}

Status SceneBuilder::baseColorFor(int materialIndex, BaseColor* out) {
  *out = BaseColor();
  // glTF's default material: white, untextured, metallic 1 and roughness 1 (glTF 2.0 §3.9.6).
  out->pbr.metallic = 1.0f;
  if (materialIndex == -1) return Status::ok();
  if (materialIndex < 0 || static_cast<std::size_t>(materialIndex) >= model_.materials.size()) {
    return fail("material " + std::to_string(materialIndex) + " does not exist");
  }
  const tinygltf::Material& material = model_.materials[static_cast<std::size_t>(materialIndex)];
  const std::string label =
      "material " + std::to_string(materialIndex) + (material.name.empty() ? "" : " ('" + material.name + "')");
  const std::vector<double>& f = material.pbrMetallicRoughness.baseColorFactor;
  if (f.size() >= 3) out->factor = {static_cast<float>(f[0]), static_cast<float>(f[1]), static_cast<float>(f[2])};
  readMetallicRoughness(material, label, &out->pbr);
  if (!material.alphaMode.empty() && material.alphaMode != "OPAQUE") ++counters_.nonOpaquePrimitives;
  if (material.extensions.count("KHR_materials_pbrSpecularGlossiness") != 0) {
    notes_.insert(label + ": KHR_materials_pbrSpecularGlossiness ignored; its metallic-roughness base colour is used");
  }
  const tinygltf::NormalTextureInfo& normal = material.normalTexture;
  if (normal.index >= 0) {
    if (static_cast<std::size_t>(normal.index) >= model_.textures.size()) {
      return fail(label + ": normalTexture refers to texture " + std::to_string(normal.index) +
                  ", which does not exist");
    }
    out->normalTexCoord = normal.texCoord;
    readTextureTransform(normal.extensions, &out->normalUv, &out->normalTexCoord);
    out->normalMap = normalMapFor(normal, label);
  }
  const tinygltf::TextureInfo& info = material.pbrMetallicRoughness.baseColorTexture;
  if (info.index < 0) return Status::ok();
  if (static_cast<std::size_t>(info.index) >= model_.textures.size()) {
    return fail(label + ": baseColorTexture refers to texture " + std::to_string(info.index) +
                ", which does not exist");
  }
  out->texCoord = info.texCoord;
  readTextureTransform(info.extensions, &out->uv, &out->texCoord);
  out->texture = textureFor(info.index, label, out);
  return Status::ok();
}

// glTF 2.0 §3.7.2.1 allows TEXCOORD_n as float or normalised unsigned byte/short;
// KHR_mesh_quantization adds normalised signed and unnormalised integer types.
std::string texcoordTypeProblem(const tinygltf::Model& model, const tinygltf::Accessor& acc) {
  if (acc.type != TINYGLTF_TYPE_VEC2) return "not VEC2";
  if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return "";
  const bool unsignedSmall = acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool signedSmall =
      acc.componentType == TINYGLTF_COMPONENT_TYPE_BYTE || acc.componentType == TINYGLTF_COMPONENT_TYPE_SHORT;
  if (unsignedSmall && acc.normalized) return "";
  const bool quantized = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                   "KHR_mesh_quantization") != model.extensionsUsed.end();
  if (quantized && (unsignedSmall || signedSmall)) return "";
  return "component type " + std::to_string(acc.componentType) + (acc.normalized ? " normalized" : "") +
         ", which glTF does not allow for TEXCOORD" + (quantized ? "" : " without KHR_mesh_quantization");
}

// Appends the primitive's TEXCOORD_0/1 (vertexCount each) to the sets still intact. A set
// that is missing, mistyped or unreadable here is dropped with the reason rather than failing
// the load: only the atlas choice reads it, and that falls back to another set.
void SceneBuilder::addTexcoords(const tinygltf::Primitive& prim, const std::string& label, std::size_t vertexCount) {
  for (int set = 0; set < 2; ++set) {
    if (!texcoordAbsent_[set].empty()) continue;
    const std::string name = "TEXCOORD_" + std::to_string(set);
    auto drop = [&](const std::string& why) {
      texcoordAbsent_[set] = label + ": " + why;
      texcoord_[set] = {};
    };
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) {
      drop("no " + name);
      continue;
    }
    if (it->second < 0 || static_cast<std::size_t>(it->second) >= model_.accessors.size()) {
      drop(name + " accessor " + std::to_string(it->second) + " does not exist");
      continue;
    }
    if (const std::string p = texcoordTypeProblem(model_, model_.accessors[static_cast<std::size_t>(it->second)]);
        !p.empty()) {
      drop(name + " accessor " + std::to_string(it->second) + " is " + p);
      continue;
    }
    FloatElements uv;
    if (Status s = readFloatAccessor(model_, it->second, vertexCount, &uv); !s.isOk()) {
      drop(name + ": " + s.message());
      continue;
    }
    if (uv.count != vertexCount) {
      drop(name + " has " + std::to_string(uv.count) + " elements, POSITION " + std::to_string(vertexCount));
      continue;
    }
    for (std::size_t v = 0; v < vertexCount; ++v) texcoord_[set].push_back({uv.values[2 * v], uv.values[2 * v + 1]});
  }
}

Status SceneBuilder::addPrimitive(int meshIndex, int primitiveIndex, const glm::dmat4& world) {
  const tinygltf::Primitive& prim =
      model_.meshes[static_cast<std::size_t>(meshIndex)].primitives[static_cast<std::size_t>(primitiveIndex)];
  const std::string label = meshLabel(meshIndex) + " primitive " + std::to_string(primitiveIndex);
  switch (prim.mode) {
    case TINYGLTF_MODE_POINTS: ++counters_.pointPrimitives; return Status::ok();
    case TINYGLTF_MODE_LINE:
    case TINYGLTF_MODE_LINE_LOOP:
    case TINYGLTF_MODE_LINE_STRIP: ++counters_.linePrimitives; return Status::ok();
    case TINYGLTF_MODE_TRIANGLES:
    case TINYGLTF_MODE_TRIANGLE_STRIP:
    case TINYGLTF_MODE_TRIANGLE_FAN: break;
    default: return fail(label + ": unknown primitive mode " + std::to_string(prim.mode));
  }
  const auto attribute = [&](const std::string& name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const int positionAccessor = attribute("POSITION");
  if (positionAccessor < 0) {
    ++counters_.noPositionPrimitives;
    return Status::ok();
  }
  if (static_cast<std::size_t>(positionAccessor) < model_.accessors.size()) {
    const tinygltf::Accessor& acc = model_.accessors[static_cast<std::size_t>(positionAccessor)];
    if (acc.bufferView < 0 && !acc.sparse.isSparse && prim.extensions.count("KHR_draco_mesh_compression") != 0) {
      return fail(
          label +
          ": geometry is only stored compressed (KHR_draco_mesh_compression), which this loader does not decode");
    }
    if (acc.count > kMaxSceneVertices - positions_.size()) {
      return fail(label + ": the scene would have more than " + std::to_string(kMaxSceneVertices) +
                  " vertices (2^26), the limit");
    }
  }
  const std::size_t vertexBudget = kMaxSceneVertices - positions_.size();
  auto readAttribute = [&](const char* name, int accessor, std::size_t expectedCount,
                           std::initializer_list<int> components, FloatElements* out) -> Status {
    if (Status s = readFloatAccessor(model_, accessor, vertexBudget, out); !s.isOk()) {
      return fail(label + ", attribute " + name + ": " + s.message());
    }
    if (std::find(components.begin(), components.end(), out->components) == components.end()) {
      return fail(label + ", attribute " + name + ": accessor " + std::to_string(accessor) + " has " +
                  std::to_string(out->components) + " components per element, which " + name + " cannot have");
    }
    if (expectedCount != SIZE_MAX && out->count != expectedCount) {
      return fail(label + ", attribute " + name + ": " + std::to_string(out->count) + " elements, but POSITION has " +
                  std::to_string(expectedCount));
    }
    return Status::ok();
  };

  FloatElements position;
  if (Status s = readAttribute("POSITION", positionAccessor, SIZE_MAX, {3}, &position); !s.isOk()) return s;
  const std::size_t n = position.count;

  FloatElements normal;
  const int normalAccessor = attribute("NORMAL");
  if (normalAccessor >= 0) {
    if (Status s = readAttribute("NORMAL", normalAccessor, n, {3}, &normal); !s.isOk()) return s;
  } else {
    ++counters_.primitivesWithoutNormals;
  }
  FloatElements color;
  const int colorAccessor = attribute("COLOR_0");
  if (colorAccessor >= 0) {
    if (Status s = readAttribute("COLOR_0", colorAccessor, n, {3, 4}, &color); !s.isOk()) return s;
  }
  BaseColor base;
  if (Status s = baseColorFor(prim.material, &base); !s.isOk()) return fail(label + ": " + s.message());
  FloatElements uv;
  if (base.texture != nullptr) {
    const std::string name = "TEXCOORD_" + std::to_string(base.texCoord);
    const int uvAccessor = attribute(name);
    if (uvAccessor < 0) {
      notes_.insert(label + ": its baseColorTexture uses " + name + ", which the primitive lacks; texture ignored");
      base.texture = nullptr;
    } else if (Status s = readAttribute(name.c_str(), uvAccessor, n, {2}, &uv); !s.isOk()) {
      return s;
    }
  }
  FloatElements normalUv, tangent;
  if (base.normalMap >= 0) {
    const std::string name = "TEXCOORD_" + std::to_string(base.normalTexCoord);
    const int uvAccessor = attribute(name);
    if (uvAccessor < 0) {
      notes_.insert(label + ": its normalTexture uses " + name + ", which the primitive lacks; normal map ignored");
      base.normalMap = -1;
    } else if (Status s = readAttribute(name.c_str(), uvAccessor, n, {2}, &normalUv); !s.isOk()) {
      return s;
    }
    const int tangentAccessor = attribute("TANGENT");
    if (base.normalMap >= 0 && tangentAccessor >= 0) {
      if (Status s = readAttribute("TANGENT", tangentAccessor, n, {4}, &tangent); !s.isOk()) return s;
    }
  }
  if (!prim.targets.empty()) ++counters_.morphedPrimitives;
  addTexcoords(prim, label, n);

  // Vertex order of the primitive's triangles, in glTF's front-face (CCW) convention.
  std::vector<std::uint32_t> order;
  if (prim.indices >= 0) {
    if (Status s = readIndexAccessor(model_, prim.indices, 3 * kMaxSceneTriangles + 2, &order); !s.isOk()) {
      return fail(label + ", indices: " + s.message());
    }
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (order[i] >= n) {
        return fail(label + ": index " + std::to_string(order[i]) + " at position " + std::to_string(i) +
                    " is out of range (the primitive has " + std::to_string(n) + " vertices)");
      }
    }
  } else if (prim.indices != -1) {
    return fail(label + ": indices accessor " + std::to_string(prim.indices) + " does not exist");
  } else {
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  }
  std::vector<std::uint32_t> tri;  // local vertex numbers, 3 per triangle
  if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
    counters_.trailingIndices += order.size() % 3;
    order.resize(order.size() - order.size() % 3);
    tri = std::move(order);
  } else if (order.size() >= 3) {
    // glTF 2.0 §3.7.2.1: strip triangle i is (v_i, v_i+1+i%2, v_i+2-i%2); fan triangle i is
    // (v_i+1, v_i+2, v_0). Both keep the first triangle's orientation throughout.
    tri.reserve(3 * (order.size() - 2));
    for (std::size_t i = 0; i + 2 < order.size(); ++i) {
      if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        tri.insert(tri.end(), {order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]});
      } else {
        tri.insert(tri.end(), {order[i + 1], order[i + 2], order[0]});
      }
    }
  }
  if (tri.size() / 3 > kMaxSceneTriangles - indices_.size() / 3) {
    return fail(label + ": the scene would have more than " + std::to_string(kMaxSceneTriangles) +
                " triangles (2^27), the limit");
  }

  // A mirroring transform (negative determinant) turns counter-clockwise into clockwise:
  // swapping two corners restores it. Normals need no flip: the inverse-transpose already
  // maps an outward normal to the mirrored surface's outward normal.
  const glm::dmat3 linear(world);
  const bool mirrored = glm::determinant(linear) < 0.0;
  const glm::dmat3 normalMatrix = glm::inverseTranspose(linear);
  const auto base0 = static_cast<std::uint32_t>(positions_.size());
  for (std::size_t t = 0; t + 2 < tri.size(); t += 3) {
    indices_.push_back(base0 + tri[t]);
    indices_.push_back(base0 + (mirrored ? tri[t + 2] : tri[t + 1]));
    indices_.push_back(base0 + (mirrored ? tri[t + 1] : tri[t + 2]));
    triangleObject_.push_back(static_cast<std::uint32_t>(objectNames_.size() - 1));
  }

  const bool textured = base.texture != nullptr;
  for (std::size_t v = 0; v < n; ++v) {
    const float* p = &position.values[3 * v];
    const glm::dvec4 wp = world * glm::dvec4(p[0], p[1], p[2], 1.0);
    positions_.push_back({static_cast<float>(wp.x), static_cast<float>(wp.y), static_cast<float>(wp.z)});

    Vec3 nv = kFallbackNormal;
    bool usable = false;
    if (!normal.values.empty()) {
      const float* q = &normal.values[3 * v];
      const glm::dvec3 wn = normalMatrix * glm::dvec3(q[0], q[1], q[2]);
      const double len = glm::length(wn);
      if (len > 1e-20 && std::isfinite(len)) {
        nv = {static_cast<float>(wn.x / len), static_cast<float>(wn.y / len), static_cast<float>(wn.z / len)};
        usable = isFinite(nv);
      }
      if (!usable) ++counters_.unusableNormals;
    }
    normals_.push_back(usable ? nv : kFallbackNormal);
    needsNormal_.push_back(usable ? 0 : 1);

    Rgb a = base.factor;
    if (textured) {
      float u = 0, w = 0;
      base.uv.apply(uv.values[2 * v], uv.values[2 * v + 1], &u, &w);
      const Rgb texel = sampleBilinear(*base.texture, u, w, base.wrapS, base.wrapT);
      a = {a.r * texel.r, a.g * texel.g, a.b * texel.b};
    }
    if (!color.values.empty()) {
      const float* c = &color.values[static_cast<std::size_t>(color.components) * v];
      a = {a.r * c[0], a.g * c[1], a.b * c[2]};
    }
    std::size_t& bad = counters_.albedoOutOfRange;
    albedo_.push_back({albedoInRange(a.r, &bad), albedoInRange(a.g, &bad), albedoInRange(a.b, &bad)});
    pbr_.push_back(base.pbr);
    addNormalMapVertex(base, normalUv, tangent, v, linear, mirrored);
  }
  ++counters_.trianglePrimitives;
  return Status::ok();
}

Status SceneBuilder::finish(const std::string& fallbackName, Scene* out, std::vector<std::string>* warnings) {
  auto warn = [&](const std::string& line) {
    if (warnings) warnings->push_back(line);
  };
  const Counters& c = counters_;
  if (c.pointPrimitives)
    warn("skipped " + plural(c.pointPrimitives, "POINTS primitive", "POINTS primitives") +
         ": only triangles are baked");
  if (c.linePrimitives)
    warn("skipped " + plural(c.linePrimitives, "LINES primitive", "LINES/LINE_STRIP/LINE_LOOP primitives") +
         ": only triangles are baked");
  if (c.noPositionPrimitives)
    warn("skipped " + plural(c.noPositionPrimitives, "primitive", "primitives") + " without POSITION");

  if (indices_.empty()) {
    if (c.pointPrimitives || c.linePrimitives) {
      return fail("no triangles to bake: the scene has only POINTS or LINES primitives (" +
                  std::to_string(c.pointPrimitives) + " POINTS, " + std::to_string(c.linePrimitives) + " LINES)");
    }
    return fail("no triangles to bake in the " +
                std::string(model_.defaultScene >= 0 ? "default scene" : "file's root nodes") + " (the file has " +
                plural(model_.nodes.size(), "node", "nodes") + " and " +
                plural(model_.meshes.size(), "mesh", "meshes") + ")");
  }
  const std::size_t triangleCount = indices_.size() / 3;
  const TriangleCleanupStats dropped = removeBadTriangles(positions_, &indices_, &triangleObject_);
  if (indices_.empty()) {
    return fail(triangleCount == 1
                    ? std::string("no triangles to bake: the only triangle has zero area or non-finite positions")
                    : "no triangles to bake: all " + std::to_string(triangleCount) +
                          " triangles have zero area or non-finite positions");
  }
  if (dropped.nonFinite)
    warn("dropped " + plural(dropped.nonFinite, "triangle", "triangles") +
         " with non-finite (NaN or infinite) positions");
  if (dropped.zeroArea) warn("dropped " + plural(dropped.zeroArea, "zero-area triangle", "zero-area triangles"));
  if (c.trailingIndices)
    warn("ignored " + plural(c.trailingIndices, "trailing index", "trailing indices") +
         " that do not make a whole triangle");

  // Normals are computed only for vertices a surviving triangle uses.
  std::vector<std::uint8_t> recompute(positions_.size(), 0);
  std::size_t toCompute = 0;
  for (std::uint32_t v : indices_) {
    if (needsNormal_[v] && !recompute[v]) {
      recompute[v] = 1;
      ++toCompute;
    }
  }
  if (toCompute > 0) {
    const std::size_t fallbacks = computeVertexNormals(positions_, indices_, recompute, &normals_);
    std::string why;
    if (c.primitivesWithoutNormals)
      why += plural(c.primitivesWithoutNormals, "primitive has", "primitives have") + " no NORMAL";
    if (c.unusableNormals)
      why += std::string(why.empty() ? "" : "; ") + plural(c.unusableNormals, "NORMAL value is", "NORMAL values are") +
             " zero or non-finite";
    warn("computed smooth (area- and angle-weighted) normals for " + plural(toCompute, "vertex", "vertices") + " (" +
         why + ")");
    if (fallbacks) {
      warn(plural(fallbacks, "vertex has", "vertices have") +
           " no triangle giving a usable normal (isolated, or opposite faces cancel): fallback normal used");
    }
  }

  // Tangents for normal-mapped vertices without a usable TANGENT, from the finished normals.
  bool anyNormalMap = false;
  for (std::uint32_t v : indices_) anyNormalMap = anyNormalMap || normalMapOf_[v] >= 0;
  std::size_t tangentsComputed = 0;
  if (anyNormalMap) {
    std::vector<std::uint8_t> recomputeTangent(positions_.size(), 0);
    for (std::uint32_t v : indices_) {
      if (needsTangent_[v] && !recomputeTangent[v]) {
        recomputeTangent[v] = 1;
        ++tangentsComputed;
      }
    }
    if (tangentsComputed > 0) {
      const std::size_t fallbacks =
          computeVertexTangents(positions_, normals_, normalMapUv_, indices_, recomputeTangent, &tangents_);
      warn("computed tangents for " + plural(tangentsComputed, "normal-mapped vertex", "normal-mapped vertices") +
           " (no usable TANGENT)" +
           (fallbacks ? "; " + plural(fallbacks, "has", "have") + " degenerate texture coordinates: arbitrary tangent" : ""));
    }
  }

  Scene scene;
  if (anyNormalMap) {
    scene.normalMaps = std::move(normalMaps_);
    scene.normalMapOf = std::move(normalMapOf_);
    scene.normalMapUv = std::move(normalMapUv_);
    scene.tangents = std::move(tangents_);
  }
  scene.positions = std::move(positions_);
  scene.normals = std::move(normals_);
  scene.albedo = std::move(albedo_);
  scene.pbr = std::move(pbr_);
  scene.indices = std::move(indices_);
  scene.triangleObject = std::move(triangleObject_);
  scene.objectNames = std::move(objectNames_);
  for (int set = 0; set < 2; ++set) {
    scene.texcoordAbsent[set] = std::move(texcoordAbsent_[set]);
    if (scene.texcoordAbsent[set].empty()) scene.texcoord[set] = std::move(texcoord_[set]);
  }
  scene.name = sceneName_.empty() ? fallbackName : sceneName_;
  const std::size_t removed = removeUnreferencedVertices(&scene);
  if (removed) warn("removed " + plural(removed, "vertex", "vertices") + " that no remaining triangle uses");

  if (c.skinnedNodes)
    warn("ignored the skins of " + plural(c.skinnedNodes, "node", "nodes") + ": meshes are baked in their bind pose");
  if (c.morphedPrimitives)
    warn("ignored the morph targets of " + plural(c.morphedPrimitives, "primitive", "primitives") +
         ": base geometry used");
  if (c.nonOpaquePrimitives)
    warn(plural(c.nonOpaquePrimitives, "primitive uses", "primitives use") +
         " alphaMode MASK or BLEND: baked as opaque");
  if (c.unnormalisedRotations)
    warn(plural(c.unnormalisedRotations, "node rotation was", "node rotations were") +
         " not unit quaternions: normalised");
  if (c.albedoOutOfRange)
    warn(plural(c.albedoOutOfRange, "albedo channel value lies", "albedo channel values lie") +
         " outside glTF's [0, 1] (base colour x texture x COLOR_0): brought to the nearest bound");
  if (c.materialOutOfRange)
    warn(plural(c.materialOutOfRange, "metallic, roughness or specular factor lies", "metallic, roughness or specular factors lie") +
         " outside glTF's [0, 1]: brought to the nearest bound");
  for (const std::string& note : notes_) warn(note);
  *out = std::move(scene);
  return Status::ok();
}

// tinygltf's own file reader, recording each file it reads (external buffers and images).
bool readAndRecordFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* files) {
  if (!tinygltf::ReadWholeFile(out, err, path, nullptr)) return false;
  static_cast<std::vector<SceneFile>*>(files)->push_back({path, out->size(), crc32c(*out)});
  return true;
}

Status loadGltfUnguarded(const std::string& path, Scene* out, std::vector<std::string>* warnings,
                         std::vector<SceneFile>* files) {
  const std::string quoted = "'" + path + "'";
  auto failFile = [&](const std::string& problem) { return fail(quoted + ": " + problem); };

  std::vector<unsigned char> bytes;
  if (Status s = readFileBytes(path, kMaxGltfFileBytes, &bytes); !s.isOk()) return s;  // names the path
  if (bytes.empty()) return failFile("the file is empty");

  std::filesystem::path fsPath(path);
  std::string baseDir = fsPath.parent_path().string();
  if (baseDir.empty()) baseDir = ".";
  std::string extension = fsPath.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });

  tinygltf::Model model;
  tinygltf::TinyGLTF parser;
  ImageDecodeLog imageLog;
  imageLog.model = &model;
  parser.SetImageLoader(&decodeGltfImage, &imageLog);
  std::vector<SceneFile> read{{path, bytes.size(), crc32c(bytes)}};
  parser.SetFsCallbacks({&tinygltf::FileExists, &tinygltf::ExpandFilePath, &readAndRecordFile, &tinygltf::WriteWholeFile, &read});
  std::string err, warn;
  std::vector<std::string> notes;
  bool parsed = false;
  std::string jsonText;  // for the extension scan if tinygltf fails
  if (hasGlbMagic(bytes)) {
    std::size_t length = 0;
    if (Status s = checkGlbContainer(bytes, &length, &notes); !s.isOk()) return failFile(s.message());
    jsonText.assign(reinterpret_cast<const char*>(bytes.data()) + 20,
                    std::min<std::size_t>(readU32(bytes, 12), length - 20));
    if (Status s = checkGltfJson(jsonText, &notes); !s.isOk()) return failFile(s.message());
    parsed = parser.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(length), baseDir);
  } else if (extension == ".glb") {
    char shown[64];
    std::snprintf(shown, sizeof shown, "%02x %02x %02x %02x", bytes.size() > 0 ? bytes[0] : 0,
                  bytes.size() > 1 ? bytes[1] : 0, bytes.size() > 2 ? bytes[2] : 0, bytes.size() > 3 ? bytes[3] : 0);
    return failFile(std::string("not a binary glTF: bad magic (the file starts with ") + shown + ", not 'glTF')");
  } else if (!looksLikeJsonObject(bytes)) {
    return failFile("neither glTF JSON (no '{' at the start) nor binary glTF (no 'glTF' magic)");
  } else {
    jsonText.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (Status s = checkGltfJson(jsonText, &notes); !s.isOk()) return failFile(s.message());
    parsed = parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                        static_cast<unsigned int>(bytes.size()), baseDir);
  }
  imageLog.model = nullptr;
  if (!parsed) {
    for (const std::string& name : scanRequiredExtensions(jsonText)) {
      if (!isSupportedRequiredExtension(name)) return failFile(unsupportedExtension(name).message());
    }
    return failFile("glTF parser: " + oneLine(err.empty() ? "unknown error" : err));
  }
  for (const std::string& name : model.extensionsRequired) {
    if (!isSupportedRequiredExtension(name)) return failFile(unsupportedExtension(name).message());
  }

  std::vector<std::string> collected;
  for (const std::string& note : notes) collected.push_back(note);
  if (!warn.empty()) collected.push_back("glTF parser: " + oneLine(warn));
  SceneBuilder builder(model, imageLog);
  if (Status s = builder.addDefaultScene(); !s.isOk()) return failFile(s.message());
  if (Status s = builder.finish(fsPath.stem().string(), out, &collected); !s.isOk()) return failFile(s.message());
  if (warnings) warnings->insert(warnings->end(), collected.begin(), collected.end());
  if (files) *files = std::move(read);
  return Status::ok();
}

}  // namespace

Status loadGltf(const std::string& path, Scene* out, std::vector<std::string>* warnings, std::vector<SceneFile>* files) {
  if (out == nullptr) return fail("loadGltf: no output scene");
  *out = Scene();
  // tinygltf (nlohmann json inside) and the standard library may throw, bad_alloc above
  // all; nothing may escape, and `out` stays empty on any failure.
  try {
    Status s = loadGltfUnguarded(path, out, warnings, files);
    if (!s.isOk()) *out = Scene();
    return s;
  } catch (const std::bad_alloc&) {
    *out = Scene();
    return Status::error(StatusCode::kResourceExhausted, "'" + path + "': out of memory while loading");
  } catch (const std::exception& e) {
    *out = Scene();
    return fail("'" + path + "': " + e.what());
  } catch (...) {
    *out = Scene();
    return fail("'" + path + "': unknown exception while loading");
  }
}

}  // namespace prt::bake
