#include "native/byte_compressors.h"

#include <brotli/decode.h>
#include <brotli/encode.h>
#include <zstd.h>

#include <cstring>
#include <vector>

namespace prt {

Status zstdCompressedSize(std::span<const std::uint8_t> bytes, int level, std::size_t* out) {
  std::vector<std::uint8_t> packed(ZSTD_compressBound(bytes.size()));
  const std::size_t n = ZSTD_compress(packed.data(), packed.size(), bytes.data(), bytes.size(), level);
  if (ZSTD_isError(n)) return Status::error(StatusCode::kInternal, std::string("zstd: ") + ZSTD_getErrorName(n));
  // A size is only worth reporting if the bytes come back.
  std::vector<std::uint8_t> back(bytes.size());
  const std::size_t m = ZSTD_decompress(back.data(), back.size(), packed.data(), n);
  if (ZSTD_isError(m) || m != bytes.size() || (m > 0 && std::memcmp(back.data(), bytes.data(), m) != 0)) {
    return Status::error(StatusCode::kInternal, "zstd: the compressed bytes do not decompress to the input");
  }
  *out = n;
  return Status::ok();
}

Status brotliCompressedSize(std::span<const std::uint8_t> bytes, int quality, int lgwin, std::size_t* out) {
  std::size_t n = BrotliEncoderMaxCompressedSize(bytes.size());
  if (n == 0) return Status::error(StatusCode::kResourceExhausted, "brotli: input too large");
  std::vector<std::uint8_t> packed(n);
  if (!BrotliEncoderCompress(quality, lgwin, BROTLI_MODE_GENERIC, bytes.size(), bytes.data(), &n, packed.data())) {
    return Status::error(StatusCode::kInternal, "brotli: compression failed");
  }
  std::vector<std::uint8_t> back(bytes.size());
  std::size_t m = back.size();
  if (BrotliDecoderDecompress(n, packed.data(), &m, back.data()) != BROTLI_DECODER_RESULT_SUCCESS || m != bytes.size() ||
      (m > 0 && std::memcmp(back.data(), bytes.data(), m) != 0)) {
    return Status::error(StatusCode::kInternal, "brotli: the compressed bytes do not decompress to the input");
  }
  *out = n;
  return Status::ok();
}

}  // namespace prt
