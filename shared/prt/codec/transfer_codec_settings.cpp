// Names of the transfer codec's encodings and settings (prt/transfer_codec.h).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "prt/transfer_codec.h"

namespace prt {
namespace {

// A target in (0, 1) with up to 6 significant digits, positional ("0.0125") down to 1e-6,
// scientific below ("2.5e-7"). snprintf would do, but shared/ stays free of <cstdio>.
std::string formatTarget(double t) {
  if (!(t > 0.0 && t < 1.0)) return std::to_string(t);
  int e = static_cast<int>(std::floor(std::log10(t)));
  long long digits = std::llround(t / std::pow(10.0, e - 5));
  if (digits >= 1000000) {  // rounding carried into a new digit
    digits /= 10;
    ++e;
  }
  std::string d = std::to_string(digits);
  while (d.size() > 1 && d.back() == '0') d.pop_back();
  if (e >= -6) {
    std::string text = "0.";
    text.append(static_cast<std::size_t>(-e - 1), '0');
    text += d;
    return text;
  }
  std::string text(1, d[0]);
  if (d.size() > 1) {
    text += '.';
    text.append(d, 1, std::string::npos);
  }
  text += 'e';
  text += std::to_string(e);
  return text;
}

}  // namespace

const char* transferEncodingName(TransferEncoding encoding) {
  switch (encoding) {
    case TransferEncoding::kFloat32: return "f32";
    case TransferEncoding::kFloat16: return "f16";
    case TransferEncoding::kQuant16: return "q16";
    case TransferEncoding::kQuant8: return "q8";
    case TransferEncoding::kCpca: return "cpca";
  }
  return "unknown";
}

Status parseTransferSetting(std::string_view text, const TransferCodecSettings& defaults, TransferCodecSettings* out) {
  TransferCodecSettings s = defaults;
  const std::size_t at = text.find('@');
  const std::string_view name = text.substr(0, at);
  auto bad = [&](const std::string& why) {
    return Status::error(StatusCode::kInvalidArgument, "setting '" + std::string(text) + "': " + why);
  };
  if (name == "f32") s.encoding = TransferEncoding::kFloat32;
  else if (name == "f16") s.encoding = TransferEncoding::kFloat16;
  else if (name == "q16") s.encoding = TransferEncoding::kQuant16;
  else if (name == "q8") s.encoding = TransferEncoding::kQuant8;
  else if (name == "cpca8" || name == "cpca16" || name == "cpca8b8" || name == "cpca16b8") {
    // cpca<weight bits>[b8]: the name says both widths, whatever `defaults` held.
    s.encoding = TransferEncoding::kCpca;
    s.cpcaWeightBits = name.starts_with("cpca8") ? 8 : 16;
    s.cpcaBasisBits = name.ends_with("b8") ? 8 : 16;
  } else {
    return bad("unknown setting (expected f32, f16, q16, q8, cpca8, cpca16, cpca8b8 or cpca16b8, the CPCA ones optionally "
               "@TARGET, e.g. cpca8@0.02)");
  }
  if (at != std::string_view::npos) {
    if (s.encoding != TransferEncoding::kCpca) return bad("only CPCA settings take a target (@)");
    const std::string number(text.substr(at + 1));
    char* end = nullptr;
    errno = 0;
    const double target = number.empty() ? NAN : std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || errno != 0 || !(target > 0.0 && target < 1.0)) {
      return bad("the target must be a relative error in (0, 1), e.g. 0.02");
    }
    s.cpcaTargetError = target;
  }
  *out = s;
  return Status::ok();
}

std::string transferSettingName(const TransferCodecSettings& settings) {
  if (settings.encoding != TransferEncoding::kCpca) return transferEncodingName(settings.encoding);
  return "cpca" + std::to_string(settings.cpcaWeightBits) + (settings.cpcaBasisBits == 8 ? "b8" : "") + "@" +
         formatTarget(settings.cpcaTargetError);
}

}  // namespace prt
