// CRC-32C (prt/checksum.h): the standard check value, and the fast path (the CPU's crc32
// instruction where there is one) equal to the table reference at every length and
// alignment, continued over pieces as one.
#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>
#include <vector>

#include "prt/checksum.h"

namespace prt {
namespace {

std::span<const std::uint8_t> bytesOf(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(Crc32c, CheckValue) {
  EXPECT_EQ(crc32c(bytesOf("123456789")), 0xE3069283u);
  EXPECT_EQ(crc32cTables(bytesOf("123456789")), 0xE3069283u);
  EXPECT_EQ(crc32c({}), 0u);
}

TEST(Crc32c, FastPathEqualsTablesAtEveryLengthAndAlignment) {
  std::vector<std::uint8_t> data(4096 + 16);
  std::uint32_t x = 12345;
  for (std::uint8_t& b : data) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(x >> 24);
  }
  for (std::size_t offset = 0; offset < 8; ++offset) {
    for (std::size_t n = 0; n <= 300; ++n) {
      const std::span<const std::uint8_t> s(data.data() + offset, n);
      ASSERT_EQ(crc32c(s), crc32cTables(s)) << "offset " << offset << ", " << n << " bytes";
    }
  }
  const std::span<const std::uint8_t> all(data.data(), 4096);
  EXPECT_EQ(crc32c(all), crc32cTables(all));
  EXPECT_EQ(crc32c(all.subspan(1000), crc32c(all.first(1000))), crc32c(all));
}

// The fast path's three lanes (3 KiB at a time, joined by shift tables) at lengths around
// whole multiples of 3 KiB, from a nonzero starting CRC, against the tables.
TEST(Crc32c, ThreeLaneFastPathEqualsTables) {
  std::vector<std::uint8_t> data(40000);
  std::uint32_t x = 777;
  for (std::uint8_t& b : data) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(x >> 24);
  }
  for (std::size_t n : {3071u, 3072u, 3073u, 3080u, 6143u, 6144u, 6151u, 9216u, 12289u, 39990u}) {
    for (std::size_t offset : {0u, 3u}) {
      const std::span<const std::uint8_t> s(data.data() + offset, n);
      ASSERT_EQ(crc32c(s), crc32cTables(s)) << "offset " << offset << ", " << n << " bytes";
      ASSERT_EQ(crc32c(s, 0x12345678u), crc32cTables(s, 0x12345678u)) << "continued, " << n << " bytes";
    }
  }
}

// crc32cCombine gives the checksum of a ++ b from the two pieces' checksums, at every split
// of a message (empty pieces included) and for long second pieces (many bits of the length).
TEST(Crc32c, CombineEqualsTheWholeAtEverySplit) {
  std::vector<std::uint8_t> data(5000);
  std::uint32_t x = 99;
  for (std::uint8_t& b : data) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(x >> 24);
  }
  const std::span<const std::uint8_t> all(data.data(), 300);
  for (std::size_t split = 0; split <= all.size(); ++split) {
    const auto a = all.first(split), b = all.subspan(split);
    ASSERT_EQ(crc32cCombine(crc32c(a), crc32c(b), b.size()), crc32c(all)) << "split at " << split;
  }
  const std::span<const std::uint8_t> whole(data);
  for (std::size_t split : {0u, 1u, 7u, 1000u, 4095u}) {
    const auto a = whole.first(split), b = whole.subspan(split);
    ASSERT_EQ(crc32cCombine(crc32c(a), crc32c(b), b.size()), crc32c(whole)) << "split at " << split;
  }
  EXPECT_EQ(crc32cCombine(0x12345678u, crc32c({}), 0), 0x12345678u);  // nothing appended
}

}  // namespace
}  // namespace prt
