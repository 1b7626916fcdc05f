#include "baker/unwrap/uv_unwrap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "baker/unwrap/child_process.h"
#include "baker/unwrap/prtm_mesh.h"
#include "baker/unwrap/seam_split.h"
#include "baker/unwrap/smart_uv_project_script.h"
#include "baker/unwrap/unwrap_workspace.h"

namespace prt::bake {
namespace {

// Blender's island_margin accepts 0..1.
constexpr double kMaxMargin = 1.0;

// The first margin: P + 2 texels at the side (a gap must hold the padding plus a partly
// covered texel on either side, as the check rasterises conservatively). Blender scales the
// margin down with the packing, so the check decides and each retry doubles it.
double firstMargin(int padding, int side) { return std::min(kMaxMargin, (padding + 2.0) / side); }

std::string formatMargin(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", m);
  return text;
}

std::string installAdvice() {
  return "install it (apt-get install --no-install-recommends blender, as scripts/install-deps.sh does) or give "
         "its path (prt-bake --blender PATH), or give the glTF a valid TEXCOORD_1 lightmap atlas";
}

// Runs the script once; on success the per-corner UVs are in *uvs.
Status runBlender(const UvUnwrapOptions& o, UnwrapWorkspace& ws, const Scene& scene, double margin,
                  std::vector<Uv>* uvs, double* seconds) {
  const std::size_t triangles = scene.indices.size() / 3;
  const std::string atlas = ws.path(UnwrapWorkspace::kAtlas);
  std::remove(atlas.c_str());  // never read a previous attempt's result
  const std::vector<std::string> argv = {o.blender, "-b", "--factory-startup", "--python-exit-code", "3",
                                         "--python", ws.path(UnwrapWorkspace::kScript), "--",
                                         ws.path(UnwrapWorkspace::kMesh), atlas, formatMargin(margin)};
  const auto limit = std::chrono::milliseconds(static_cast<long long>(std::ceil(o.timeoutSeconds * 1000.0)));
  ChildResult r;
  const Status ran = runChild(argv, ws.path(UnwrapWorkspace::kLog), limit, &r,
                              [&ws](pid_t pid) { ws.setChild(pid); }, [&ws] { ws.setChild(0); });
  if (!ran.isOk()) {
    if (ran.code() == StatusCode::kNotFound) {
      return Status::error(StatusCode::kNotFound, "Blender not found (" + ran.message() +
                                                      "): generating a lightmap atlas needs Blender (3.4); " +
                                                      installAdvice());
    }
    return Status::error(ran.code(), "cannot run Blender to generate a lightmap atlas: " + ran.message());
  }
  *seconds = r.seconds;
  const std::string tail = logTail(ws.path(UnwrapWorkspace::kLog), 6);
  if (r.timedOut) {
    char limitText[32];
    std::snprintf(limitText, sizeof limitText, "%g", o.timeoutSeconds);
    return Status::error(StatusCode::kResourceExhausted,
                         "Blender's Smart UV Project ran past the time limit of " + std::string(limitText) + " s on " +
                             std::to_string(triangles) + " triangles and was killed (prt-bake --unwrap-timeout " +
                             "raises the limit)" + (tail.empty() ? "" : "; its last output: " + tail));
  }
  if (r.exitStatus != 0) {
    const std::string how = r.signal != 0 ? "was killed by signal " + std::to_string(r.signal) + " (" +
                                                std::string(strsignal(r.signal)) + ")"
                                          : "exited with status " + std::to_string(r.exitStatus);
    return Status::error(StatusCode::kUnavailable, "Blender (" + o.blender + ") failed generating a lightmap atlas: it " +
                                                       how + (tail.empty() ? ", printing nothing" : "; its last output: " + tail));
  }
  std::vector<Vec3> positions;
  if (Status s = readPrtmCorners(atlas, triangles, &positions, uvs); !s.isOk()) {
    return Status::error(StatusCode::kUnavailable, "Blender (" + o.blender + ") exited without a usable atlas: " +
                                                       s.message() + (tail.empty() ? "" : "; its last output: " + tail));
  }
  // Blender must have laid out our triangles, corner for corner: the corners map back by order.
  for (std::size_t c = 0; c < positions.size(); ++c) {
    const Vec3 a = positions[c], b = scene.positions[scene.indices[c]];
    if (std::memcmp(&a, &b, sizeof a) != 0) {
      return Status::error(StatusCode::kUnavailable,
                           "Blender (" + o.blender + ") returned a different mesh: corner " + std::to_string(c) +
                               " of its atlas is not where the scene's is");
    }
  }
  return Status::ok();
}

// Why an invalid layout cannot be fixed by a larger margin, and what to do instead.
std::string adviceFor(const UvAtlasReport& r) {
  std::string why;
  if (r.overlappingPairs > 0) {
    why = "Smart UV Project leaves overlapping islands where the mesh itself is broken (inconsistent winding, "
          "non-manifold or stacked pieces, as in reconstructed scans)";
  }
  if (r.degenerate > 0) {
    why += std::string(why.empty() ? "Smart UV Project" : " and") +
           " collapses sliver triangles to zero UV area (as in CAD exports)";
  }
  if (!why.empty()) {
    return why + "; repair the mesh (consistent winding, non-manifold pieces split off, slivers merged) or give the "
                 "glTF a valid TEXCOORD_1 lightmap atlas";
  }
  return "a larger texture size or a smaller atlas padding leaves more room for the gutter";
}

}  // namespace

Status unwrapUvAtlas(const Scene& scene, const UvUnwrapOptions& o, Scene* out, UvUnwrapReport* report) {
  *report = UvUnwrapReport{};
  const auto t0 = std::chrono::steady_clock::now();
  if (o.size < 1 || o.size > kMaxAtlasSize || o.padding < 0 || o.padding > kMaxAtlasPadding || o.maxAttempts < 1 ||
      !(o.timeoutSeconds > 0.0) || o.blender.empty()) {
    return Status::error(StatusCode::kInvalidArgument, "unwrapUvAtlas: options out of range");
  }
  if (scene.indices.empty() || scene.indices.size() % 3 != 0) {
    return Status::error(StatusCode::kInvalidArgument, "unwrapUvAtlas: the scene has no triangles");
  }
  UnwrapWorkspace ws;
  PRT_RETURN_IF_ERROR(ws.create());
  const std::string_view script = kSmartUvProjectScript;
  PRT_RETURN_IF_ERROR(writeScratchFile(ws.path(UnwrapWorkspace::kScript),
                                       {reinterpret_cast<const std::uint8_t*>(script.data()), script.size()}));
  PRT_RETURN_IF_ERROR(writePrtmMesh(ws.path(UnwrapWorkspace::kMesh), scene.positions, scene.indices));

  int side = o.size;
  double margin = firstMargin(o.padding, side);
  for (int attempt = 1;; ++attempt) {
    UvUnwrapAttempt a;
    a.margin = margin;
    std::vector<Uv> uvs;
    PRT_RETURN_IF_ERROR(runBlender(o, ws, scene, margin, &uvs, &a.seconds));
    Scene unwrapped;
    PRT_RETURN_IF_ERROR(splitSeams(scene, uvs, &unwrapped));
    if (o.sideFromLayout) PRT_RETURN_IF_ERROR(o.sideFromLayout(unwrapped, &side));
    a.side = side;
    UvAtlasTarget target;
    target.width = target.height = side;
    target.padding = o.padding;
    UvAtlasReport check;
    PRT_RETURN_IF_ERROR(checkUvAtlas(unwrapped.positions, unwrapped.indices, unwrapped.texcoord[1], target,
                                     "generated atlas", &check));
    a.result = check.summary();
    report->attempts.push_back(a);
    if (o.log) {
      char line[160];
      std::snprintf(line, sizeof line, "atlas attempt %d: Smart UV Project, margin %.4g, %dx%d: %.1f s, ", attempt,
                    margin, side, side, a.seconds);
      o.log(line + a.result);
    }
    if (check.valid()) {
      report->side = side;
      report->atlas = std::move(check);
      report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      *out = std::move(unwrapped);
      return Status::ok();
    }
    // Only a gutter that is too narrow gets better with a larger margin.
    const bool gutterOnly = check.nonFinite == 0 && check.outOfRange == 0 && check.degenerate == 0 &&
                            check.overlappingPairs == 0;
    const double next = std::min(kMaxMargin, 2.0 * std::max(margin, firstMargin(o.padding, side)));
    if (!gutterOnly || attempt >= o.maxAttempts || next <= margin) {
      std::string message = "the generated lightmap atlas (Blender Smart UV Project, " + std::to_string(attempt) +
                            (attempt == 1 ? " attempt" : " attempts") + ", last margin " + formatMargin(margin) +
                            ") is not valid at " + std::to_string(side) + "x" + std::to_string(side) + ", padding " +
                            std::to_string(o.padding) + ": " + check.summary();
      if (!check.problems.empty()) message += " (first: " + check.problems.front() + ")";
      return Status::error(StatusCode::kInvalidArgument, message + "; " + adviceFor(check));
    }
    margin = next;
  }
}

}  // namespace prt::bake
