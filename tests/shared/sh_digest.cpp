// Prints SH results at fixed inputs, one "name value" per line. Built natively and with
// Emscripten; tests/compare_digests.mjs checks the two outputs agree.
#include <cstdio>
#include <vector>

#include "prt/cubemap.h"
#include "prt/patch_placement.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "prt/sh_rotation.h"
#include "prt/sh_window.h"
#include "prt/sh_zonal.h"

using namespace prt;

namespace {

void print(const char* name, int index, double value) { std::printf("%s[%d] %.9g\n", name, index, value); }

int fail(const Status& s) {
  std::fprintf(stderr, "sh_digest: %s\n", s.toString().c_str());
  return 1;
}

}  // namespace

int main() {
  Pcg32 rng(2024);
  for (int k = 0; k < 8; ++k) std::printf("pcg[%d] %u\n", k, rng.next());

  const Vec3 dirs[] = {{0, 0, 1}, {0.48f, -0.6f, 0.64f}, {-0.8f, 0.36f, -0.48f}};
  std::vector<float> y(shCoeffCount(kMaxShOrder));
  int n = 0;
  for (const Vec3& d : dirs) {
    if (Status s = evalShBasis(kMaxShOrder, d, y); !s.isOk()) return fail(s);
    for (float v : y) print("basis", n++, v);
  }

  ShRotation rot;
  if (Status s = ShRotation::make(8, rotationAxisAngle({1, 2, 3}, 0.8f), &rot); !s.isOk()) return fail(s);
  n = 0;
  for (int l = 0; l < 8; ++l)
    for (int a = -l; a <= l; ++a)
      for (int b = -l; b <= l; ++b) print("rotation", n++, rot.at(l, a, b));

  std::vector<float> zonal(8);
  if (Status s = zonalCircularLight(8, 0.4f, 3.0f, zonal); !s.isOk()) return fail(s);
  for (int l = 0; l < 8; ++l) print("circular", l, zonal[l]);
  if (Status s = zonalClampedCosine(8, zonal); !s.isOk()) return fail(s);
  for (int l = 0; l < 8; ++l) print("cosine", l, zonal[l]);

  DirectionSet h;
  if (Status s = hammersleySphere(64, &h); !s.isOk()) return fail(s);
  for (std::size_t k = 0; k < 8; ++k) print("hammersley_z", static_cast<int>(k), h.z[k]);
  DirectionSet st;
  if (Status s = stratifiedSphere(8, 5, &st); !s.isOk()) return fail(s);
  for (std::size_t k = 0; k < 8; ++k) print("stratified_x", static_cast<int>(k), st.x[k]);

  CubeMap cube;
  cube.size = 16;
  for (int f = 0; f < 6; ++f) {
    cube.faces[f].resize(16 * 16 * 3);
    for (std::size_t i = 0; i < cube.faces[f].size(); ++i) cube.faces[f][i] = static_cast<float>((i * 7 + f * 13) % 17) / 17.0f;
  }
  std::vector<Rgb> c;
  if (Status s = projectCubeMap(5, cube, &c); !s.isOk()) return fail(s);
  if (Status s = applyShWindow(ShWindow::kLanczos, 5, 0.0f, c); !s.isOk()) return fail(s);
  for (std::size_t i = 0; i < c.size(); ++i) {
    print("cube_r", static_cast<int>(i), c[i].r);
    print("cube_b", static_cast<int>(i), c[i].b);
  }

  // Patch placements (prt/patch_placement.h): the baker's q and the wasm client's must agree.
  Pcg32 patchRng(77);
  for (int k = 0; k < 8; ++k) {
    // Two statements: the order in which a call's arguments are evaluated differs by compiler.
    const float a = patchRng.nextFloat(), b = patchRng.nextFloat();
    const Vec3 n = squareToSphere(a, b);
    const Vec3 t = patchTangent(n);
    const PatchPlacement placement{n * 3.0f, t * 20.0f, cross(n, t) * 20.0f};
    float u = 0, v = 0;
    patchCoordinates(placement, n * 3.0f + Vec3{0.137f, -0.071f, 0.029f} * static_cast<float>(k), &u, &v);
    print("patch_tangent_x", k, t.x);
    print("patch_tangent_z", k, t.z);
    print("patch_u", k, u);
    print("patch_v", k, v);
  }
  return 0;
}
