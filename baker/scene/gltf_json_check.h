// Checks of a glTF file's JSON that tinygltf does not make, run before it parses the file,
// so that what it would read as empty or silently default gets a message naming the
// problem: glTF 1.0 files (objects keyed by id where 2.0 has arrays), meshes whose
// `primitives` is not an array (errors), and materials whose fields have the wrong shape
// (warnings: the field is ignored, as tinygltf does, and the warning names material and field).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "prt/status.h"

namespace prt::bake {

// Checks `json` (the .gltf text or a .glb's JSON chunk; safe on untrusted input). Returns an
// error for a file that cannot be baked as glTF 2.0 for a reason tinygltf would misreport;
// appends one line per suspicious material field to *warnings. Text that is not valid JSON
// passes (tinygltf reports the syntax error itself).
Status checkGltfJson(std::string_view json, std::vector<std::string>* warnings);

}  // namespace prt::bake
