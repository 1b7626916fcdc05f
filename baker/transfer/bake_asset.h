// The baker as one library call: a loaded Scene in, an asset ready to encode out, with what
// a caller prints or logs about it. prt-bake's bake command is this call between argument
// parsing and writing; a sharded or remote bake calls the same function.
//
//   scene -> [glossy materials] -> optimizeMeshOrder -> local lighting defaults -> bakeTransfer
//         -> BakedAsset (chosen passes) -> [transfer codec] -> (asset, report)
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "baker/scene/glossy_materials.h"
#include "baker/biscale/id_map_synthesis.h"
#include "baker/scene/parametric_id_map.h"
#include "baker/scene/scene.h"
#include "baker/transfer/texel_bake.h"
#include "baker/transfer/transfer_bake.h"
#include "baker/unwrap/uv_unwrap.h"
#include "prt/asset.h"
#include "prt/status.h"
#include "prt/transfer_codec.h"

namespace prt::bake {

struct TextureSetPlan;  // texture_sets.h

// Transfer textures (docs/transfer-textures.md): the vector passes baked per texel over the
// scene's lightmap atlas (TEXCOORD_1, else TEXCOORD_0: chooseUvAtlas, else a generated one),
// one atlas for the scene, or one per object (texture sets: `sets`, texture_sets.h).
//
// How many atlases (docs/transfer-textures.md, "Texture sets"): kScene one for the whole scene
// (the glTF set, else a generated one); kObject one per object, each from its own UVs fitted
// to a square, else generated; kAuto the scene's one unless its sets are invalid only because
// objects overlap each other, or objects' texel densities differ by more than
// kMaxTexelDensityRatio, and then one per object.
enum class TextureSets { kAuto, kScene, kObject };
inline constexpr double kMaxTexelDensityRatio = 2.0;

struct TexelBakeSettings {
  int textureSize = 0;         // atlas side in texels (square), 1..kMaxAtlasSize; 0: from texelsPerUnit
  double texelsPerUnit = 0.0;  // texels per metre of surface when textureSize is 0; 0 too: 512 texels
  int padding = 2;             // gutter texels the atlas must keep between charts at that size
  int dilation = 3;            // gutter texels filled from the charts (texel_bake.h)
  bool keepVertexPasses = true;  // store the per-vertex vector passes as well (the panel compares them)
  // When neither UV set is a valid atlas: generate one (unwrapUvAtlas; its size, padding and
  // sideFromLayout come from the fields above). nullopt: fail instead.
  std::optional<UvUnwrapOptions> unwrap;
  // > 0: also bake and store the texels' TPFL visibility pass at this order (2..kMaxShOrder;
  // 2n - 1 for order-n lighting is exact, fewer bands an approximation: docs/transfer-textures.md,
  // "Glossy by the triple product"). Distant lighting only; the scene gets the glossy material
  // split (options.glossyMaterials) as with transfer.glossy, and the asset its specular materials.
  int visibilityOrder = 0;
  TextureSets sets = TextureSets::kAuto;
};

// The atlas side for `settings` on `scene`'s set `texcoord`: textureSize when given, else
// ceil(texelsPerUnit x sqrt(surface area / UV area)) so a metre of surface spans about
// texelsPerUnit texels. kInvalidArgument when the result is outside 1..kMaxAtlasSize (naming
// it: a limit is never clamped silently) or the set has no UV area.
Status texelAtlasSize(const Scene& scene, int texcoord, const TexelBakeSettings& settings, int* side);

struct AssetBakeOptions {
  // Order, samples, bounces, threads, progress; lighting.model picks distant or local.
  // With local lighting, lighting.center and .radius are ignored: see lightCenter/lightRadius.
  BakeOptions transfer;
  // Local lighting's sphere; each one not given comes from the scene (defaultLightingSphere).
  std::optional<Vec3> lightCenter;
  std::optional<float> lightRadius;
  // Which passes the asset stores (unshadowed and shadowed cost nothing extra to compute;
  // interreflected is computed only when stored).
  bool storeUnshadowed = true, storeShadowed = true, storeInterreflected = true;
  // With transfer.glossy or texels->visibilityOrder: the glossy material split (applied to the
  // scene before the bake). transfer.glossy stores the matrix passes: shadowed always,
  // interreflected when transfer.glossyBounces > 0.
  GlossyMaterialOptions glossyMaterials;
  std::optional<std::string> name;                 // default: the scene's name
  std::optional<TransferCodecSettings> compress;   // default: float32, uncompressed
  // The glossy matrix passes' setting, when it differs from `compress` (which must then be
  // set): their size and the client's relight cost follow their own trade-off.
  std::optional<TransferCodecSettings> compressMatrices;
  std::optional<TexelBakeSettings> texels;         // default: vertex passes only
  // Bi-scale radiance transfer (docs/bi-scale.md): an RTT file's bytes and its placement
  // through a UV set (the parametric id map), stored with the asset for the client's meso
  // scale; needs transfer.glossy (the matrices are the macro scale). Vertex bakes only (the
  // sharded bake refuses it).
  struct BiScale {
    std::vector<std::uint8_t> rtt;
    ParametricIdMap placement;
    // Set: the synthesised id map instead (docs/bi-scale.md, "Synthesised id map"), per
    // triangle (idMapSize 0: no UVs needed) or over one atlas of idMapSize texels a side (the
    // scene's UVs when they make a valid atlas, else one generated like --texels's, with
    // `unwrap`; not with texels: one atlas serves both, not yet); vertex tangents follow
    // patchTangent.
    std::optional<IdMapSettings> synthesised;
    int idMapSize = 0;
    std::optional<UvUnwrapOptions> unwrap = UvUnwrapOptions{};
  };
  std::optional<BiScale> biScale;
};

// One atlas of the texture set, in the asset's atlas order.
struct TexelAtlasReport {
  std::string object;        // what it covers: an object's name, or "the whole scene"
  int texcoord = -1;         // the glTF set its UVs come from (0 or 1), -1 when generated
  int size = 0;              // side, texels (square)
  std::size_t triangles = 0, charts = 0;
  std::uint64_t sampledTexels = 0;
  double texelsPerMetre = 0.0;  // sqrt(texels its triangles cover in UV / their surface area)
  std::optional<UvUnwrapReport> generated;
};

struct TexelBakeReport {
  // The glTF set used as the atlas (0 or 1), -1 when generated or when the atlases differ.
  int texcoord = -1;
  std::optional<UvUnwrapReport> generated;  // how the atlas was generated, when it was
  int size = 0;                      // the first atlas's side, texels
  std::vector<TexelAtlasReport> atlases;  // one per atlas
  std::string sets;                  // why one atlas or one per object, one line
  std::uint64_t texels = 0, sampledTexels = 0;
  std::size_t charts = 0;
  std::size_t normalMappedTexels = 0;  // sampled texels shaded with a normal map's normal
  std::vector<std::string> rejected;  // why the other UV set (or both, when generated) was not used
  int bounces = 0;
  int visibilityOrder = 0;           // the stored TPFL visibility pass's order; 0 without one
  std::vector<PassStats> passes;
};

struct CompressedPass {
  TransferKind kind = TransferKind::kUnshadowed;
  TransferForm form = TransferForm::kVector;
  TransferDomain domain = TransferDomain::kVertex;
  std::size_t floatBytes = 0, encodedBytes = 0;
  TransferEncodeReport codec;
};

struct AssetBakeReport {
  std::size_t vertices = 0, triangles = 0;
  LightingInfo lighting;  // as baked: local defaults filled in
  int bounces = 0;
  int glossyBounces = 0;
  std::vector<double> bounceEnergy;
  std::vector<PassStats> passes;
  std::size_t verticesOutsideLight = 0;  // local lighting only
  std::size_t tangentFallbacks = 0;      // bi-scale: vertices whose triangles have no UV area (any tangent)
  std::size_t placements = 0;            // bi-scale, synthesised id map: its cells
  int idMapSize = 0;                     // and its atlas's side (0: parametric)
  std::vector<CompressedPass> compressed;  // one per stored pass when options.compress is set
  std::optional<TexelBakeReport> texels;   // when options.texels is set
};

// Bakes `scene` (consumed: its arrays move into the asset) into `*asset`, deterministic for
// a given (scene, options). `started`, when set, is called once with the report's vertices,
// triangles and lighting filled in, before the long part. Errors: the bake's and the codec's,
// prefixed with the pass they belong to; with options.texels, when neither UV set is a valid
// atlas at the chosen size, the generator's (texels.unwrap) or, without it, kInvalidArgument
// giving each set's reason (a generated atlas splits vertices at its seams, before `started`);
// kInvalidArgument when a visibility pass is asked for under local lighting (before any work).
Status bakeAsset(Scene&& scene, const AssetBakeOptions& options, BakedAsset* asset, AssetBakeReport* report,
                 const std::function<void(const AssetBakeReport&)>& started = {});

// The steps bakeAsset takes just before and after bakeTransfer, shared with a sharded bake
// (baker/shard) that runs bakeTransfer's pieces itself. prepareVertexBake applies no glossy
// material split and picks no atlas: prepareAssetScene (below) does those first.
// Puts *scene in bake order (optimizeMeshOrder, grouped by `triangleGroup` when given: the
// texture sets' atlas per triangle, permuted with the triangles) and sets *transfer to the
// options bakeAsset passes to bakeTransfer (local lighting's sphere resolved, interreflection
// as stored).
void prepareVertexBake(const AssetBakeOptions& options, Scene* scene, BakeOptions* transfer,
                       std::vector<std::uint32_t>* triangleGroup = nullptr);

// The options prepareVertexBake sets for a scene already in bake order (`prepared`): what a
// sharded bake's shards use with the prepared scene the plan stored.
BakeOptions vertexBakeOptions(const AssetBakeOptions& options, const Scene& prepared);

// The asset bakeAsset makes of a finished vertex bake: the chosen passes of `result`, named
// and lit as `options` and `lighting` say, encoded with options.compress (reported in
// *compressed). Errors: the codec's, as bakeAsset reports them.
Status assembleVertexAsset(Scene&& scene, BakeResult&& result, const AssetBakeOptions& options,
                           const LightingInfo& lighting, BakedAsset* asset, std::vector<CompressedPass>* compressed);

// bakeAsset's preparation of `scene`, shared with a sharded bake's plan: the glossy material
// split (transfer.glossy or a texel visibility pass), the texture set (options.texels; *atlas
// left empty without), then prepareVertexBake grouped by atlas. Errors: the split's and planTextureSets'.
Status prepareAssetScene(const AssetBakeOptions& options, Scene* scene, BakeOptions* transfer, TextureSetPlan* atlas);

// The asset's atlases of a planned texture set on the prepared scene's `triangles`: each a
// run of triangles (plan.triangleAtlas, or all of them for one atlas), square at its size.
std::vector<TextureAtlas> texelAtlasesOf(const TextureSetPlan& plan, std::size_t triangles);

// The texel bake's options bakeAsset derives from options.texels (must be set) and the vertex
// bake's `transfer` (glossy off; progress named "texel ..." through transfer's, which must outlive them).
TexelBakeOptions texelBakeOptions(const AssetBakeOptions& options, const BakeOptions& transfer);

// The asset bakeAsset makes of a finished vertex bake and texel bake over `atlasUv` and
// `atlases` (options.texels set): assembleVertexAsset's, then the texel passes options stores,
// the atlases, coverage and normals. Errors: the codec's.
Status assembleTexelAsset(Scene&& scene, BakeResult&& vertex, TexelBakeResult&& texels, std::span<const Uv> atlasUv,
                          std::vector<TextureAtlas> atlases, const AssetBakeOptions& options, const LightingInfo& lighting,
                          BakedAsset* asset, std::vector<CompressedPass>* compressed);

}  // namespace prt::bake
