// prt-bench-uv-atlas: the native half of the UV unwrapper evaluation (uv-atlas-eval.sh,
// docs/transfer-textures.md "UV atlas"). The unwrappers under trial (xatlasjs in Node,
// Blender in Python) exchange meshes with it in a raw format (mesh_raw.md), so that every
// generator sees the same world-space soup the baker loads and every result is judged by the
// baker's own atlas check.
//
//   prt-bench-uv-atlas export IN.gltf|glb OUT.mesh     the loaded scene, no UVs
//   prt-bench-uv-atlas check IN.mesh SIZE PADDING      the atlas check as one JSON line
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "baker/scene/gltf_loader.h"
#include "baker/scene/uv_atlas_check.h"

namespace {

using prt::bake::Uv;
using prt::Vec3;

struct RawMesh {
  std::vector<Vec3> positions;
  std::vector<Uv> uvs;  // empty or one per position
  std::vector<std::uint32_t> indices;
};

constexpr char kMagic[4] = {'P', 'R', 'T', 'M'};

bool writeRaw(const std::string& path, const RawMesh& m) {
  std::ofstream out(path, std::ios::binary);
  const std::uint32_t header[3] = {static_cast<std::uint32_t>(m.positions.size()),
                                   static_cast<std::uint32_t>(m.indices.size() / 3), m.uvs.empty() ? 0u : 1u};
  out.write(kMagic, 4);
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out.write(reinterpret_cast<const char*>(m.positions.data()), static_cast<std::streamsize>(m.positions.size() * 12));
  out.write(reinterpret_cast<const char*>(m.uvs.data()), static_cast<std::streamsize>(m.uvs.size() * 8));
  out.write(reinterpret_cast<const char*>(m.indices.data()), static_cast<std::streamsize>(m.indices.size() * 4));
  return static_cast<bool>(out);
}

// Reads what writeRaw writes (and what the generators write); sizes are checked against the
// file length before anything is allocated.
bool readRaw(const std::string& path, RawMesh* m, std::string* error) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return *error = "cannot open " + path, false;
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  char magic[4];
  std::uint32_t header[3];
  if (size < 16 || !in.read(magic, 4) || std::memcmp(magic, kMagic, 4) != 0 ||
      !in.read(reinterpret_cast<char*>(header), sizeof header))
    return *error = path + ": not a PRTM mesh", false;
  const std::uint64_t n = header[0], t = header[1], hasUv = header[2];
  if (hasUv > 1 || 16 + n * 12 + hasUv * n * 8 + t * 12 != size)
    return *error = path + ": the header's counts do not match the file size", false;
  m->positions.resize(n);
  m->uvs.resize(hasUv ? n : 0);
  m->indices.resize(3 * t);
  in.read(reinterpret_cast<char*>(m->positions.data()), static_cast<std::streamsize>(n * 12));
  in.read(reinterpret_cast<char*>(m->uvs.data()), static_cast<std::streamsize>(m->uvs.size() * 8));
  in.read(reinterpret_cast<char*>(m->indices.data()), static_cast<std::streamsize>(t * 12));
  return static_cast<bool>(in) || (*error = path + ": short read", false);
}

int usage() {
  std::fprintf(stderr, "usage: prt-bench-uv-atlas export IN.gltf OUT.mesh | check IN.mesh SIZE PADDING\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage();
  const std::string mode = argv[1];
  if (mode == "export" && argc == 4) {
    prt::bake::Scene scene;
    if (const prt::Status s = prt::bake::loadGltf(argv[2], &scene, nullptr); !s.isOk()) {
      std::fprintf(stderr, "%s\n", s.message().c_str());
      return 1;
    }
    RawMesh m{scene.positions, {}, scene.indices};
    if (!writeRaw(argv[3], m)) return std::fprintf(stderr, "cannot write %s\n", argv[3]), 1;
    std::printf("{\"vertices\":%zu,\"triangles\":%zu}\n", m.positions.size(), m.indices.size() / 3);
    return 0;
  }
  if (mode == "check" && argc == 5) {
    RawMesh m;
    std::string error;
    if (!readRaw(argv[2], &m, &error)) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
    if (m.uvs.empty()) return std::fprintf(stderr, "%s has no UVs\n", argv[2]), 1;
    const prt::bake::UvAtlasTarget target{std::atoi(argv[3]), std::atoi(argv[3]), std::atoi(argv[4])};
    prt::bake::UvAtlasReport r;
    if (const prt::Status s = prt::bake::checkUvAtlas(m.positions, m.indices, m.uvs, target, "generated", &r);
        !s.isOk()) {
      std::fprintf(stderr, "%s\n", s.message().c_str());
      return 1;
    }
    std::printf(
        "{\"valid\":%s,\"triangles\":%zu,\"vertices\":%zu,\"charts\":%zu,\"usedTexelFraction\":%.4f,"
        "\"outOfRange\":%zu,\"nonFinite\":%zu,\"degenerate\":%zu,\"overlappingPairs\":%zu,\"deepestOverlapTexels\":%.4g,\"paddingConflicts\":%zu,"
        "\"summary\":\"%s\",\"first\":\"%s\"}\n",
        r.valid() ? "true" : "false", r.triangles, m.positions.size(), r.charts, r.usedTexelFraction, r.outOfRange,
        r.nonFinite, r.degenerate, r.overlappingPairs, r.deepestOverlapTexels, r.paddingConflicts, r.summary().c_str(),
        r.problems.empty() ? "" : r.problems.front().c_str());
    for (const std::string& line : r.problems) std::fprintf(stderr, "%s\n", line.c_str());
    return 0;
  }
  return usage();
}
