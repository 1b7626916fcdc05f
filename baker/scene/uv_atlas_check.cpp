#include "baker/scene/uv_atlas_check.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "baker/scene/mesh_cleanup.h"

namespace prt::bake {
namespace {

struct P2 {
  double x = 0, y = 0;
};

using Tri2 = std::array<P2, 3>;

// Shared edges and vertices project to bit-identical values, so a tolerance far below a
// texel (1/16384) only absorbs rounding in near-collinear cases; overlaps thinner than it are
// too thin to matter for any texel.
constexpr double kOverlapEpsilon = 1e-7;

// Separating-axis test on two convex polygons: how deep their interiors intersect (the
// smallest overlap of their projections on any edge normal of either, in their units), or 0
// when some axis separates them by more than -eps. Polygons that only share an edge or a
// vertex are separated by that edge's normal, so they do not count.
template <std::size_t N, std::size_t M>
double overlapDepth(const std::array<P2, N>& a, const std::array<P2, M>& b, double eps) {
  double depth = INFINITY;
  auto separatedBy = [&](P2 p, P2 q) {
    const double nx = q.y - p.y, ny = p.x - q.x;
    const double len = std::hypot(nx, ny);
    if (len == 0.0) return false;  // a repeated corner gives no axis
    double minA = INFINITY, maxA = -INFINITY, minB = INFINITY, maxB = -INFINITY;
    for (const P2& v : a) {
      const double d = v.x * nx + v.y * ny;
      minA = std::min(minA, d);
      maxA = std::max(maxA, d);
    }
    for (const P2& v : b) {
      const double d = v.x * nx + v.y * ny;
      minB = std::min(minB, d);
      maxB = std::max(maxB, d);
    }
    const double margin = eps * len;
    depth = std::min(depth, (std::min(maxA, maxB) - std::max(minA, minB)) / len);
    return maxA <= minB + margin || maxB <= minA + margin;
  };
  for (std::size_t i = 0; i < N; ++i)
    if (separatedBy(a[i], a[(i + 1) % N])) return 0.0;
  for (std::size_t i = 0; i < M; ++i)
    if (separatedBy(b[i], b[(i + 1) % M])) return 0.0;
  return depth;
}

// floor(x) clamped to [0, last], clamped before the conversion: a UV of 1e30 would overflow int.
int toIndex(double x, int last) { return static_cast<int>(std::clamp(std::floor(x), 0.0, static_cast<double>(last))); }

double twiceArea(P2 a, P2 b, P2 c) { return std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)); }

double longestEdgeSquared(P2 a, P2 b, P2 c) {
  auto d2 = [](P2 p, P2 q) { return (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y); };
  return std::max({d2(a, b), d2(b, c), d2(c, a)});
}

bool hasArea3d(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const double area2 = length(cross(e1, e2));
  const double longest = std::max({dot(e1, e1), dot(e2, e2), dot(c - b, c - b)});
  return area2 > kDegenerateRelativeArea * longest;
}

// Union-find over triangles.
struct Components {
  std::vector<std::uint32_t> parent;
  explicit Components(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// A corner identified by its position and UV values (not its index: soups duplicate
// vertices, and a stacked copy that reuses the UVs but not the positions is another chart).
struct CornerKey {
  std::array<std::uint32_t, 5> bits;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  std::size_t operator()(const CornerKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

std::uint32_t floatBits(float f) { return std::bit_cast<std::uint32_t>(f == 0.0f ? 0.0f : f); }  // -0 is 0

// Chart of every triangle: triangles sharing an edge whose two corners agree in position and
// UV are one chart. Returns chart ids 0 … charts-1 in order of first triangle.
std::vector<std::uint32_t> chartsOf(std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
                                    std::span<const Uv> uvs, std::size_t* charts) {
  const std::size_t triangles = indices.size() / 3;
  std::unordered_map<CornerKey, std::uint32_t, CornerHash> cornerIds;
  cornerIds.reserve(positions.size());
  std::vector<std::uint32_t> corner(indices.size());
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const Vec3 p = positions[indices[i]];
    const Uv t = uvs[indices[i]];
    const CornerKey key{{floatBits(p.x), floatBits(p.y), floatBits(p.z), floatBits(t.u), floatBits(t.v)}};
    corner[i] = cornerIds.emplace(key, static_cast<std::uint32_t>(cornerIds.size())).first->second;
  }
  Components components(triangles);
  std::unordered_map<std::uint64_t, std::uint32_t> edgeOwner;
  edgeOwner.reserve(indices.size());
  for (std::size_t t = 0; t < triangles; ++t) {
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = corner[3 * t + static_cast<std::size_t>(e)];
      const std::uint32_t b = corner[3 * t + static_cast<std::size_t>((e + 1) % 3)];
      const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      const auto [it, inserted] = edgeOwner.emplace(key, static_cast<std::uint32_t>(t));
      if (!inserted) components.join(it->second, static_cast<std::uint32_t>(t));
    }
  }
  std::vector<std::uint32_t> chart(triangles);
  std::vector<std::uint32_t> idOfRoot(triangles, UINT32_MAX);
  std::uint32_t next = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t root = components.find(static_cast<std::uint32_t>(t));
    if (idOfRoot[root] == UINT32_MAX) idOfRoot[root] = next++;
    chart[t] = idOfRoot[root];
  }
  *charts = next;
  return chart;
}

class Checker {
 public:
  Checker(std::span<const Vec3> positions, std::span<const std::uint32_t> indices, std::span<const Uv> uvs,
          const UvAtlasTarget& target, std::string_view setName, UvAtlasReport* report)
      : positions_(positions), indices_(indices), uvs_(uvs), target_(target), set_(setName), r_(*report) {}

  void run();

 private:
  Tri2 tri(std::size_t t) const {
    Tri2 out;
    for (std::size_t k = 0; k < 3; ++k) {
      const Uv uv = uvs_[indices_[3 * t + k]];
      out[k] = {uv.u, uv.v};
    }
    return out;
  }
  void note(const std::string& line) {
    if (r_.problems.size() < kMaxListedProblems) r_.problems.push_back(std::string(set_) + ": " + line);
  }
  void checkCorners();
  void findOverlaps();
  void rasterise();
  void checkPadding();

  std::span<const Vec3> positions_;
  std::span<const std::uint32_t> indices_;
  std::span<const Uv> uvs_;
  UvAtlasTarget target_;
  std::string_view set_;
  UvAtlasReport& r_;

  std::vector<std::uint8_t> usable_;       // finite, non-degenerate: takes part in overlap and raster
  std::vector<std::uint32_t> chart_;       // per triangle
  std::vector<std::uint32_t> firstOfChart_;
  std::vector<std::int32_t> owner_;        // per texel: chart, -1 none, -2 two charts
};

void Checker::checkCorners() {
  const std::size_t n = r_.triangles;
  usable_.assign(n, 0);
  for (std::size_t t = 0; t < n; ++t) {
    bool finite = true, inRange = true;
    for (std::size_t k = 0; k < 3; ++k) {
      const Uv uv = uvs_[indices_[3 * t + k]];
      if (!std::isfinite(uv.u) || !std::isfinite(uv.v)) {
        finite = false;
      } else if (uv.u < 0.0f || uv.u > 1.0f || uv.v < 0.0f || uv.v > 1.0f) {
        inRange = false;
      }
    }
    if (!finite) {
      if (r_.nonFinite++ == 0) note("triangle " + std::to_string(t) + " has a non-finite (NaN or infinite) UV");
      continue;
    }
    if (!inRange) {
      // Reported and left out of the overlap scan and the rasterisation: a tiled set's
      // triangles reach far beyond [0, 1], and clamped into the grid they would pile up in
      // its border cells.
      if (r_.outOfRange++ == 0) {
        const Tri2 p = tri(t);
        note("triangle " + std::to_string(t) + " has a UV outside [0, 1] (" + std::to_string(p[0].x) + ", " +
           std::to_string(p[0].y) + "), (" + std::to_string(p[1].x) + ", " + std::to_string(p[1].y) + "), (" +
           std::to_string(p[2].x) + ", " + std::to_string(p[2].y) + ")");
      }
      continue;
    }
    const Tri2 p = tri(t);
    const Vec3 a = positions_[indices_[3 * t]], b = positions_[indices_[3 * t + 1]], c = positions_[indices_[3 * t + 2]];
    const double longest = longestEdgeSquared(p[0], p[1], p[2]);
    const bool flat = longest == 0.0 || twiceArea(p[0], p[1], p[2]) <= kDegenerateRelativeArea * longest;
    if (flat) {
      if (hasArea3d(a, b, c) && r_.degenerate++ == 0)
        note("triangle " + std::to_string(t) + " has zero UV area but a non-zero surface area");
      continue;
    }
    usable_[t] = 1;
  }
}

void Checker::findOverlaps() {
  const std::size_t n = r_.triangles;
  // Uniform grid over [0, 1]² with about one triangle per cell; out-of-range corners are
  // clamped into the border cells, which keeps them in the test.
  // Large triangles enter many cells: the grid is coarsened until the entries stay within a
  // budget, so that a layout of many full-square triangles cannot exhaust memory.
  struct Box {
    int x0, y0, x1, y1;
  };
  std::vector<Box> boxes(n);
  int g = static_cast<int>(std::clamp(std::sqrt(static_cast<double>(n)), 1.0, 2048.0));
  const double entryBudget = 16.0 * static_cast<double>(n) + 1e6;
  for (;;) {
    auto cellOf = [g](double x) { return toIndex(x * g, g - 1); };
    double entries = 0;
    for (std::size_t t = 0; t < n; ++t) {
      if (!usable_[t]) continue;
      const Tri2 p = tri(t);
      const double minX = std::min({p[0].x, p[1].x, p[2].x}), maxX = std::max({p[0].x, p[1].x, p[2].x});
      const double minY = std::min({p[0].y, p[1].y, p[2].y}), maxY = std::max({p[0].y, p[1].y, p[2].y});
      boxes[t] = {cellOf(minX), cellOf(minY), cellOf(maxX), cellOf(maxY)};
      entries += (boxes[t].x1 - boxes[t].x0 + 1.0) * (boxes[t].y1 - boxes[t].y0 + 1.0);
    }
    if (entries <= entryBudget || g == 1) break;
    g = std::max(1, g / 2);
  }
  std::vector<std::size_t> start(static_cast<std::size_t>(g) * g + 1, 0);
  for (std::size_t t = 0; t < n; ++t) {
    if (!usable_[t]) continue;
    for (int y = boxes[t].y0; y <= boxes[t].y1; ++y)
      for (int x = boxes[t].x0; x <= boxes[t].x1; ++x) ++start[static_cast<std::size_t>(y) * g + x + 1];
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::uint32_t> entries(start.back());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < n; ++t) {
    if (!usable_[t]) continue;
    for (int y = boxes[t].y0; y <= boxes[t].y1; ++y)
      for (int x = boxes[t].x0; x <= boxes[t].x1; ++x)
        entries[fill[static_cast<std::size_t>(y) * g + x]++] = static_cast<std::uint32_t>(t);
  }
  for (int cy = 0; cy < g; ++cy) {
    for (int cx = 0; cx < g; ++cx) {
      const std::size_t cell = static_cast<std::size_t>(cy) * g + cx;
      for (std::size_t i = start[cell]; i < start[cell + 1]; ++i) {
        const std::uint32_t a = entries[i];
        const Tri2 pa = tri(a);
        for (std::size_t j = i + 1; j < start[cell + 1]; ++j) {
          const std::uint32_t b = entries[j];
          // Each pair is tested once, in the first cell both boxes cover.
          if (std::max(boxes[a].x0, boxes[b].x0) != cx || std::max(boxes[a].y0, boxes[b].y0) != cy) continue;
          const double depth = overlapDepth(pa, tri(b), kOverlapEpsilon);
          if (depth <= 0.0) continue;
          r_.deepestOverlapTexels =
              std::max(r_.deepestOverlapTexels, depth * std::max(target_.width, target_.height));
          if (r_.overlappingPairs++ < 3)
            note("triangles " + std::to_string(std::min(a, b)) + " and " + std::to_string(std::max(a, b)) +
                 " overlap in UV space");
          if (r_.overlappingPairs >= kMaxOverlapsCounted) {
            r_.overlapCountCapped = true;
            return;
          }
        }
      }
    }
  }
}

void Checker::rasterise() {
  const int w = target_.width, h = target_.height;
  owner_.assign(static_cast<std::size_t>(w) * h, -1);
  // A layout that covers the texture many times over (stacked charts) would cost that many
  // texel tests; past the budget the rasterisation stops, with its statistics incomplete.
  const double budget = 64.0 * w * h + 64.0 * static_cast<double>(r_.triangles);
  double tests = 0;
  for (std::size_t t = 0; t < r_.triangles; ++t) {
    if (!usable_[t]) continue;
    Tri2 p = tri(t);
    for (P2& v : p) v = {v.x * w, v.y * h};  // texel units
    const double minX = std::min({p[0].x, p[1].x, p[2].x}), maxX = std::max({p[0].x, p[1].x, p[2].x});
    const double minY = std::min({p[0].y, p[1].y, p[2].y}), maxY = std::max({p[0].y, p[1].y, p[2].y});
    const int x0 = toIndex(minX, w - 1);
    const int x1 = toIndex(std::ceil(maxX) - 1.0, w - 1);
    const int y0 = toIndex(minY, h - 1);
    const int y1 = toIndex(std::ceil(maxY) - 1.0, h - 1);
    const auto c = static_cast<std::int32_t>(chart_[t]);
    tests += (x1 - x0 + 1.0) * (y1 - y0 + 1.0);
    if (tests > budget) {
      r_.rasterIncomplete = true;
      note("the layout covers the texture more than 64 times over; texel statistics are incomplete");
      break;
    }
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::array<P2, 4> texel{P2{double(x), double(y)}, P2{x + 1.0, double(y)}, P2{x + 1.0, y + 1.0},
                                      P2{double(x), y + 1.0}};
        // Conservative: any texel the triangle's interior reaches gets a sample.
        if (overlapDepth(p, texel, 1e-9) <= 0.0) continue;
        std::int32_t& o = owner_[static_cast<std::size_t>(y) * w + x];
        if (o == -1) {
          o = c;
          ++r_.usedTexels;
        } else if (o >= 0 && o != c) {
          if (r_.paddingConflicts++ == 0)
            note("charts of triangles " + std::to_string(firstOfChart_[static_cast<std::size_t>(o)]) + " and " +
                 std::to_string(t) + " share texel (" + std::to_string(x) + ", " + std::to_string(y) + ") at " +
                 std::to_string(w) + "x" + std::to_string(h));
          o = -2;
        }
      }
    }
  }
  r_.usedTexelFraction = static_cast<double>(r_.usedTexels) / (static_cast<double>(w) * h);
}

void Checker::checkPadding() {
  const int w = target_.width, h = target_.height, pad = target_.padding;
  if (pad == 0) return;
  auto at = [&](int x, int y) { return owner_[static_cast<std::size_t>(y) * w + x]; };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::int32_t c = at(x, y);
      if (c < 0) continue;
      // Only a chart's boundary texels can be nearest to another chart (a straight path
      // from an interior texel to the other chart leaves through the boundary), so interior
      // texels are skipped.
      bool boundary = false;
      for (int dy = -1; dy <= 1 && !boundary; ++dy)
        for (int dx = -1; dx <= 1 && !boundary; ++dx) {
          const int nx = x + dx, ny = y + dy;
          boundary = nx < 0 || ny < 0 || nx >= w || ny >= h || at(nx, ny) != c;
        }
      if (!boundary) continue;
      for (int dy = -pad; dy <= pad; ++dy) {
        const int ny = y + dy;
        if (ny < 0 || ny >= h) continue;
        bool found = false;
        for (int dx = -pad; dx <= pad && !found; ++dx) {
          const int nx = x + dx;
          if (nx < 0 || nx >= w) continue;
          const std::int32_t o = at(nx, ny);
          if (o == -1 || o == c) continue;
          found = true;
          if (r_.paddingConflicts++ == 0 && o >= 0)
            note("charts of triangles " + std::to_string(firstOfChart_[static_cast<std::size_t>(c)]) + " and " +
                 std::to_string(firstOfChart_[static_cast<std::size_t>(o)]) + " are closer than " +
                 std::to_string(pad) + " texels at texel (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        }
        if (found) break;
      }
    }
  }
}

void Checker::run() {
  r_.triangles = indices_.size() / 3;
  checkCorners();
  chart_ = chartsOf(positions_, indices_, uvs_, &r_.charts);
  firstOfChart_.assign(r_.charts, 0);
  for (std::size_t t = r_.triangles; t-- > 0;) firstOfChart_[chart_[t]] = static_cast<std::uint32_t>(t);
  findOverlaps();
  rasterise();
  checkPadding();
}

}  // namespace

std::string UvAtlasReport::summary() const {
  std::string s;
  auto add = [&](std::size_t n, const std::string& what) {
    if (n) s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(nonFinite, "triangles with non-finite UVs");
  add(outOfRange, "triangles outside [0, 1]");
  add(degenerate, "zero-area UV triangles");
  if (overlappingPairs) {
    char deepest[64];
    std::snprintf(deepest, sizeof deepest, " (deepest %.3g texels)", deepestOverlapTexels);
    s += (s.empty() ? "" : ", ") + std::string(overlapCountCapped ? "at least " : "") +
         std::to_string(overlappingPairs) + " overlapping triangle pairs" + deepest;
  }
  add(paddingConflicts, "texels without the required gutter");
  if (rasterIncomplete) s += (s.empty() ? "" : ", ") + std::string("texel statistics incomplete");
  if (s.empty()) s = "valid";
  char use[96];
  std::snprintf(use, sizeof use, "; %zu chart%s, %.1f%% of texels used", charts, charts == 1 ? "" : "s",
                100.0 * usedTexelFraction);
  return s + use;
}

Status checkUvAtlas(std::span<const Vec3> positions, std::span<const std::uint32_t> indices,
                    std::span<const Uv> uvs, const UvAtlasTarget& target, std::string_view setName,
                    UvAtlasReport* out) {
  auto fail = [&](const std::string& m) {
    return Status::error(StatusCode::kInvalidArgument, "UV atlas check of " + std::string(setName) + ": " + m);
  };
  if (out == nullptr) return fail("no report");
  *out = UvAtlasReport();
  if (uvs.size() != positions.size())
    return fail(std::to_string(uvs.size()) + " UVs for " + std::to_string(positions.size()) + " positions");
  if (indices.size() % 3 != 0) return fail("the index count " + std::to_string(indices.size()) + " is not a multiple of 3");
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= positions.size())
      return fail("index " + std::to_string(indices[i]) + " at " + std::to_string(i) + " is out of range");
  }
  if (target.width < 1 || target.width > kMaxAtlasSize || target.height < 1 || target.height > kMaxAtlasSize)
    return fail("texture size " + std::to_string(target.width) + "x" + std::to_string(target.height) +
                " is outside 1 … " + std::to_string(kMaxAtlasSize));
  if (target.padding < 0 || target.padding > kMaxAtlasPadding)
    return fail("padding " + std::to_string(target.padding) + " is outside 0 … " + std::to_string(kMaxAtlasPadding));
  Checker(positions, indices, uvs, target, setName, out).run();
  return Status::ok();
}

Status countUvCharts(std::span<const Vec3> positions, std::span<const std::uint32_t> indices, std::span<const Uv> uvs,
                     std::size_t* charts) {
  if (uvs.size() != positions.size() || indices.size() % 3 != 0) {
    return Status::error(StatusCode::kInvalidArgument, "countUvCharts: one UV per position, 3 indices per triangle");
  }
  for (std::uint32_t i : indices) {
    if (i >= positions.size()) return Status::error(StatusCode::kInvalidArgument, "countUvCharts: an index is out of range");
  }
  (void)chartsOf(positions, indices, uvs, charts);
  return Status::ok();
}

}  // namespace prt::bake
