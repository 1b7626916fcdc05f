#include "page_policy.h"

namespace prt::serve {

bool isDocumentType(std::string_view contentType) {
  return contentType.starts_with("text/html") || contentType.starts_with("image/svg+xml");
}

void addDocumentPolicy(std::string_view contentType, boost::beast::http::response<boost::beast::http::empty_body>& head) {
  if (!isDocumentType(contentType)) return;
  head.set("Content-Security-Policy", kContentSecurityPolicy);
  // For browsers older than CSP's frame-ancestors.
  head.set("X-Frame-Options", "DENY");
  // The page fetches only its own origin; nothing about it needs to travel elsewhere.
  head.set("Referrer-Policy", "no-referrer");
}

}  // namespace prt::serve
