#include "baker/scene/gltf_accessor.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

namespace prt::bake {
namespace {

// glTF buffers are little-endian; the baker runs on little-endian hosts (x86-64, arm64).
static_assert(std::endian::native == std::endian::little, "glTF buffers are read with memcpy");

// byteStride is at most 252 in valid files; this bound only keeps the size arithmetic
// below from overflowing on hostile ones.
constexpr std::uint64_t kMaxStride = std::uint64_t{1} << 32;

std::string accessorLabel(const tinygltf::Model& model, int index) {
  std::string s = "accessor " + std::to_string(index);
  const std::string& name = model.accessors[static_cast<std::size_t>(index)].name;
  if (!name.empty()) s += " ('" + name + "')";
  return s;
}

std::string bufferLabel(const tinygltf::Model& model, int index) {
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(index)];
  std::string s = "buffer " + std::to_string(index);
  if (!buffer.uri.empty() && buffer.uri.rfind("data:", 0) != 0) {
    s += " ('" + buffer.uri + "')";
  } else if (!buffer.name.empty()) {
    s += " ('" + buffer.name + "')";
  }
  return s;
}

Status fail(const std::string& message) { return Status::error(StatusCode::kInvalidArgument, message); }

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices (column padding rules) are never vertex data we read
  }
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// One component as float, normalised per glTF 2.0 §3.11 when asked.
float readComponent(const unsigned char* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float c = load<std::int8_t>(p);
      return normalized ? std::max(c / 127.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float c = load<std::uint8_t>(p);
      return normalized ? c / 255.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float c = load<std::int16_t>(p);
      return normalized ? std::max(c / 32767.0f, -1.0f) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float c = load<std::uint16_t>(p);
      return normalized ? c / 65535.0f : c;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      const double c = load<std::int32_t>(p);
      return static_cast<float>(normalized ? std::max(c / 2147483647.0, -1.0) : c);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const double c = load<std::uint32_t>(p);
      return static_cast<float>(normalized ? c / 4294967295.0 : c);
    }
    default: return load<float>(p);
  }
}

std::uint32_t readIndex(const unsigned char* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
    default: return load<std::uint32_t>(p);
  }
}

// Where `count` elements of `elementSize` bytes lie: `byteOffset` into bufferView `view`,
// `stride` bytes apart (the view's byteStride when `strided` and set, else packed).
struct Located {
  const unsigned char* first = nullptr;
  std::uint64_t stride = 0;
};

Status locate(const tinygltf::Model& model, const std::string& what, int view, std::uint64_t byteOffset,
              std::uint64_t count, std::uint64_t elementSize, bool strided, Located* out) {
  if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size()) {
    return fail(what + ": bufferView " + std::to_string(view) + " does not exist (the file has " +
                std::to_string(model.bufferViews.size()) + ")");
  }
  const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(view)];
  const std::string viewName = "bufferView " + std::to_string(view);
  if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size()) {
    return fail(what + ": " + viewName + " refers to buffer " + std::to_string(bv.buffer) + ", which does not exist");
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
  const std::uint64_t bufferSize = data.size();
  if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset) {
    return fail(what + ": " + viewName + " (byteOffset " + std::to_string(bv.byteOffset) + ", byteLength " +
                std::to_string(bv.byteLength) + ") reaches past the end of " + bufferLabel(model, bv.buffer) +
                ", which holds " + std::to_string(bufferSize) + " bytes");
  }
  std::uint64_t stride = elementSize;
  if (strided && bv.byteStride != 0) {
    if (bv.byteStride < elementSize || bv.byteStride > kMaxStride) {
      return fail(what + ": " + viewName + " has byteStride " + std::to_string(bv.byteStride) +
                  ", which does not fit elements of " + std::to_string(elementSize) + " bytes");
    }
    stride = bv.byteStride;
  }
  out->stride = stride;
  if (count == 0) return Status::ok();
  // Checked in two steps so that no sum can wrap around.
  const std::uint64_t span = (count - 1) * stride + elementSize;
  if (byteOffset > bv.byteLength || span > bv.byteLength - byteOffset) {
    return fail(what + ": " + std::to_string(count) + " elements of " + std::to_string(elementSize) + " bytes, " +
                std::to_string(stride) + " bytes apart from byteOffset " + std::to_string(byteOffset) +
                ", reach past the end of " + viewName + " (byteLength " + std::to_string(bv.byteLength) + ")");
  }
  out->first = data.data() + bv.byteOffset + byteOffset;
  return Status::ok();
}

// Calls store(element, bytes) for every stored element of accessor `index`: the dense
// elements first (none when the accessor has no bufferView), then sparse substitutions.
// Every byte range is checked before prepare() is called, so the caller allocates its
// output only for an accessor its buffers can actually back.
template <typename Prepare, typename Store>
Status forEachElement(const tinygltf::Model& model, int index, std::size_t maxCount, int elementSize, Prepare prepare,
                      Store store) {
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  const std::string what = accessorLabel(model, index);
  const std::uint64_t count = acc.count;
  const auto size = static_cast<std::uint64_t>(elementSize);
  Located dense;
  if (acc.bufferView >= 0) {
    if (Status s = locate(model, what, acc.bufferView, acc.byteOffset, count, size, true, &dense); !s.isOk()) return s;
  } else if (acc.bufferView != -1) {
    return fail(what + ": bufferView " + std::to_string(acc.bufferView) + " does not exist");
  }
  const auto& sparse = acc.sparse;
  Located indices;
  Located values;
  std::uint64_t sparseCount = 0;
  if (sparse.isSparse) {
    if (sparse.count < 1 || static_cast<std::uint64_t>(sparse.count) > count ||
        static_cast<std::uint64_t>(sparse.count) > maxCount) {
      return fail(what + ": sparse count " + std::to_string(sparse.count) + " is outside 1…" + std::to_string(count));
    }
    if (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      return fail(what + ": sparse indices have component type " + std::to_string(sparse.indices.componentType) +
                  "; glTF allows unsigned byte, short or int");
    }
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
      return fail(what + ": sparse byteOffset is negative");
    sparseCount = static_cast<std::uint64_t>(sparse.count);
    const auto indexSize = static_cast<std::uint64_t>(componentSize(sparse.indices.componentType));
    if (Status s =
            locate(model, what + " sparse indices", sparse.indices.bufferView,
                   static_cast<std::uint64_t>(sparse.indices.byteOffset), sparseCount, indexSize, false, &indices);
        !s.isOk()) {
      return s;
    }
    if (Status s = locate(model, what + " sparse values", sparse.values.bufferView,
                          static_cast<std::uint64_t>(sparse.values.byteOffset), sparseCount, size, false, &values);
        !s.isOk()) {
      return s;
    }
  }

  prepare();
  if (dense.first != nullptr) {
    for (std::uint64_t i = 0; i < count; ++i) store(static_cast<std::size_t>(i), dense.first + i * dense.stride);
  }
  for (std::uint64_t k = 0; k < sparseCount; ++k) {
    const std::uint32_t target = readIndex(indices.first + k * indices.stride, sparse.indices.componentType);
    if (target >= count) {
      return fail(what + ": sparse index " + std::to_string(target) + " is out of range (count " +
                  std::to_string(count) + ")");
    }
    store(static_cast<std::size_t>(target), values.first + k * values.stride);
  }
  return Status::ok();
}

Status checkAccessor(const tinygltf::Model& model, int index, std::size_t maxCount) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    return fail("accessor " + std::to_string(index) + " does not exist (the file has " +
                std::to_string(model.accessors.size()) + ")");
  }
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  if (acc.count > maxCount) {
    return fail(accessorLabel(model, index) + " has " + std::to_string(acc.count) + " elements, above the limit of " +
                std::to_string(maxCount));
  }
  if (componentSize(acc.componentType) == 0) {
    return fail(accessorLabel(model, index) + " has unknown component type " + std::to_string(acc.componentType));
  }
  return Status::ok();
}

}  // namespace

Status readFloatAccessor(const tinygltf::Model& model, int index, std::size_t maxCount, FloatElements* out) {
  *out = FloatElements();
  if (Status s = checkAccessor(model, index, maxCount); !s.isOk()) return s;
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  const int components = componentCount(acc.type);
  if (components == 0) {
    return fail(accessorLabel(model, index) + " has a matrix or unknown type; vertex data must be SCALAR or VEC2…VEC4");
  }
  const int size = componentSize(acc.componentType);
  std::vector<float> values;
  const Status s = forEachElement(
      model, index, maxCount, components * size,
      [&] { values.assign(acc.count * static_cast<std::size_t>(components), 0.0f); },
      [&](std::size_t i, const unsigned char* p) {
        for (int c = 0; c < components; ++c) {
          values[i * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] =
              readComponent(p + c * size, acc.componentType, acc.normalized);
        }
      });
  if (!s.isOk()) return s;
  out->components = components;
  out->count = acc.count;
  out->values = std::move(values);
  return Status::ok();
}

Status readIndexAccessor(const tinygltf::Model& model, int index, std::size_t maxCount,
                         std::vector<std::uint32_t>* out) {
  out->clear();
  if (Status s = checkAccessor(model, index, maxCount); !s.isOk()) return s;
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  if (acc.type != TINYGLTF_TYPE_SCALAR || (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                           acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                           acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    return fail(accessorLabel(model, index) +
                " cannot hold indices: glTF indices are SCALAR unsigned byte, short or int");
  }
  std::vector<std::uint32_t> values;
  const Status s = forEachElement(
      model, index, maxCount, componentSize(acc.componentType), [&] { values.assign(acc.count, 0); },
      [&](std::size_t i, const unsigned char* p) { values[i] = readIndex(p, acc.componentType); });
  if (!s.isOk()) return s;
  *out = std::move(values);
  return Status::ok();
}

}  // namespace prt::bake
