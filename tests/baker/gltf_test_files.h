// Writes small glTF files for the loader tests at test time, so the corpus (valid and
// malformed) lives in readable code rather than in committed binaries.
//
// GltfWriter collects binary data into one buffer and the JSON of each top-level array as
// text; tests add raw JSON where they want something malformed. GltfDir is a scratch
// directory removed after each test (kept when PRT_KEEP_GLTF_TEST_FILES is set).
#pragma once

#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace prt::bake::test {

// One triangle's positions (x, y, z per corner) in the z = 0 plane, facing +z: the smallest
// valid mesh for the loader tests.
inline const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = bytes[i] << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// JSON array text of comma-separated items ("" when empty).
inline std::string jsonArray(const std::vector<std::string>& items) {
  std::string s = "[";
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? "," : "") + items[i];
  return s + "]";
}

// An RGB PNG of width x height pixels (rgb: 3 bytes a pixel, rows top to bottom) as a data URI.
inline std::string rgbPngDataUri(int width, int height, const unsigned char* rgb) {
  std::vector<std::uint8_t> png;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        out->insert(out->end(), bytes, bytes + size);
      },
      &png, width, height, 3, rgb, width * 3);
  return "data:image/png;base64," + base64(png);
}

// A 2×2 sRGB PNG as a data URI: top-left grey 128, top-right red, bottom-left green,
// bottom-right blue.
inline std::string twoByTwoPngDataUri() {
  const unsigned char rgb[] = {128, 128, 128, 255, 0, 0, 0, 255, 0, 0, 0, 255};
  return rgbPngDataUri(2, 2, rgb);
}

enum class BufferStorage { kDataUri, kExternal, kGlb };

class GltfWriter {
 public:
  // Appends raw bytes to the buffer (4-byte aligned) and a bufferView over them.
  int addView(const void* data, std::size_t size, int byteStride = 0) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    const std::size_t offset = bin_.size();
    bin_.resize(offset + size);
    if (size) std::memcpy(bin_.data() + offset, data, size);
    std::string view =
        "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) + ",\"byteLength\":" + std::to_string(size);
    if (byteStride) view += ",\"byteStride\":" + std::to_string(byteStride);
    bufferViews.push_back(view + "}");
    return static_cast<int>(bufferViews.size()) - 1;
  }
  int addAccessor(int view, int componentType, std::size_t count, const std::string& type, bool normalized = false,
                  const std::string& extra = "") {
    std::string a = "{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" + std::to_string(componentType) +
                    ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"";
    if (normalized) a += ",\"normalized\":true";
    accessors.push_back(a + extra + "}");
    return static_cast<int>(accessors.size()) - 1;
  }
  // Float attribute data: values.size() / components elements.
  int addFloats(const std::vector<float>& values, const std::string& type) {
    const std::size_t components = type == "SCALAR" ? 1 : static_cast<std::size_t>(type[3] - '0');
    const int view = addView(values.data(), values.size() * sizeof(float));
    return addAccessor(view, 5126, values.size() / components, type);
  }
  // Indices as unsigned byte (5121), short (5123) or int (5125).
  int addIndices(const std::vector<std::uint32_t>& values, int componentType = 5125) {
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t v : values) {
      const int size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
      for (int b = 0; b < size; ++b) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * b)));
    }
    return addAccessor(addView(bytes.data(), bytes.size()), componentType, values.size(), "SCALAR");
  }
  // A one-primitive mesh; `attributes` is JSON members, e.g. "\"POSITION\":0".
  int addMesh(const std::string& attributes, int indices = -1, int mode = 4, int material = -1) {
    std::string p = "{\"attributes\":{" + attributes + "}";
    if (indices >= 0) p += ",\"indices\":" + std::to_string(indices);
    if (mode != 4) p += ",\"mode\":" + std::to_string(mode);
    if (material >= 0) p += ",\"material\":" + std::to_string(material);
    meshes.push_back("{\"primitives\":[" + p + "}]}");
    return static_cast<int>(meshes.size()) - 1;
  }

  std::string json(BufferStorage storage, const std::string& binName = "data.bin") const {
    std::string buffer = "{\"byteLength\":" + std::to_string(bin_.size());
    if (storage == BufferStorage::kDataUri)
      buffer += ",\"uri\":\"data:application/octet-stream;base64," + base64(bin_) + "\"";
    if (storage == BufferStorage::kExternal) buffer += ",\"uri\":\"" + binName + "\"";
    buffer += "}";
    std::string s = "{\"asset\":{\"version\":\"2.0\"}";
    if (!extensionsRequired.empty()) {
      s += ",\"extensionsUsed\":" + jsonArray(extensionsRequired) +
           ",\"extensionsRequired\":" + jsonArray(extensionsRequired);
    }
    if (scene >= 0) s += ",\"scene\":" + std::to_string(scene);
    if (!scenes.empty()) s += ",\"scenes\":" + jsonArray(scenes);
    if (!nodes.empty()) s += ",\"nodes\":" + jsonArray(nodes);
    if (!meshes.empty()) s += ",\"meshes\":" + jsonArray(meshes);
    if (!materials.empty()) s += ",\"materials\":" + jsonArray(materials);
    if (!textures.empty()) s += ",\"textures\":" + jsonArray(textures);
    if (!images.empty()) s += ",\"images\":" + jsonArray(images);
    if (!samplers.empty()) s += ",\"samplers\":" + jsonArray(samplers);
    if (!bin_.empty() || !bufferViews.empty()) s += ",\"buffers\":[" + buffer + "]";
    if (!bufferViews.empty()) s += ",\"bufferViews\":" + jsonArray(bufferViews);
    if (!accessors.empty()) s += ",\"accessors\":" + jsonArray(accessors);
    return s + extraTopLevel + "}";
  }

  // The binary container: header, JSON chunk (space-padded), BIN chunk (zero-padded).
  std::vector<std::uint8_t> glb() const {
    std::string text = json(BufferStorage::kGlb);
    while (text.size() % 4 != 0) text += ' ';
    std::vector<std::uint8_t> bin = bin_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    const std::size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin.size());
    std::vector<std::uint8_t> out(total);
    std::size_t at = 0;
    auto put = [&](const void* data, std::size_t size) {
      std::memcpy(out.data() + at, data, size);
      at += size;
    };
    auto u32 = [&](std::uint32_t v) { put(&v, 4); };  // little-endian hosts only
    put("glTF", 4);
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);  // "JSON"
    put(text.data(), text.size());
    if (!bin.empty()) {
      u32(static_cast<std::uint32_t>(bin.size()));
      u32(0x004E4942u);  // "BIN\0"
      put(bin.data(), bin.size());
    }
    return out;
  }

  const std::vector<std::uint8_t>& bin() const { return bin_; }

  int scene = 0;  // -1: no "scene" property
  std::vector<std::string> scenes{"{\"nodes\":[0]}"};
  std::vector<std::string> nodes{"{\"mesh\":0}"};
  std::vector<std::string> meshes, materials, textures, images, samplers, bufferViews, accessors, extensionsRequired;
  std::string extraTopLevel;  // raw ",\"key\":value" members

 private:
  std::vector<std::uint8_t> bin_;
};

// A scratch directory per test, removed afterwards.
class GltfDir {
 public:
  GltfDir() {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps concurrent runs (say a native and a sanitizer build) apart.
    std::string name =
        std::string("prt_scene_tests_") + std::to_string(getpid()) + "_" + info->test_suite_name() + "_" + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  // Set PRT_KEEP_GLTF_TEST_FILES to keep the files for inspection.
  ~GltfDir() {
    if (std::getenv("PRT_KEEP_GLTF_TEST_FILES") != nullptr) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  GltfDir(const GltfDir&) = delete;
  GltfDir& operator=(const GltfDir&) = delete;

  std::string write(const std::string& name, const std::string& text) const {
    return write(name, std::vector<std::uint8_t>(text.begin(), text.end()));
  }
  std::string write(const std::string& name, const std::vector<std::uint8_t>& bytes) const {
    const std::filesystem::path p = path_ / name;
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return p.string();
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace prt::bake::test
