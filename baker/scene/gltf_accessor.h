// Bounds-checked reading of glTF accessors (vertex attributes and indices) out of the
// buffers tinygltf loaded. Every offset, stride and count is checked against the number of
// bytes actually loaded, not against the file's declared lengths: tinygltf leaves those
// checks to the caller, and a malformed file must give an error, never an out-of-bounds read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/status.h"

namespace tinygltf {
class Model;
}

namespace prt::bake {

// An accessor's elements converted to float, element-major.
struct FloatElements {
  int components = 0;  // 1 (SCALAR) … 4 (VEC4)
  std::size_t count = 0;
  std::vector<float> values;  // count × components
};

// Reads accessor `index` as floats: integer components are mapped to [0, 1] or [-1, 1] by
// glTF's rules when the accessor is `normalized`, converted as they are otherwise (as
// KHR_mesh_quantization allows); a missing bufferView reads as zeros and sparse
// substitutions are applied. Matrix types, unknown component types, counts above maxCount
// and byte ranges outside their bufferView or buffer are errors naming the accessor.
// Values are not checked for finiteness.
Status readFloatAccessor(const tinygltf::Model& model, int index, std::size_t maxCount, FloatElements* out);

// Reads a SCALAR unsigned byte, short or int accessor (primitive indices) with the same
// checks; the values are not compared with any vertex count.
Status readIndexAccessor(const tinygltf::Model& model, int index, std::size_t maxCount,
                         std::vector<std::uint32_t>* out);

}  // namespace prt::bake
