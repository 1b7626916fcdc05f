#include "baker/cli/compress_lightings.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <system_error>

#include "native/environment_map.h"
#include "native/image_io.h"
#include "prt/sh_basis.h"
#include "prt/sh_rotation.h"
#include "prt/sh_zonal.h"

namespace prt {
namespace {

Mat3 rotationY(float deg) {
  const float a = deg * static_cast<float>(kPi) / 180.0f, c = std::cos(a), s = std::sin(a);
  Mat3 r;
  r.m[0][0] = c;
  r.m[0][2] = s;
  r.m[2][0] = -s;
  r.m[2][2] = c;
  return r;
}

Mat3 rotationX(float deg) {
  const float a = deg * static_cast<float>(kPi) / 180.0f, c = std::cos(a), s = std::sin(a);
  Mat3 r;
  r.m[1][1] = c;
  r.m[1][2] = -s;
  r.m[2][1] = s;
  r.m[2][2] = c;
  return r;
}

Status listExrFiles(const std::string& dir, std::vector<std::string>* out) {
  std::error_code ec;
  std::filesystem::directory_iterator it(dir, ec);
  if (ec) {
    const StatusCode code = ec == std::errc::no_such_file_or_directory || ec == std::errc::not_a_directory
                                ? StatusCode::kNotFound
                                : StatusCode::kIoError;
    return Status::error(code, "cannot list environment directory '" + dir + "': " + ec.message());
  }
  for (const auto& entry : it) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ext == ".exr" && entry.is_regular_file(ec)) out->push_back(entry.path().string());
  }
  std::sort(out->begin(), out->end());
  if (out->empty()) return Status::error(StatusCode::kNotFound, "no .exr files in environment directory '" + dir + "'");
  return Status::ok();
}

}  // namespace

Status makeTestLightings(const std::string& envDir, int order, std::vector<TestLighting>* out) {
  std::vector<std::string> files;
  if (Status s = listExrFiles(envDir, &files); !s.isOk()) return s;
  const std::size_t n2 = static_cast<std::size_t>(shCoeffCount(order));
  std::vector<TestLighting> lightings;
  for (const std::string& file : files) {
    RgbImage image;
    if (Status s = loadImage(file, &image); !s.isOk()) return s;
    const char* aspect = "";
    const std::optional<EnvLayout> layout = guessLayout(image.width, image.height, &aspect);
    if (!layout) return Status::error(StatusCode::kInvalidArgument, "'" + file + "': cannot guess its layout from its aspect ratio");
    std::vector<Rgb> coeffs;
    if (Status s = projectLayout(*layout, order, image, &coeffs); !s.isOk()) return s;
    const std::string name = std::filesystem::path(file).filename().string();
    for (const EnvRotation& r : kTestEnvRotations) {
      ShRotation rotation;
      if (Status s = ShRotation::make(order, rotationX(r.tiltDeg) * rotationY(r.yawDeg), &rotation); !s.isOk()) return s;
      TestLighting l;
      l.name = name + " yaw " + std::to_string(static_cast<int>(r.yawDeg)) + " tilt " + std::to_string(static_cast<int>(r.tiltDeg));
      l.coeffs.resize(n2);
      if (Status s = rotation.apply(coeffs, l.coeffs); !s.isOk()) return s;
      lightings.push_back(std::move(l));
    }
  }
  const struct {
    const char* name;
    Vec3 axis;
  } caps[] = {{"cap +y", {0, 1, 0}},          {"cap -y", {0, -1, 0}},          {"cap +x+y", {1, 1, 0}},
              {"cap -x+z", {-1, 0.3f, 1}},    {"cap +z-x low", {-0.4f, 0.1f, 1}}, {"cap -z+y", {0.2f, 0.7f, -1}}};
  std::vector<float> zonal(static_cast<std::size_t>(order)), placed(n2);
  if (Status s = zonalCircularLight(order, kTestCapRadius, 1.0f, zonal); !s.isOk()) return s;
  for (const auto& cap : caps) {
    if (Status s = placeZonal(order, zonal, cap.axis, placed); !s.isOk()) return s;
    TestLighting l;
    l.name = cap.name;
    for (float c : placed) l.coeffs.push_back(Rgb{c, c, c});
    lightings.push_back(std::move(l));
  }
  *out = std::move(lightings);
  return Status::ok();
}

}  // namespace prt
