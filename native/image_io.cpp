#include "native/image_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <new>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfRgbaFile.h>
#include <stb_image.h>

#include "native/file_io.h"
#include "native/radiance_hdr.h"

namespace prt {
namespace {

Status problem(std::string message) { return Status::error(StatusCode::kInvalidArgument, std::move(message)); }
// A system call that just failed, with the code its errno stands for.
Status failed(std::string message) { return Status::error(statusCodeForErrno(errno), std::move(message)); }

// ---- OpenEXR ----------------------------------------------------------------------------

Status loadExr(const std::string& path, RgbImage* out) {
  // OpenEXR reports every problem (bad header, truncated chunk, unsupported compression)
  // by throwing; this function is the wall that turns them into a Status.
  try {
    // Imf::RgbaInputFile reads every channel as half: a float channel would lose its low
    // mantissa bits, and values above 65504 (a sun) would become infinite. So pixels are
    // read as float through the general interface, with RgbaInputFile's choice of
    // channels: Y, when present, as grey (missing R, G or B as 0 otherwise), and only
    // luminance/chroma files (Y with RY, BY) through RgbaInputFile, which converts them.
    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& channels = file.header().channels();
    const bool hasY = channels.findChannel("Y") != nullptr;
    const bool hasChroma = channels.findChannel("RY") != nullptr || channels.findChannel("BY") != nullptr;
    if (!hasY && !channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B")) {
      return problem("OpenEXR file has no R, G, B or Y channel");
    }
    std::unique_ptr<Imf::RgbaInputFile> yca;
    if (hasY && hasChroma) yca = std::make_unique<Imf::RgbaInputFile>(path.c_str());
    // The display window is the image; the data window holds the stored pixels, which may
    // cover only part of it (the rest is black) or spill past it (cropped).
    const Imath::Box2i disp = file.header().displayWindow();
    const Imath::Box2i data = file.header().dataWindow();
    const std::int64_t width = std::int64_t{disp.max.x} - disp.min.x + 1;
    const std::int64_t height = std::int64_t{disp.max.y} - disp.min.y + 1;
    if (Status s = checkImageSize(width, height); !s.isOk()) return s;
    const std::int64_t dataWidth = std::int64_t{data.max.x} - data.min.x + 1;
    if (dataWidth < 1 || dataWidth > kMaxImageSide) {
      return problem("OpenEXR data window is " + std::to_string(dataWidth) + " pixels wide; at most " +
                     std::to_string(kMaxImageSide) + " are supported");
    }
    out->width = static_cast<int>(width);
    out->height = static_cast<int>(height);
    const std::size_t rowFloats = static_cast<std::size_t>(width) * 3;
    // Reserved, then filled row by row: a corrupt file that claims a huge size fails on its
    // first missing chunk having touched little memory.
    out->rgb.clear();
    out->rgb.reserve(rowFloats * static_cast<std::size_t>(height));

    const int x0 = std::max(disp.min.x, data.min.x), x1 = std::min(disp.max.x, data.max.x);
    const int y0 = std::max(disp.min.y, data.min.y), y1 = std::min(disp.max.y, data.max.y);
    if (x0 <= x1) {
      // Strips of 256 rows (the largest chunk any compression uses, DWAB's) bound memory
      // without decompressing a chunk twice. 3 floats per pixel (only the first for Y).
      constexpr int kStrip = 256;
      const std::size_t stride = static_cast<std::size_t>(dataWidth);
      std::vector<float> strip(stride * kStrip * 3);
      std::vector<Imf::Rgba> ycaStrip(yca ? stride * kStrip : 0);
      for (int ys = y0; ys <= y1; ys += kStrip) {
        const int ye = std::min(y1, ys + kStrip - 1);
        if (yca) {
          // OpenEXR addresses the frame buffer by absolute pixel coordinates.
          Imf::Rgba* origin = ycaStrip.data() - static_cast<std::ptrdiff_t>(data.min.x) -
                              static_cast<std::ptrdiff_t>(ys) * static_cast<std::ptrdiff_t>(stride);
          yca->setFrameBuffer(origin, 1, stride);
          yca->readPixels(ys, ye);
          for (std::size_t i = 0; i < stride * static_cast<std::size_t>(ye - ys + 1); ++i) {
            strip[i * 3] = ycaStrip[i].r;
            strip[i * 3 + 1] = ycaStrip[i].g;
            strip[i * 3 + 2] = ycaStrip[i].b;
          }
        } else {
          Imf::FrameBuffer fb;
          const Imath::V2i origin(data.min.x, ys);
          const std::size_t xStride = 3 * sizeof(float), yStride = xStride * stride;
          const char* names[3] = {"R", "G", "B"};
          for (int c = 0; c < (hasY ? 1 : 3); ++c) {
            // Channels the file lacks read as the fill value, 0.
            fb.insert(hasY ? "Y" : names[c], Imf::Slice::Make(Imf::FLOAT, strip.data() + c, origin, dataWidth,
                                                              ye - ys + 1, xStride, yStride, 1, 1, 0.0));
          }
          file.setFrameBuffer(fb);
          file.readPixels(ys, ye);
        }
        const bool grey = hasY && !yca;
        out->rgb.resize(rowFloats * static_cast<std::size_t>(ye - disp.min.y + 1), 0.0f);
        for (int y = ys; y <= ye; ++y) {
          const float* row = strip.data() + static_cast<std::size_t>(y - ys) * stride * 3;
          float* dst = out->rgb.data() + rowFloats * static_cast<std::size_t>(y - disp.min.y);
          for (int x = x0; x <= x1; ++x) {
            const float* p = row + static_cast<std::size_t>(x - data.min.x) * 3;
            float* d = dst + static_cast<std::size_t>(x - disp.min.x) * 3;
            d[0] = p[0];
            d[1] = grey ? p[0] : p[1];
            d[2] = grey ? p[0] : p[2];
          }
        }
      }
    }
    out->rgb.resize(rowFloats * static_cast<std::size_t>(height), 0.0f);  // rows below the data: black
    return Status::ok();
  } catch (const std::bad_alloc&) {
    return Status::error(StatusCode::kResourceExhausted, "out of memory while reading the OpenEXR file");
  } catch (const std::exception& e) {
    return problem(std::string("cannot read OpenEXR data (the file is corrupt or truncated): ") + e.what());
  } catch (...) {
    return problem("cannot read OpenEXR data (the file is corrupt or truncated)");
  }
}

// ---- stb_image (PNG, JPEG) --------------------------------------------------------------

// stb_image's own memory and FILE readers pad a short file with zeros and can "succeed" on
// a truncated image. Reading through callbacks lets us notice any read past the end.
struct StbSource {
  std::FILE* file = nullptr;
  bool readPastEnd = false;
  bool readError = false;

  static int read(void* user, char* data, int size) {
    auto* self = static_cast<StbSource*>(user);
    const std::size_t n = std::fread(data, 1, static_cast<std::size_t>(size), self->file);
    if (n == 0 && size > 0) {
      if (std::ferror(self->file)) self->readError = true;
      else self->readPastEnd = true;
    }
    return static_cast<int>(n);
  }
  static void skip(void* user, int n) {
    auto* self = static_cast<StbSource*>(user);
    if (std::fseek(self->file, n, SEEK_CUR) != 0) self->readError = true;
  }
  // Not feof() alone: skip()'s fseek clears the end-of-file indicator, and once stb_image
  // has seen the end it reads no more, so the indicator would never come back. Its loops
  // that scan for a marker until eof() (JPEG, after a segment skipped past the end) would
  // then spin forever.
  static int eof(void* user) {
    auto* self = static_cast<StbSource*>(user);
    return self->readPastEnd || std::feof(self->file) ? 1 : 0;
  }

  Status rewind() {
    readPastEnd = false;
    std::clearerr(file);
    if (std::fseek(file, 0, SEEK_SET) != 0) return failed(std::string("cannot seek: ") + std::strerror(errno));
    return Status::ok();
  }
};

constexpr stbi_io_callbacks kStbCallbacks = {&StbSource::read, &StbSource::skip, &StbSource::eof};

float srgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

// A lookup table per bit depth: a 16-bit image would otherwise cost a pow() per value.
std::vector<float> srgbTable(int levels) {
  std::vector<float> table(static_cast<std::size_t>(levels));
  for (int i = 0; i < levels; ++i) table[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / (levels - 1));
  return table;
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

std::uint32_t bigEndian32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

// PNG and JPEG through stb_image. `head` holds the file's first `headLength` bytes.
Status loadWithStb(std::FILE* file, ImageFormat format, const unsigned char* head, std::size_t headLength,
                   RgbImage* out) {
  const char* name = imageFormatName(format);
  // stbi_info reports a bad PNG size only as "unknown image type", so read IHDR here.
  if (format == ImageFormat::kPng && headLength >= 24 && std::equal(head + 12, head + 16, "IHDR")) {
    if (Status s = checkImageSize(bigEndian32(head + 16), bigEndian32(head + 20)); !s.isOk()) return s;
  }
  StbSource src{file};
  if (Status s = src.rewind(); !s.isOk()) return s;
  int w = 0, h = 0, comp = 0;
  // Checking the size before decoding spares a decode of a huge image; when stb cannot
  // read the header, decoding anyway gets its precise reason for the message.
  const bool haveInfo = stbi_info_from_callbacks(&kStbCallbacks, &src, &w, &h, &comp) != 0;
  if (haveInfo) {
    if (Status s = checkImageSize(w, h); !s.isOk()) return s;
  }
  bool sixteenBit = false;
  if (format == ImageFormat::kPng) {
    if (Status s = src.rewind(); !s.isOk()) return s;
    sixteenBit = stbi_is_16_bit_from_callbacks(&kStbCallbacks, &src) != 0;
  }
  if (Status s = src.rewind(); !s.isOk()) return s;

  int dw = 0, dh = 0, dc = 0;
  std::unique_ptr<void, StbFree> pixels;
  if (sixteenBit) {
    pixels.reset(stbi_load_16_from_callbacks(&kStbCallbacks, &src, &dw, &dh, &dc, 3));
  } else {
    pixels.reset(stbi_load_from_callbacks(&kStbCallbacks, &src, &dw, &dh, &dc, 3));
  }
  if (src.readError) return failed(std::string("read error: ") + std::strerror(errno));
  // A failure after reading up to the end of the file is almost always a cut-off file:
  // stb_image's reasons for it ("outofdata", "bad zlib header") do not say so.
  const bool atEnd = src.readPastEnd || std::feof(file);
  if (!pixels || src.readPastEnd) {
    const char* why = pixels ? nullptr : stbi_failure_reason();
    std::string m = atEnd ? std::string("truncated ") + name + " file: the data ends before the image is complete"
                          : std::string("corrupt ") + name + " data";
    if (why) m.append(" (stb_image: ").append(why).append(")");
    return problem(std::move(m));
  }
  if (Status s = checkImageSize(dw, dh); !s.isOk()) return s;
  if (haveInfo && (dw != w || dh != h)) return problem(std::string("corrupt ") + name + " header (its size changed while decoding)");

  out->width = dw;
  out->height = dh;
  const std::size_t count = static_cast<std::size_t>(dw) * static_cast<std::size_t>(dh) * 3;
  out->rgb.resize(count);
  if (sixteenBit) {
    const std::vector<float> table = srgbTable(65536);
    const auto* p = static_cast<const std::uint16_t*>(pixels.get());
    for (std::size_t i = 0; i < count; ++i) out->rgb[i] = table[p[i]];
  } else {
    const std::vector<float> table = srgbTable(256);
    const auto* p = static_cast<const unsigned char*>(pixels.get());
    for (std::size_t i = 0; i < count; ++i) out->rgb[i] = table[p[i]];
  }
  return Status::ok();
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::string hexBytes(const unsigned char* bytes, std::size_t n) {
  static const char kHex[] = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    if (i) s += ' ';
    s += kHex[bytes[i] >> 4];
    s += kHex[bytes[i] & 15];
  }
  return s;
}

// loadImage without the file name in its messages and without the exception wall.
Status loadImageUnguarded(const std::string& path, RgbImage* out) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) return Status::error(StatusCode::kNotFound, "no such file");
  if (st.type() == std::filesystem::file_type::directory) return problem("is a directory, not an image file");
  // A FIFO or device would block or never end: refused before it is opened.
  if (!ec && st.type() != std::filesystem::file_type::regular) return problem("not a regular file");

  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) return failed(std::string("cannot open: ") + std::strerror(errno));
  unsigned char head[32] = {};
  const std::size_t got = std::fread(head, 1, sizeof head, file.get());
  if (std::ferror(file.get())) return failed(std::string("cannot read: ") + std::strerror(errno));
  if (got == 0) return problem("file is empty");

  const ImageFormat format = detectImageFormat(head, got);
  Status s;
  switch (format) {
    case ImageFormat::kOpenExr:
      file.reset();  // OpenEXR opens the file itself
      s = loadExr(path, out);
      break;
    case ImageFormat::kRadianceHdr:
      if (std::fseek(file.get(), 0, SEEK_SET) != 0) return failed(std::string("cannot seek: ") + std::strerror(errno));
      s = readRadianceHdr(file.get(), out);
      break;
    case ImageFormat::kPng:
    case ImageFormat::kJpeg:
      s = loadWithStb(file.get(), format, head, got, out);
      break;
    case ImageFormat::kUnknown:
      return problem("unknown image format (expected OpenEXR, Radiance HDR, PNG or JPEG; the file starts with " +
                     hexBytes(head, std::min<std::size_t>(got, 8)) + ")");
  }
  if (!s.isOk()) return s;
  // Catches non-finite pixels (an EXR half can hold inf and NaN) with their position.
  return checkImage(*out, "image");
}

}  // namespace

const char* imageFormatName(ImageFormat format) {
  switch (format) {
    case ImageFormat::kOpenExr: return "OpenEXR";
    case ImageFormat::kRadianceHdr: return "Radiance HDR";
    case ImageFormat::kPng: return "PNG";
    case ImageFormat::kJpeg: return "JPEG";
    case ImageFormat::kUnknown: break;
  }
  return "unknown";
}

ImageFormat detectImageFormat(const unsigned char* bytes, std::size_t size) {
  auto startsWith = [&](std::initializer_list<unsigned char> sig) {
    return size >= sig.size() && std::equal(sig.begin(), sig.end(), bytes);
  };
  if (startsWith({0x76, 0x2f, 0x31, 0x01})) return ImageFormat::kOpenExr;
  if (startsWith({0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) return ImageFormat::kPng;
  if (startsWith({0xff, 0xd8, 0xff})) return ImageFormat::kJpeg;
  // "#?RADIANCE" or "#?RGBE"; stb_image reports any other program name as unsupported.
  if (startsWith({'#', '?'})) return ImageFormat::kRadianceHdr;
  return ImageFormat::kUnknown;
}

Status checkImageSize(std::int64_t width, std::int64_t height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1) return problem("image has zero size (" + size + ")");
  if (width > kMaxImageSide || height > kMaxImageSide) {
    return problem("image is too large (" + size + "); each side must be at most " + std::to_string(kMaxImageSide));
  }
  if (width * height > kMaxImagePixels) {
    return problem("image is too large (" + size + "); at most " + std::to_string(kMaxImagePixels) + " pixels");
  }
  return Status::ok();
}

Status loadImage(const std::string& path, RgbImage* out) {
  *out = RgbImage{};
  Status s;
  try {
    s = loadImageUnguarded(path, out);
  } catch (const std::bad_alloc&) {
    s = Status::error(StatusCode::kResourceExhausted, "out of memory while loading the image");
  } catch (const std::exception& e) {
    s = problem(std::string("cannot load: ") + e.what());
  }
  if (s.isOk()) return s;
  *out = RgbImage{};
  return Status::error(s.code(), "'" + path + "': " + s.message());
}

}  // namespace prt
