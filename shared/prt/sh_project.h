// Projection of spherical functions onto real SH: c_i = integral f(w) y_i(w) dw, by
// quadrature over direction sets, cube maps, equirectangular and angular light-probe maps.
//
// World frame of all image projections (docs/sh-conventions.md): right-handed, +y up (the
// glTF and WebGL frame). SH themselves keep z as their polar axis; that is a property of
// the basis, not of the scene.
#pragma once

#include <span>
#include <vector>

#include "prt/cubemap.h"
#include "prt/image.h"
#include "prt/sampling.h"
#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Accumulates sum_k weight_k value_k y_i(dir_k), evaluating the basis in batches.
class ShProjector {
 public:
  // Checks the order; the projector starts empty.
  static Status make(int order, ShProjector* out);

  // Adds one sample. Trusted-caller fast path: `unitDir` must be unit length and finite,
  // `weight` in steradians.
  void add(Vec3 unitDir, Rgb value, double weight);

  // The order*order RGB coefficients of everything added so far.
  std::vector<Rgb> coefficients();
  // Sum of the weights added (4pi for a complete quadrature of the sphere).
  double weightSum() const { return weightSum_; }
  int order() const { return order_; }

 private:
  void flush();
  static constexpr std::size_t kBatch = 256;
  int order_ = 0;
  std::size_t pending_ = 0;
  double weightSum_ = 0.0;
  std::vector<float> x_, y_, z_, r_, g_, b_;  // pending samples, value pre-multiplied by weight
  std::vector<float> basis_;                  // order*order x kBatch scratch
  std::vector<double> sum_;                   // order*order x 3
};

// Monte Carlo projection: values[k] is f(dirs[k]); every sample weighs dirs.weight.
// values.size() must equal dirs.size().
Status projectSamples(int order, const DirectionSet& dirs, std::span<const Rgb> values, std::vector<Rgb>* out);

// Equirectangular (latitude-longitude) image, three.js / glTF-viewer mapping: column u in
// [0,1] is longitude phi = 2pi (u - 1/2) measured from +x toward +z, row v in [0,1] from
// the top is latitude pi/2 - pi v; dir = (cos lat cos phi, sin lat, cos lat sin phi).
// Each pixel weighs its exact solid angle (2pi / W)(sin lat_top - sin lat_bottom).
Status projectEquirect(int order, const RgbImage& image, std::vector<Rgb>* out);

// Debevec's angular map (square image): pixel centre (u, v) in [-1,1]^2 with v up,
// r = |(u,v)| <= 1, theta = pi r, dir = (sin(theta) u/r, sin(theta) v/r, cos theta): the
// image centre looks along +z, the rim along -z. Pixels outside the disc are ignored; each
// pixel weighs the integral of the map's Jacobian pi sin(pi r)/r over its inside part
// (4x4 sub-samples).
Status projectAngularMap(int order, const RgbImage& image, std::vector<Rgb>* out);

// Cube map (GL convention, see cubemap.h), each texel weighing its exact solid angle.
Status projectCubeMap(int order, const CubeMap& cube, std::vector<Rgb>* out);

// Evaluates the expansion sum_i c_i y_i(dir) at a non-zero finite direction.
Status evalShExpansion(int order, std::span<const Rgb> coeffs, Vec3 dir, Rgb* out);

}  // namespace prt
