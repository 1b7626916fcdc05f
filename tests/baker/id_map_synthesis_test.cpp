// The synthesised id map (baker/biscale/id_map_synthesis.h) on a unit sphere and a plane with
// their own atlases, rasterised for real: coverage, gutters, q's continuity and scale inside a
// cell, the frames, the cells' size, the phases, determinism, refusals; its time on the
// default scene is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <vector>

#include "baker/biscale/id_map_synthesis.h"
#include "baker/scene/default_scene.h"
#include "baker/test_scenes.h"
#include "baker/texture/atlas_samples.h"
#include "prt/patch_placement.h"

namespace prt::bake {
namespace {

struct Mesh {
  Scene scene;
  std::vector<Uv> uv;
  std::vector<TextureAtlas> atlases;
};

// Unit sphere (poles ±y), 64 × 32 quads, latitude-longitude UVs over the whole atlas.
Mesh unitSphere(std::uint32_t side) {
  Mesh m;
  constexpr int kSlices = 64, kStacks = 32;
  test::addSphere(&m.scene, {0, 0, 0}, 1.0f, kSlices, kStacks, {0.5f, 0.5f, 0.5f});
  for (int j = 0; j <= kStacks; ++j)
    for (int i = 0; i <= kSlices; ++i) m.uv.push_back({static_cast<float>(i) / kSlices, static_cast<float>(j) / kStacks});
  m.atlases = {{side, side, 0, static_cast<std::uint32_t>(m.scene.indices.size() / 3)}};
  return m;
}

// The 2 × 2 m square y = 0 (normal +y), 8 × 8 quads, mapped to UVs [0.1, 0.9]²: gutters all round.
Mesh plane(std::uint32_t side) {
  Mesh m;
  constexpr int kQuads = 8;
  test::addPlane(&m.scene, 1.0f, kQuads, 0.0f, {0.5f, 0.5f, 0.5f});
  for (int j = 0; j <= kQuads; ++j)
    for (int i = 0; i <= kQuads; ++i) m.uv.push_back({0.1f + 0.8f * i / kQuads, 0.1f + 0.8f * j / kQuads});
  m.atlases = {{side, side, 0, static_cast<std::uint32_t>(m.scene.indices.size() / 3)}};
  return m;
}

Status synthesise(const Mesh& m, const IdMapSettings& s, SynthesisedIdMap* out) {
  return synthesiseIdMap(m.scene.positions, m.scene.normals, m.scene.indices, m.uv, m.atlases, s, out);
}

AtlasSamples samplesOf(const Mesh& m) {
  AtlasSamples samples;
  const std::vector<Rgb> albedo(m.scene.positions.size());
  EXPECT_TRUE(rasteriseAtlases(m.scene.positions, m.scene.normals, albedo, m.scene.indices, m.uv, m.atlases, &samples).isOk());
  return samples;
}

struct DVec {
  double x, y, z;
};
DVec toD(Vec3 a) { return {a.x, a.y, a.z}; }
double dotD(DVec a, DVec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DVec sub(DVec a, DVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DVec crossD(DVec a, DVec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lenD(DVec a) { return std::sqrt(dotD(a, a)); }
// The difference of two values in [0, 1) taken modulo 1, in [-0.5, 0.5).
double wrapped(double d) { return d - std::floor(d + 0.5); }

constexpr double kSpherePatch = 0.1, kPlanePatch = 0.05, kCellPatches = 3;

IdMapSettings settings(double patchWidth, std::uint64_t seed = 1) {
  IdMapSettings s;
  s.patchWidth = patchWidth;
  s.cellPatches = kCellPatches;
  s.seed = seed;
  return s;
}

TEST(IdMapSynthesis, EverySampledTexelHasAPlacement) {
  for (const bool sphere : {true, false}) {
    const Mesh m = sphere ? unitSphere(256) : plane(256);
    SynthesisedIdMap map;
    ASSERT_TRUE(synthesise(m, settings(sphere ? kSpherePatch : kPlanePatch), &map).isOk());
    const AtlasSamples samples = samplesOf(m);
    ASSERT_EQ(map.placementOfTexel.size(), samples.sampled.size());
    ASSERT_GT(samples.texels.size(), 40000u);
    for (const AtlasTexel& t : samples.texels) {
      ASSERT_NE(map.placementOfTexel[t.index], kNoPlacement) << "texel " << t.index;
      ASSERT_LT(map.placementOfTexel[t.index], map.placements.size());
    }
    std::printf("%s: %zu placements over %zu sampled texels\n", sphere ? "unit sphere" : "plane", map.placements.size(),
                samples.texels.size());
  }
}

// The plane's chart is a rectangle, so each gutter texel's nearest sampled texel is its
// clamped position: within 3 texels (Chebyshev) it carries that texel's placement, beyond, none.
// `atlas` of `samples` is side × side texels from texel `first` on.
void expectRectangleGutters(const SynthesisedIdMap& map, const AtlasSamples& samples, std::uint32_t atlas, int side) {
  const std::uint64_t first = samples.firstTexel[atlas];
  int x0 = side, y0 = side, x1 = -1, y1 = -1;
  std::size_t count = 0;
  for (const AtlasTexel& t : samples.texels) {
    if (t.atlas != atlas) continue;
    x0 = std::min(x0, t.x), y0 = std::min(y0, t.y), x1 = std::max(x1, t.x), y1 = std::max(y1, t.y);
    ++count;
  }
  ASSERT_EQ(count, static_cast<std::size_t>((x1 - x0 + 1) * (y1 - y0 + 1)));  // a full rectangle
  int gutters = 0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int cx = std::clamp(x, x0, x1), cy = std::clamp(y, y0, y1);
      if (cx == x && cy == y) continue;
      const std::uint16_t got = map.placementOfTexel[first + static_cast<std::uint64_t>(y) * side + x];
      if (std::max(std::abs(cx - x), std::abs(cy - y)) <= 3) {
        ASSERT_EQ(got, map.placementOfTexel[first + static_cast<std::uint64_t>(cy) * side + cx]) << x << ", " << y;
        ++gutters;
      } else {
        ASSERT_EQ(got, kNoPlacement) << x << ", " << y;
      }
    }
  EXPECT_GT(gutters, 4 * 3 * (x1 - x0));
}

TEST(IdMapSynthesis, GuttersCopyTheNearestSampledTexel) {
  const Mesh m = plane(256);
  SynthesisedIdMap map;
  ASSERT_TRUE(synthesise(m, settings(kPlanePatch), &map).isOk());
  expectRectangleGutters(map, samplesOf(m), 0, 256);
}

// Two objects, two atlases (a texture set each): the sphere's 128² atlas, then the plane's
// 256², texels numbered atlas after atlas. The sphere floats 3 m above the plane, so no cell
// spans both: each atlas uses placements of its own, the sphere's covers every texel, and the
// plane's gutters follow its own chart at its offset.
TEST(IdMapSynthesis, TwoAtlasesAreNumberedAtlasAfterAtlas) {
  Mesh m = unitSphere(128);
  const std::uint32_t sphereTriangles = static_cast<std::uint32_t>(m.scene.indices.size() / 3);
  const Mesh p = plane(256);
  const auto base = static_cast<std::uint32_t>(m.scene.positions.size());
  for (Vec3& v : m.scene.positions) v.y += 3.0f;
  m.scene.positions.insert(m.scene.positions.end(), p.scene.positions.begin(), p.scene.positions.end());
  m.scene.normals.insert(m.scene.normals.end(), p.scene.normals.begin(), p.scene.normals.end());
  for (std::uint32_t i : p.scene.indices) m.scene.indices.push_back(base + i);
  m.uv.insert(m.uv.end(), p.uv.begin(), p.uv.end());
  m.atlases = {{128, 128, 0, sphereTriangles},
               {256, 256, sphereTriangles, static_cast<std::uint32_t>(p.scene.indices.size() / 3)}};
  SynthesisedIdMap map;
  ASSERT_TRUE(synthesise(m, settings(kPlanePatch), &map).isOk());
  ASSERT_EQ(map.placementOfTexel.size(), 128u * 128u + 256u * 256u);
  const AtlasSamples samples = samplesOf(m);
  std::vector<int> atlasOf(map.placements.size(), -1);
  for (std::uint64_t i = 0; i < map.placementOfTexel.size(); ++i) {
    const std::uint16_t id = map.placementOfTexel[i];
    const int atlas = i < 128u * 128u ? 0 : 1;
    if (atlas == 0) {
      ASSERT_NE(id, kNoPlacement) << "sphere texel " << i;
    }
    if (id == kNoPlacement) continue;
    ASSERT_LT(id, map.placements.size());
    ASSERT_TRUE(atlasOf[id] == -1 || atlasOf[id] == atlas) << "placement " << id << " in both atlases";
    atlasOf[id] = atlas;
  }
  expectRectangleGutters(map, samples, 1, 256);
}

// Inside a cell q is the linear map of the placement: right and down neighbours of one
// placement differ in q (modulo 1) by (dot(Δp, axisU), dot(Δp, axisV)) to 1e-4 relative (plus
// 1e-6 for float rounding of q), and on the plane that step's length is |Δp| / patchWidth. Few
// neighbour pairs cross a border: the cells are regions, not speckle.
TEST(IdMapSynthesis, QIsContinuousAndToScaleInsideACell) {
  for (const bool sphere : {true, false}) {
    const Mesh m = sphere ? unitSphere(256) : plane(256);
    const double width = sphere ? kSpherePatch : kPlanePatch;
    SynthesisedIdMap map;
    ASSERT_TRUE(synthesise(m, settings(width), &map).isOk());
    const AtlasSamples samples = samplesOf(m);
    std::vector<std::int64_t> sampleAt(samples.sampled.size(), -1);
    for (std::size_t k = 0; k < samples.texels.size(); ++k) sampleAt[samples.texels[k].index] = static_cast<std::int64_t>(k);
    std::size_t inside = 0, across = 0;
    double worst = 0;
    for (const AtlasTexel& a : samples.texels) {
      for (const std::uint64_t next : {a.index + 1, a.index + 256}) {
        if ((next == a.index + 1 && a.x == 255) || next >= sampleAt.size() || sampleAt[next] < 0) continue;
        const AtlasTexel& b = samples.texels[static_cast<std::size_t>(sampleAt[next])];
        const std::uint16_t id = map.placementOfTexel[a.index];
        if (map.placementOfTexel[b.index] != id) {
          ++across;
          continue;
        }
        ++inside;
        const PatchPlacement& p = map.placements[id];
        float ua, va, ub, vb;
        patchCoordinates(p, a.position, &ua, &va);
        patchCoordinates(p, b.position, &ub, &vb);
        const DVec dp = sub(toD(b.position), toD(a.position));
        const double eu = dotD(dp, toD(p.axisU)), ev = dotD(dp, toD(p.axisV));
        const double du = wrapped(double{ub} - ua), dv = wrapped(double{vb} - va);
        const double expected = std::hypot(eu, ev), error = std::hypot(du - eu, dv - ev);
        ASSERT_LE(error, 1e-4 * expected + 1e-6) << "texels " << a.index << ", " << b.index;
        if (!sphere) {
          ASSERT_NEAR(std::hypot(du, dv), lenD(dp) / width, 1e-4 * lenD(dp) / width + 1e-6);
        }
        if (expected > 1e-2) worst = std::max(worst, error / expected);
      }
    }
    const double borderFraction = static_cast<double>(across) / static_cast<double>(inside + across);
    std::printf("%s: %zu neighbour pairs in a cell (worst relative error of Δq where |Δq| > 0.01: %.2e), %.1f%% across a border\n",
                sphere ? "unit sphere" : "plane", inside, worst, 100 * borderFraction);
    EXPECT_GT(inside, 50000u);
    EXPECT_LT(borderFraction, 0.2);
  }
}

// Every placement's axes: orthogonal, each 1 / patchWidth long, axisU = patchTangent(n) and
// axisV = cross(n, axisU) with n their normal, and n the surface's normal at the seed: the
// seed is origin + (phase) in the tangent plane, so n · origin is the seed's distance from the
// sphere's centre (1 less the mesh's chordal sag: up to 1 - cos 4° = 2.4e-3 on its 5.6° quads;
// 5e-3 allowed) and the origin lies within √2 patch widths of the seed. On the plane n is +y.
TEST(IdMapSynthesis, AxesAreOrthonormalInTheSeedsTangentPlane) {
  for (const bool sphere : {true, false}) {
    const Mesh m = sphere ? unitSphere(256) : plane(256);
    const double w = sphere ? kSpherePatch : kPlanePatch;
    SynthesisedIdMap map;
    ASSERT_TRUE(synthesise(m, settings(w), &map).isOk());
    for (const PatchPlacement& p : map.placements) {
      const DVec u = toD(p.axisU), v = toD(p.axisV);
      ASSERT_NEAR(lenD(u) * w, 1.0, 1e-6);
      ASSERT_NEAR(lenD(v) * w, 1.0, 1e-6);
      ASSERT_NEAR(dotD(u, v) * w * w, 0.0, 1e-6);
      const DVec n = crossD(u, v);
      const double nl = lenD(n);
      const Vec3 normal{static_cast<float>(n.x / nl), static_cast<float>(n.y / nl), static_cast<float>(n.z / nl)};
      const Vec3 t = patchTangent(normal);
      ASSERT_NEAR(dotD(toD(t), u) * w, 1.0, 1e-5);
      if (sphere) {
        const DVec o = toD(p.origin), unitN{n.x / nl, n.y / nl, n.z / nl};
        const double along = dotD(o, unitN);
        ASSERT_NEAR(along, 1.0, 5e-3);
        const DVec off{o.x - along * unitN.x, o.y - along * unitN.y, o.z - along * unitN.z};
        ASSERT_LE(lenD(off), std::sqrt(2.0) * w + 1e-5);
      } else {
        ASSERT_NEAR(n.y / nl, 1.0, 1e-6);
        ASSERT_NEAR(p.origin.y, 0.0, 1e-6);
      }
    }
  }
}

// A cell's area from its texels (each texel the area its owner triangle gives a texel); its
// diameter the diameter of a disc of that area (the settings' definition). The mean is within a
// factor 1.5 of cellPatches × patchWidth. The mean extent (twice the farthest texel from the
// cell's centroid) is printed.
TEST(IdMapSynthesis, MeanCellDiameterMatchesTheSettings) {
  for (const bool sphere : {true, false}) {
    const Mesh m = sphere ? unitSphere(256) : plane(256);
    const double w = sphere ? kSpherePatch : kPlanePatch, target = kCellPatches * w;
    SynthesisedIdMap map;
    ASSERT_TRUE(synthesise(m, settings(w), &map).isOk());
    const AtlasSamples samples = samplesOf(m);
    const auto& pos = m.scene.positions;
    const auto& idx = m.scene.indices;
    std::vector<double> area(map.placements.size()), cx(map.placements.size()), cy(map.placements.size()),
        cz(map.placements.size()), count(map.placements.size());
    for (const AtlasTexel& t : samples.texels) {
      const std::uint32_t* c = &idx[3 * std::size_t{t.triangle}];
      const DVec a = toD(pos[c[0]]), b = toD(pos[c[1]]), d = toD(pos[c[2]]);
      const double world = 0.5 * lenD(crossD(sub(b, a), sub(d, a)));
      const Uv ua = m.uv[c[0]], ub = m.uv[c[1]], ud = m.uv[c[2]];
      const double texels = 0.5 * std::fabs((double{ub.u} - ua.u) * (double{ud.v} - ua.v) - (double{ud.u} - ua.u) * (double{ub.v} - ua.v)) * 256.0 * 256.0;
      const std::uint16_t id = map.placementOfTexel[t.index];
      area[id] += world / texels;
      cx[id] += t.position.x, cy[id] += t.position.y, cz[id] += t.position.z, count[id] += 1;
    }
    std::vector<double> extent(map.placements.size());
    for (const AtlasTexel& t : samples.texels) {
      const std::uint16_t id = map.placementOfTexel[t.index];
      const DVec c{cx[id] / count[id], cy[id] / count[id], cz[id] / count[id]};
      extent[id] = std::max(extent[id], 2 * lenD(sub(toD(t.position), c)));
    }
    double meanDiameter = 0, meanExtent = 0, total = 0;
    for (std::size_t i = 0; i < area.size(); ++i) {
      meanDiameter += 2 * std::sqrt(area[i] / kPi);
      meanExtent += extent[i];
      total += area[i];
    }
    meanDiameter /= static_cast<double>(area.size());
    meanExtent /= static_cast<double>(area.size());
    std::printf("%s: area %.3f in %zu cells, mean diameter %.4f (target %.4f), mean extent %.4f\n",
                sphere ? "unit sphere" : "plane", total, area.size(), meanDiameter, target, meanExtent);
    EXPECT_GT(meanDiameter, target / 1.5);
    EXPECT_LT(meanDiameter, target * 1.5);
  }
}

// Every placement's phase against one global lattice (the plane's axes are all equal): two
// cells whose phases match would continue each other's pattern. Few phases lie within 0.005
// of another's (random: about 1.8% at this count; one lattice for all: 100%), and nearly every
// pair of adjacent cells shows a phase jump at its border.
TEST(IdMapSynthesis, PhasesDifferFromCellToCell) {
  const Mesh m = plane(256);
  SynthesisedIdMap map;
  ASSERT_TRUE(synthesise(m, settings(kPlanePatch), &map).isOk());
  const std::size_t n = map.placements.size();
  std::vector<std::pair<double, double>> phase(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PatchPlacement& p = map.placements[i];
    const DVec o = toD(p.origin);
    phase[i] = {dotD(o, toD(p.axisU)) - std::floor(dotD(o, toD(p.axisU))), dotD(o, toD(p.axisV)) - std::floor(dotD(o, toD(p.axisV)))};
  }
  auto torus = [&](std::size_t i, std::size_t j) {
    return std::hypot(wrapped(phase[i].first - phase[j].first), wrapped(phase[i].second - phase[j].second));
  };
  std::size_t matched = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j && torus(i, j) < 0.005) {
        ++matched;
        break;
      }
  // Adjacent cells: placements of horizontally adjacent texels.
  std::map<std::pair<std::uint16_t, std::uint16_t>, bool> neighbours;
  for (std::size_t k = 0; k + 1 < map.placementOfTexel.size(); ++k) {
    const std::uint16_t a = map.placementOfTexel[k], b = map.placementOfTexel[k + 1];
    if (a != b && a != kNoPlacement && b != kNoPlacement && (k + 1) % 256 != 0) neighbours[{std::min(a, b), std::max(a, b)}] = true;
  }
  std::size_t jumps = 0;
  for (const auto& [pair, unused] : neighbours) jumps += torus(pair.first, pair.second) > 0.01;
  std::printf("plane: %zu of %zu phases within 0.005 of another; %zu of %zu adjacent cell pairs jump by > 0.01\n", matched, n,
              jumps, neighbours.size());
  EXPECT_LT(static_cast<double>(matched), 0.1 * static_cast<double>(n));
  EXPECT_GT(static_cast<double>(jumps), 0.9 * static_cast<double>(neighbours.size()));
}

TEST(IdMapSynthesis, SameSeedSameBytesOtherSeedOthers) {
  const Mesh m = unitSphere(128);
  SynthesisedIdMap a, b, c;
  ASSERT_TRUE(synthesise(m, settings(kSpherePatch, 42), &a).isOk());
  ASSERT_TRUE(synthesise(m, settings(kSpherePatch, 42), &b).isOk());
  ASSERT_TRUE(synthesise(m, settings(kSpherePatch, 43), &c).isOk());
  ASSERT_EQ(a.placements.size(), b.placements.size());
  EXPECT_EQ(std::memcmp(a.placements.data(), b.placements.data(), a.placements.size() * sizeof(PatchPlacement)), 0);
  EXPECT_EQ(a.placementOfTexel, b.placementOfTexel);
  EXPECT_NE(a.placementOfTexel, c.placementOfTexel);
  const std::size_t common = std::min(a.placements.size(), c.placements.size());
  EXPECT_NE(std::memcmp(a.placements.data(), c.placements.data(), common * sizeof(PatchPlacement)), 0);
}

TEST(IdMapSynthesis, BadSettingsAreRefusedByName) {
  const Mesh m = unitSphere(64);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  SynthesisedIdMap out;
  out.placements.resize(3);
  auto refused = [&](IdMapSettings s, const char* name) {
    const Status st = synthesise(m, s, &out);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(st.message().find(name), std::string::npos) << st.message();
    EXPECT_TRUE(out.placements.empty() && out.placementOfTexel.empty());
    return st.message();
  };
  for (const double bad : {0.0, -0.1, std::nan(""), kInf}) refused(settings(bad), "patchWidth");
  for (const double bad : {0.5, 0.0, std::nan(""), kInf}) {
    IdMapSettings s = settings(kSpherePatch);
    s.cellPatches = bad;
    refused(s, "cellPatches");
  }
  IdMapSettings gutter = settings(kSpherePatch);
  gutter.gutterTexels = -1;
  refused(gutter, "gutterTexels");
  // The mesh's 12.54 / (π/4 × 0.003²) = 1.774 million cells.
  const std::string many = refused(settings(0.001), "patchWidth");
  EXPECT_NE(many.find("65535"), std::string::npos) << many;
  EXPECT_NE(many.find("needs 1.774"), std::string::npos) << many;
  EXPECT_NE(many.find("cellPatches"), std::string::npos) << many;

  Mesh shortNormals = m;
  shortNormals.scene.normals.pop_back();
  EXPECT_EQ(synthesise(shortNormals, settings(kSpherePatch), &out).code(), StatusCode::kSizeMismatch);
  Mesh badIndex = m;
  badIndex.scene.indices[4] = 1u << 30;
  EXPECT_EQ(synthesise(badIndex, settings(kSpherePatch), &out).code(), StatusCode::kInvalidArgument);
  // A triangle collapsed to a point in space (its UVs still cover texels): nothing to place on.
  Mesh point;
  point.scene.positions = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  point.scene.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  point.scene.indices = {0, 1, 2};
  point.uv = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.1f, 0.9f}};
  point.atlases = {{16, 16, 0, 1}};
  const Status zero = synthesise(point, settings(kSpherePatch), &out);
  EXPECT_EQ(zero.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(zero.message().find("zero area"), std::string::npos) << zero.message();
}

// Not asserted: the time on the built-in room (one 512² atlas over its lightmap UVs), patches
// 5 cm wide, cells 15 cm across.
TEST(IdMapSynthesis, DefaultSceneTime) {
  const Scene scene = makeDefaultScene(512);
  ASSERT_EQ(scene.texcoord[1].size(), scene.positions.size());
  const std::vector<TextureAtlas> atlases = {{512, 512, 0, static_cast<std::uint32_t>(scene.indices.size() / 3)}};
  IdMapSettings s = settings(0.05);
  SynthesisedIdMap map;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(synthesiseIdMap(scene.positions, scene.normals, scene.indices, scene.texcoord[1], atlases, s, &map).isOk());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t covered = static_cast<std::size_t>(
      std::count_if(map.placementOfTexel.begin(), map.placementOfTexel.end(), [](std::uint16_t p) { return p != kNoPlacement; }));
  std::printf("default scene, 512² atlas: %.3f s, %zu placements (%zu bytes), %zu of %zu texels with a placement (%zu bytes)\n",
              seconds, map.placements.size(), map.placements.size() * sizeof(PatchPlacement), covered,
              map.placementOfTexel.size(), map.placementOfTexel.size() * sizeof(std::uint16_t));
  const AtlasSamples samples = [&] {
    AtlasSamples r;
    const std::vector<Rgb> albedo(scene.positions.size());
    EXPECT_TRUE(rasteriseAtlases(scene.positions, scene.normals, albedo, scene.indices, scene.texcoord[1], atlases, &r).isOk());
    return r;
  }();
  for (const AtlasTexel& t : samples.texels) ASSERT_NE(map.placementOfTexel[t.index], kNoPlacement);
}

}  // namespace
}  // namespace prt::bake
