// The scene of a sharded bake, prepared once by `plan` (docs/scale-out.md): written beside
// the plan, read by every shard and merge instead of loading and preparing the glTF again,
// after checking that the scene's files are still the ones the plan was made from.
#pragma once

#include <span>
#include <string>

#include "baker/scene/scene.h"
#include "baker/shard/bake_plan.h"
#include "prt/status.h"

namespace prt::bake {

// Writes `scene` (prepared: glossy split, optimizeMeshOrder) and a texel plan's `atlasUv` to preparedScenePath(planPath),
// atomically, for the plan `plan` (its id set by encodeBakePlan). `inputs`: files it must not replace.
Status writePreparedScene(const BakePlan& plan, const std::string& planPath, const Scene& scene,
                          std::span<const Uv> atlasUv, std::span<const std::string> inputs);

// kInvalidArgument naming the scene and the file when a file of plan.sceneFiles has another
// size or CRC-32C than when the plan was made (the scene changed: make a new plan); the read's
// error (kNotFound for a missing one) naming it otherwise. Reads each file once, loads nothing.
Status checkSceneFiles(const BakePlan& plan);

// Reads the prepared scene of the plan at `planPath` into *scene (named plan.sceneName) and
// its atlas UVs into *atlasUv (one per vertex in a texel plan, else none):
// present, of this plan, checksums intact, its hash the plan's scene hash, its sizes the
// plan's. Errors name the file (kNotFound: missing, run plan again; kCorrupt and the
// container's codes: damaged; kInvalidArgument: another plan's).
Status readPreparedScene(const BakePlan& plan, const std::string& planPath, Scene* scene, std::vector<Uv>* atlasUv);

}  // namespace prt::bake
