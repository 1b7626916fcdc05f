// native/json_text: exact escapes for the characters JSON requires escaped, UTF-8 passed
// through, malformed UTF-8 as Latin-1 escapes, numbers at 9 significant digits. Every
// output is parsed back with nlohmann_json, an independent parser (and UTF-8 validator).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "native/json_text.h"
#include "native_test_files.h"

namespace prt {
namespace {

using nlohmann::json;
using test::cat;

// Parses `text` as one whole JSON document; discarded (is_discarded()) when it does not parse.
json parse(const std::string& text) { return json::parse(text, nullptr, /*allow_exceptions=*/false); }

// The UTF-8 encoding of U+00XX: what a Latin-1 byte b escaped as \u00XX parses back to.
std::string latin1(unsigned char b) {
  if (b < 0x80) return std::string(1, static_cast<char>(b));
  return {static_cast<char>(0xc0 | (b >> 6)), static_cast<char>(0x80 | (b & 0x3f))};
}

std::string escape(unsigned char b) {
  static const char kHex[] = "0123456789abcdef";
  return std::string("\\u00") + kHex[b >> 4] + kHex[b & 15];
}

std::string inQuotes(std::string_view s) { return cat("\"", s, "\""); }

// Checks that jsonString(s) parses with nlohmann_json to the string `decoded`.
void expectParsesTo(std::string_view s, const std::string& decoded) {
  const std::string text = jsonString(s);
  const json j = parse(text);
  ASSERT_FALSE(j.is_discarded()) << text;
  ASSERT_TRUE(j.is_string()) << text;
  EXPECT_EQ(j.get<std::string>(), decoded) << text;
}

TEST(JsonString, QuotesAndBackslashes) {
  EXPECT_EQ(jsonString(""), "\"\"");
  EXPECT_EQ(jsonString("plain text / slash"), "\"plain text / slash\"");
  EXPECT_EQ(jsonString("a\"b\\c"), R"("a\"b\\c")");
  EXPECT_EQ(jsonString("\\\""), R"("\\\"")");
  EXPECT_EQ(jsonString("C:\\dir\\\"x\".exr"), R"("C:\\dir\\\"x\".exr")");
  for (std::string_view s : {"a\"b\\c", "\\\"", "\"\"\"", "\\\\\\"}) expectParsesTo(s, std::string(s));
}

// Every control character (and DEL) as \u00XX, lower-case hex; nothing else escaped.
TEST(JsonString, ControlCharactersAsUnicodeEscapes) {
  for (int c = 0; c < 0x20; ++c) {
    const std::string s(1, static_cast<char>(c));
    EXPECT_EQ(jsonString(s), inQuotes(escape(static_cast<unsigned char>(c)))) << "byte " << c;
    expectParsesTo(s, s);
  }
  EXPECT_EQ(jsonString("\x7f"), inQuotes("\\u007f"));
  EXPECT_EQ(jsonString("\n"), inQuotes("\\u000a"));
  EXPECT_EQ(jsonString("\x1f"), inQuotes("\\u001f"));
  // An embedded NUL is a character of the string, not its end.
  EXPECT_EQ(jsonString(std::string_view("a\0b", 3)), inQuotes("a\\u0000b"));
  expectParsesTo(std::string_view("a\0b", 3), std::string("a\0b", 3));
  for (int c = 0x20; c < 0x7f; ++c) {
    if (c == '"' || c == '\\') continue;
    EXPECT_EQ(jsonString(std::string(1, static_cast<char>(c))), inQuotes(std::string(1, static_cast<char>(c))));
  }
}

TEST(JsonString, WellFormedUtf8PassesThrough) {
  const std::vector<std::string> valid = {
      "\xc2\x80",          // U+0080, the first two-byte character
      "caf\xc3\xa9",       // é
      "\xdf\xbf",          // U+07FF
      "\xe0\xa0\x80",      // U+0800, the first three-byte character
      "\xe2\x82\xac",      // €
      "\xed\x9f\xbf",      // U+D7FF, just below the surrogates
      "\xee\x80\x80",      // U+E000, just above them
      "\xef\xbf\xbf",      // U+FFFF
      "\xf0\x90\x80\x80",  // U+10000, the first four-byte character
      "\xf0\x9d\x84\x9e",  // 𝄞
      "\xf4\x8f\xbf\xbf",  // U+10FFFF, the last character
      "\xe2\x80\xa8",      // U+2028 (valid JSON unescaped)
      "\xe6\x97\xa5\xe6\x9c\xac/\xd0\x9a\xd0\xb8\xd1\x97\xd0\xb2.exr",
  };
  for (const std::string& s : valid) {
    EXPECT_EQ(jsonString(s), inQuotes(s));
    expectParsesTo(s, s);
  }
}

// Bytes that are not part of a well-formed sequence become \u00XX of their Latin-1
// reading; the well-formed sequences around them still pass through.
TEST(JsonString, MalformedUtf8AsLatin1Escapes) {
  struct Case {
    std::string input;
    std::string expected;  // the JSON text between the quotes
  };
  const std::vector<Case> cases = {
      {"\x80", escape(0x80)},  // lone continuation
      {"\xbf", escape(0xbf)},
      {"\xc0\x80", escape(0xc0) + escape(0x80)},                     // overlong NUL
      {"\xc1\xbf", escape(0xc1) + escape(0xbf)},                     // overlong
      {"\xe0\x80\x80", escape(0xe0) + escape(0x80) + escape(0x80)},  // overlong
      {"\xe0\x9f\xbf", escape(0xe0) + escape(0x9f) + escape(0xbf)},  // overlong
      {"\xed\xa0\x80", escape(0xed) + escape(0xa0) + escape(0x80)},  // surrogate U+D800
      {"\xed\xbf\xbf", escape(0xed) + escape(0xbf) + escape(0xbf)},  // surrogate U+DFFF
      {"\xf0\x80\x80\x80", escape(0xf0) + escape(0x80) + escape(0x80) + escape(0x80)},
      {"\xf4\x90\x80\x80", escape(0xf4) + escape(0x90) + escape(0x80) + escape(0x80)},  // > U+10FFFF
      {"\xf5\x80\x80\x80", escape(0xf5) + escape(0x80) + escape(0x80) + escape(0x80)},
      {"\xf8\x88\x80\x80\x80", escape(0xf8) + escape(0x88) + escape(0x80) + escape(0x80) + escape(0x80)},
      {"\xfe\xff", escape(0xfe) + escape(0xff)},
      {"\xe2\x82", escape(0xe2) + escape(0x82)},         // cut at the end
      {"\xe2\x82x", escape(0xe2) + escape(0x82) + "x"},  // cut before ASCII
      {"\xf0\x9d\x84", escape(0xf0) + escape(0x9d) + escape(0x84)},
      {"\xe2\xc3\xa9", escape(0xe2) + "\xc3\xa9"},      // then a valid é
      {"\xc3\xa9\xa9", cat("\xc3\xa9", escape(0xa9))},  // é, then a stray byte
      {"a\xff\"b", cat("a", escape(0xff), "\\\"b")},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(jsonString(c.input), inQuotes(c.expected));
    // The parsed string: each escaped byte as its Latin-1 character, the rest unchanged.
    std::string decoded;
    const json j = parse(inQuotes(c.expected));
    ASSERT_TRUE(j.is_string()) << c.expected;
    decoded = j.get<std::string>();
    std::string expectedDecoded;
    for (std::size_t i = 0; i < c.expected.size();) {
      if (c.expected.compare(i, 4, "\\u00") == 0) {
        expectedDecoded +=
            latin1(static_cast<unsigned char>(std::strtol(c.expected.substr(i + 4, 2).c_str(), nullptr, 16)));
        i += 6;
      } else if (c.expected[i] == '\\') {
        expectedDecoded += c.expected[i + 1];
        i += 2;
      } else {
        expectedDecoded += c.expected[i++];
      }
    }
    EXPECT_EQ(decoded, expectedDecoded);
  }
}

// Random byte strings: the output always parses as a JSON string; when nlohmann_json
// judges the input well-formed UTF-8 it comes back unchanged and unescaped, and when it
// does not, some byte was escaped.
TEST(JsonString, RandomBytesAlwaysParseAndAgreeOnUtf8Validity) {
  const unsigned char alphabet[] = {'a',  '"',  '\\', 0x00, 0x1f, 0x7f, 0x80, 0x8f, 0x90, 0x9f, 0xa0,
                                    0xbf, 0xc0, 0xc2, 0xdf, 0xe0, 0xed, 0xef, 0xf0, 0xf4, 0xf5, 0xff};
  std::uint32_t s = 2024;
  int valid = 0, invalid = 0;
  for (int iter = 0; iter < 20000; ++iter) {
    s = s * 1664525u + 1013904223u;
    const std::size_t length = (s >> 24) % 9;
    std::string in;
    for (std::size_t k = 0; k < length; ++k) {
      s = s * 1664525u + 1013904223u;
      in += static_cast<char>(alphabet[(s >> 16) % sizeof alphabet]);
    }
    const std::string text = jsonString(in);
    const json j = parse(text);
    ASSERT_FALSE(j.is_discarded()) << text;
    ASSERT_TRUE(j.is_string());
    bool wellFormed = true;
    try {
      (void)json(in).dump();
    } catch (const json::type_error&) {
      wellFormed = false;
    }
    // Count the \u00XX escapes of bytes >= 0x80.
    bool escapedHigh = false;
    for (std::size_t i = 0; i + 6 <= text.size(); ++i) {
      if (text.compare(i, 4, "\\u00") == 0 && text[i + 4] >= '8') escapedHigh = true;
      if (text[i] == '\\') ++i;  // skip the escaped character
    }
    if (wellFormed) {
      ++valid;
      EXPECT_EQ(j.get<std::string>(), in) << text;
      EXPECT_FALSE(escapedHigh) << text;
    } else {
      ++invalid;
      EXPECT_TRUE(escapedHigh) << text;
    }
  }
  EXPECT_GT(valid, 1000);
  EXPECT_GT(invalid, 1000);
}

TEST(JsonNumber, Integers) {
  EXPECT_EQ(jsonNumber(0), "0");
  EXPECT_EQ(jsonNumber(1), "1");
  EXPECT_EQ(jsonNumber(-1), "-1");
  EXPECT_EQ(jsonNumber(42), "42");
  EXPECT_EQ(jsonNumber(1000000), "1000000");
  EXPECT_EQ(jsonNumber(16777216), "16777216");    // 2^24
  EXPECT_EQ(jsonNumber(123456789), "123456789");  // 9 digits: still exact
  EXPECT_EQ(jsonNumber(-0.0), "-0");
  EXPECT_EQ(jsonNumber(0.5), "0.5");
  EXPECT_EQ(jsonNumber(0.1), "0.1");
  EXPECT_EQ(jsonNumber(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(jsonNumber(1e21), "1e+21");
  for (const char* text : {"0", "1", "-1", "42", "16777216", "123456789"}) {
    const json j = parse(jsonNumber(std::strtod(text, nullptr)));
    ASSERT_TRUE(j.is_number_integer()) << text;
    EXPECT_EQ(j.get<long long>(), std::strtoll(text, nullptr, 10));
  }
}

TEST(JsonNumber, NonFiniteIsNull) {
  for (double v : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(jsonNumber(v), "null");
    EXPECT_TRUE(parse(jsonNumber(v)).is_null());
  }
}

// "9 significant digits (round-trips a float)": every finite float comes back bit for bit
// through strtod, and nlohmann_json reads the same number.
TEST(JsonNumber, EveryKindOfFloatRoundTrips) {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               0.1f,
                               1.0f / 3.0f,
                               2.5e-3f,
                               1e-7f,
                               65504.0f,
                               16777217.0f,
                               std::numeric_limits<float>::min(),
                               std::numeric_limits<float>::max(),
                               std::numeric_limits<float>::lowest(),
                               std::numeric_limits<float>::denorm_min(),
                               std::numeric_limits<float>::epsilon(),
                               3.14159274f,
                               -2.71828175f};
  std::uint32_t s = 7;
  while (values.size() < 100000) {
    s = s * 1664525u + 1013904223u;
    float f;
    std::memcpy(&f, &s, sizeof f);
    if (std::isfinite(f)) values.push_back(f);
  }
  for (float f : values) {
    const std::string text = jsonNumber(f);
    const float back = static_cast<float>(std::strtod(text.c_str(), nullptr));
    std::uint32_t a, b;
    std::memcpy(&a, &f, sizeof a);
    std::memcpy(&b, &back, sizeof b);
    ASSERT_EQ(a, b) << f << " -> " << text;
    const json j = parse(text);
    ASSERT_TRUE(j.is_number()) << text;
    ASSERT_EQ(j.get<double>(), std::strtod(text.c_str(), nullptr)) << text;
  }
}

// Doubles keep 9 significant digits (the contract promises no more): within half a unit
// in the 9th digit, and valid JSON at every magnitude.
TEST(JsonNumber, DoublesToNineDigits) {
  EXPECT_EQ(jsonNumber(123456789012.0), "1.23456789e+11");
  EXPECT_EQ(jsonNumber(0.1 + 0.2), "0.3");
  std::uint64_t s = 11;
  for (int i = 0; i < 20000; ++i) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    double d;
    std::memcpy(&d, &s, sizeof d);
    if (!std::isfinite(d) || d == 0.0) continue;
    const std::string text = jsonNumber(d);
    const double back = std::strtod(text.c_str(), nullptr);
    ASSERT_LE(std::fabs(back - d), std::fabs(d) * 5.0000001e-9) << d << " -> " << text;
    const json j = parse(text);
    ASSERT_TRUE(j.is_number()) << text;
    ASSERT_EQ(j.get<double>(), back) << text;
  }
}

// Numbers and strings together in a document parse to what they hold.
TEST(JsonText, DocumentOfBoth) {
  const std::string doc = cat("{", jsonString("na\"me\x01\xff"), ": [", jsonNumber(0.25), ", ",
                              jsonNumber(std::numeric_limits<double>::infinity()), ", ", jsonNumber(-1e-30), "]}");
  const json j = parse(doc);
  ASSERT_TRUE(j.is_object()) << doc;
  const std::string key = std::string("na\"me\x01") + latin1(0xff);
  ASSERT_TRUE(j.contains(key)) << doc;
  const json& a = j[key];
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].get<double>(), 0.25);
  EXPECT_TRUE(a[1].is_null());
  EXPECT_EQ(a[2].get<double>(), -1e-30);
}

}  // namespace
}  // namespace prt
