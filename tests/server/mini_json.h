// A strict little JSON reader for checking the server's documents in tests (RFC 8259;
// \u escapes are decoded to UTF-8, surrogate pairs included).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace prt::serve::test {

struct Json {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject } type = Type::kNull;
  bool boolean = false;
  double number = 0;
  std::string string;
  std::vector<Json> array;
  std::map<std::string, Json> object;

  // Member `key` of an object; a null value when absent or not an object.
  const Json& operator[](const std::string& key) const;
  // Element i of an array; a null value when out of range.
  const Json& operator[](std::size_t i) const;
  bool has(const std::string& key) const { return type == Type::kObject && object.count(key) > 0; }
  bool isNull() const { return type == Type::kNull; }
};

// Parses the whole of `text`; false (with *error) on any syntax error or trailing bytes.
bool parseJson(std::string_view text, Json* out, std::string* error);

}  // namespace prt::serve::test
