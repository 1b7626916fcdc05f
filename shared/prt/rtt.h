// Radiance transfer textures (Sloan et al. 2003, "Bi-scale radiance transfer", §3 and §4.2):
// a patch's meso-scale response to SH lighting as a function of position and view, and its
// file format (docs/bi-scale.md, "RTT file", byte by byte). Shared by the baker (prt-bake
// rtt writes it) and the client (reads it); the reader is safe on untrusted bytes.
//
// Frame: the patch's tangent frame, +z its macro normal, +x along u (the tangent), +y along
// v; the patch spans [0, 1)^2 in (u, v) and repeats. B_i(u, w) is the radiance leaving the
// patch at u toward the unit direction w (z > 0) under lighting y_i in that frame, per unit
// SH coefficient: exit radiance = sum_i B_i(u, w) L_i.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "prt/status.h"
#include "prt/vec3.h"

namespace prt {

// Limits the reader accepts (and the baker writes within).
inline constexpr int kMaxRttOrder = 8;
inline constexpr int kMaxRttSpatial = 1024;
inline constexpr int kMaxRttViews = 32;

struct Rtt {
  int order = 0;        // SH bands n (n^2 coefficients per channel)
  int channels = 0;     // 1 (grey albedo) or 3 (RGB)
  int spatial = 0;      // S: S x S spatial samples, sample (x, y) centred at ((x + 0.5) / S, (y + 0.5) / S)
  int views = 0;        // V: V x V view samples (rttViewDirection); 1: view-independent (the diffuse special case)
  // B, float: coefficient i of channel c at spatial sample (x, y) and view sample (a, b) at
  // [(((y * S + x) * V + b) * V + a) * channels + c] * n^2 + i.
  std::vector<float> coeffs;

  std::size_t coeffCount() const;  // S^2 V^2 channels n^2 for the shape fields
};

// View sample (a, b) of V x V (a, b < V): the centre of its cell of the unit square mapped to
// the upper hemisphere by Shirley & Chiu's concentric map to the disk, then the equal-area
// (Lambert azimuthal) map of the disk to the hemisphere: both area-preserving, so every view
// sample covers 2 pi / V^2 sr. V = 1 gives +z.
Vec3 rttViewDirection(int a, int b, int views);

// The inverse: continuous view-sample coordinates (a, b) in [0, V) of a unit direction with
// z >= 0 (a sample's centre direction maps to a + 0.5, b + 0.5); for bilinear lookups.
void rttViewCoordinates(Vec3 w, int views, float* a, float* b);

// Serialises `rtt` (shape fields and coeffs consistent; kInvalidArgument otherwise).
Status encodeRtt(const Rtt& rtt, std::vector<std::uint8_t>* out);

// Parses an RTT file: every field range-checked, sizes checked against the bytes, the
// CRC-32C checked; kBadMagic, kBadVersion, kTruncated, kChecksumMismatch or kCorrupt otherwise.
// Safe on untrusted bytes.
Status decodeRtt(std::span<const std::uint8_t> bytes, Rtt* out);

}  // namespace prt
