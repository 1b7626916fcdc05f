#include "baker/shard/byte_io.h"

#include <cstring>

namespace prt::bake {

void ByteWriter::raw(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  out_->insert(out_->end(), p, p + bytes);
}

bool ByteReader::raw(void* data, std::size_t bytes) {
  if (bytes > remaining()) return false;
  if (bytes > 0) std::memcpy(data, bytes_.data() + offset_, bytes);
  offset_ += bytes;
  return true;
}

namespace {

template <typename T>
bool readArray(ByteReader* r, std::uint64_t count, std::vector<T>* v) {
  if (count > r->remaining() / sizeof(T)) return false;
  v->resize(static_cast<std::size_t>(count));
  return r->raw(v->data(), v->size() * sizeof(T));
}

}  // namespace

bool ByteReader::floats(std::uint64_t count, std::vector<float>* v) { return readArray(this, count, v); }
bool ByteReader::doubles(std::uint64_t count, std::vector<double>* v) { return readArray(this, count, v); }
bool ByteReader::u32s(std::uint64_t count, std::vector<std::uint32_t>* v) { return readArray(this, count, v); }

bool ByteReader::floatView(std::uint64_t count, std::span<const float>* v) {
  const std::uint8_t* p = bytes_.data() + offset_;
  if (count > remaining() / sizeof(float) || reinterpret_cast<std::uintptr_t>(p) % alignof(float) != 0) return false;
  *v = std::span<const float>(reinterpret_cast<const float*>(p), static_cast<std::size_t>(count));
  offset_ += static_cast<std::size_t>(count) * sizeof(float);
  return true;
}

bool ByteReader::string(std::size_t maxBytes, std::string* s) {
  std::uint32_t n = 0;
  if (!u32(&n) || n > maxBytes || n > remaining()) return false;
  s->resize(n);
  return raw(s->data(), n);
}

}  // namespace prt::bake
