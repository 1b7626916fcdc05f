// Names of the transfer codec's encodings and settings (prt/transfer_codec.h).
#include <algorithm>
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
  static const char* const kUnknown =
      "unknown setting (expected f32, f16, q16, q8, cpca8, cpca16, cpca8b8 or cpca16b8, the CPCA ones optionally with a basis "
      "limit nN and @TARGET, e.g. cpca8@0.02, cpca16b8n8@0.045)";
  auto bad = [&](const std::string& why) {
    return Status::error(StatusCode::kInvalidArgument, "setting '" + std::string(text) + "': " + why);
  };
  if (name == "f32") s.encoding = TransferEncoding::kFloat32;
  else if (name == "f16") s.encoding = TransferEncoding::kFloat16;
  else if (name == "q16") s.encoding = TransferEncoding::kQuant16;
  else if (name == "q8") s.encoding = TransferEncoding::kQuant8;
  else if (name.starts_with("cpca")) {
    // cpca<weight bits>[b8][n<N'>]: the name says both widths, whatever `defaults` held.
    const std::size_t n = name.find('n');
    const std::string_view widths = name.substr(0, n);
    if (widths != "cpca8" && widths != "cpca16" && widths != "cpca8b8" && widths != "cpca16b8") return bad(kUnknown);
    s.encoding = TransferEncoding::kCpca;
    s.cpcaWeightBits = widths.starts_with("cpca8") ? 8 : 16;
    s.cpcaBasisBits = widths.ends_with("b8") ? 8 : 16;
    if (n != std::string_view::npos) {
      const std::string_view digits = name.substr(n + 1);
      int limit = -1;
      if (digits.size() >= 1 && digits.size() <= 2 && std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        limit = std::stoi(std::string(digits));
      if (!(limit >= 0 && limit <= 32)) return bad("the basis limit n<N> takes N from 0 to 32, e.g. cpca16b8n8@0.045");
      s.cpcaMaxVectors = limit;
    }
  } else {
    return bad(kUnknown);
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
  std::string name = "cpca" + std::to_string(settings.cpcaWeightBits);
  if (settings.cpcaBasisBits == 8) name += "b8";
  if (settings.cpcaMaxVectors != 32) {
    name += 'n';
    name += std::to_string(settings.cpcaMaxVectors);
  }
  name += '@';
  name += formatTarget(settings.cpcaTargetError);
  return name;
}

}  // namespace prt
