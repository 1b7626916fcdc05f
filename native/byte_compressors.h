// One-shot zstd and brotli compression, for `prt-bake compress-report`'s sizes. The server
// has its own encoders (server/compression.h) tuned for speed; these run at the maximum
// levels, which is what a once-per-asset precompressed variant can afford.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "prt/status.h"

namespace prt {

inline constexpr int kReportZstdLevel = 19;     // `zstd -19`
inline constexpr int kReportBrotliQuality = 11; // brotli's maximum
inline constexpr int kReportBrotliWindow = 24;  // log2 window: 16 MiB, brotli's largest standard window

// Size in bytes of `bytes` compressed with zstd at `level`, checked by decompressing it.
Status zstdCompressedSize(std::span<const std::uint8_t> bytes, int level, std::size_t* out);

// Size in bytes of `bytes` compressed with brotli at `quality` and window 2^lgwin.
Status brotliCompressedSize(std::span<const std::uint8_t> bytes, int quality, int lgwin, std::size_t* out);

}  // namespace prt
