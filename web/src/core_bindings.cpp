// Embind bindings of the GL-free shared code (asset decoding, SH evaluation, projection and
// rotation). Compiled into both the browser module and the Node module the tests load.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/cubemap.h"
#include "prt/sh_basis.h"
#include "prt/sh_project.h"
#include "prt/sh_rotation.h"
#include "transfer_texture.h"

using emscripten::val;

namespace {

std::vector<std::uint8_t> bytesFrom(const val& array) {
  return emscripten::convertJSArrayToNumberVector<std::uint8_t>(array);
}

// {ok, error, order, vertices, triangles, name, passes:[{kind, channels, bounces}]}, or with
// ok false the reader's named error.
val inspectAsset(const val& bytes) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::BakedAsset asset;
  val out = val::object();
  const prt::Status s = prt::decodeAsset(data, &asset);
  out.set("ok", s.isOk());
  out.set("error", s.isOk() ? std::string() : s.toString());
  if (!s.isOk()) return out;
  out.set("order", asset.shOrder);
  out.set("vertices", static_cast<double>(asset.positions.size()));
  out.set("triangles", static_cast<double>(asset.indices.size() / 3));
  out.set("name", asset.name);
  val passes = val::array();
  for (const prt::TransferPass& p : asset.passes) {
    val pass = val::object();
    pass.set("kind", std::string(prt::transferKindName(p.kind)));
    pass.set("channels", p.channels);
    pass.set("bounces", p.bounces);
    passes.call<void>("push", pass);
  }
  out.set("passes", passes);
  return out;
}

// Exit radiance of every vertex under constant unit radiance for `kind`, flat RGB: the same
// numbers `prt-bake shade --light constant` prints natively.
val shadeConstant(const val& bytes, const std::string& kind) {
  const std::vector<std::uint8_t> data = bytesFrom(bytes);
  prt::BakedAsset asset;
  if (!prt::decodeAsset(data, &asset).isOk()) return val::null();
  for (const prt::TransferPass& p : asset.passes) {
    if (kind != prt::transferKindName(p.kind)) continue;
    const int n2 = prt::shCoeffCount(asset.shOrder);
    const float l0 = static_cast<float>(2.0 * std::sqrt(prt::kPi));
    std::vector<float> out(asset.positions.size() * 3);
    for (std::size_t v = 0; v < asset.positions.size(); ++v) {
      for (int c = 0; c < 3; ++c) {
        const float albedo = c == 0 ? asset.albedo[v].r : c == 1 ? asset.albedo[v].g : asset.albedo[v].b;
        out[3 * v + c] = p.channels == 1 ? albedo * l0 * p.coeffs[v * n2] : l0 * p.coeffs[(v * 3 + c) * n2];
      }
    }
    return val::array(out);
  }
  return val::null();
}

val evalBasis(int order, float x, float y, float z) {
  std::vector<float> out(static_cast<std::size_t>(prt::shCoeffCount(std::max(1, std::min(order, prt::kMaxShOrder)))));
  const prt::Status s = prt::evalShBasis(order, {x, y, z}, out);
  if (!s.isOk()) return val(s.toString());
  return val::array(out);
}

// Rotates flat coefficients (one channel) by a row-major 3x3 matrix.
val rotateCoefficients(int order, const val& coeffs, const val& matrix) {
  const std::vector<float> in = emscripten::convertJSArrayToNumberVector<float>(coeffs);
  const std::vector<float> m = emscripten::convertJSArrayToNumberVector<float>(matrix);
  if (m.size() != 9) return val(std::string("matrix must hold 9 values"));
  prt::Mat3 r;
  for (int i = 0; i < 9; ++i) r.m[i / 3][i % 3] = m[static_cast<std::size_t>(i)];
  prt::ShRotation rot;
  if (prt::Status s = prt::ShRotation::make(order, r, &rot); !s.isOk()) return val(s.toString());
  std::vector<float> out(in.size());
  if (prt::Status s = rot.apply(in, out); !s.isOk()) return val(s.toString());
  return val::array(out);
}

// Projects a cube map given as 6 faces of size*size*3 floats (GL order), returns flat RGB.
val projectCube(int order, int size, const val& faces) {
  prt::CubeMap cube;
  cube.size = size;
  for (int f = 0; f < 6; ++f) cube.faces[static_cast<std::size_t>(f)] = emscripten::convertJSArrayToNumberVector<float>(faces[f]);
  std::vector<prt::Rgb> c;
  if (prt::Status s = prt::projectCubeMap(order, cube, &c); !s.isOk()) return val(s.toString());
  std::vector<float> flat;
  for (const prt::Rgb& v : c) flat.insert(flat.end(), {v.r, v.g, v.b});
  return val::array(flat);
}

}  // namespace

EMSCRIPTEN_BINDINGS(prt_core) {
  emscripten::function("inspectAsset", &inspectAsset);
  emscripten::function("shadeConstant", &shadeConstant);
  emscripten::function("evalBasis", &evalBasis);
  emscripten::function("rotateCoefficients", &rotateCoefficients);
  emscripten::function("projectCube", &projectCube);
}
