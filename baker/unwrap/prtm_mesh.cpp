#include "baker/unwrap/prtm_mesh.h"

#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "native/file_io.h"

namespace prt::bake {
namespace {

static_assert(std::endian::native == std::endian::little, "PRTM is little-endian; this writer copies memory as is");
static_assert(sizeof(Vec3) == 12 && sizeof(Uv) == 8, "PRTM stores packed float32 triples and pairs");

constexpr char kMagic[4] = {'P', 'R', 'T', 'M'};

template <typename T>
void append(std::vector<std::uint8_t>* out, const T* data, std::size_t count) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + count * sizeof(T));
}

}  // namespace

Status writeScratchFile(const std::string& path, std::span<const std::uint8_t> bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return Status::error(statusCodeForErrno(errno), "cannot create '" + path + "': " + std::strerror(errno));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const int writeErrno = errno;
  if (std::fclose(f) != 0 || !written) {
    const int e = written ? errno : writeErrno;
    return Status::error(statusCodeForErrno(e), "cannot write '" + path + "': " + std::strerror(e));
  }
  return Status::ok();
}

Status writePrtmMesh(const std::string& path, std::span<const Vec3> positions, std::span<const std::uint32_t> indices) {
  if (positions.size() > UINT32_MAX || indices.size() / 3 > UINT32_MAX || indices.size() % 3 != 0) {
    return Status::error(StatusCode::kInvalidArgument, "the mesh is too large for the unwrapper's exchange format");
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(16 + positions.size() * 12 + indices.size() * 4);
  const std::uint32_t header[3] = {static_cast<std::uint32_t>(positions.size()),
                                   static_cast<std::uint32_t>(indices.size() / 3), 0u};
  append(&bytes, kMagic, 4);
  append(&bytes, header, 3);
  append(&bytes, positions.data(), positions.size());
  append(&bytes, indices.data(), indices.size());
  // A scratch file in a private directory: no rename or fsync needed (nobody else reads it,
  // and a crash discards it), and writeFileAtomically's signal handler must not replace the
  // unwrap workspace's.
  return writeScratchFile(path, bytes);
}

Status readPrtmCorners(const std::string& path, std::size_t triangles, std::vector<Vec3>* positions,
                       std::vector<Uv>* uvs) {
  const std::uint64_t corners = 3 * static_cast<std::uint64_t>(triangles);
  const std::uint64_t expected = 16 + corners * (12 + 8 + 4);
  std::vector<std::uint8_t> bytes;
  PRT_RETURN_IF_ERROR(readFileBytes(path, expected, &bytes));
  auto bad = [&](const std::string& why) {
    return Status::error(StatusCode::kCorrupt, "the unwrapped mesh '" + path + "' " + why);
  };
  if (bytes.size() != expected) {
    return bad("has " + std::to_string(bytes.size()) + " bytes, expected " + std::to_string(expected));
  }
  std::uint32_t header[3];
  std::memcpy(header, bytes.data() + 4, sizeof header);
  if (std::memcmp(bytes.data(), kMagic, 4) != 0 || header[0] != corners || header[1] != triangles || header[2] != 1) {
    return bad("does not hold one UV'd vertex per corner of " + std::to_string(triangles) + " triangles");
  }
  const std::uint8_t* p = bytes.data() + 16;
  positions->resize(corners);
  uvs->resize(corners);
  std::memcpy(positions->data(), p, corners * 12);
  std::memcpy(uvs->data(), p + corners * 12, corners * 8);
  const std::uint8_t* idx = p + corners * 20;
  for (std::uint64_t c = 0; c < corners; ++c) {
    std::uint32_t i;
    std::memcpy(&i, idx + 4 * c, 4);
    if (i != c) return bad("is not in corner order (index " + std::to_string(c) + " is " + std::to_string(i) + ")");
  }
  return Status::ok();
}

}  // namespace prt::bake
