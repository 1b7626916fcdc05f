#include "baker/texture/texel_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <string>

#include "baker/scene/mesh_cleanup.h"
#include "baker/texture/texel_triangle.h"

namespace prt::bake {
namespace {

constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

// Texels resolved per band: the per-texel bests of one band of rows live at a time, so memory
// beyond the output stays a few MiB at any atlas size.
constexpr std::size_t kBandTexels = std::size_t{1} << 20;

Status fail(StatusCode code, const std::string& message) {
  return Status::error(code, "texel rasterisation: " + message);
}

std::string vertexOf(std::size_t corner, std::uint32_t v) {
  return "vertex " + std::to_string(v) + " (triangle " + std::to_string(corner / 3) + ")";
}

Status validate(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const std::uint32_t> indices,
                std::span<const Uv> uvs, int width, int height) {
  if (width < 1 || width > kMaxAtlasSize || height < 1 || height > kMaxAtlasSize)
    return fail(StatusCode::kInvalidArgument, "atlas size " + std::to_string(width) + "x" + std::to_string(height) +
                                                  " is outside 1 … " + std::to_string(kMaxAtlasSize));
  if (normals.size() != positions.size() || uvs.size() != positions.size())
    return fail(StatusCode::kSizeMismatch, std::to_string(positions.size()) + " positions, " +
                                               std::to_string(normals.size()) + " normals and " +
                                               std::to_string(uvs.size()) + " UVs: they must be one per vertex");
  if (indices.size() % 3 != 0)
    return fail(StatusCode::kInvalidArgument,
                "the index count " + std::to_string(indices.size()) + " is not a multiple of 3");
  // Triangle numbers are stored as uint32, with the top value meaning "none".
  if (indices.size() / 3 >= kNoTriangle)
    return fail(StatusCode::kInvalidArgument, std::to_string(indices.size() / 3) + " triangles is too many");
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const std::uint32_t v = indices[i];
    if (v >= positions.size())
      return fail(StatusCode::kInvalidArgument, "index " + std::to_string(v) + " at " + std::to_string(i) +
                                                    " is out of range (" + std::to_string(positions.size()) +
                                                    " vertices)");
    const Uv uv = uvs[v];
    if (!std::isfinite(uv.u) || !std::isfinite(uv.v))
      return fail(StatusCode::kNotFinite, "the UV of " + vertexOf(i, v) + " is not finite");
    if (uv.u < 0.0f || uv.u > 1.0f || uv.v < 0.0f || uv.v > 1.0f)
      return fail(StatusCode::kInvalidArgument, "the UV (" + std::to_string(uv.u) + ", " + std::to_string(uv.v) +
                                                    ") of " + vertexOf(i, v) + " is outside [0, 1]");
    if (!isFinite(positions[v]))
      return fail(StatusCode::kNotFinite, "the position of " + vertexOf(i, v) + " is not finite");
    if (!isFinite(normals[v]))
      return fail(StatusCode::kNotFinite, "the normal of " + vertexOf(i, v) + " is not finite");
    const Vec3 n = normals[v];
    if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f)
      return fail(StatusCode::kInvalidArgument, "the normal of " + vertexOf(i, v) + " is zero");
  }
  return Status::ok();
}

// The atlas check's test (uv_atlas_check.cpp), in UV units, so a set that passed the check
// loses no triangle here.
bool degenerateUv(Uv a, Uv b, Uv c) {
  const double abx = double(b.u) - a.u, aby = double(b.v) - a.v;
  const double acx = double(c.u) - a.u, acy = double(c.v) - a.v;
  const double bcx = double(c.u) - b.u, bcy = double(c.v) - b.v;
  const double longest = std::max({abx * abx + aby * aby, acx * acx + acy * acy, bcx * bcx + bcy * bcy});
  return longest == 0.0 || std::abs(abx * acy - aby * acx) <= kDegenerateRelativeArea * longest;
}

struct Prepared {
  TexelTriangle corners;
  TexelRange rows;
};

struct DVec3 {
  double x = 0, y = 0, z = 0;
};
DVec3 toD(Vec3 v) { return {v.x, v.y, v.z}; }
double norm(DVec3 v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
Vec3 toUnitFloat(DVec3 v, double len) {
  return {static_cast<float>(v.x / len), static_cast<float>(v.y / len), static_cast<float>(v.z / len)};
}

class Rasteriser {
 public:
  Rasteriser(std::span<const Vec3> positions, std::span<const Vec3> normals, std::span<const std::uint32_t> indices,
             std::span<const Uv> uvs, TexelRaster* out)
      : positions_(positions), normals_(normals), indices_(indices), uvs_(uvs), out_(*out) {}

  Status run();

 private:
  void prepare();
  Status sweepBand(int row0, int row1);
  void emitBand(int row0, int row1);
  TexelSample sampleOf(std::uint32_t texel, std::uint32_t triangle);

  std::span<const Vec3> positions_, normals_;
  std::span<const std::uint32_t> indices_;
  std::span<const Uv> uvs_;
  TexelRaster& out_;

  std::vector<Prepared> prepared_;         // per triangle
  std::vector<std::uint32_t> byFirstRow_;  // usable triangles, by first row, then index
  std::size_t nextToActivate_ = 0;
  std::vector<std::uint32_t> active_;  // triangles reaching the current band
  std::vector<double> bestDistance2_;  // per texel of the band
  std::vector<std::uint32_t> bestTriangle_;
  double visits_ = 0, visitBudget_ = 0;
};

void Rasteriser::prepare() {
  const std::size_t n = indices_.size() / 3;
  const double w = out_.width, h = out_.height;
  prepared_.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const Uv a = uvs_[indices_[3 * t]], b = uvs_[indices_[3 * t + 1]], c = uvs_[indices_[3 * t + 2]];
    if (degenerateUv(a, b, c)) {
      ++out_.degenerateTriangles;
      continue;
    }
    Prepared& p = prepared_[t];
    p.corners = {TexelPoint{a.u * w, a.v * h}, TexelPoint{b.u * w, b.v * h}, TexelPoint{c.u * w, c.v * h}};
    p.rows = texelRows(p.corners, out_.height);
    byFirstRow_.push_back(static_cast<std::uint32_t>(t));
  }
  std::stable_sort(byFirstRow_.begin(), byFirstRow_.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return prepared_[x].rows.first < prepared_[y].rows.first; });
}

Status Rasteriser::sweepBand(int row0, int row1) {
  const int w = out_.width;
  std::fill(bestTriangle_.begin(), bestTriangle_.end(), kNoTriangle);
  while (nextToActivate_ < byFirstRow_.size() && prepared_[byFirstRow_[nextToActivate_]].rows.first <= row1)
    active_.push_back(byFirstRow_[nextToActivate_++]);
  for (const std::uint32_t t : active_) {
    const Prepared& p = prepared_[t];
    for (int y = std::max(row0, p.rows.first); y <= std::min(row1, p.rows.last); ++y) {
      const TexelRange span = texelRowSpan(p.corners, y, w);
      visits_ += span.last - span.first + 1;
      if (visits_ > visitBudget_)
        return fail(StatusCode::kResourceExhausted,
                    "the triangles touch more texels than the budget of " +
                        std::to_string(static_cast<long long>(kMaxTexelVisitsPerTexel)) + " per atlas texel and " +
                        std::to_string(static_cast<long long>(kMaxTexelVisitsPerTriangle)) +
                        " per triangle (stacked charts?)");
      const std::size_t rowBase = static_cast<std::size_t>(y - row0) * static_cast<std::size_t>(w);
      for (int x = span.first; x <= span.last; ++x) {
        const double d2 = nearestPoint(p.corners, TexelPoint{x + 0.5, y + 0.5}).distance2;
        const std::size_t k = rowBase + static_cast<std::size_t>(x);
        // Explicit tie-break on the index, so the owner does not depend on visiting order.
        if (bestTriangle_[k] == kNoTriangle || d2 < bestDistance2_[k] ||
            (d2 == bestDistance2_[k] && t < bestTriangle_[k])) {
          bestDistance2_[k] = d2;
          bestTriangle_[k] = t;
        }
      }
    }
  }
  std::erase_if(active_, [&](std::uint32_t t) { return prepared_[t].rows.last <= row1; });
  return Status::ok();
}

TexelSample Rasteriser::sampleOf(std::uint32_t texel, std::uint32_t triangle) {
  const auto w = static_cast<std::uint32_t>(out_.width);
  const TexelPoint centre{texel % w + 0.5, texel / w + 0.5};
  const NearestPoint np = nearestPoint(prepared_[triangle].corners, centre);
  TexelSample s;
  s.texel = texel;
  s.triangle = triangle;
  s.uvDistance = static_cast<float>(std::sqrt(np.distance2));
  DVec3 pos, nrm;
  std::size_t heaviest = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint32_t v = indices_[3 * std::size_t{triangle} + k];
    const double b = np.bary[k];
    s.bary[k] = static_cast<float>(b);
    if (b > np.bary[heaviest]) heaviest = k;
    const DVec3 p = toD(positions_[v]), n = toD(normals_[v]);
    const double nl = norm(n);
    pos = {pos.x + b * p.x, pos.y + b * p.y, pos.z + b * p.z};
    nrm = {nrm.x + b * n.x / nl, nrm.y + b * n.y / nl, nrm.z + b * n.z / nl};
  }
  s.position = {static_cast<float>(pos.x), static_cast<float>(pos.y), static_cast<float>(pos.z)};
  // Corner normals are unit here, so a length this small means they (nearly) cancel out.
  if (const double len = norm(nrm); len > 1e-6) {
    s.normal = toUnitFloat(nrm, len);
    return s;
  }
  ++out_.normalFallbacks;
  const std::size_t base = 3 * std::size_t{triangle};
  const DVec3 p0 = toD(positions_[indices_[base]]), p1 = toD(positions_[indices_[base + 1]]),
              p2 = toD(positions_[indices_[base + 2]]);
  const DVec3 e1{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, e2{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
  const DVec3 face{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  if (const double len = norm(face); len > 0.0 && std::isfinite(len)) {
    s.normal = toUnitFloat(face, len);
  } else {
    const DVec3 n = toD(normals_[indices_[base + heaviest]]);
    s.normal = toUnitFloat(n, norm(n));
  }
  return s;
}

void Rasteriser::emitBand(int row0, int row1) {
  const auto w = static_cast<std::size_t>(out_.width);
  for (int y = row0; y <= row1; ++y) {
    for (std::size_t x = 0; x < w; ++x) {
      const std::uint32_t t = bestTriangle_[static_cast<std::size_t>(y - row0) * w + x];
      if (t == kNoTriangle) continue;
      const std::size_t texel = static_cast<std::size_t>(y) * w + x;
      out_.coverage[texel] = 1;
      out_.samples.push_back(sampleOf(static_cast<std::uint32_t>(texel), t));
    }
  }
}

Status Rasteriser::run() {
  const int w = out_.width, h = out_.height;
  out_.coverage.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  prepare();
  visitBudget_ = kMaxTexelVisitsPerTexel * w * h + kMaxTexelVisitsPerTriangle * static_cast<double>(prepared_.size());
  const int bandRows = static_cast<int>(std::clamp<std::size_t>(kBandTexels / static_cast<std::size_t>(w), 1, h));
  bestDistance2_.assign(static_cast<std::size_t>(bandRows) * static_cast<std::size_t>(w), 0.0);
  bestTriangle_.assign(bestDistance2_.size(), kNoTriangle);
  for (int row0 = 0; row0 < h; row0 += bandRows) {
    const int row1 = std::min(h, row0 + bandRows) - 1;
    PRT_RETURN_IF_ERROR(sweepBand(row0, row1));
    emitBand(row0, row1);
  }
  return Status::ok();
}

}  // namespace

Status rasteriseTexels(std::span<const Vec3> positions, std::span<const Vec3> normals,
                       std::span<const std::uint32_t> indices, std::span<const Uv> uvs, int width, int height,
                       TexelRaster* out) {
  if (out == nullptr) return fail(StatusCode::kInvalidArgument, "no output");
  *out = TexelRaster();
  PRT_RETURN_IF_ERROR(validate(positions, normals, indices, uvs, width, height));
  out->width = width;
  out->height = height;
  Status status;
  try {
    status = Rasteriser(positions, normals, indices, uvs, out).run();
  } catch (const std::bad_alloc&) {
    status = fail(StatusCode::kResourceExhausted,
                  "out of memory at " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (!status.isOk()) *out = TexelRaster();
  return status;
}

}  // namespace prt::bake
