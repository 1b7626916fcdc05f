#include "encoded_variants.h"

#include "temp_file.h"

namespace prt::serve {

std::string etagFor(const std::string& baseTag, Encoding encoding) {
  std::string tag = "\"" + baseTag;
  if (encoding != Encoding::kIdentity) tag += std::string(".") + encodingTag(encoding);
  return tag + "\"";
}

std::vector<Variant> makeEncodedVariants(std::span<const std::uint8_t> bytes, const std::string& baseTag,
                                         VariantStorage storage, std::string* problems) {
  std::vector<Variant> variants;
  for (const Encoding e : {Encoding::kBrotli, Encoding::kZstd, Encoding::kGzip}) {
    std::string packed;
    if (Status s = compressBytes(e, bytes, &packed); !s.isOk()) {
      if (problems) *problems += s.message() + "; ";
      continue;
    }
    if (packed.size() * 20 > bytes.size() * 19) continue;
    Variant v;
    v.encoding = e;
    v.etag = etagFor(baseTag, e);
    if (storage == VariantStorage::kMemory) {
      v.body = memoryBody(std::move(packed));
    } else {
      v.body.size = packed.size();
      if (Status s = writeTempFile(packed, &v.body.file); !s.isOk()) {
        if (problems) *problems += s.message() + "; ";
        continue;
      }
    }
    variants.push_back(std::move(v));
  }
  return variants;
}

}  // namespace prt::serve
