// What the matrix codec's tests share (transfer_codec_matrix_test.cpp, _weights_test.cpp,
// _basis8_test.cpp): a seeded generator, encode/decode that fail the test on an error, and
// the two packings.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "prt/transfer_codec.h"
#include "prt/transfer_matrix.h"

namespace prt::codec_test {

using Bytes = std::vector<std::uint8_t>;

// A 64-bit LCG: the same sequence on every platform and toolchain (native and wasm).
struct Lcg {
  std::uint64_t s;
  double next() {  // uniform in [0, 1)
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) * 0x1.0p-53;
  }
  double gauss() {
    const double u = 1.0 - next(), v = next();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
  }
};

// encodeTransferMatrix's blob; an error fails the calling test (and returns what was written).
inline Bytes encodeOrDie(const std::vector<float>& x, int order, MatrixPacking packing, int channels,
                         const TransferCodecSettings& s, TransferEncodeReport* report = nullptr) {
  Bytes blob;
  const Status st = encodeTransferMatrix(x, order, packing, channels, s, &blob, report);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return blob;
}

// decodeTransferMatrix of the first `bands` bands; an error fails the calling test.
inline std::vector<float> decodeOrDie(const Bytes& blob, int bands) {
  std::vector<float> out;
  const Status st = decodeTransferMatrix(blob, bands, &out);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return out;
}

inline constexpr MatrixPacking kPackings[] = {MatrixPacking::kSymmetric, MatrixPacking::kFull};

}  // namespace prt::codec_test
