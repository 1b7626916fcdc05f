#include "mini_json.h"

#include <cstdlib>

namespace prt::serve::test {
namespace {

const Json kNull{};

struct Parser {
  std::string_view s;
  std::size_t i = 0;
  std::string error;

  void ws() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) ++i;
  }
  bool fail(const std::string& what) {
    if (error.empty()) error = what + " at offset " + std::to_string(i);
    return false;
  }
  bool literal(std::string_view word) {
    if (s.substr(i, word.size()) != word) return fail("bad literal");
    i += word.size();
    return true;
  }
  static void putUtf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xc0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xe0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (cp & 0x3f));
    }
  }
  bool hex4(unsigned* out) {
    if (i + 4 > s.size()) return fail("short \\u escape");
    *out = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s[i++];
      const int v = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (v < 0) return fail("bad \\u escape");
      *out = *out * 16 + static_cast<unsigned>(v);
    }
    return true;
  }
  bool str(std::string* out) {
    if (i >= s.size() || s[i] != '"') return fail("expected string");
    ++i;
    while (i < s.size() && s[i] != '"') {
      const auto c = static_cast<unsigned char>(s[i]);
      if (c < 0x20) return fail("control character in string");
      if (c != '\\') {
        *out += static_cast<char>(c);
        ++i;
        continue;
      }
      if (++i >= s.size()) return fail("unterminated escape");
      const char e = s[i++];
      switch (e) {
        case '"': *out += '"'; break;
        case '\\': *out += '\\'; break;
        case '/': *out += '/'; break;
        case 'b': *out += '\b'; break;
        case 'f': *out += '\f'; break;
        case 'n': *out += '\n'; break;
        case 'r': *out += '\r'; break;
        case 't': *out += '\t'; break;
        case 'u': {
          unsigned cp = 0;
          if (!hex4(&cp)) return false;
          if (cp >= 0xd800 && cp < 0xdc00 && s.substr(i, 2) == "\\u") {
            i += 2;
            unsigned lo = 0;
            if (!hex4(&lo)) return false;
            cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
          }
          putUtf8(*out, cp);
          break;
        }
        default: return fail("bad escape");
      }
    }
    if (i >= s.size()) return fail("unterminated string");
    ++i;
    return true;
  }
  bool value(Json* v, int depth) {
    if (depth > 64) return fail("too deep");
    ws();
    if (i >= s.size()) return fail("unexpected end");
    const char c = s[i];
    if (c == '{') {
      v->type = Json::Type::kObject;
      ++i;
      ws();
      if (i < s.size() && s[i] == '}') return ++i, true;
      for (;;) {
        ws();
        std::string key;
        if (!str(&key)) return false;
        ws();
        if (i >= s.size() || s[i] != ':') return fail("expected ':'");
        ++i;
        if (!value(&v->object[key], depth + 1)) return false;
        ws();
        if (i < s.size() && s[i] == ',') { ++i; continue; }
        if (i < s.size() && s[i] == '}') return ++i, true;
        return fail("expected ',' or '}'");
      }
    }
    if (c == '[') {
      v->type = Json::Type::kArray;
      ++i;
      ws();
      if (i < s.size() && s[i] == ']') return ++i, true;
      for (;;) {
        v->array.emplace_back();
        if (!value(&v->array.back(), depth + 1)) return false;
        ws();
        if (i < s.size() && s[i] == ',') { ++i; continue; }
        if (i < s.size() && s[i] == ']') return ++i, true;
        return fail("expected ',' or ']'");
      }
    }
    if (c == '"') {
      v->type = Json::Type::kString;
      return str(&v->string);
    }
    if (c == 't') { v->type = Json::Type::kBool; v->boolean = true; return literal("true"); }
    if (c == 'f') { v->type = Json::Type::kBool; return literal("false"); }
    if (c == 'n') { v->type = Json::Type::kNull; return literal("null"); }
    // Number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
    const std::size_t start = i;
    if (s[i] == '-') ++i;
    auto digits = [&] { const std::size_t b = i; while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i; return i > b; };
    if (i < s.size() && s[i] == '0') ++i; else if (!digits()) return fail("bad number");
    if (i < s.size() && s[i] == '.') { ++i; if (!digits()) return fail("bad fraction"); }
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
      ++i;
      if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
      if (!digits()) return fail("bad exponent");
    }
    v->type = Json::Type::kNumber;
    v->number = std::strtod(std::string(s.substr(start, i - start)).c_str(), nullptr);
    return true;
  }
};

}  // namespace

const Json& Json::operator[](const std::string& key) const {
  if (type != Type::kObject) return kNull;
  const auto it = object.find(key);
  return it == object.end() ? kNull : it->second;
}

const Json& Json::operator[](std::size_t idx) const {
  return type == Type::kArray && idx < array.size() ? array[idx] : kNull;
}

bool parseJson(std::string_view text, Json* out, std::string* error) {
  Parser p{text, 0, {}};
  *out = Json{};
  if (!p.value(out, 0)) {
    *error = p.error;
    return false;
  }
  p.ws();
  if (p.i != text.size()) {
    *error = "trailing bytes at offset " + std::to_string(p.i);
    return false;
  }
  return true;
}

}  // namespace prt::serve::test
