// libFuzzer entry point for the RTT reader (prt/rtt.h, docs/bi-scale.md "RTT file"). Build:
//   clang++ -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -Ishared \
//     tests/fuzz/rtt_fuzz.cpp shared/prt/rtt.cpp shared/prt/bi_scale.cpp shared/prt/checksum.cpp \
//     shared/prt/sh_rotation.cpp shared/prt/sh_basis.cpp shared/prt/transfer_matrix.cpp shared/prt/status.cpp shared/prt/vec3.cpp \
//     -o rtt_fuzz
//   ./rtt_fuzz -max_total_time=60 CORPUS_DIR
//
// Random bytes almost never pass the CRC, which would confine the fuzzer to the header
// checks: with bit 0 of the first byte set, the rest gets its trailing checksum recomputed
// before decoding, so the shape, size and coefficient checks are reached too. Beyond "no
// crash, no sanitizer report" it traps when a decoded RTT does not re-encode to the same
// bytes, or when a lookup of it is not finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "prt/bi_scale.h"
#include "prt/checksum.h"
#include "prt/rtt.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool reseal = data[0] & 1;
  std::vector<std::uint8_t> bytes(data + 1, data + size);
  if (reseal && bytes.size() >= 4) {
    const std::uint32_t crc = prt::crc32c(std::span<const std::uint8_t>(bytes.data(), bytes.size() - 4));
    for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
  }
  prt::Rtt rtt;
  if (!prt::decodeRtt(bytes, &rtt).isOk()) return 0;
  std::vector<std::uint8_t> again;
  if (!prt::encodeRtt(rtt, &again).isOk() || again != bytes) std::abort();
  std::vector<float> out(static_cast<std::size_t>(rtt.channels * rtt.order * rtt.order));
  for (int k = 0; k < 4; ++k) {
    const float t = static_cast<float>(k) * 0.7f - 0.9f;
    prt::rttLookup(rtt, t, 1.0f - t, prt::Vec3{t, -0.3f * t, 0.5f}, k % 2 == 0, out.data());
    for (float v : out)
      if (!std::isfinite(v)) std::abort();
  }
  return 0;
}
