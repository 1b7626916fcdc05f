#include "prt/rtt.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "prt/checksum.h"
#include "prt/little_endian.h"

namespace prt {
namespace {

constexpr std::uint8_t kMagic[8] = {'P', 'R', 'T', 'R', 'T', 'T', '1', '\n'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 40;  // magic, 6 u32, u64 count
constexpr float kPiF = static_cast<float>(kPi);

bool shapeInRange(int order, int channels, int spatial, int views) {
  return order >= 1 && order <= kMaxRttOrder && (channels == 1 || channels == 3) && spatial >= 1 && spatial <= kMaxRttSpatial &&
         views >= 1 && views <= kMaxRttViews;
}

std::uint64_t countFor(int order, int channels, int spatial, int views) {
  const auto s = static_cast<std::uint64_t>(spatial), v = static_cast<std::uint64_t>(views);
  return s * s * v * v * static_cast<std::uint64_t>(channels) * static_cast<std::uint64_t>(order * order);
}

}  // namespace

std::size_t Rtt::coeffCount() const {
  if (!shapeInRange(order, channels, spatial, views)) return 0;
  return static_cast<std::size_t>(countFor(order, channels, spatial, views));
}

Vec3 rttViewDirection(int a, int b, int views) {
  // Concentric map (Shirley & Chiu 1997) of the cell centre to the unit disk.
  const float sx = 2.0f * (static_cast<float>(a) + 0.5f) / static_cast<float>(views) - 1.0f;
  const float sy = 2.0f * (static_cast<float>(b) + 0.5f) / static_cast<float>(views) - 1.0f;
  float r = 0.0f, phi = 0.0f;
  if (sx != 0.0f || sy != 0.0f) {
    if (std::fabs(sx) > std::fabs(sy)) {
      r = sx;
      phi = (kPiF / 4.0f) * (sy / sx);
    } else {
      r = sy;
      phi = (kPiF / 2.0f) - (kPiF / 4.0f) * (sx / sy);
    }
  }
  const float dx = r * std::cos(phi), dy = r * std::sin(phi);
  // Equal-area map of the unit disk to the hemisphere: z = 1 - r^2, xy scaled by sqrt(2 - r^2).
  const float r2 = std::min(1.0f, dx * dx + dy * dy);
  const float k = std::sqrt(2.0f - r2);
  return {dx * k, dy * k, 1.0f - r2};
}

void rttViewCoordinates(Vec3 w, int views, float* a, float* b) {
  const float z = std::clamp(w.z, 0.0f, 1.0f);
  const float k = std::sqrt(1.0f + z);  // sqrt(2 - r^2) with r^2 = 1 - z
  const float dx = k > 0.0f ? w.x / k : 0.0f, dy = k > 0.0f ? w.y / k : 0.0f;
  // Inverse concentric map: disk point (r, phi) back to the square's [-1, 1]^2.
  const float r = std::sqrt(dx * dx + dy * dy);
  float phi = std::atan2(dy, dx);
  if (phi < -kPiF / 4.0f) phi += 2.0f * kPiF;  // phi in [-pi/4, 7pi/4)
  float sx = 0.0f, sy = 0.0f;
  if (phi < kPiF / 4.0f) {
    sx = r;
    sy = phi * r / (kPiF / 4.0f);
  } else if (phi < 3.0f * kPiF / 4.0f) {
    sy = r;
    sx = -(phi - kPiF / 2.0f) * r / (kPiF / 4.0f);
  } else if (phi < 5.0f * kPiF / 4.0f) {
    sx = -r;
    sy = -(phi - kPiF) * r / (kPiF / 4.0f);
  } else {
    sy = -r;
    sx = (phi - 3.0f * kPiF / 2.0f) * r / (kPiF / 4.0f);
  }
  const float v = static_cast<float>(views);
  *a = std::clamp((sx + 1.0f) * 0.5f * v, 0.0f, v);
  *b = std::clamp((sy + 1.0f) * 0.5f * v, 0.0f, v);
}

Status encodeRtt(const Rtt& rtt, std::vector<std::uint8_t>* out) {
  if (!shapeInRange(rtt.order, rtt.channels, rtt.spatial, rtt.views) || rtt.coeffs.size() != rtt.coeffCount()) {
    return Status::error(StatusCode::kInvalidArgument, "RTT shape out of range or coefficient count disagrees");
  }
  std::vector<std::uint8_t> b(kHeaderBytes + 4 * rtt.coeffs.size() + 4);
  std::memcpy(b.data(), kMagic, sizeof kMagic);
  const std::uint32_t fields[6] = {kVersion,
                                   static_cast<std::uint32_t>(rtt.order),
                                   static_cast<std::uint32_t>(rtt.channels),
                                   static_cast<std::uint32_t>(rtt.spatial),
                                   static_cast<std::uint32_t>(rtt.views),
                                   0u};
  for (int i = 0; i < 6; ++i) writeLe32(&b[8 + 4 * static_cast<std::size_t>(i)], fields[i]);
  writeLe64(&b[32], rtt.coeffs.size());
  for (std::size_t i = 0; i < rtt.coeffs.size(); ++i) writeLe32(&b[kHeaderBytes + 4 * i], floatBits(rtt.coeffs[i]));
  const std::size_t body = b.size() - 4;
  writeLe32(&b[body], crc32c(std::span<const std::uint8_t>(b.data(), body)));
  *out = std::move(b);
  return Status::ok();
}

Status decodeRtt(std::span<const std::uint8_t> bytes, Rtt* out) {
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    return Status::error(StatusCode::kBadMagic, "not an RTT file (magic PRTRTT1)");
  }
  if (bytes.size() < kHeaderBytes + 4) return Status::error(StatusCode::kTruncated, "RTT file ends inside its header");
  const std::uint32_t version = readLe32(&bytes[8]);
  if (version != kVersion) {
    return Status::error(StatusCode::kBadVersion, "RTT version " + std::to_string(version) + " (this reader reads 1)");
  }
  const std::uint32_t order = readLe32(&bytes[12]), channels = readLe32(&bytes[16]), spatial = readLe32(&bytes[20]),
                      views = readLe32(&bytes[24]), flags = readLe32(&bytes[28]);
  const std::uint64_t count = readLe64(&bytes[32]);
  if (order < 1 || order > kMaxRttOrder || (channels != 1 && channels != 3) || spatial < 1 || spatial > kMaxRttSpatial || views < 1 ||
      views > kMaxRttViews || flags != 0) {
    return Status::error(StatusCode::kCorrupt, "RTT header out of range (order " + std::to_string(order) + ", channels " +
                                                   std::to_string(channels) + ", spatial " + std::to_string(spatial) + ", views " +
                                                   std::to_string(views) + ", flags " + std::to_string(flags) + ")");
  }
  const int o = static_cast<int>(order), c = static_cast<int>(channels), s = static_cast<int>(spatial), v = static_cast<int>(views);
  if (count != countFor(o, c, s, v)) return Status::error(StatusCode::kCorrupt, "RTT coefficient count disagrees with its shape");
  // count <= 1024^2 * 32^2 * 3 * 64 < 2^38: the byte size below cannot overflow.
  const std::uint64_t need = kHeaderBytes + 4 * count + 4;
  if (bytes.size() < need) return Status::error(StatusCode::kTruncated, "RTT file ends inside its coefficients");
  if (bytes.size() > need) return Status::error(StatusCode::kCorrupt, "RTT file has bytes after its checksum");
  const std::size_t body = static_cast<std::size_t>(need) - 4;
  if (readLe32(&bytes[body]) != crc32c(bytes.first(body))) return Status::error(StatusCode::kChecksumMismatch, "RTT checksum mismatch");
  Rtt r;
  r.order = o;
  r.channels = c;
  r.spatial = s;
  r.views = v;
  r.coeffs.resize(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < r.coeffs.size(); ++i) {
    r.coeffs[i] = readLeF32(&bytes[kHeaderBytes + 4 * i]);
    if (!std::isfinite(r.coeffs[i])) return Status::error(StatusCode::kCorrupt, "RTT coefficient " + std::to_string(i) + " is not finite");
  }
  *out = std::move(r);
  return Status::ok();
}

}  // namespace prt
