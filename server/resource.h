// What the server knows about one URL's content before it looks at a request: its
// representations (identity plus any precompressed variants), their validators and how
// caches may keep them. respond.h turns a Resource and a request into a reply.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "compression.h"
#include "open_file.h"

namespace prt::serve {

// Where a body's bytes come from: a shared file (sent with sendfile) or shared memory
// (small generated documents). Exactly one of the two is set.
struct BodySource {
  FileRef file;
  std::shared_ptr<const std::string> memory;
  std::uint64_t size = 0;
};

struct Variant {
  Encoding encoding = Encoding::kIdentity;
  BodySource body;
  std::string etag;  // strong, quoted: "\"0123abcd\""
};

struct Resource {
  std::string contentType;
  std::string cacheControl;
  std::vector<Variant> variants;  // identity first, then the encodings that paid off
};

// A memory body holding `text`.
BodySource memoryBody(std::string text);

}  // namespace prt::serve
