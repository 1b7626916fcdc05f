// The transfer codec (docs/transfer-codec.md): error bounds of every encoding against
// independent references, band-prefix decoding, determinism, and a decoder that rejects
// every truncation, every single-byte corruption and every crafted inconsistency with a
// named error (also run under ASan + UBSan, and in wasm).
//
// The helpers below re-implement the layout from the document, not from the codec's
// sources: `referenceDecode` is an independent decoder (double precision, ldexp for
// float16), `reseal` recomputes every checksum after a deliberate edit so the decoder's
// content checks are reached rather than stopped at a checksum.
#include "prt/transfer_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "prt/asset.h"
#include "prt/checksum.h"
#include "prt/sampling.h"
#include "prt/sh_basis.h"
#include "prt/sh_zonal.h"
#include "transfer_codec_eigen.h"
#include "prt/half_float.h"
#include "transfer_codec_kmeans.h"
#include "transfer_codec_streams.h"

namespace prt {
namespace {

using Bytes = std::vector<std::uint8_t>;
namespace tc = transfer_codec;

// ---- The layout, straight from the document ----------------------------------------------

constexpr std::size_t kHdrVersionMajor = 4, kHdrEncoding = 8, kHdrWeightBits = 9, kHdrOrder = 10, kHdrChannels = 11,
                      kHdrVertices = 12, kHdrClusters = 16, kHdrParts = 20, kHdrBlobSize = 24, kHdrTableCrc = 32,
                      kHdrReserved = 36, kHdrCrc = 44, kHeaderBytes = 48, kEntryBytes = 24;
constexpr std::size_t kEType = 0, kEBand = 2, kECrc = 4, kEOffset = 8, kESize = 16;

std::uint16_t rd16(const Bytes& b, std::size_t at) { return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8)); }
std::uint32_t rd32(const Bytes& b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}
std::uint64_t rd64(const Bytes& b, std::size_t at) {
  return static_cast<std::uint64_t>(rd32(b, at)) | static_cast<std::uint64_t>(rd32(b, at + 4)) << 32;
}
void wr16(Bytes& b, std::size_t at, std::uint16_t v) {
  b[at] = static_cast<std::uint8_t>(v);
  b[at + 1] = static_cast<std::uint8_t>(v >> 8);
}
void wr32(Bytes& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void wr64(Bytes& b, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint32_t bitsOf(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
float floatOf(std::uint32_t u) {
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

std::size_t entryAt(std::size_t i) { return kHeaderBytes + i * kEntryBytes; }
std::size_t partOffset(const Bytes& b, std::size_t i) { return static_cast<std::size_t>(rd64(b, entryAt(i) + kEOffset)); }
std::size_t partSize(const Bytes& b, std::size_t i) { return static_cast<std::size_t>(rd64(b, entryAt(i) + kESize)); }

// Recomputes part, table and header checksums wherever they fit in the bytes.
void reseal(Bytes& b) {
  if (b.size() < kHeaderBytes) return;
  const std::uint64_t parts = rd32(b, kHdrParts);
  const std::uint64_t tableEnd = kHeaderBytes + parts * kEntryBytes;
  if (tableEnd <= b.size()) {
    for (std::size_t i = 0; i < parts; ++i) {
      const std::uint64_t off = rd64(b, entryAt(i) + kEOffset), size = rd64(b, entryAt(i) + kESize);
      if (off <= b.size() && size <= b.size() - off) {
        wr32(b, entryAt(i) + kECrc, crc32c({b.data() + off, static_cast<std::size_t>(size)}));
      }
    }
    wr32(b, kHdrTableCrc, crc32c({b.data() + kHeaderBytes, static_cast<std::size_t>(tableEnd - kHeaderBytes)}));
  }
  wr32(b, kHdrCrc, crc32c({b.data(), kHdrCrc}));
}

// binary16 value by its definition (sign, 5-bit exponent biased by 15, 10-bit fraction).
double halfValue(std::uint16_t h) {
  const int e = (h >> 10) & 31, f = h & 1023;
  const double sign = (h & 0x8000) ? -1.0 : 1.0;
  if (e == 31) return f ? std::numeric_limits<double>::quiet_NaN() : sign * std::numeric_limits<double>::infinity();
  return e == 0 ? sign * std::ldexp(f, -24) : sign * std::ldexp(1024 + f, e - 25);
}

// The float bits behind an ordered key of `width` bytes (document: "Value keys").
std::uint32_t keyToBits(std::int64_t key, int width) {
  if (key >= 0) return static_cast<std::uint32_t>(key);
  return (1u << (8 * width - 1)) | static_cast<std::uint32_t>(-1 - key);
}

// Stream `s` of a group: filters, then byte planes, most significant first (document: "Streams").
std::vector<std::int64_t> referenceStream(const Bytes& b, std::size_t group, std::size_t streams, std::size_t count,
                                          int width, std::size_t s) {
  std::vector<std::int64_t> out(count);
  const int filter = b[group + s];
  const std::int64_t modulus = std::int64_t{1} << (8 * width);
  std::int64_t previous = 0;
  for (std::size_t v = 0; v < count; ++v) {
    std::uint64_t code = 0;
    for (int p = 0; p < width; ++p) code = code * 256 + b[group + streams + (static_cast<std::size_t>(p) * streams + s) * count + v];
    const std::int64_t e = (code % 2 == 0) ? static_cast<std::int64_t>(code / 2) : -static_cast<std::int64_t>(code / 2) - 1;
    std::int64_t t = filter == 1 ? previous + e : e;
    t = ((t % modulus) + modulus) % modulus;        // wrap into [0, 2^bits)
    if (t >= modulus / 2) t -= modulus;             // two's complement
    out[v] = t;
    previous = t;
  }
  return out;
}

// An independent decoder of the whole blob in double precision, from the document alone.
std::vector<double> referenceDecode(const Bytes& b) {
  const int enc = b[kHdrEncoding], order = b[kHdrOrder], C = b[kHdrChannels];
  const std::size_t V = rd32(b, kHdrVertices), K = rd32(b, kHdrClusters), n2 = static_cast<std::size_t>(order * order);
  std::vector<double> out(V * static_cast<std::size_t>(C) * n2, 0.0);
  const bool cpca = enc == 5;
  std::vector<std::int64_t> ids;
  if (cpca) ids = referenceStream(b, partOffset(b, 0), 1, V, K <= 256 ? 1 : 2, 0);
  for (int l = 0; l < order; ++l) {
    const std::size_t width = static_cast<std::size_t>(2 * l + 1), D = static_cast<std::size_t>(C) * width;
    std::size_t at = partOffset(b, static_cast<std::size_t>(l) + (cpca ? 1 : 0));
    auto put = [&](std::size_t v, std::size_t d, double x) {
      out[(v * static_cast<std::size_t>(C) + d / width) * n2 + static_cast<std::size_t>(l * l) + d % width] = x;
    };
    if (!cpca) {
      const int w = enc == 1 ? 4 : enc == 4 ? 1 : 2;
      const bool quant = enc == 3 || enc == 4;
      std::vector<double> steps(D, 0.0);
      if (quant) {
        for (std::size_t s = 0; s < D; ++s, at += 4) steps[s] = floatOf(rd32(b, at));
      }
      for (std::size_t s = 0; s < D; ++s) {
        const std::vector<std::int64_t> t = referenceStream(b, at, D, V, w, s);
        for (std::size_t v = 0; v < V; ++v) {
          double x = 0.0;
          if (quant) x = static_cast<double>(t[v]) * steps[s];
          else if (enc == 2) x = halfValue(static_cast<std::uint16_t>(keyToBits(t[v], 2)));
          else x = floatOf(keyToBits(t[v], 4));
          put(v, s, x);
        }
      }
      continue;
    }
    const std::size_t n = rd32(b, at);
    at += 4;
    std::vector<double> steps(K), means(K * D), basis(K * n * D);
    for (std::size_t k = 0; k < K; ++k, at += 4) steps[k] = floatOf(rd32(b, at));
    for (std::size_t i = 0; i < K * D; ++i, at += 4) means[i] = floatOf(rd32(b, at));
    for (std::size_t i = 0; i < K * n * D; ++i, at += 2) basis[i] = halfValue(rd16(b, at));
    std::vector<std::vector<std::int64_t>> weights(n);
    for (std::size_t j = 0; j < n; ++j) weights[j] = referenceStream(b, at, n, V, b[kHdrWeightBits] / 8, j);
    for (std::size_t v = 0; v < V; ++v) {
      const std::size_t k = static_cast<std::size_t>(ids[v]) & (K <= 256 ? 0xffu : 0xffffu);
      for (std::size_t d = 0; d < D; ++d) {
        double x = means[k * D + d];
        for (std::size_t j = 0; j < n; ++j) x += static_cast<double>(weights[j][v]) * steps[k] * basis[(k * n + j) * D + d];
        put(v, d, x);
      }
    }
  }
  return out;
}

// ---- Test data ---------------------------------------------------------------------------

// Transfer that looks like a bake: a diffuse clamped cosine about the vertex normal times a
// visibility factor and an albedo per channel, normals drawn around a few surface
// orientations (so clusters exist), plus a little noise.
std::vector<float> makeTransfer(std::size_t vertices, int order, int channels, std::uint64_t seed) {
  Pcg32 rng(seed);
  const std::size_t n2 = static_cast<std::size_t>(order * order);
  std::vector<float> zonal(static_cast<std::size_t>(order)), placed(n2);
  EXPECT_TRUE(zonalClampedCosine(order, zonal).isOk());
  const Vec3 walls[] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {0.6f, 0.8f, 0}, {0, -1, 0}};
  std::vector<float> t(vertices * static_cast<std::size_t>(channels) * n2);
  for (std::size_t v = 0; v < vertices; ++v) {
    const Vec3 base = walls[rng.next() % 6];
    const Vec3 jitter = squareToSphere(rng.nextFloat(), rng.nextFloat()) * 0.25f;
    Vec3 n = base + jitter;
    n = n * (1.0f / length(n));
    EXPECT_TRUE(placeZonal(order, zonal, n, placed).isOk());
    const float visibility = 0.3f + 0.7f * rng.nextFloat();
    for (int c = 0; c < channels; ++c) {
      const float albedo = (0.5f + 0.1f * static_cast<float>(c)) / 3.14159265f;
      for (std::size_t i = 0; i < n2; ++i) {
        const float noise = 0.001f * (rng.nextFloat() - 0.5f);
        t[(v * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)) * n2 + i] = albedo * visibility * placed[i] + noise;
      }
    }
  }
  return t;
}

TransferCodecSettings setting(const char* name) {
  TransferCodecSettings s;
  EXPECT_TRUE(parseTransferSetting(name, TransferCodecSettings{}, &s).isOk()) << name;
  return s;
}

const char* const kAllSettings[] = {"f32", "f16", "q16", "q8", "cpca8@0.05", "cpca16@0.01"};

Bytes encode(const std::vector<float>& t, int order, int channels, const TransferCodecSettings& s,
             TransferEncodeReport* report = nullptr) {
  Bytes blob;
  const Status st = encodeTransfer(t, order, channels, s, &blob, report);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return blob;
}

std::vector<float> decodeAll(const Bytes& blob, int bands) {
  std::vector<float> out;
  const Status st = decodeTransfer(blob, bands, &out);
  EXPECT_TRUE(st.isOk()) << st.toString();
  return out;
}

double relativeError(const std::vector<float>& a, const std::vector<float>& b) {
  double e = 0.0, s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    e += (static_cast<double>(a[i]) - b[i]) * (static_cast<double>(a[i]) - b[i]);
    s += static_cast<double>(a[i]) * a[i];
  }
  return std::sqrt(e / s);
}

// ---- float16 ------------------------------------------------------------------------------

TEST(TransferCodecHalf, HalfToFloatIsExactForEveryBitPattern) {
  for (std::uint32_t h = 0; h < 65536; ++h) {
    const double want = halfValue(static_cast<std::uint16_t>(h));
    const float got = prt::halfToFloat(static_cast<std::uint16_t>(h));
    if (std::isnan(want)) {
      EXPECT_TRUE(std::isnan(got)) << h;
    } else {
      EXPECT_EQ(static_cast<double>(got), want) << h;
      EXPECT_EQ(std::signbit(got), (h & 0x8000u) != 0) << h;
      EXPECT_EQ(prt::floatToHalf(got), h) << "round trip of " << h;
    }
    EXPECT_EQ(prt::isFiniteHalf(static_cast<std::uint16_t>(h)), std::isfinite(want)) << h;
  }
}

// Nearest half by search over all finite non-negative halves, ties to the even bit pattern;
// past the midpoint between 65504 and 2^16 (the next value the format would have) infinity.
std::uint16_t referenceNearestHalf(float x) {
  const double a = std::fabs(static_cast<double>(x));
  const std::uint16_t sign = std::signbit(x) ? 0x8000 : 0;
  if (a >= 65520.0) return sign | 0x7c00;
  std::uint16_t lo = 0, hi = 0x7bff;  // halfValue is increasing on 0..0x7bff
  while (hi - lo > 1) {
    const auto mid = static_cast<std::uint16_t>((lo + hi) / 2);
    (halfValue(mid) <= a ? lo : hi) = mid;
  }
  const double dl = a - halfValue(lo), dh = halfValue(hi) - a;
  const std::uint16_t best = dl < dh ? lo : dh < dl ? hi : ((lo & 1) == 0 ? lo : hi);
  return sign | best;
}

TEST(TransferCodecHalf, FloatToHalfRoundsToNearestEven) {
  std::vector<float> xs = {0.0f, -0.0f, 1.0f, -1.0f, 65504.0f, 65519.99f, 65520.0f, 1e9f, -1e9f, 1e-9f, 5.96e-8f,
                           2.98e-8f, 2.9802322e-8f, 2.9802326e-8f, 6.1035156e-5f, 6.1e-5f, 0.1f, 1.0f / 3.0f};
  for (std::uint32_t h = 0; h < 0x7bff; ++h) {  // every midpoint, and one float either side of it
    const double mid = 0.5 * (halfValue(static_cast<std::uint16_t>(h)) + halfValue(static_cast<std::uint16_t>(h + 1)));
    const float m = static_cast<float>(mid);
    ASSERT_EQ(static_cast<double>(m), mid);  // 12 significant bits: exact in float
    xs.insert(xs.end(), {m, std::nextafter(m, 0.0f), std::nextafter(m, 1e9f), -m});
  }
  Pcg32 rng(7);
  for (int i = 0; i < 20000; ++i) xs.push_back(floatOf(rng.next() & 0x7fffffffu));  // every magnitude
  for (float x : xs) {
    if (!std::isfinite(x)) continue;
    EXPECT_EQ(prt::floatToHalf(x), referenceNearestHalf(x)) << x;
  }
  EXPECT_EQ(prt::floatToHalf(std::numeric_limits<float>::infinity()), 0x7c00);
  EXPECT_FALSE(prt::isFiniteHalf(prt::floatToHalf(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(prt::halfToFloat(prt::floatToHalf(std::numeric_limits<float>::quiet_NaN()))));
}

// ---- Streams ------------------------------------------------------------------------------

TEST(TransferCodecStreams, ZigZagMapsSmallMagnitudesToSmallCodes) {
  EXPECT_EQ(tc::zigzag(0, 1), 0u);
  EXPECT_EQ(tc::zigzag(-1, 1), 1u);
  EXPECT_EQ(tc::zigzag(1, 1), 2u);
  EXPECT_EQ(tc::zigzag(127, 1), 254u);
  EXPECT_EQ(tc::zigzag(-128, 1), 255u);
  EXPECT_EQ(tc::zigzag(-32768, 2), 65535u);
  EXPECT_EQ(tc::zigzag(std::numeric_limits<std::int32_t>::min(), 4), 0xffffffffu);
  for (int w : {1, 2, 4}) {
    for (std::int64_t v : {0LL, 1LL, -1LL, 100LL, -100LL, 32767LL, -32768LL, 2147483647LL, -2147483648LL}) {
      const std::int32_t x = tc::wrapToWidth(v, w);
      EXPECT_EQ(tc::unzigzag(tc::zigzag(x, w)), x) << w << " " << v;
    }
  }
  EXPECT_EQ(tc::wrapToWidth(128, 1), -128);
  EXPECT_EQ(tc::wrapToWidth(-129, 1), 127);
  EXPECT_EQ(tc::wrapToWidth(70000, 2), 70000 - 65536);
}

TEST(TransferCodecStreams, GroupRoundTripsAndLaysOutPlanesAsDocumented) {
  Pcg32 rng(3);
  for (int width : {1, 2, 4}) {
    const std::size_t streams = 3, count = 257;
    std::vector<std::int32_t> values(streams * count);
    for (std::size_t i = 0; i < count; ++i) {
      values[i] = tc::wrapToWidth(static_cast<std::int64_t>(i) * 3 - 200, width);        // ramp: delta pays
      values[count + i] = static_cast<std::int32_t>(rng.next() % 2);                       // noise: deltas cost more
      values[2 * count + i] = tc::wrapToWidth(-static_cast<std::int64_t>(i % 5), width);  // small
    }
    Bytes group;
    tc::putStreamGroup(values, streams, count, width, group);
    ASSERT_EQ(group.size(), tc::streamGroupBytes(streams, count, width));
    EXPECT_EQ(group[0], 1) << "a ramp is stored as deltas";
    EXPECT_EQ(group[1], 0) << "0/1 noise is stored as it is";
    for (std::size_t s = 0; s < streams; ++s) {
      std::vector<std::int32_t> back(count);
      ASSERT_TRUE(tc::getStream(group.data(), streams, count, width, s, back));
      const std::vector<std::int64_t> ref = referenceStream(group, 0, streams, count, width, s);
      for (std::size_t i = 0; i < count; ++i) {
        ASSERT_EQ(back[i], values[s * count + i]) << width << " " << s << " " << i;
        ASSERT_EQ(ref[i], values[s * count + i]) << "the document's reading, " << width << " " << s << " " << i;
      }
    }
    group[1] = 2;
    std::vector<std::int32_t> back(count);
    EXPECT_FALSE(tc::getStream(group.data(), streams, count, width, 1, back)) << "unknown filter";
  }
}

// ---- PCA and k-means ----------------------------------------------------------------------

TEST(TransferCodecEigen, RecoversKnownSpectra) {
  Pcg32 rng(11);
  for (int n : {1, 2, 3, 9, 27, 93}) {
    // Q = product of Householder reflections (orthogonal), A = Q diag(lambda) Q^T.
    const std::size_t N = static_cast<std::size_t>(n);
    std::vector<double> q(N * N, 0.0);
    for (std::size_t i = 0; i < N; ++i) q[i * N + i] = 1.0;
    for (int r = 0; r < 3; ++r) {
      std::vector<double> u(N);
      double norm = 0.0;
      for (double& x : u) {
        x = rng.nextFloat() - 0.5;
        norm += x * x;
      }
      for (double& x : u) x /= std::sqrt(norm);
      std::vector<double> next(N * N);
      for (std::size_t i = 0; i < N; ++i) {
        for (std::size_t j = 0; j < N; ++j) {
          double s = 0.0;
          for (std::size_t k = 0; k < N; ++k) s += q[i * N + k] * ((k == j ? 1.0 : 0.0) - 2.0 * u[k] * u[j]);
          next[i * N + j] = s;
        }
      }
      q = next;
    }
    std::vector<double> lambda(N);
    for (std::size_t i = 0; i < N; ++i) lambda[i] = (i % 4 == 3) ? lambda[i - 1] : std::ldexp(1.0, -static_cast<int>(i) / 2) * (1 + 0.1 * static_cast<double>(i % 3));
    std::vector<double> a(N * N, 0.0);
    for (std::size_t i = 0; i < N; ++i) {
      for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t k = 0; k < N; ++k) a[i * N + j] += q[i * N + k] * lambda[k] * q[j * N + k];
      }
    }
    const tc::SymmetricEigen e = tc::symmetricEigen(n, a);
    std::vector<double> sorted = lambda;
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    for (std::size_t j = 0; j < N; ++j) {
      EXPECT_NEAR(e.values[j], sorted[j], 1e-12) << n << " " << j;
      double big = 0.0;
      for (std::size_t i = 0; i < N; ++i) {
        double av = 0.0;
        for (std::size_t k = 0; k < N; ++k) av += a[i * N + k] * e.vectors[j * N + k];
        EXPECT_NEAR(av, e.values[j] * e.vectors[j * N + i], 1e-12);
        if (std::fabs(e.vectors[j * N + i]) > std::fabs(big)) big = e.vectors[j * N + i];
      }
      EXPECT_GT(big, 0.0) << "sign convention";
      for (std::size_t k = 0; k < N; ++k) {
        double dot = 0.0;
        for (std::size_t i = 0; i < N; ++i) dot += e.vectors[j * N + i] * e.vectors[k * N + i];
        EXPECT_NEAR(dot, j == k ? 1.0 : 0.0, 1e-12);
      }
    }
  }
}

TEST(TransferCodecKMeans, SeparatesWellSeparatedBlobsDeterministically) {
  const int dims = 10;
  const std::size_t perBlob = 300;
  Pcg32 rng(5);
  std::vector<float> points;
  std::vector<int> truth;
  for (std::size_t i = 0; i < 5 * perBlob; ++i) {
    const int blob = static_cast<int>(rng.next() % 5);
    truth.push_back(blob);
    for (int d = 0; d < dims; ++d) points.push_back((d == blob ? 10.0f : 0.0f) + rng.nextFloat() - 0.5f);
  }
  tc::KMeansOptions o;
  o.clusters = 5;
  o.maxTrainingPoints = 500;  // exercises the strided sample
  const tc::KMeansResult r = tc::kMeans(points, truth.size(), dims, o);
  ASSERT_EQ(r.clusters, 5);
  std::vector<int> blobOf(5, -1);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    int& b = blobOf[r.assignment[i]];
    if (b < 0) b = truth[i];
    EXPECT_EQ(b, truth[i]) << "point " << i;
  }
  EXPECT_EQ(tc::kMeans(points, truth.size(), dims, o).assignment, r.assignment);

  std::vector<float> three;  // three distinct points repeated: at most three clusters survive
  for (int i = 0; i < 90; ++i) three.insert(three.end(), {static_cast<float>(i % 3), 0.0f});
  o.clusters = 8;
  const tc::KMeansResult t = tc::kMeans(three, 90, 2, o);
  EXPECT_LE(t.clusters, 3);
  for (int i = 3; i < 90; ++i) EXPECT_EQ(t.assignment[static_cast<std::size_t>(i)], t.assignment[static_cast<std::size_t>(i % 3)]);
}

// ---- Round trips within the stated bounds --------------------------------------------------

TEST(TransferCodec, Float32IsBitExact) {
  std::vector<float> t = makeTransfer(300, 4, 3, 1);
  t[0] = -0.0f;
  t[1] = 1e-40f;  // subnormal
  t[2] = -kMaxTransferMagnitude;  // the largest magnitude the format holds
  t[3] = std::numeric_limits<float>::min();
  const std::vector<float> back = decodeAll(encode(t, 4, 3, setting("f32")), 4);
  ASSERT_EQ(back.size(), t.size());
  for (std::size_t i = 0; i < t.size(); ++i) ASSERT_EQ(bitsOf(back[i]), bitsOf(t[i])) << i;
}

TEST(TransferCodec, Float16IsTheNearestHalf) {
  std::vector<float> t = makeTransfer(300, 3, 1, 2);
  t[5] = 65504.0f;
  t[6] = -1e-7f;  // subnormal half
  TransferEncodeReport report;
  const Bytes blob = encode(t, 3, 1, setting("f16"), &report);
  const std::vector<float> back = decodeAll(blob, 3);
  double maxAbs = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    ASSERT_EQ(static_cast<double>(back[i]), halfValue(referenceNearestHalf(t[i]))) << i;
    // The stated bound: |error| <= max(2^-11 |x|, 2^-25).
    const double err = std::fabs(static_cast<double>(back[i]) - t[i]);
    ASSERT_LE(err, std::max(std::ldexp(std::fabs(static_cast<double>(t[i])), -11), std::ldexp(1.0, -25))) << i;
    maxAbs = std::max(maxAbs, err);
  }
  EXPECT_EQ(report.maxAbsError, maxAbs);
  EXPECT_EQ(report.bytes, blob.size());
}

TEST(TransferCodec, QuantisationErrorIsWithinHalfAStepPerCoefficient) {
  for (int channels : {1, 3}) {
    for (const char* name : {"q16", "q8"}) {
      const int order = 5, bits = std::string(name) == "q8" ? 8 : 16, levels = (1 << (bits - 1)) - 1;
      std::vector<float> t = makeTransfer(500, order, channels, 3);
      for (std::size_t i = 0; i < 25; ++i) t[i] = 0.0f;                        // a zero stream or two
      for (std::size_t v = 0; v < 500; ++v) t[v * static_cast<std::size_t>(channels) * 25 + 24] = 0.0f;
      const std::vector<float> back = decodeAll(encode(t, order, channels, setting(name)), order);
      const std::size_t stride = static_cast<std::size_t>(channels) * 25;
      double worstRatio = 0.0;
      for (std::size_t s = 0; s < stride; ++s) {  // per channel and coefficient
        double scale = 0.0;
        for (std::size_t v = 0; v < 500; ++v) scale = std::max(scale, std::fabs(static_cast<double>(t[v * stride + s])));
        for (std::size_t v = 0; v < 500; ++v) {
          const double x = t[v * stride + s], err = std::fabs(static_cast<double>(back[v * stride + s]) - x);
          // docs/transfer-codec.md: |x' - x| <= (scale/Q)(1/2 + 2^-21) + 2^-24 |x|.
          ASSERT_LE(err, scale / levels * (0.5 + std::ldexp(1.0, -21)) + std::ldexp(std::fabs(x), -24))
              << name << " channels " << channels << " stream " << s << " vertex " << v;
          if (scale > 0.0) worstRatio = std::max(worstRatio, err / (scale / levels));
        }
        if (scale == 0.0) {
          for (std::size_t v = 0; v < 500; ++v) ASSERT_EQ(back[v * stride + s], 0.0f);
        }
      }
      EXPECT_GT(worstRatio, 0.4) << "the bound is nearly reached, so it is the real one";
    }
  }
}

TEST(TransferCodec, CpcaMeetsItsTargetAndReportsTheTrueError) {
  for (int channels : {1, 3}) {
    const int order = 4;
    const std::vector<float> t = makeTransfer(1500, order, channels, 4);
    for (const char* name : {"cpca8@0.05", "cpca8@0.02", "cpca16@0.02", "cpca16@0.004"}) {
      const TransferCodecSettings s = setting(name);
      TransferEncodeReport report;
      const Bytes blob = encode(t, order, channels, s, &report);
      const std::vector<float> back = decodeAll(blob, order);
      const double rel = relativeError(t, back);
      EXPECT_LE(rel, s.cpcaTargetError) << name;
      EXPECT_NEAR(report.relativeError, rel, 1e-9 * rel + 1e-12) << name;
      EXPECT_GE(report.clusters, 1);
      EXPECT_EQ(report.clusters, static_cast<int>(rd32(blob, kHdrClusters)));
      ASSERT_EQ(report.vectorsPerBand.size(), static_cast<std::size_t>(order));
      EXPECT_GT(report.candidatesTried, 1);
      // The independent decoder agrees (double vs float arithmetic).
      const std::vector<double> ref = referenceDecode(blob);
      for (std::size_t i = 0; i < back.size(); ++i) ASSERT_NEAR(back[i], ref[i], 1e-5) << name << " " << i;
      // At a loose target, smaller than float16 before any entropy coding.
      if (s.cpcaTargetError >= 0.05) {
        EXPECT_LT(blob.size(), t.size() * 2) << name;
      }
    }
  }
}

TEST(TransferCodec, CpcaRepresentsLowRankClustersExactlyEnough) {
  // Three clusters, each exactly mean + w * axis per band: the search must find a model with
  // few clusters and vectors; 16-bit weights leave only quantisation and float16 axes.
  const int order = 3, channels = 3;
  const std::size_t V = 900, stride = static_cast<std::size_t>(channels * order * order);
  Pcg32 rng(9);
  std::vector<float> centre(3 * stride), axis(3 * stride), t(V * stride);
  for (float& x : centre) x = rng.nextFloat();
  for (float& x : axis) x = rng.nextFloat() - 0.5f;
  for (std::size_t v = 0; v < V; ++v) {
    const std::size_t k = v % 3;
    const float w = rng.nextFloat() - 0.5f;
    for (std::size_t i = 0; i < stride; ++i) t[v * stride + i] = centre[k * stride + i] + w * axis[k * stride + i];
  }
  TransferEncodeReport report;
  const Bytes blob = encode(t, order, channels, setting("cpca16@0.001"), &report);
  EXPECT_LE(relativeError(t, decodeAll(blob, order)), 0.001);
  EXPECT_LE(report.clusters, 4);
  for (int n : report.vectorsPerBand) EXPECT_LE(n, 2);
}

TEST(TransferCodec, CpcaBandsRenderLikeTheExpandedTransfer) {
  // Sloan 2003: per cluster and band the lighting's dot products with mean and axes, per
  // vertex a weighted sum; the result equals the plain dot product with the expansion.
  const int order = 4, channels = 3;
  const std::vector<float> t = makeTransfer(400, order, channels, 6);
  const Bytes blob = encode(t, order, channels, setting("cpca8@0.03"));
  CpcaTransfer cpca;
  ASSERT_TRUE(decodeCpcaTransfer(blob, order, &cpca).isOk());
  const std::vector<float> expanded = decodeAll(blob, order);
  std::vector<float> again(expanded.size());
  ASSERT_TRUE(cpcaReconstruct(cpca, again).isOk());
  EXPECT_EQ(again, expanded);
  // The stored form (levels and per-cluster steps, which the web client folds into its
  // per-cluster constants) gives exactly the dequantised weights.
  EXPECT_EQ(cpca.weightBits, 8);
  for (const CpcaBand& b : cpca.bands) {
    ASSERT_EQ(b.steps.size(), cpca.clusterCount);
    ASSERT_EQ(b.levels.size(), b.weights.size());
    for (std::size_t i = 0; i < b.levels.size(); ++i) {
      const std::size_t v = i / static_cast<std::size_t>(b.vectors);
      ASSERT_LE(std::abs(static_cast<int>(b.levels[i])), 127);
      ASSERT_EQ(static_cast<float>(b.levels[i]) * b.steps[cpca.clusterOf[v]], b.weights[i]) << b.band << " " << i;
    }
  }

  Pcg32 rng(1);
  std::vector<float> light(static_cast<std::size_t>(channels * order * order));  // [channel][coefficient]
  for (float& x : light) x = rng.nextFloat() - 0.3f;
  for (std::size_t v = 0; v < cpca.vertexCount; ++v) {
    const std::size_t k = cpca.clusterOf[v];
    for (int c = 0; c < channels; ++c) {
      double direct = 0.0, clustered = 0.0;
      for (int i = 0; i < order * order; ++i) {
        direct += static_cast<double>(expanded[(v * 3 + static_cast<std::size_t>(c)) * 16 + static_cast<std::size_t>(i)]) *
                  light[static_cast<std::size_t>(c * 16 + i)];
      }
      for (const CpcaBand& b : cpca.bands) {
        const int w = 2 * b.band + 1;
        auto dotWithLight = [&](const float* vec) {  // this channel's part of a band vector
          double s = 0.0;
          for (int m = 0; m < w; ++m) s += static_cast<double>(vec[c * w + m]) * light[static_cast<std::size_t>(c * 16 + b.band * b.band + m)];
          return s;
        };
        const std::size_t D = static_cast<std::size_t>(b.dims), N = static_cast<std::size_t>(b.vectors);
        clustered += dotWithLight(&b.means[k * D]);
        for (std::size_t j = 0; j < N; ++j) clustered += b.weights[v * N + j] * dotWithLight(&b.basis[(k * N + j) * D]);
      }
      ASSERT_NEAR(clustered, direct, 1e-4) << v << " " << c;
    }
  }
}

TEST(TransferCodec, EveryEncodingMatchesTheIndependentDecoder) {
  const std::vector<float> t = makeTransfer(200, 4, 3, 8);
  for (const char* name : kAllSettings) {
    const Bytes blob = encode(t, 4, 3, setting(name));
    const std::vector<float> back = decodeAll(blob, 4);
    const std::vector<double> ref = referenceDecode(blob);
    ASSERT_EQ(ref.size(), back.size());
    const bool exact = std::string(name)[0] != 'c';  // per-coefficient encodings: the same single rounding
    for (std::size_t i = 0; i < back.size(); ++i) {
      if (exact) {
        ASSERT_EQ(static_cast<double>(back[i]), static_cast<double>(static_cast<float>(ref[i]))) << name << " " << i;
      } else {
        ASSERT_NEAR(back[i], ref[i], 1e-5) << name << " " << i;
      }
    }
  }
}

// ---- Band-progressive decoding, determinism --------------------------------------------------

TEST(TransferCodec, AnyBandPrefixDecodesAsTheLowerOrderTransfer) {
  const int order = 5, channels = 3;
  const std::vector<float> t = makeTransfer(150, order, channels, 10);
  for (const char* name : kAllSettings) {
    const Bytes blob = encode(t, order, channels, setting(name));
    const std::vector<float> full = decodeAll(blob, order);
    TransferBlobInfo info;
    ASSERT_TRUE(readTransferBlobInfo(blob, &info).isOk());
    EXPECT_EQ(info.bandsAvailable, order);
    for (int b = 1; b <= order; ++b) {
      // Only the bytes up to the end of band b-1's part.
      const TransferPartInfo& last = info.parts[info.parts.size() - static_cast<std::size_t>(order - b) - 1];
      ASSERT_EQ(last.band, b - 1);
      const Bytes prefix(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(last.offset + last.size));
      TransferBlobInfo prefixInfo;
      ASSERT_TRUE(readTransferBlobInfo(prefix, &prefixInfo).isOk());
      EXPECT_EQ(prefixInfo.bandsAvailable, b);
      for (const Bytes* bytes : {&blob, &prefix}) {
        const std::vector<float> part = decodeAll(*bytes, b);
        ASSERT_EQ(part.size(), 150u * channels * static_cast<std::size_t>(b * b));
        for (std::size_t v = 0; v < 150; ++v) {
          for (std::size_t c = 0; c < 3; ++c) {
            for (std::size_t i = 0; i < static_cast<std::size_t>(b * b); ++i) {
              ASSERT_EQ(bitsOf(part[(v * 3 + c) * static_cast<std::size_t>(b * b) + i]), bitsOf(full[(v * 3 + c) * 25 + i]))
                  << name << " bands " << b;
            }
          }
        }
      }
      if (b < order) {
        std::vector<float> out;
        EXPECT_EQ(decodeTransfer(prefix, b + 1, &out).code(), StatusCode::kTruncated) << name;
      }
    }
  }
}

TEST(TransferCodec, EncodingIsDeterministic) {
  const std::vector<float> t = makeTransfer(700, 4, 3, 12);
  for (const char* name : kAllSettings) {
    EXPECT_EQ(encode(t, 4, 3, setting(name)), encode(t, 4, 3, setting(name))) << name;
  }
  TransferCodecSettings other = setting("cpca8@0.05");
  other.seed = 99;
  Bytes a = encode(t, 4, 3, other);
  EXPECT_LE(relativeError(t, decodeAll(a, 4)), 0.05);
}

TEST(TransferCodec, HeaderAndPartTableFollowTheDocument) {
  const std::vector<float> t = makeTransfer(100, 3, 1, 13);
  for (const char* name : kAllSettings) {
    const Bytes b = encode(t, 3, 1, setting(name));
    const bool cpca = name[0] == 'c';
    EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "PRTT");
    EXPECT_EQ(rd16(b, kHdrVersionMajor), 1);
    EXPECT_EQ(rd16(b, kHdrVersionMajor + 2), 0);
    EXPECT_EQ(b[kHdrOrder], 3);
    EXPECT_EQ(b[kHdrChannels], 1);
    EXPECT_EQ(rd32(b, kHdrVertices), 100u);
    EXPECT_EQ(rd32(b, kHdrParts), cpca ? 4u : 3u);
    EXPECT_EQ(rd64(b, kHdrBlobSize), b.size());
    EXPECT_EQ(rd64(b, kHdrReserved), 0u);
    EXPECT_EQ(rd32(b, kHdrCrc), crc32c({b.data(), 44}));
    EXPECT_EQ(rd32(b, kHdrTableCrc), crc32c({b.data() + kHeaderBytes, kEntryBytes * rd32(b, kHdrParts)}));
    std::size_t at = kHeaderBytes + kEntryBytes * rd32(b, kHdrParts);
    for (std::size_t p = 0; p < rd32(b, kHdrParts); ++p) {
      EXPECT_EQ(rd16(b, entryAt(p) + kEType), cpca && p == 0 ? 1 : 2);
      EXPECT_EQ(rd16(b, entryAt(p) + kEBand), cpca ? (p == 0 ? 0u : p - 1) : p);
      EXPECT_EQ(partOffset(b, p), at);
      EXPECT_EQ(rd32(b, entryAt(p) + kECrc), crc32c({b.data() + at, partSize(b, p)}));
      at += partSize(b, p);
    }
    EXPECT_EQ(at, b.size());
    if (!cpca) {  // per-coefficient part sizes: S * (4 if quantised) + S + S * V * bytes
      const int w = b[kHdrEncoding] == 1 ? 4 : b[kHdrEncoding] == 4 ? 1 : 2;
      const std::size_t stepBytes = (b[kHdrEncoding] == 3 || b[kHdrEncoding] == 4) ? 4 : 0;
      for (std::size_t l = 0; l < 3; ++l) EXPECT_EQ(partSize(b, l), (2 * l + 1) * (stepBytes + 1 + 100 * static_cast<std::size_t>(w)));
    }
  }
}

TEST(TransferCodec, MatchesTheWorkedExampleInTheDocument) {
  const Bytes want = {
      0x50, 0x52, 0x54, 0x54, 0x01, 0x00, 0x00, 0x00, 0x04, 0x00, 0x01, 0x01, 0x02, 0x00, 0x00, 0x00,  //
      0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x4f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //
      0x15, 0x43, 0x3e, 0xf6, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd7, 0x99, 0x4e, 0xf8,  //
      0x02, 0x00, 0x00, 0x00, 0x04, 0x72, 0x34, 0x2f, 0x48, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,  //
      0x07, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x05, 0x02, 0x81, 0x3b, 0x00, 0xfe, 0x7d};
  const Bytes blob = encode({0.5f, -0.25f}, 1, 1, setting("q8"));
  EXPECT_EQ(blob, want);
  // The step is the smallest float with step * 127 >= 0.5.
  const float step = floatOf(0x3b810205u);
  EXPECT_GE(static_cast<double>(step) * 127, 0.5);
  EXPECT_LT(static_cast<double>(std::nextafter(step, 0.0f)) * 127, 0.5);
  EXPECT_EQ(decodeAll(want, 1), (std::vector<float>{127 * step, -63 * step}));
}

// ---- Hostile input --------------------------------------------------------------------------

TEST(TransferCodec, EveryTruncationIsRejected) {
  const std::vector<float> t = makeTransfer(12, 3, 3, 14);
  for (const char* name : kAllSettings) {
    const Bytes blob = encode(t, 3, 3, setting(name));
    const std::vector<float> full = decodeAll(blob, 3);
    for (std::size_t n = 0; n < blob.size(); ++n) {
      const Bytes prefix(blob.begin(), blob.begin() + static_cast<std::ptrdiff_t>(n));
      std::vector<float> out;
      const Status s = decodeTransfer(prefix, 3, &out);
      ASSERT_EQ(s.code(), StatusCode::kTruncated) << name << " prefix " << n << ": " << s.toString();
      ASSERT_FALSE(s.message().empty());
      TransferBlobInfo info;
      if (!readTransferBlobInfo(prefix, &info).isOk() || info.bandsAvailable == 0) continue;
      // What the prefix still holds decodes, and agrees with the full decode.
      const int b = info.bandsAvailable;
      ASSERT_TRUE(decodeTransfer(prefix, b, &out).isOk()) << name << " prefix " << n;
      for (std::size_t v = 0; v < 12; ++v) {
        for (std::size_t i = 0; i < static_cast<std::size_t>(b * b); ++i) {
          ASSERT_EQ(bitsOf(out[(v * 3) * static_cast<std::size_t>(b * b) + i]), bitsOf(full[v * 27 + i]));
        }
      }
    }
  }
}

TEST(TransferCodec, EverySingleByteCorruptionIsCaught) {
  const std::vector<float> t = makeTransfer(10, 3, 3, 15);
  for (const char* name : kAllSettings) {
    const Bytes blob = encode(t, 3, 3, setting(name));
    for (std::size_t i = 0; i < blob.size(); ++i) {
      for (std::uint8_t flip : {0x01, 0x80, 0xff}) {
        Bytes bad = blob;
        bad[i] ^= flip;
        std::vector<float> out;
        const Status s = decodeTransfer(bad, 3, &out);
        ASSERT_FALSE(s.isOk()) << name << " byte " << i;
        ASSERT_FALSE(s.message().empty());
      }
    }
  }
}

TEST(TransferCodec, ResealedRandomCorruptionIsRejectedOrDecodesToFiniteValues) {
  const std::vector<float> t = makeTransfer(40, 3, 3, 16);
  Pcg32 rng(17);
  for (const char* name : kAllSettings) {
    const Bytes blob = encode(t, 3, 3, setting(name));
    int rejected = 0;
    for (int trial = 0; trial < 400; ++trial) {
      Bytes bad = blob;
      const int flips = 1 + static_cast<int>(rng.next() % 4);
      for (int f = 0; f < flips; ++f) bad[rng.next() % bad.size()] ^= static_cast<std::uint8_t>(1 + rng.next() % 255);
      reseal(bad);
      for (int bands = 1; bands <= 3; ++bands) {
        std::vector<float> out;
        const Status s = decodeTransfer(bad, bands, &out);
        if (!s.isOk()) {
          ASSERT_FALSE(s.message().empty());
          rejected += bands == 3;
          continue;
        }
        for (float x : out) ASSERT_TRUE(std::isfinite(x)) << name;
      }
    }
    EXPECT_GT(rejected, 0) << name;
  }
}

// Applies `edit` to a fresh blob, reseals it, and expects decodeTransfer to fail with `code`
// and a message containing `needle`.
void expectRejected(const Bytes& blob, const std::function<void(Bytes&)>& edit, StatusCode code, const std::string& needle,
                    bool resealAfter = true) {
  Bytes b = blob;
  edit(b);
  if (resealAfter) reseal(b);
  std::vector<float> out;
  const Status s = decodeTransfer(b, b.size() >= 11 ? std::max<int>(1, b[kHdrOrder]) : 1, &out);
  EXPECT_EQ(s.code(), code) << s.toString();
  EXPECT_NE(s.message().find(needle), std::string::npos) << "'" << s.message() << "' lacks '" << needle << "'";
}

TEST(TransferCodec, CraftedContainerErrorsAreNamed) {
  const std::vector<float> t = makeTransfer(20, 2, 3, 18);
  const Bytes q8 = encode(t, 2, 3, setting("q8"));
  const Bytes cpca = encode(t, 2, 3, setting("cpca8@0.05"));
  expectRejected(q8, [](Bytes& b) { b[0] = 'X'; }, StatusCode::kBadMagic, "PRTT", false);
  expectRejected(q8, [](Bytes& b) { wr16(b, 4, 2); }, StatusCode::kBadVersion, "2.0 is newer", false);
  expectRejected(q8, [](Bytes& b) { b[20] ^= 1; }, StatusCode::kChecksumMismatch, "header checksum", false);
  expectRejected(q8, [](Bytes& b) { b[kHdrEncoding] = 9; }, StatusCode::kCorrupt, "unknown encoding 9");
  expectRejected(q8, [](Bytes& b) { b[kHdrWeightBits] = 8; }, StatusCode::kCorrupt, "weight bits 8");
  expectRejected(cpca, [](Bytes& b) { b[kHdrWeightBits] = 12; }, StatusCode::kCorrupt, "weight bits 12");
  expectRejected(q8, [](Bytes& b) { b[kHdrOrder] = 17; }, StatusCode::kCorrupt, "order 17");
  expectRejected(q8, [](Bytes& b) { b[kHdrChannels] = 2; }, StatusCode::kCorrupt, "channels 2");
  expectRejected(q8, [](Bytes& b) { wr32(b, kHdrVertices, 0); }, StatusCode::kCorrupt, "vertex count 0");
  expectRejected(q8, [](Bytes& b) { wr32(b, kHdrClusters, 1); }, StatusCode::kCorrupt, "cluster count 1");
  expectRejected(cpca, [](Bytes& b) { wr32(b, kHdrClusters, 21); }, StatusCode::kCorrupt, "cluster count 21");
  expectRejected(cpca, [](Bytes& b) { wr32(b, kHdrClusters, 0); }, StatusCode::kCorrupt, "cluster count 0");
  expectRejected(q8, [](Bytes& b) { wr32(b, kHdrParts, 3); }, StatusCode::kCorrupt, "part count 3");
  expectRejected(q8, [](Bytes& b) { b[kHdrReserved + 3] = 1; }, StatusCode::kCorrupt, "reserved header byte 39");
  expectRejected(q8, [](Bytes& b) { wr64(b, kHdrBlobSize, 60); }, StatusCode::kCorrupt, "smaller than header and part table");
  expectRejected(q8, [](Bytes& b) { wr64(b, kHdrBlobSize, b.size() + 1); }, StatusCode::kCorrupt, "not at the blob size");
  expectRejected(q8, [](Bytes& b) { b.push_back(0); }, StatusCode::kCorrupt, "longer than its declared size");
  expectRejected(q8, [](Bytes& b) {
    b[kHdrTableCrc] ^= 1;
    wr32(b, kHdrCrc, crc32c({b.data(), kHdrCrc}));  // a header that vouches for a wrong table CRC
  }, StatusCode::kChecksumMismatch, "part table checksum", false);
  expectRejected(q8, [](Bytes& b) { b[entryAt(1) + kEBand] ^= 1; }, StatusCode::kChecksumMismatch, "part table checksum", false);
  expectRejected(q8, [](Bytes& b) { wr16(b, entryAt(1) + kEBand, 0); }, StatusCode::kCorrupt, "part 1 is type 2 band 0, expected band 1");
  expectRejected(cpca, [](Bytes& b) { wr16(b, entryAt(0) + kEType, 2); }, StatusCode::kCorrupt, "clusters part");
  expectRejected(q8, [](Bytes& b) { wr64(b, entryAt(1) + kEOffset, partOffset(b, 1) + 1); }, StatusCode::kCorrupt, "back to back");
  expectRejected(q8, [](Bytes& b) { wr64(b, entryAt(1) + kESize, 1ull << 62); }, StatusCode::kCorrupt, "runs past the blob size");
  expectRejected(q8, [](Bytes& b) {
    wr64(b, entryAt(0) + kESize, partSize(b, 0) - 1);
    wr64(b, entryAt(1) + kEOffset, partOffset(b, 1) - 1);
    wr64(b, entryAt(1) + kESize, partSize(b, 1) + 1);
  }, StatusCode::kCorrupt,
     "part 0 (band 0) is " + std::to_string(partSize(q8, 0) - 1) + " bytes, expected " + std::to_string(partSize(q8, 0)));
  expectRejected(q8, [](Bytes& b) { b[partOffset(b, 1) + 10] ^= 4; }, StatusCode::kChecksumMismatch, "part 1 (band 1) checksum", false);
}

TEST(TransferCodec, CraftedContentErrorsAreNamed) {
  const std::vector<float> t = makeTransfer(20, 2, 3, 19);
  const Bytes q8 = encode(t, 2, 3, setting("q8"));
  const Bytes f16 = encode(t, 2, 3, setting("f16"));
  const Bytes f32 = encode(t, 2, 3, setting("f32"));
  // q8 band 0: 3 steps, 3 filters, 3 planes of 20 bytes.
  auto band0 = [](const Bytes& b) { return partOffset(b, 0); };
  expectRejected(q8, [&](Bytes& b) { wr32(b, band0(b), bitsOf(std::numeric_limits<float>::quiet_NaN())); }, StatusCode::kCorrupt,
                 "channel 0 coefficient 0: step");
  expectRejected(q8, [&](Bytes& b) { wr32(b, band0(b) + 4, bitsOf(-1.0f)); }, StatusCode::kCorrupt, "channel 1 coefficient 0: step");
  expectRejected(q8, [&](Bytes& b) { wr32(b, band0(b), bitsOf(3e38f)); }, StatusCode::kCorrupt, "step");
  expectRejected(q8, [&](Bytes& b) { b[band0(b) + 12 + 2] = 2; }, StatusCode::kCorrupt, "unknown filter 2");
  expectRejected(q8, [&](Bytes& b) {
    b[band0(b) + 12] = 0;         // stream 0 without filter
    b[band0(b) + 15 + 5] = 255;   // zig-zag 255 = level -128
  }, StatusCode::kCorrupt, "vertex 5: level -128 is outside +-127");
  // float16 band 0: 3 filters, then 3 high-byte planes and 3 low-byte planes of 20.
  expectRejected(f16, [&](Bytes& b) {
    b[band0(b)] = 0;
    b[band0(b) + 3 + 7] = 0xf8;  // key 0x7c00 * 2 zig-zagged: +infinity
    b[band0(b) + 3 + 60 + 7] = 0;
  }, StatusCode::kCorrupt, "vertex 7: not a finite float16");
  expectRejected(f32, [&](Bytes& b) {
    b[band0(b) + 1] = 0;
    b[band0(b) + 3 + 20 + 4] = 0xff;  // stream 1, top byte plane: a NaN pattern
    b[band0(b) + 3 + 60 + 20 + 4] = 0x00;
  }, StatusCode::kCorrupt, "not a finite float32");

  const Bytes cpca = encode(t, 2, 3, setting("cpca8@0.05"));
  const std::size_t K = rd32(cpca, kHdrClusters);
  expectRejected(cpca, [&](Bytes& b) {
    b[partOffset(b, 0)] = 0;
    b[partOffset(b, 0) + 1 + 3] = static_cast<std::uint8_t>(2 * K);  // zig-zag of K: one past the last cluster
  }, StatusCode::kCorrupt, "vertex 3 is in cluster " + std::to_string(K));
  const std::size_t band1 = partOffset(cpca, 2);
  expectRejected(cpca, [&](Bytes& b) { wr32(b, band1, 10); }, StatusCode::kCorrupt, "10 principal vectors, more than the band's 9");
  expectRejected(cpca, [&](Bytes& b) { wr32(b, band1, rd32(b, band1) == 9 ? 8 : rd32(b, band1) + 1); }, StatusCode::kCorrupt,
                 "bytes, expected");
  expectRejected(cpca, [&](Bytes& b) { wr32(b, band1 + 4, bitsOf(-2.0f)); }, StatusCode::kCorrupt, "weight step of cluster 0");
  expectRejected(cpca, [&](Bytes& b) { wr32(b, band1 + 4 + 4 * K, bitsOf(std::numeric_limits<float>::infinity())); },
                 StatusCode::kCorrupt, "mean of cluster 0, dimension 0 is not finite");
  expectRejected(cpca, [&](Bytes& b) { wr32(b, band1 + 4 + 4 * K, bitsOf(1e30f)); }, StatusCode::kCorrupt,
                 "mean of cluster 0, dimension 0 is not finite or beyond the transfer range");
  if (rd32(cpca, band1) > 0) {
    expectRejected(cpca, [&](Bytes& b) { wr16(b, band1 + 4 + 4 * K + 36 * K, 0x7e00); }, StatusCode::kCorrupt,
                   "principal vector 0 of cluster 0 is not finite");
  }

  CpcaTransfer out;
  EXPECT_EQ(decodeCpcaTransfer(q8, 2, &out).code(), StatusCode::kInvalidArgument);
}

// Finite values that overflow once reconstructed (a huge step times its levels, or a huge
// mean) are rejected by every reader, not left to turn exit radiance into infinity.
TEST(TransferCodec, OverflowingCpcaIsRejectedByEveryReader) {
  const std::vector<float> t = makeTransfer(30, 2, 3, 23);
  const Bytes cpca = encode(t, 2, 3, setting("cpca8@0.05"));
  const std::size_t band1 = partOffset(cpca, 2), K = rd32(cpca, kHdrClusters);
  ASSERT_GT(rd32(cpca, band1), 0u) << "band 1 needs a principal vector for this test";
  for (float step : {1e30f, 1e10f, 2000.0f}) {  // 2000 x 127 levels: finite, beyond 65504
    Bytes bad = cpca;
    for (std::size_t k = 0; k < K; ++k) wr32(bad, band1 + 4 + 4 * k, bitsOf(step));
    reseal(bad);
    std::vector<float> out;
    Status s = decodeTransfer(bad, 2, &out);
    EXPECT_EQ(s.code(), StatusCode::kCorrupt) << step;
    EXPECT_NE(s.message().find("beyond the transfer range"), std::string::npos) << s.message();
    CpcaTransfer direct;  // the renderer's path, which never reconstructs
    s = decodeCpcaTransfer(bad, 2, &direct);
    EXPECT_EQ(s.code(), StatusCode::kCorrupt) << step;
    EXPECT_NE(s.message().find("beyond the transfer range"), std::string::npos) << s.message();

    // In an asset: the writer copies the blob (it checks only its shape), the reader refuses it.
    BakedAsset a;
    a.shOrder = 2;
    for (int v = 0; v < 30; ++v) {
      a.positions.push_back({static_cast<float>(v), 0, 0});
      a.normals.push_back({0, 1, 0});
      a.albedo.push_back({0.5f, 0.5f, 0.5f});
    }
    a.indices = {0, 1, 2};
    a.sampling = "hammersley";
    a.passes.push_back({TransferKind::kInterreflected, 3, 1, t, bad});
    Bytes file;
    ASSERT_TRUE(encodeAsset(a, &file).isOk());
    EXPECT_EQ(verifyAsset(file, nullptr).code(), StatusCode::kCorrupt);
    BakedAsset decoded;
    EXPECT_EQ(decodeAsset(file, &decoded).code(), StatusCode::kCorrupt);
  }
  // Raw float32 transfer beyond the range is refused when written and when read.
  BakedAsset a;
  a.shOrder = 1;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  a.albedo = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  a.indices = {0, 1, 2};
  a.sampling = "hammersley";
  a.passes.push_back({TransferKind::kShadowed, 1, 0, {1.0f, 2.0f, 65504.0f}, {}});
  Bytes file;
  ASSERT_TRUE(encodeAsset(a, &file).isOk());
  ASSERT_TRUE(verifyAsset(file, nullptr).isOk());
  a.passes[0].coeffs[2] = 1e30f;
  EXPECT_EQ(encodeAsset(a, &file).code(), StatusCode::kInvalidArgument);
}

TEST(TransferCodec, DecoderArgumentsAreChecked) {
  const std::vector<float> t = makeTransfer(10, 3, 1, 20);
  const Bytes blob = encode(t, 3, 1, setting("f16"));
  std::vector<float> out;
  EXPECT_EQ(decodeTransfer(blob, 0, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decodeTransfer(blob, 4, &out).code(), StatusCode::kInvalidArgument);
  std::vector<float> wrong(10 * 4 - 1);
  EXPECT_EQ(decodeTransfer(blob, 2, std::span<float>(wrong)).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(decodeTransfer(Bytes{}, 1, &out).code(), StatusCode::kTruncated);
  EXPECT_EQ(decodeTransfer(Bytes{'P', 'R'}, 1, &out).code(), StatusCode::kTruncated);
  EXPECT_EQ(decodeTransfer(Bytes{'P', 'R', 'T', 'A', 1, 0, 0, 0}, 1, &out).code(), StatusCode::kBadMagic);
  CpcaTransfer bad;
  bad.vertexCount = 2;
  bad.clusterCount = 1;
  bad.channels = 1;
  bad.clusterOf = {0, 1};
  bad.bands.resize(1);
  bad.bands[0].dims = 1;
  bad.bands[0].means = {0.0f};
  std::vector<float> two(2);
  EXPECT_EQ(cpcaReconstruct(bad, two).code(), StatusCode::kSizeMismatch) << "cluster id out of range";
  // Finite parts whose sum overflows: named, not passed on as infinity.
  bad.clusterOf = {0, 0};
  bad.bands[0].vectors = 1;
  bad.bands[0].means = {3e38f};
  bad.bands[0].basis = {1.0f};
  bad.bands[0].weights = {0.0f, 3e38f};
  const Status s = cpcaReconstruct(bad, two);
  EXPECT_EQ(s.code(), StatusCode::kCorrupt);
  EXPECT_NE(s.message().find("vertex 1, band 0 reconstructs to a non-finite value"), std::string::npos) << s.message();
}

TEST(TransferCodec, EncoderInputIsChecked) {
  const std::vector<float> t = makeTransfer(10, 2, 3, 21);
  Bytes out;
  EXPECT_EQ(encodeTransfer(t, 2, 2, {}, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransfer(t, 0, 3, {}, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransfer(t, 17, 3, {}, &out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(encodeTransfer(std::span<const float>(t.data(), t.size() - 1), 2, 3, {}, &out).code(), StatusCode::kSizeMismatch);
  EXPECT_EQ(encodeTransfer(std::span<const float>(), 2, 3, {}, &out).code(), StatusCode::kSizeMismatch);
  std::vector<float> bad = t;
  bad[7] = std::numeric_limits<float>::quiet_NaN();
  Status s = encodeTransfer(bad, 2, 3, {}, &out);
  EXPECT_EQ(s.code(), StatusCode::kNotFinite);
  EXPECT_NE(s.message().find("vertex 0, channel 1, coefficient 3"), std::string::npos) << s.message();
  bad = t;
  bad[13] = 70000.0f;  // beyond kMaxTransferMagnitude, in every encoding
  for (const char* name : kAllSettings) {
    s = encodeTransfer(bad, 2, 3, setting(name), &out);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(s.message().find("(65504, kMaxTransferMagnitude)"), std::string::npos) << s.message();
  }
  bad[13] = 65504.0f;
  EXPECT_TRUE(encodeTransfer(bad, 2, 3, setting("q8"), &out).isOk());
  EXPECT_TRUE(encodeTransfer(bad, 2, 3, setting("f16"), &out).isOk());
  TransferCodecSettings c = setting("cpca8");
  c.cpcaWeightBits = 12;
  EXPECT_EQ(encodeTransfer(t, 2, 3, c, &out).code(), StatusCode::kInvalidArgument);
  c = setting("cpca8");
  c.cpcaTargetError = 0.0;
  EXPECT_EQ(encodeTransfer(t, 2, 3, c, &out).code(), StatusCode::kInvalidArgument);
  c.cpcaTargetError = 0.02;
  c.cpcaMaxClusters = 0;
  EXPECT_EQ(encodeTransfer(t, 2, 3, c, &out).code(), StatusCode::kInvalidArgument);
  // A target 8-bit weights cannot reach is an error that says what to do.
  const std::vector<float> big = makeTransfer(400, 3, 3, 22);
  c = setting("cpca8@0.00001");
  c.cpcaMaxClusters = 4;
  s = encodeTransfer(big, 3, 3, c, &out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("16-bit weights"), std::string::npos) << s.message();
}

TEST(TransferCodec, ZeroAndTinyInputsEncode) {
  for (const char* name : kAllSettings) {
    const std::vector<float> zeros(3 * 9, 0.0f);  // one vertex, order 3, RGB
    const Bytes blob = encode(zeros, 3, 3, setting(name));
    EXPECT_EQ(decodeAll(blob, 3), zeros) << name;
    std::vector<float> one = {0.25f};  // one vertex, order 1, scalar
    EXPECT_NEAR(decodeAll(encode(one, 1, 1, setting(name)), 1)[0], 0.25f, 0.25f / 100) << name;
  }
}

TEST(TransferCodec, SettingNamesRoundTrip) {
  for (const char* name : {"f32", "f16", "q16", "q8", "cpca8@0.02", "cpca16@0.005", "cpca8@1e-7", "cpca16@0.0125"}) {
    TransferCodecSettings s;
    ASSERT_TRUE(parseTransferSetting(name, {}, &s).isOk()) << name;
    EXPECT_EQ(transferSettingName(s), name);
  }
  TransferCodecSettings d;
  d.cpcaTargetError = 0.03;
  TransferCodecSettings s;
  ASSERT_TRUE(parseTransferSetting("cpca16", d, &s).isOk());
  EXPECT_EQ(s.cpcaWeightBits, 16);
  EXPECT_EQ(s.cpcaTargetError, 0.03);
  for (const char* bad : {"", "f64", "q8@0.1", "cpca8@", "cpca8@0", "cpca8@1", "cpca8@abc", "cpca8@0.1x", "cpca4"}) {
    const Status st = parseTransferSetting(bad, {}, &s);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(st.message().find(bad), std::string::npos) << st.message();
  }
}

}  // namespace
}  // namespace prt
