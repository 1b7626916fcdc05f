#include "compression.h"

#include <brotli/encode.h>
#include <zlib.h>
#include <zstd.h>
#include <zstd_errors.h>

#include <limits>

namespace prt::serve {
namespace {

// Measured on baked rooms (2.8 and 4.9 MB; docs/server.md): the variants are 37-48% of
// the original whatever the level, so levels are picked for speed. gzip 6 (zlib's default;
// 9 buys under 0.5%): 21 MB/s.
constexpr int kGzipLevel = 6;
// zstd 9: as small as 12 at twice its speed (50 MB/s); 19 saves 0.5% more at 5 MB/s.
constexpr int kZstdLevel = 9;
// Brotli 5: within 0.2% of 9 at 4x its speed (30 MB/s); 11 saves 2% more at 0.3 MB/s,
// which would hold a scan of a 100 MB asset for five minutes.
constexpr int kBrotliQuality = 5;

Status fail(StatusCode code, const char* what) { return Status::error(code, what); }

// Each encoder below gets an output buffer of its library's worst-case bound, so "does not
// fit" cannot happen: a failure is memory (kResourceExhausted) or a bug (kInternal).

Status gzip(std::span<const std::uint8_t> in, std::string* out) {
  if (in.size() > std::numeric_limits<uInt>::max()) return fail(StatusCode::kResourceExhausted, "gzip: input too large");
  z_stream z{};
  // windowBits 15 + 16: a gzip wrapper rather than zlib's own.
  if (const int init = deflateInit2(&z, kGzipLevel, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY); init != Z_OK) {
    // Z_MEM_ERROR is memory; the other result (Z_STREAM_ERROR) means these constants are wrong.
    return init == Z_MEM_ERROR ? fail(StatusCode::kResourceExhausted, "gzip: out of memory")
                               : fail(StatusCode::kInternal, "gzip: init failed");
  }
  out->resize(deflateBound(&z, static_cast<uLong>(in.size())));
  z.next_in = const_cast<Bytef*>(in.data());  // zlib's API is not const-correct; it only reads
  z.avail_in = static_cast<uInt>(in.size());
  z.next_out = reinterpret_cast<Bytef*>(out->data());
  z.avail_out = static_cast<uInt>(out->size());
  const int rc = deflate(&z, Z_FINISH);
  const std::size_t written = out->size() - z.avail_out;
  deflateEnd(&z);
  if (rc != Z_STREAM_END) return fail(StatusCode::kInternal, "gzip: deflate failed");
  out->resize(written);
  return Status::ok();
}

Status zstd(std::span<const std::uint8_t> in, std::string* out) {
  out->resize(ZSTD_compressBound(in.size()));
  const std::size_t n = ZSTD_compress(out->data(), out->size(), in.data(), in.size(), kZstdLevel);
  if (ZSTD_isError(n)) {
    return ZSTD_getErrorCode(n) == ZSTD_error_memory_allocation ? fail(StatusCode::kResourceExhausted, "zstd: out of memory")
                                                                : fail(StatusCode::kInternal, "zstd: compression failed");
  }
  out->resize(n);
  return Status::ok();
}

Status brotli(std::span<const std::uint8_t> in, std::string* out) {
  std::size_t n = BrotliEncoderMaxCompressedSize(in.size());
  if (n == 0) return fail(StatusCode::kResourceExhausted, "brotli: input too large");
  out->resize(n);
  if (!BrotliEncoderCompress(kBrotliQuality, BROTLI_DEFAULT_WINDOW, BROTLI_MODE_GENERIC, in.size(), in.data(), &n,
                             reinterpret_cast<std::uint8_t*>(out->data()))) {
    // With a buffer of the maximum compressed size, the encoder fails only to allocate.
    return fail(StatusCode::kResourceExhausted, "brotli: compression failed (out of memory)");
  }
  out->resize(n);
  return Status::ok();
}

}  // namespace

const char* encodingToken(Encoding encoding) {
  switch (encoding) {
    case Encoding::kIdentity: return "identity";
    case Encoding::kGzip: return "gzip";
    case Encoding::kZstd: return "zstd";
    case Encoding::kBrotli: return "br";
  }
  return "identity";
}

const char* encodingTag(Encoding encoding) {
  switch (encoding) {
    case Encoding::kIdentity: return "";
    case Encoding::kGzip: return "gz";
    case Encoding::kZstd: return "zst";
    case Encoding::kBrotli: return "br";
  }
  return "";
}

Status compressBytes(Encoding encoding, std::span<const std::uint8_t> bytes, std::string* out) {
  switch (encoding) {
    case Encoding::kGzip: return gzip(bytes, out);
    case Encoding::kZstd: return zstd(bytes, out);
    case Encoding::kBrotli: return brotli(bytes, out);
    case Encoding::kIdentity: break;
  }
  return fail(StatusCode::kInvalidArgument, "identity is not a compression");
}

}  // namespace prt::serve
