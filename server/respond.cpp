#include "respond.h"

#include <vector>

#include "http_date.h"
#include "native/json_text.h"
#include "negotiation.h"

namespace prt::serve {

void addCommonHeaders(http::response<http::empty_body>& head) {
  head.set(http::field::server, "prt-serve");
  head.set(http::field::date, httpDateNow());
  // The server knows every type it sends; browsers must not guess another (an uploaded
  // .prt sniffed as HTML would be a script injection).
  head.set("X-Content-Type-Options", "nosniff");
}

Reply respond(const RequestHead& request, const Resource& resource) {
  Reply reply;
  auto& head = reply.head;
  head.version(request.version());
  addCommonHeaders(head);

  std::vector<EncodingOffer> offers;
  offers.reserve(resource.variants.size());
  for (const Variant& v : resource.variants) offers.push_back({v.encoding, v.body.size});
  const Variant& chosen = resource.variants[chooseEncoding(request[http::field::accept_encoding], offers)];

  head.set(http::field::content_type, resource.contentType);
  head.set(http::field::cache_control, resource.cacheControl);
  head.set(http::field::etag, chosen.etag);
  head.set(http::field::accept_ranges, "bytes");
  if (resource.variants.size() > 1) head.set(http::field::vary, "Accept-Encoding");
  if (chosen.encoding != Encoding::kIdentity) head.set(http::field::content_encoding, encodingToken(chosen.encoding));

  const bool isHead = request.method() == http::verb::head;
  const std::uint64_t size = chosen.body.size;

  if (const auto inm = request.find(http::field::if_none_match); inm != request.end()) {
    if (ifNoneMatchHits(inm->value(), chosen.etag)) {
      head.result(http::status::not_modified);
      // A 304 describes the representation it validates but has no body; Content-Length
      // would claim one.
      head.erase(http::field::content_type);
      head.erase(http::field::accept_ranges);
      head.erase(http::field::content_encoding);
      return reply;
    }
  }

  ByteRange range{0, size};
  RangeOutcome outcome = RangeOutcome::kWhole;
  if (const auto r = request.find(http::field::range); r != request.end()) {
    bool rangeApplies = true;
    // If-Range: the range only holds for the version the client has (strong comparison).
    if (const auto ifRange = request.find(http::field::if_range); ifRange != request.end()) {
      rangeApplies = ifRange->value() == chosen.etag;
    }
    if (rangeApplies) outcome = parseRange(r->value(), size, &range);
  }
  if (outcome == RangeOutcome::kUnsatisfiable) {
    head.result(http::status::range_not_satisfiable);
    head.set(http::field::content_range, "bytes */" + std::to_string(size));
    head.erase(http::field::content_encoding);
    head.set(http::field::content_type, "text/plain; charset=utf-8");
    head.content_length(0);
    return reply;
  }
  if (outcome == RangeOutcome::kPartial) {
    head.result(http::status::partial_content);
    head.set(http::field::content_range, "bytes " + std::to_string(range.first) + "-" +
                                             std::to_string(range.first + range.length - 1) + "/" + std::to_string(size));
  } else {
    head.result(http::status::ok);
    range = {0, size};
  }
  head.content_length(range.length);
  reply.body = chosen.body;
  reply.offset = range.first;
  reply.length = isHead ? 0 : range.length;
  return reply;
}

Reply errorReply(unsigned version, http::status status, std::string_view message, bool json, bool close) {
  Reply reply;
  auto& head = reply.head;
  head.version(version);
  head.result(status);
  addCommonHeaders(head);
  head.set(http::field::cache_control, "no-store");
  std::string text;
  if (json) {
    head.set(http::field::content_type, "application/json");
    text = "{\"error\":" + jsonString(message) + "}\n";
  } else {
    head.set(http::field::content_type, "text/plain; charset=utf-8");
    text = std::to_string(static_cast<unsigned>(status)) + " " + std::string(http::obsolete_reason(status)) + ": " +
           std::string(message) + "\n";
  }
  head.content_length(text.size());
  reply.body = memoryBody(std::move(text));
  reply.length = reply.body.size;
  reply.close = close;
  return reply;
}

}  // namespace prt::serve
