#include "baker/transfer/texture_sets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "baker/scene/uv_atlas_choice.h"
#include "baker/scene/uv_atlas_sets.h"
#include "baker/unwrap/uv_unwrap.h"

namespace prt::bake {
namespace {

std::string setName(int set) { return "TEXCOORD_" + std::to_string(set); }

std::string absentLine(const Scene& scene, int set) {
  return setName(set) + ": absent" + (scene.texcoordAbsent[set].empty() ? "" : " (" + scene.texcoordAbsent[set] + ")");
}

bool fromTexelsPerUnit(const TexelBakeSettings& t) {
  return t.textureSize == 0 && t.texelsPerUnit > 0.0 && std::isfinite(t.texelsPerUnit);
}

// ---- one atlas for the whole scene (the behaviour before texture sets) -----------------

// The glTF set to bake texels over, at the side it is baked at; choice->texcoord -1 when
// neither is a valid atlas, with each set's reason in *rejected.
Status chooseSceneSet(const Scene& scene, const TexelBakeSettings& t, UvAtlasChoice* choice, int* side,
                      std::vector<std::string>* rejected) {
  // The atlas must be valid at the size it will be baked at, and the size from
  // --texels-per-unit depends on the set: try each set at its own size, TEXCOORD_1 first.
  *choice = UvAtlasChoice();
  for (int set : {1, 0}) {
    if (scene.texcoord[set].empty()) {
      rejected->push_back(absentLine(scene, set));
      continue;
    }
    int size = 0;
    if (Status s = texelAtlasSize(scene, set, t, &size); !s.isOk()) {
      rejected->push_back(setName(set) + ": " + s.message());
      continue;
    }
    UvAtlasTarget target;
    target.width = target.height = size;
    target.padding = t.padding;
    UvAtlasChoice c;
    PRT_RETURN_IF_ERROR(chooseUvAtlas(scene, target, &c));
    if (c.texcoord == set) {
      *choice = std::move(c);
      *side = size;
      return Status::ok();
    }
    for (const std::string& line : c.rejected) {
      if (line.rfind(setName(set), 0) == 0) rejected->push_back(line);
    }
  }
  return Status::ok();
}

// Replaces *scene by one with a generated atlas as TEXCOORD_1; `side` the first guess, or,
// from texels per unit, the guess the layout then corrects.
Status generateAtlas(const TexelBakeSettings& t, int side, Scene* scene, TexelAtlasReport* atlas) {
  UvUnwrapOptions o = *t.unwrap;
  o.padding = t.padding;
  o.size = side;
  if (fromTexelsPerUnit(t)) {
    // The side follows the layout's UV area; the first guess assumes it fills half the square.
    o.size = static_cast<int>(std::clamp(std::ceil(t.texelsPerUnit * std::sqrt(2.0 * surfaceArea(*scene))), 1.0,
                                         static_cast<double>(kMaxAtlasSize)));
    o.sideFromLayout = [&t](const Scene& unwrapped, int* s) { return texelAtlasSize(unwrapped, 1, t, s); };
  }
  Scene unwrapped;
  UvUnwrapReport report;
  PRT_RETURN_IF_ERROR(unwrapUvAtlas(*scene, o, &unwrapped, &report));
  *scene = std::move(unwrapped);
  atlas->texcoord = -1;
  atlas->size = report.side;
  atlas->charts = report.atlas.charts;
  atlas->generated = std::move(report);
  return Status::ok();
}

std::string noValidSetError(const std::string& what, const std::vector<std::string>& rejected) {
  std::string message = "no UV set is a valid lightmap atlas for transfer textures" + what;
  for (const std::string& line : rejected) message += "; " + line;
  return message + " (docs/transfer-textures.md: give the glTF a TEXCOORD_1 lightmap atlas)";
}

Status planSceneAtlas(const TexelBakeSettings& t, const UvAtlasChoice& choice, int side, Scene* scene,
                      TextureSetPlan* plan) {
  TexelAtlasReport atlas;
  atlas.object = "the whole scene";
  atlas.triangles = scene->indices.size() / 3;
  if (choice.texcoord >= 0) {
    atlas.texcoord = choice.texcoord;
    atlas.size = side;
    atlas.charts = choice.report.charts;
    plan->texcoord = choice.texcoord;
  } else {
    if (!t.unwrap) return Status::error(StatusCode::kInvalidArgument, noValidSetError("", plan->rejected));
    int guess = 512;
    if (!fromTexelsPerUnit(t)) PRT_RETURN_IF_ERROR(texelAtlasSize(*scene, -1, t, &guess));
    PRT_RETURN_IF_ERROR(generateAtlas(t, guess, scene, &atlas));
    plan->texcoord = 1;
  }
  plan->atlases = {std::move(atlas)};
  return Status::ok();
}

// ---- one atlas per object ---------------------------------------------------------------

// One object's piece of the scene and the atlas it gets.
struct ObjectAtlas {
  Scene part;
  double surface = 0.0;
  double fittedUvArea[2] = {0.0, 0.0};  // of each set after fitUvsToSquare (0: absent)
  TexelAtlasReport atlas;
  std::vector<std::string> rejected;
};

// The side that gives object `o` the texel density of the whole set: from texels per unit
// (texelAtlasSize over the fitted set), or a share of a total budget of N² texels (N the
// texture size, 512 by default) with the same texels per metre on every object.
Status objectSide(const TexelBakeSettings& t, const ObjectAtlas& o, int set, double budgetDensity, int* side) {
  const double area = set >= 0 ? o.fittedUvArea[set] : 0.5;  // a generated layout: about half the square
  if (!(area > 0.0)) return Status::error(StatusCode::kInvalidArgument, "the UV set has no area");
  if (fromTexelsPerUnit(t)) {
    if (set >= 0) return texelAtlasSize(o.part, set, t, side);
    *side = static_cast<int>(std::clamp(std::ceil(t.texelsPerUnit * std::sqrt(o.surface / area)), 1.0,
                                        static_cast<double>(kMaxAtlasSize)));
    return Status::ok();
  }
  const double wanted = std::ceil(std::sqrt(budgetDensity * o.surface / area));
  *side = static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(kMaxAtlasSize)));
  return Status::ok();
}

// Texels per square metre that spread a budget of side² texels over the objects.
double budgetDensity(const TexelBakeSettings& t, const std::vector<ObjectAtlas>& objects) {
  const double side = t.textureSize != 0 ? t.textureSize : 512.0;
  double need = 0.0;  // sum of surface / UV area: texels needed per unit density
  for (const ObjectAtlas& o : objects) {
    const double area = o.fittedUvArea[1] > 0.0 ? o.fittedUvArea[1] : o.fittedUvArea[0] > 0.0 ? o.fittedUvArea[0] : 0.5;
    need += o.surface / area;
  }
  return need > 0.0 ? side * side / need : 0.0;
}

// Picks object o's own glTF set (TEXCOORD_1, then 0, each fitted to the square and checked at
// its side); o.atlas.texcoord stays -1 when neither is valid, with the reasons in o.rejected.
Status chooseObjectSet(const TexelBakeSettings& t, double density, ObjectAtlas* o) {
  for (int set : {1, 0}) {
    const std::string label = o->atlas.object + ": " + setName(set);
    if (o->part.texcoord[set].empty()) {
      o->rejected.push_back(o->atlas.object + ": " + absentLine(o->part, set));
      continue;
    }
    int side = 0;
    if (Status s = objectSide(t, *o, set, density, &side); !s.isOk()) {
      o->rejected.push_back(label + ": " + s.message());
      continue;
    }
    UvAtlasTarget target;
    target.width = target.height = side;
    target.padding = t.padding;
    UvAtlasReport report;
    PRT_RETURN_IF_ERROR(checkUvAtlas(o->part.positions, o->part.indices, o->part.texcoord[set], target, setName(set), &report));
    if (report.valid()) {
      o->atlas.texcoord = set;
      o->atlas.size = side;
      o->atlas.charts = report.charts;
      return Status::ok();
    }
    std::string line = label + ": " + report.summary();
    if (!report.problems.empty()) line += " (first: " + report.problems.front() + ")";
    o->rejected.push_back(line);
  }
  return Status::ok();
}

// Every object's part with its sets fitted and its own set chosen (no generation yet).
Status chooseObjectSets(const TexelBakeSettings& t, const Scene& scene, const SceneObjects& objects,
                        std::vector<ObjectAtlas>* out) {
  out->clear();
  out->resize(objects.triangles.size());
  for (std::size_t k = 0; k < objects.triangles.size(); ++k) {
    ObjectAtlas& o = (*out)[k];
    o.part = scenePart(scene, objects.triangles[k]);
    o.surface = surfaceArea(o.part);
    o.atlas.object = objects.names[k];
    o.atlas.triangles = objects.triangles[k].size();
    for (int set = 0; set < 2; ++set) {
      if (o.part.texcoord[set].empty()) continue;
      fitUvsToSquare(o.part, &o.part.texcoord[set]);
      o.fittedUvArea[set] = uvArea(o.part, o.part.texcoord[set]);
    }
  }
  const double density = budgetDensity(t, *out);
  for (ObjectAtlas& o : *out) PRT_RETURN_IF_ERROR(chooseObjectSet(t, density, &o));
  return Status::ok();
}

// Generates the atlases the objects lack, then puts the parts back together, atlas after
// atlas, each part's atlas UVs in texcoord[1].
Status planObjectAtlases(const TexelBakeSettings& t, std::vector<ObjectAtlas>&& objects, Scene* scene,
                         TextureSetPlan* plan) {
  const double density = budgetDensity(t, objects);
  for (ObjectAtlas& o : objects) {
    if (o.atlas.texcoord >= 0) continue;
    if (!t.unwrap) {
      return Status::error(StatusCode::kInvalidArgument, noValidSetError(" of " + o.atlas.object, o.rejected));
    }
    int guess = 0;
    PRT_RETURN_IF_ERROR(objectSide(t, o, -1, density, &guess));
    if (Status s = generateAtlas(t, guess, &o.part, &o.atlas); !s.isOk()) {
      return Status::error(s.code(), o.atlas.object + ": " + s.message());
    }
  }
  constexpr std::size_t kListedObjectLines = 8;
  std::size_t objectLines = 0;
  Scene assembled;
  plan->triangleAtlas.clear();
  plan->atlases.clear();
  for (std::size_t k = 0; k < objects.size(); ++k) {
    ObjectAtlas& o = objects[k];
    if (o.atlas.texcoord == 0) o.part.texcoord[1] = o.part.texcoord[0];
    // TEXCOORD_0 no longer means one thing across parts (fitted here, raw there): drop it.
    o.part.texcoord[0].clear();
    plan->triangleAtlas.insert(plan->triangleAtlas.end(), o.part.indices.size() / 3, static_cast<std::uint32_t>(k));
    // A thousand instances would repeat one reason a thousand times: list the first few.
    for (std::string& line : o.rejected) {
      if (++objectLines <= kListedObjectLines) plan->rejected.push_back(std::move(line));
    }
    plan->atlases.push_back(std::move(o.atlas));
    appendScenePart(&assembled, std::move(o.part));
  }
  if (objectLines > kListedObjectLines) {
    plan->rejected.push_back("(" + std::to_string(objectLines - kListedObjectLines) + " more objects' UV sets not used)");
  }
  assembled.texcoordAbsent[0] = "replaced by the objects' atlases";
  *scene = std::move(assembled);
  plan->texcoord = 1;
  return Status::ok();
}

// max / min over objects of sqrt(UV area / surface area) in `uvs` (the texel density one
// atlas would give each), and the two objects' names; 1 with fewer than two measurable objects.
double densityRatio(const Scene& scene, const SceneObjects& objects, int set, std::string* densest, std::string* sparsest) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t k = 0; k < objects.triangles.size(); ++k) {
    const Scene part = scenePart(scene, objects.triangles[k]);
    const double surface = surfaceArea(part), area = uvArea(part, part.texcoord[set]);
    if (!(surface > 0.0) || !(area > 0.0)) continue;
    const double d = std::sqrt(area / surface);
    if (lo == 0.0 || d < lo) lo = d, *sparsest = objects.names[k];
    if (d > hi) hi = d, *densest = objects.names[k];
  }
  return lo > 0.0 ? hi / lo : 1.0;
}

std::string ratioText(double r) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", r);
  return text;
}

}  // namespace

Status planTextureSets(const TexelBakeSettings& t, Scene* scene, TextureSetPlan* plan) {
  *plan = TextureSetPlan();
  const SceneObjects objects = sceneObjects(*scene);
  const std::size_t count = objects.triangles.size();
  const std::string objectsText = std::to_string(count) + (count == 1 ? " object" : " objects");
  if (t.sets == TextureSets::kObject) {
    if (count > kMaxAssetAtlases) {
      return Status::error(StatusCode::kInvalidArgument,
                           "--texture-sets object: the scene has " + objectsText + ", but an asset holds at most " +
                               std::to_string(kMaxAssetAtlases) + " atlases; the first past the limit is " +
                               objects.names[kMaxAssetAtlases] + " (use --texture-sets scene or auto)");
    }
    std::vector<ObjectAtlas> parts;
    PRT_RETURN_IF_ERROR(chooseObjectSets(t, *scene, objects, &parts));
    plan->reason = "one atlas per object (--texture-sets object, " + objectsText + ")";
    return planObjectAtlases(t, std::move(parts), scene, plan);
  }
  UvAtlasChoice choice;
  int side = 0;
  PRT_RETURN_IF_ERROR(chooseSceneSet(*scene, t, &choice, &side, &plan->rejected));
  const bool splittable = t.sets == TextureSets::kAuto && count > 1 && count <= kMaxAssetAtlases;
  if (choice.texcoord >= 0) {
    std::string densest, sparsest;
    const double ratio = splittable ? densityRatio(*scene, objects, choice.texcoord, &densest, &sparsest) : 1.0;
    if (ratio > kMaxTexelDensityRatio) {
      std::vector<ObjectAtlas> parts;
      PRT_RETURN_IF_ERROR(chooseObjectSets(t, *scene, objects, &parts));
      plan->reason = "one atlas per object (" + objectsText + "): in " + setName(choice.texcoord) + " " + densest +
                     " has " + ratioText(ratio) + "x the texels per metre of " + sparsest + " (more than " +
                     ratioText(kMaxTexelDensityRatio) + "x wastes texels)";
      return planObjectAtlases(t, std::move(parts), scene, plan);
    }
    plan->reason = "one atlas: " + setName(choice.texcoord) + " is valid for the whole scene";
    if (t.sets == TextureSets::kScene) plan->reason += " (--texture-sets scene)";
    return planSceneAtlas(t, choice, side, scene, plan);
  }
  if (splittable) {
    // Invalid as one atlas: if some object's own set is valid alone, the objects overlap each
    // other (instances, or each its own [0, 1] lightmap) and each gets its own atlas.
    std::vector<ObjectAtlas> parts;
    PRT_RETURN_IF_ERROR(chooseObjectSets(t, *scene, objects, &parts));
    const auto valid = static_cast<std::size_t>(
        std::count_if(parts.begin(), parts.end(), [](const ObjectAtlas& o) { return o.atlas.texcoord >= 0; }));
    if (valid > 0) {
      plan->reason = "one atlas per object: no UV set is valid for the whole scene, but " + std::to_string(valid) +
                     " of " + objectsText + " have a valid one alone (objects overlap each other)";
      return planObjectAtlases(t, std::move(parts), scene, plan);
    }
  }
  plan->reason = t.sets == TextureSets::kScene ? "one atlas (--texture-sets scene)"
                 : count > kMaxAssetAtlases
                     ? "one atlas: " + objectsText + " are more than the " + std::to_string(kMaxAssetAtlases) + " atlases an asset holds"
                 : count > 1 ? "one atlas: no object has a valid UV set of its own either"
                             : "one atlas: the scene is one object";
  return planSceneAtlas(t, choice, side, scene, plan);
}

}  // namespace prt::bake
