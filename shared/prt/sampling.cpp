#include "prt/sampling.h"

#include <cmath>
#include <string>

namespace prt {

Pcg32::Pcg32(std::uint64_t seed, std::uint64_t stream) {
  inc_ = (stream << 1u) | 1u;
  next();
  state_ += seed;
  next();
}

std::uint32_t Pcg32::next() {
  const std::uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + inc_;
  const std::uint32_t xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
  const std::uint32_t rot = static_cast<std::uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

Vec3 squareToSphere(float u, float v) {
  const float z = 1.0f - 2.0f * u;
  const float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
  const float phi = static_cast<float>(2.0 * kPi) * v;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

namespace {

float radicalInverse2(std::uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return static_cast<float>(static_cast<double>(bits) * 2.3283064365386963e-10);
}

void resize(DirectionSet* out, std::size_t n) {
  out->x.resize(n);
  out->y.resize(n);
  out->z.resize(n);
  out->weight = 4.0 * kPi / static_cast<double>(n);
}

void store(DirectionSet* out, std::size_t k, Vec3 d) {
  out->x[k] = d.x;
  out->y[k] = d.y;
  out->z[k] = d.z;
}

}  // namespace

Status hammersleySphere(std::size_t count, DirectionSet* out) {
  if (count < 1 || count > (std::size_t{1} << 26)) {
    return Status::error(StatusCode::kInvalidArgument,
                         "Hammersley sample count " + std::to_string(count) + " is outside [1, 2^26]");
  }
  resize(out, count);
  for (std::size_t k = 0; k < count; ++k) {
    const float u = static_cast<float>((static_cast<double>(k) + 0.5) / static_cast<double>(count));
    store(out, k, squareToSphere(u, radicalInverse2(static_cast<std::uint32_t>(k))));
  }
  return Status::ok();
}

Status stratifiedSphere(std::size_t side, std::uint64_t seed, DirectionSet* out) {
  if (side < 1 || side > 8192) {
    return Status::error(StatusCode::kInvalidArgument,
                         "stratified grid side " + std::to_string(side) + " is outside [1, 8192]");
  }
  resize(out, side * side);
  Pcg32 rng(seed);
  const float inv = 1.0f / static_cast<float>(side);
  for (std::size_t i = 0; i < side; ++i) {
    for (std::size_t j = 0; j < side; ++j) {
      const float u = (static_cast<float>(i) + rng.nextFloat()) * inv;
      const float v = (static_cast<float>(j) + rng.nextFloat()) * inv;
      store(out, i * side + j, squareToSphere(std::fmin(u, 1.0f), v));
    }
  }
  return Status::ok();
}

}  // namespace prt
