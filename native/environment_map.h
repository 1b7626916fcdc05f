// Environment-map layouts and their SH projection, shared by `prt-bake probe`,
// `prt-bake shade` and the server's /api/lights.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "prt/image.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

enum class EnvLayout { kEquirect, kAngular, kCross };

// "equirect" | "angular" | "cross".
const char* layoutName(EnvLayout layout);

// Parses a layout name; the error lists the valid names.
Status parseLayout(std::string_view name, EnvLayout* out);

// The layout an image's aspect ratio implies (2:1 equirect, 1:1 angular, 4:3 or 3:4 cross),
// with the ratio in words in *aspect; nullopt if none.
std::optional<EnvLayout> guessLayout(int width, int height, const char** aspect);

// Projects `image` read as `layout` onto SH radiance coefficients of `order`.
Status projectLayout(EnvLayout layout, int order, const RgbImage& image, std::vector<Rgb>* out);

}  // namespace prt
