#include "native/environment_map.h"

#include <string>

#include "prt/cubemap.h"
#include "prt/sh_project.h"

namespace prt {

const char* layoutName(EnvLayout layout) {
  switch (layout) {
    case EnvLayout::kEquirect: return "equirect";
    case EnvLayout::kAngular: return "angular";
    case EnvLayout::kCross: return "cross";
  }
  return "unknown";
}

Status parseLayout(std::string_view name, EnvLayout* out) {
  for (EnvLayout l : {EnvLayout::kEquirect, EnvLayout::kAngular, EnvLayout::kCross}) {
    if (name == layoutName(l)) {
      *out = l;
      return Status::ok();
    }
  }
  return Status::error(StatusCode::kInvalidArgument,
                       "unknown --format '" + std::string(name) + "' (expected equirect, angular or cross)");
}

std::optional<EnvLayout> guessLayout(int w, int h, const char** aspect) {
  if (w == 2 * h) { *aspect = "2:1"; return EnvLayout::kEquirect; }
  if (w == h) { *aspect = "1:1"; return EnvLayout::kAngular; }
  if (3 * w == 4 * h) { *aspect = "4:3"; return EnvLayout::kCross; }
  if (4 * w == 3 * h) { *aspect = "3:4"; return EnvLayout::kCross; }
  return std::nullopt;
}

Status projectLayout(EnvLayout layout, int order, const RgbImage& image, std::vector<Rgb>* out) {
  switch (layout) {
    case EnvLayout::kEquirect: return projectEquirect(order, image, out);
    case EnvLayout::kAngular: return projectAngularMap(order, image, out);
    case EnvLayout::kCross: {
      CubeMap cube;
      if (Status s = cubeMapFromCross(image, &cube); !s.isOk()) return s;
      return projectCubeMap(order, cube, out);
    }
  }
  return Status::error(StatusCode::kInvalidArgument, "unknown layout");
}

}  // namespace prt
