// Small analytic scenes for baker tests, built in code.
#pragma once

#include <cmath>

#include "baker/scene/scene.h"

namespace prt::bake::test {

// Square grid in the y = height plane, [-half, half]^2 in x and z, normal +y, n x n quads.
inline void addPlane(Scene* s, float half, int n, float height, Rgb albedo) {
  const auto base = static_cast<std::uint32_t>(s->positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      s->positions.push_back({-half + 2.0f * half * i / n, height, -half + 2.0f * half * j / n});
      s->normals.push_back({0, 1, 0});
      s->albedo.push_back(albedo);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = base + j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
      // counter-clockwise seen from +y: (x,z) grid with z toward the viewer
      for (std::uint32_t v : {a, c, b, b, c, d}) s->indices.push_back(v);
    }
}

// UV sphere with outward normals.
inline void addSphere(Scene* s, Vec3 centre, float radius, int slices, int stacks, Rgb albedo) {
  const auto base = static_cast<std::uint32_t>(s->positions.size());
  for (int j = 0; j <= stacks; ++j) {
    const float theta = static_cast<float>(kPi) * j / stacks;
    for (int i = 0; i <= slices; ++i) {
      const float phi = 2.0f * static_cast<float>(kPi) * i / slices;
      const Vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
      s->positions.push_back(centre + n * radius);
      s->normals.push_back(n);
      s->albedo.push_back(albedo);
    }
  }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const std::uint32_t a = base + j * (slices + 1) + i, b = a + 1, c = a + (slices + 1), d = c + 1;
      for (std::uint32_t v : {a, b, c, b, d, c}) s->indices.push_back(v);
    }
}

}  // namespace prt::bake::test
