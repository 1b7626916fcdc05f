#include "baker/scene/uv_atlas_choice.h"

namespace prt::bake {

Status chooseUvAtlas(const Scene& scene, const UvAtlasTarget& target, UvAtlasChoice* out) {
  if (out == nullptr) return Status::error(StatusCode::kInvalidArgument, "chooseUvAtlas: no output");
  *out = UvAtlasChoice();
  for (int set : {1, 0}) {
    const std::string name = "TEXCOORD_" + std::to_string(set);
    const std::vector<Uv>& uvs = scene.texcoord[set];
    if (uvs.empty()) {
      const std::string& why = scene.texcoordAbsent[set];
      out->rejected.push_back(name + ": absent" + (why.empty() ? "" : " (" + why + ")"));
      continue;
    }
    UvAtlasReport report;
    if (Status s = checkUvAtlas(scene.positions, scene.indices, uvs, target, name, &report); !s.isOk()) return s;
    if (report.valid()) {
      out->texcoord = set;
      out->report = std::move(report);
      return Status::ok();
    }
    std::string line = name + ": " + report.summary();
    if (!report.problems.empty()) line += " (first: " + report.problems.front() + ")";
    out->rejected.push_back(line);
  }
  return Status::ok();
}

}  // namespace prt::bake
