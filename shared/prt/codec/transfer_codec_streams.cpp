#include "transfer_codec_streams.h"

#include <array>
#include <cmath>
#include <cstring>

namespace prt::transfer_codec {

void putU8(std::vector<std::uint8_t>& out, std::uint8_t v) { out.push_back(v); }
void putU16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void putU64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void putF32(std::vector<std::uint8_t>& out, float v) { putU32(out, floatBits(v)); }

std::uint32_t zigzag(std::int32_t value, int width) {
  const auto u = static_cast<std::uint32_t>(value);
  const std::uint32_t signMask = value < 0 ? 0xffffffffu : 0u;
  const std::uint32_t code = (u << 1) ^ signMask;
  return width >= 4 ? code : code & ((1u << (8 * width)) - 1u);
}

std::int32_t unzigzag(std::uint32_t code) {
  const std::uint32_t u = (code >> 1) ^ (0u - (code & 1u));
  std::int32_t v;
  std::memcpy(&v, &u, sizeof v);  // two's complement reinterpretation, defined for every u
  return v;
}

std::int32_t wrapToWidth(std::int64_t value, int width) {
  const int bits = 8 * width;
  const std::uint64_t mask = bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1u;
  std::uint64_t u = static_cast<std::uint64_t>(value) & mask;
  if (bits < 64 && (u >> (bits - 1)) & 1u) u |= ~mask;  // sign-extend
  std::int64_t s;
  std::memcpy(&s, &u, sizeof s);
  return static_cast<std::int32_t>(s);
}

namespace {

// The zig-zag codes of one stream after `filter`.
void filteredCodes(const std::int32_t* values, std::size_t count, int width, StreamFilter filter,
                   std::vector<std::uint32_t>& codes) {
  codes.resize(count);
  std::int64_t previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int32_t e = filter == StreamFilter::kDelta ? wrapToWidth(values[i] - previous, width) : values[i];
    codes[i] = zigzag(e, width);
    previous = values[i];
  }
}

// Order-0 entropy in bytes of byte plane p (0 = most significant) of the codes.
double planeEntropyBytes(const std::vector<std::uint32_t>& codes, int width, int p) {
  std::array<std::size_t, 256> histogram{};
  const int shift = 8 * (width - 1 - p);
  for (std::uint32_t c : codes) ++histogram[(c >> shift) & 0xffu];
  const double n = static_cast<double>(codes.size());
  double bits = 0.0;
  for (std::size_t h : histogram) {
    if (h != 0) bits -= static_cast<double>(h) * std::log2(static_cast<double>(h) / n);
  }
  return bits / 8.0;
}

double codesEntropyBytes(const std::vector<std::uint32_t>& codes, int width) {
  double total = 0.0;
  for (int p = 0; p < width; ++p) total += planeEntropyBytes(codes, width, p);
  return total;
}

// The filter with the smaller entropy estimate (ties: none), and that estimate.
StreamFilter chooseFilter(const std::int32_t* values, std::size_t count, int width, std::vector<std::uint32_t>& codes,
                          double* entropyBytes) {
  filteredCodes(values, count, width, StreamFilter::kNone, codes);
  const double plain = codesEntropyBytes(codes, width);
  filteredCodes(values, count, width, StreamFilter::kDelta, codes);
  const double delta = codesEntropyBytes(codes, width);
  *entropyBytes = delta < plain ? delta : plain;
  return delta < plain ? StreamFilter::kDelta : StreamFilter::kNone;
}

}  // namespace

std::uint64_t streamGroupBytes(std::uint64_t streams, std::uint64_t count, int width) {
  return streams + streams * count * static_cast<std::uint64_t>(width);
}

void putStreamGroup(std::span<const std::int32_t> values, std::size_t streams, std::size_t count, int width,
                    std::vector<std::uint8_t>& out) {
  std::vector<std::uint32_t> codes;
  std::vector<StreamFilter> filters(streams);
  for (std::size_t s = 0; s < streams; ++s) {
    double unused = 0.0;
    filters[s] = chooseFilter(values.data() + s * count, count, width, codes, &unused);
    out.push_back(static_cast<std::uint8_t>(filters[s]));
  }
  const std::size_t planes = out.size();
  out.resize(planes + streams * count * static_cast<std::size_t>(width));
  for (std::size_t s = 0; s < streams; ++s) {
    filteredCodes(values.data() + s * count, count, width, filters[s], codes);
    for (int p = 0; p < width; ++p) {
      std::uint8_t* plane = out.data() + planes + (static_cast<std::size_t>(p) * streams + s) * count;
      const int shift = 8 * (width - 1 - p);
      for (std::size_t i = 0; i < count; ++i) plane[i] = static_cast<std::uint8_t>(codes[i] >> shift);
    }
  }
}

double estimateStreamGroupBytes(std::span<const std::int32_t> values, std::size_t streams, std::size_t count,
                                int width) {
  std::vector<std::uint32_t> codes;
  double total = static_cast<double>(streams);
  for (std::size_t s = 0; s < streams; ++s) {
    double bytes = 0.0;
    chooseFilter(values.data() + s * count, count, width, codes, &bytes);
    total += bytes;
  }
  return total;
}

namespace {

// The low 8*W bits of u, sign-extended.
template <int W>
std::int32_t signExtend(std::uint32_t u) {
  if constexpr (W == 1) return static_cast<std::int8_t>(static_cast<std::uint8_t>(u));
  if constexpr (W == 2) return static_cast<std::int16_t>(static_cast<std::uint16_t>(u));
  std::int32_t v;
  std::memcpy(&v, &u, sizeof v);
  return v;
}

// getStream's loop for one width and filter (the decoder's hot path: a branch-free body).
// Deltas are summed modulo 2^32; only the low 8*W bits matter to the wrap, so this equals
// wrapToWidth(previous + e, W) at every step.
template <int W, bool Delta>
void readStream(const std::uint8_t* planes, std::size_t streams, std::size_t count, std::size_t stream, std::int32_t* out) {
  const std::uint8_t* plane[W];
  for (int p = 0; p < W; ++p) plane[p] = planes + (static_cast<std::size_t>(p) * streams + stream) * count;
  std::uint32_t previous = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t code = 0;
    for (int p = 0; p < W; ++p) code = (code << 8) | plane[p][i];
    std::uint32_t u = static_cast<std::uint32_t>(unzigzag(code));
    if constexpr (Delta) u += previous;
    previous = u;
    out[i] = signExtend<W>(u);
  }
}

template <int W>
void readStream(bool delta, const std::uint8_t* planes, std::size_t streams, std::size_t count, std::size_t stream,
                std::int32_t* out) {
  if (delta) {
    readStream<W, true>(planes, streams, count, stream, out);
  } else {
    readStream<W, false>(planes, streams, count, stream, out);
  }
}

}  // namespace

bool getStream(const std::uint8_t* group, std::size_t streams, std::size_t count, int width, std::size_t stream,
               std::span<std::int32_t> out) {
  const std::uint8_t filter = group[stream];
  if (filter > static_cast<std::uint8_t>(StreamFilter::kDelta) || out.size() < count) return false;
  const bool delta = filter == static_cast<std::uint8_t>(StreamFilter::kDelta);
  const std::uint8_t* planes = group + streams;
  switch (width) {
    case 1: readStream<1>(delta, planes, streams, count, stream, out.data()); return true;
    case 2: readStream<2>(delta, planes, streams, count, stream, out.data()); return true;
    case 4: readStream<4>(delta, planes, streams, count, stream, out.data()); return true;
    default: return false;
  }
}

}  // namespace prt::transfer_codec
