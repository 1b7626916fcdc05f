// Little-endian byte writing and bounds-checked reading for the sharded bake's files
// (docs/scale-out.md). The reader never reads past its span: every read says whether the
// bytes were there, so a truncated or hostile file is an error, not a crash.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace prt::bake {

static_assert(std::endian::native == std::endian::little, "the shard files are little-endian, as this host");

// Appends values to a byte vector, little-endian.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<std::uint8_t>* out) : out_(out) {}
  void u32(std::uint32_t v) { raw(&v, sizeof v); }
  void u64(std::uint64_t v) { raw(&v, sizeof v); }
  void f64(double v) { raw(&v, sizeof v); }
  void floats(std::span<const float> v) { raw(v.data(), v.size_bytes()); }
  void doubles(std::span<const double> v) { raw(v.data(), v.size_bytes()); }
  // A u32 byte count, then the bytes.
  void string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    raw(s.data(), s.size());
  }
  void raw(const void* data, std::size_t bytes);

 private:
  std::vector<std::uint8_t>* out_;
};

// Reads values from a span; each call returns false (and reads nothing) when the span ends first.
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  bool u32(std::uint32_t* v) { return raw(v, sizeof *v); }
  bool u64(std::uint64_t* v) { return raw(v, sizeof *v); }
  bool f64(double* v) { return raw(v, sizeof *v); }
  // `count` values; the count is checked against the bytes left before anything is allocated.
  bool floats(std::uint64_t count, std::vector<float>* v);
  bool doubles(std::uint64_t count, std::vector<double>* v);
  bool u32s(std::uint64_t count, std::vector<std::uint32_t>* v);
  // `count` floats viewed in place (no copy: the span lives as long as the reader's bytes);
  // false when they are not all there or not 4-byte aligned in memory (a buffer from a
  // vector or a mapped file, with the file's 4-byte fields before them, always is).
  bool floatView(std::uint64_t count, std::span<const float>* v);
  std::size_t offset() const { return offset_; }
  // A u32 byte count (at most maxBytes), then the bytes.
  bool string(std::size_t maxBytes, std::string* s);
  bool raw(void* data, std::size_t bytes);
  std::size_t remaining() const { return bytes_.size() - offset_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
};

}  // namespace prt::bake
