#include "baker/scene/default_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "baker/scene/mesh_cleanup.h"

namespace prt::bake {
namespace {

constexpr float kCellsPerMetre = 16.0f;
constexpr float kRoomHalfWidth = 2.0f;  // x and z in [-2, 2]
constexpr float kRoomHeight = 3.0f;

// Albedos like real paints (all below 1) and each surface its own, so the
// colour bleeding in a bake can be traced to its source.
constexpr Rgb kFloor{0.75f, 0.75f, 0.75f};
constexpr Rgb kBackWall{0.75f, 0.72f, 0.68f};
constexpr Rgb kRedWall{0.75f, 0.10f, 0.08f};
constexpr Rgb kGreenWall{0.10f, 0.55f, 0.12f};
constexpr Rgb kSphere{0.80f, 0.80f, 0.80f};
constexpr Rgb kCube{0.80f, 0.50f, 0.12f};
constexpr Rgb kTallBox{0.30f, 0.45f, 0.75f};
constexpr Rgb kTorus{0.55f, 0.25f, 0.65f};

// The glossy part, read only by a glossy bake (docs/glossy.md): the room and the boxes are
// matte paint (no specular reflection at all, f0 = f90 = 0, so their shading does not depend
// on the view); the sphere is a polished white dielectric and the torus a purple metal.
constexpr PbrVertex kMatte{0.0f, 1.0f, {0.0f, 0.0f, 0.0f}, 0.0f};
constexpr PbrVertex kPolishedDielectric{0.0f, 0.3f, {0.04f, 0.04f, 0.04f}};
constexpr PbrVertex kBrushedMetal{1.0f, 0.4f, {0.04f, 0.04f, 0.04f}};

struct Surface {
  Rgb albedo;
  PbrVertex pbr = kMatte;
};

// One grid of the scene as a lightmap chart: its vertices base + j (nu + 1) + i and its
// extent in metres along i and j, so charts get texels in proportion to their surface.
struct Chart {
  std::uint32_t base = 0;
  int nu = 0, nv = 0;
  double width = 0, height = 0;  // metres
};

struct Vertex {
  Vec3 position;
  Vec3 normal;  // unit
};

// Rotation about +y, then translation: how each object is placed in the room.
struct Placement {
  Mat3 rotation;
  Vec3 offset;
  Vertex apply(Vertex v) const { return {rotation * v.position + offset, rotation * v.normal}; }
};

Placement place(float yawDegrees, Vec3 offset) {
  return {rotationAxisAngle({0, 1, 0}, yawDegrees * static_cast<float>(kPi / 180.0)), offset};
}

int cells(float metres) { return std::max(1, static_cast<int>(std::lround(metres * kCellsPerMetre))); }

Vec3 normalized(Vec3 v) { return v * (1.0f / length(v)); }

// Appends a (nu + 1) × (nv + 1) vertex grid, vertex (i, j) given by at(i, j), with two
// triangles per cell. Each triangle is wound counter-clockwise about the surface normal
// (the order is chosen per cell from the analytic normals, so callers need not get their
// parametrisation's handedness right), and triangles that collapse at a pole are skipped.
template <typename At>
void addGrid(Scene* s, std::vector<Chart>* charts, double width, double height, int nu, int nv, const Surface& surface,
             const Placement& where, At at) {
  const auto base = static_cast<std::uint32_t>(s->positions.size());
  charts->push_back({base, nu, nv, width, height});
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const Vertex v = where.apply(at(i, j));
      s->positions.push_back(v.position);
      s->normals.push_back(normalized(v.normal));
      s->albedo.push_back(surface.albedo);
      s->pbr.push_back(surface.pbr);
    }
  }
  const auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (nu + 1) + i); };
  const auto addTriangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Vec3 pa = s->positions[a], pb = s->positions[b], pc = s->positions[c];
    const Vec3 n = cross(pb - pa, pc - pa);
    if (length(n) < 1e-9f) return;  // a pole, where a whole grid row meets in one point
    const Vec3 shading = s->normals[a] + s->normals[b] + s->normals[c];
    if (dot(n, shading) >= 0) {
      s->indices.insert(s->indices.end(), {a, b, c});
    } else {
      s->indices.insert(s->indices.end(), {a, c, b});
    }
  };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      addTriangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      addTriangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
}

// A flat rectangle origin + s·edgeU + t·edgeV (s, t in [0, 1]) facing `normal`.
void addRectangle(Scene* s, std::vector<Chart>* charts, Vec3 origin, Vec3 edgeU, Vec3 edgeV, Vec3 normal,
                  const Surface& surface, const Placement& where) {
  addGrid(s, charts, length(edgeU), length(edgeV), cells(length(edgeU)), cells(length(edgeV)), surface, where, [&](int i, int j) {
    const float fu = static_cast<float>(i) / static_cast<float>(cells(length(edgeU)));
    const float fv = static_cast<float>(j) / static_cast<float>(cells(length(edgeV)));
    return Vertex{origin + edgeU * fu + edgeV * fv, normal};
  });
}

// A box resting on y = 0 with its own vertices on each face (sharp edges). The bottom face
// is left out: it lies on the floor, where no ray could reach it.
void addBox(Scene* s, std::vector<Chart>* charts, Vec3 size, const Surface& surface, const Placement& where) {
  const float hx = size.x / 2, hz = size.z / 2, h = size.y;
  const Vec3 x{size.x, 0, 0}, y{0, h, 0}, z{0, 0, size.z};
  addRectangle(s, charts, {-hx, h, -hz}, x, z, {0, 1, 0}, surface, where);   // top
  addRectangle(s, charts, {-hx, 0, hz}, x, y, {0, 0, 1}, surface, where);    // +z
  addRectangle(s, charts, {-hx, 0, -hz}, x, y, {0, 0, -1}, surface, where);  // -z
  addRectangle(s, charts, {hx, 0, -hz}, z, y, {1, 0, 0}, surface, where);    // +x
  addRectangle(s, charts, {-hx, 0, -hz}, z, y, {-1, 0, 0}, surface, where);  // -x
}

// A UV sphere; the seam column is duplicated with identical normals.
// Its chart is the equirectangular (phi, theta) map, 2 pi r by pi r.
void addSphere(Scene* s, std::vector<Chart>* charts, float radius, int segments, int rings, const Surface& surface,
               const Placement& where) {
  addGrid(s, charts, 2.0 * kPi * radius, kPi * radius, segments, rings, surface, where, [&](int i, int j) {
    const double phi = 2.0 * kPi * i / segments;
    const double theta = kPi * j / rings;
    const Vec3 n{static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                 static_cast<float>(std::sin(theta) * std::sin(phi))};
    return Vertex{n * radius, n};
  });
}

// A torus around +y (ring radius `major`, tube radius `minor`) centred at the origin.
// Its chart is the (phi, psi) map, 2 pi major by 2 pi minor.
void addTorus(Scene* s, std::vector<Chart>* charts, float major, float minor, int segments, int sides,
              const Surface& surface, const Placement& where) {
  addGrid(s, charts, 2.0 * kPi * major, 2.0 * kPi * minor, segments, sides, surface, where, [&](int i, int j) {
    const double phi = 2.0 * kPi * i / segments;
    const double psi = 2.0 * kPi * j / sides;
    const Vec3 n{static_cast<float>(std::cos(psi) * std::cos(phi)), static_cast<float>(std::sin(psi)),
                 static_cast<float>(std::cos(psi) * std::sin(phi))};
    const Vec3 ring{static_cast<float>(major * std::cos(phi)), 0.0f, static_cast<float>(major * std::sin(phi))};
    return Vertex{ring + n * minor, n};
  });
}

// Shelf-packs `charts` at `scale` UV units per metre with `gap` UV units around each; false
// when they do not fit in the unit square. Writes each chart's corner into `corner`.
bool packCharts(const std::vector<Chart>& charts, const std::vector<std::size_t>& order, double scale, double gap,
                std::vector<std::array<double, 2>>* corner) {
  double x = gap, y = gap, shelf = 0;
  for (std::size_t k : order) {
    const double w = charts[k].width * scale, h = charts[k].height * scale;
    if (x + w + gap > 1.0) {  // next shelf
      x = gap;
      y += shelf + gap;
      shelf = 0;
    }
    if (x + w + gap > 1.0 || y + h + gap > 1.0) return false;
    (*corner)[k] = {x, y};
    x += w + gap;
    shelf = std::max(shelf, h);
  }
  return true;
}

// TEXCOORD_1: every grid its own chart, area-proportional, shelf-packed with a gutter of
// max(kMinAtlasGap, (padding + 2) / side) UV units: the atlas check wants `padding` texels
// between the texels two charts reach, and conservative rasterisation reaches a texel past each
// chart edge, so a gap of padding + 2 texels at the side baked at keeps the atlas valid there
// (and from that side up). kMinAtlasGap, 8 texels at 1024², 4 at 512², is the gap for every
// side from 512 up with the default padding: those bakes do not depend on the side asked for.
// As large as fits: a lightmap atlas as an exporter would write one, so `prt-bake --default
// --texels` needs no unwrapper.
constexpr double kMinAtlasGap = 1.0 / 128.0;

// The triangles added since the previous object become the object `name` (scene.h).
void markObject(Scene* s, const char* name) {
  s->triangleObject.resize(s->indices.size() / 3, static_cast<std::uint32_t>(s->objectNames.size()));
  s->objectNames.emplace_back(name);
}

void addLightmapUvs(Scene* s, const std::vector<Chart>& charts, double gap) {
  std::vector<std::size_t> order(charts.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return charts[a].height > charts[b].height; });
  std::vector<std::array<double, 2>> corner(charts.size());
  double lo = 0.0, hi = 1.0;  // UV units per metre: lo fits, hi does not (1 m per atlas is far too big)
  for (int step = 0; step < 40; ++step) {
    const double mid = 0.5 * (lo + hi);
    (packCharts(charts, order, mid, gap, &corner) ? lo : hi) = mid;
  }
  packCharts(charts, order, lo, gap, &corner);
  s->texcoord[1].assign(s->positions.size(), Uv{});
  for (std::size_t k = 0; k < charts.size(); ++k) {
    const Chart& c = charts[k];
    for (int j = 0; j <= c.nv; ++j) {
      for (int i = 0; i <= c.nu; ++i) {
        const double u = corner[k][0] + lo * c.width * i / c.nu, v = corner[k][1] + lo * c.height * j / c.nv;
        s->texcoord[1][c.base + static_cast<std::uint32_t>(j * (c.nu + 1) + i)] = {static_cast<float>(u),
                                                                                 static_cast<float>(v)};
      }
    }
  }
  s->texcoordAbsent[0] = "the default scene has no material textures";
}

}  // namespace

Scene makeDefaultScene(int lightmapSide, int lightmapPadding) {
  Scene s;
  std::vector<Chart> charts;
  s.name = "default-room";
  const Placement room = place(0, {0, 0, 0});
  const float w = 2 * kRoomHalfWidth, r = kRoomHalfWidth;
  // The room: normals point into it.
  addRectangle(&s, &charts, {-r, 0, -r}, {0, 0, w}, {w, 0, 0}, {0, 1, 0}, {kFloor}, room);
  addRectangle(&s, &charts, {-r, 0, -r}, {w, 0, 0}, {0, kRoomHeight, 0}, {0, 0, 1}, {kBackWall}, room);
  addRectangle(&s, &charts, {-r, 0, -r}, {0, kRoomHeight, 0}, {0, 0, w}, {1, 0, 0}, {kRedWall}, room);
  addRectangle(&s, &charts, {r, 0, -r}, {0, 0, w}, {0, kRoomHeight, 0}, {-1, 0, 0}, {kGreenWall}, room);
  markObject(&s, "room");

  // The objects, spaced so none touches another or a wall: the sphere (touching the floor
  // in one point) near the red wall, the cube near the green one, the tall box casting a
  // long shadow on the back wall, the torus lying flat (self-shadowing in its hole).
  addSphere(&s, &charts, 0.5f, 64, 32, {kSphere, kPolishedDielectric}, place(0, {-0.9f, 0.5f, 0.5f}));
  markObject(&s, "sphere");
  addBox(&s, &charts, {1.0f, 1.0f, 1.0f}, {kCube}, place(25, {0.9f, 0.0f, 0.6f}));
  markObject(&s, "cube");
  addBox(&s, &charts, {0.6f, 1.8f, 0.6f}, {kTallBox}, place(-20, {-0.6f, 0.0f, -1.2f}));
  markObject(&s, "tall box");
  addTorus(&s, &charts, 0.4f, 0.14f, 64, 24, {kTorus, kBrushedMetal}, place(0, {0.7f, 0.14f, -0.9f}));
  markObject(&s, "torus");
  const double side = std::max(1, lightmapSide), padding = std::max(0, lightmapPadding);
  addLightmapUvs(&s, charts, std::max(kMinAtlasGap, (padding + 2.0) / side));
  // The sphere's pole rows have one vertex per column, and the seam column's pole vertex
  // ends up in no triangle (its triangles collapse); drop such vertices.
  removeUnreferencedVertices(&s);
  return s;
}

}  // namespace prt::bake
