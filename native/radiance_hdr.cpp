#include "native/radiance_hdr.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "native/image_io.h"

namespace prt {
namespace {

Status corrupt(const std::string& problem) {
  return Status::error(StatusCode::kInvalidArgument, "corrupt Radiance HDR file: " + problem);
}

Status truncated() {
  return Status::error(StatusCode::kInvalidArgument,
                       "truncated Radiance HDR file: the data ends before the image is complete");
}

// Buffered byte source; get() returns -1 at the end of the file or on a read error.
class ByteReader {
 public:
  explicit ByteReader(std::FILE* file) : file_(file), buffer_(1 << 16) {}

  int get() {
    if (pos_ == len_) {
      len_ = std::fread(buffer_.data(), 1, buffer_.size(), file_);
      pos_ = 0;
      if (len_ == 0) return -1;
    }
    return buffer_[pos_++];
  }
  bool failed() const { return std::ferror(file_) != 0; }

 private:
  std::FILE* file_;
  std::vector<unsigned char> buffer_;
  std::size_t pos_ = 0, len_ = 0;
};

// Reads one '\n'-terminated header line without the '\n'; false at the end of the file.
bool readLine(ByteReader& in, std::string* line, std::size_t maxLength) {
  line->clear();
  for (int c = in.get(); c != '\n'; c = in.get()) {
    if (c < 0 || line->size() >= maxLength) return false;
    line->push_back(static_cast<char>(c));
  }
  return true;
}

struct Header {
  int width = 0, height = 0;
  bool bottomUp = false;  // "+Y": the first scanline is the bottom row
};

Status parseResolution(const std::string& line, Header* h) {
  // "-Y H +X W" (top-down, the common case) or "+Y H +X W" (bottom-up).
  std::vector<std::string_view> tok;
  std::string_view rest(line);
  while (!rest.empty()) {
    const std::size_t start = rest.find_first_not_of(" \t\r");
    if (start == std::string_view::npos) break;
    rest.remove_prefix(start);
    const std::size_t end = std::min(rest.find_first_of(" \t\r"), rest.size());
    tok.push_back(rest.substr(0, end));
    rest.remove_prefix(end);
  }
  auto number = [](std::string_view t, std::int64_t* v) {
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), *v);
    return ec == std::errc() && p == t.data() + t.size();
  };
  std::int64_t height = 0, width = 0;
  if (tok.size() != 4 || !number(tok[1], &height) || !number(tok[3], &width)) {
    return corrupt("bad resolution line '" + line + "'");
  }
  if ((tok[0] != "-Y" && tok[0] != "+Y") || tok[2] != "+X") {
    return Status::error(StatusCode::kInvalidArgument,
                         "unsupported Radiance HDR orientation '" + line + "' (expected -Y H +X W or +Y H +X W)");
  }
  if (Status s = checkImageSize(width, height); !s.isOk()) return s;
  h->width = static_cast<int>(width);
  h->height = static_cast<int>(height);
  h->bottomUp = tok[0] == "+Y";
  return Status::ok();
}

Status readHeader(ByteReader& in, Header* h) {
  constexpr std::size_t kMaxLine = 4096, kMaxLines = 1024;
  std::string line;
  if (!readLine(in, &line, kMaxLine) || line.rfind("#?", 0) != 0) return corrupt("no '#?' signature line");
  for (std::size_t n = 0;; ++n) {
    if (n == kMaxLines || !readLine(in, &line, kMaxLine)) return corrupt("the header has no end");
    if (line.empty()) break;
    if (line.rfind("FORMAT=", 0) == 0) {
      const std::string format = line.substr(7, line.find_last_not_of(" \t\r") - 6);
      if (format != "32-bit_rle_rgbe") {
        return Status::error(StatusCode::kInvalidArgument,
                             "unsupported Radiance HDR format '" + format + "' (only 32-bit_rle_rgbe)");
      }
    }
  }
  if (!readLine(in, &line, kMaxLine)) return truncated();
  return parseResolution(line, h);
}

// Flat pixels with old-style runs (a pixel 1,1,1,n repeats the previous one n << shift
// times, shift growing by 8 over consecutive runs), starting with the 4 bytes in `px`.
Status readOldStyleScanline(ByteReader& in, int width, unsigned char px[4], std::vector<unsigned char>& line) {
  int x = 0, shift = 0;
  for (;;) {
    if (px[0] == 1 && px[1] == 1 && px[2] == 1) {
      if (x == 0 || shift > 16) return corrupt("a run-length pixel has nothing to repeat");
      const std::int64_t count = static_cast<std::int64_t>(px[3]) << shift;
      if (count > width - x) return corrupt("a run overflows its scanline");
      for (std::int64_t k = 0; k < count; ++k, ++x)
        for (int c = 0; c < 4; ++c) line[static_cast<std::size_t>(x) * 4 + c] = line[static_cast<std::size_t>(x - 1) * 4 + c];
      shift += 8;
    } else {
      for (int c = 0; c < 4; ++c) line[static_cast<std::size_t>(x) * 4 + c] = px[c];
      ++x;
      shift = 0;
    }
    if (x == width) return Status::ok();
    for (int c = 0; c < 4; ++c) {
      const int b = in.get();
      if (b < 0) return truncated();
      px[c] = static_cast<unsigned char>(b);
    }
  }
}

// New-style run-length scanline: each of the 4 components as runs (count > 128: one byte
// repeated count - 128 times) and dumps (count <= 128: that many bytes).
Status readNewStyleScanline(ByteReader& in, int width, std::vector<unsigned char>& line) {
  for (int c = 0; c < 4; ++c) {
    for (int x = 0; x < width;) {
      const int count = in.get();
      if (count < 0) return truncated();
      const int n = count > 128 ? count - 128 : count;
      if (n == 0 || n > width - x) return corrupt("bad run length in a scanline");
      if (count > 128) {
        const int v = in.get();
        if (v < 0) return truncated();
        for (int k = 0; k < n; ++k, ++x) line[static_cast<std::size_t>(x) * 4 + c] = static_cast<unsigned char>(v);
      } else {
        for (int k = 0; k < n; ++k, ++x) {
          const int v = in.get();
          if (v < 0) return truncated();
          line[static_cast<std::size_t>(x) * 4 + c] = static_cast<unsigned char>(v);
        }
      }
    }
  }
  return Status::ok();
}

Status readScanline(ByteReader& in, int width, std::vector<unsigned char>& line) {
  unsigned char px[4];
  for (int c = 0; c < 4; ++c) {
    const int b = in.get();
    if (b < 0) return truncated();
    px[c] = static_cast<unsigned char>(b);
  }
  // New-style scanlines open with 2, 2 and the width; only widths in [8, 0x7fff] use them.
  const bool newStyle = width >= 8 && width <= 0x7fff && px[0] == 2 && px[1] == 2 && (px[2] & 0x80) == 0;
  if (!newStyle) return readOldStyleScanline(in, width, px, line);
  if (((px[2] << 8) | px[3]) != width) return corrupt("a scanline's length disagrees with the image width");
  return readNewStyleScanline(in, width, line);
}

}  // namespace

Status readRadianceHdr(std::FILE* file, RgbImage* out) {
  ByteReader in(file);
  Header h;
  if (Status s = readHeader(in, &h); !s.isOk()) return in.failed() ? Status::error(StatusCode::kIoError, "read error") : s;
  const std::size_t rowFloats = static_cast<std::size_t>(h.width) * 3;
  out->width = h.width;
  out->height = h.height;
  // Reserved, not filled: a truncated file that claims a huge size touches only the rows
  // it really holds.
  out->rgb.clear();
  out->rgb.reserve(rowFloats * static_cast<std::size_t>(h.height));
  std::vector<unsigned char> line(static_cast<std::size_t>(h.width) * 4);
  for (int j = 0; j < h.height; ++j) {
    if (Status s = readScanline(in, h.width, line); !s.isOk()) {
      return in.failed() ? Status::error(StatusCode::kIoError, "read error") : s;
    }
    for (int x = 0; x < h.width; ++x) {
      const unsigned char* p = &line[static_cast<std::size_t>(x) * 4];
      // Mantissas scale by 2^(e - 128 - 8), as stb_image and three.js decode them.
      const float f = p[3] == 0 ? 0.0f : std::ldexp(1.0f, p[3] - 136);
      out->rgb.push_back(p[0] * f);
      out->rgb.push_back(p[1] * f);
      out->rgb.push_back(p[2] * f);
    }
  }
  if (h.bottomUp) {
    for (int j = 0; j < h.height / 2; ++j) {
      auto top = out->rgb.begin() + static_cast<std::ptrdiff_t>(rowFloats * static_cast<std::size_t>(j));
      auto bottom = out->rgb.begin() + static_cast<std::ptrdiff_t>(rowFloats * static_cast<std::size_t>(h.height - 1 - j));
      std::swap_ranges(top, top + static_cast<std::ptrdiff_t>(rowFloats), bottom);
    }
  }
  return Status::ok();
}

}  // namespace prt
