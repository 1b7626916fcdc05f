#include "router.h"

#include <charconv>
#include <exception>

#include "prt/sh_basis.h"
#include "public_error.h"
#include "request_target.h"

namespace prt::serve {
namespace {

constexpr std::string_view kAssetPrefix = "/assets/";
constexpr std::string_view kPreviewPrefix = "/api/lights/preview/";
constexpr std::string_view kBackgroundPrefix = "/api/lights/background/";

}  // namespace

Router::Router(Catalogue& catalogue, LightLibrary& lights, StaticFiles* web)
    : catalogue_(catalogue), lights_(lights), web_(web) {}

Answer Router::handle(const RequestHead& request) noexcept {
  try {
    return route(request);
  } catch (const std::exception& e) {
    // Exception text can carry paths and library internals: the log gets it, the client not.
    logDetail("internal error in a handler", e.what());
    return errorReply(request.version(), http::status::internal_server_error, "internal error", false, true);
  } catch (...) {
    return errorReply(request.version(), http::status::internal_server_error, "internal error", false, true);
  }
}

Answer Router::route(const RequestHead& request) {
  const unsigned version = request.version();
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    Reply r = errorReply(version, http::status::method_not_allowed, "only GET and HEAD are served", false);
    r.head.set(http::field::allow, "GET, HEAD");
    return r;
  }
  const std::string_view rawTarget = request.target();
  RequestTarget target;
  if (Status s = parseTarget(rawTarget, &target); !s.isOk()) {
    return errorReply(version, http::status::bad_request, s.message(), false);
  }
  const std::string_view path = target.path;

  if (path == "/api/scenes") return respond(request, *catalogue_.current()->json);
  if (path == "/api/lights") return lightsDocument(request, target.query);
  if (path.starts_with(kPreviewPrefix)) {
    if (auto r = lights_.preview(path)) return respond(request, *r);
    return errorReply(version, http::status::not_found, "no such preview", true);
  }
  if (path.starts_with(kBackgroundPrefix)) {
    if (auto r = lights_.preview(path)) return respond(request, *r);
    return errorReply(version, http::status::not_found, "no such background texture", true);
  }
  if (path.starts_with(kThumbnailPrefix)) {
    if (auto r = catalogue_.findThumbnail(path)) return respond(request, *r);
    return errorReply(version, http::status::not_found, "no such thumbnail; see /api/scenes", false);
  }
  if (path.starts_with("/api/") || path == "/api") {
    return errorReply(version, http::status::not_found, "no such API endpoint (try /api/scenes or /api/lights)", true);
  }
  if (path.starts_with(kAssetPrefix)) {
    if (auto e = catalogue_.findAsset(path)) return respond(request, *e->resource);
    // Content-addressed: an old hash is gone for good; the catalogue has the current URL.
    return errorReply(version, http::status::not_found, "no such asset version; see /api/scenes", false);
  }
  if (path.starts_with(kPartPrefix)) {
    // Only the exact URLs the catalogue lists exist; anything else under /parts/ is 404.
    if (auto r = catalogue_.findPart(path)) return respond(request, *r);
    return errorReply(version, http::status::not_found, "no such part; see /api/scenes", false);
  }
  if (web_) return web_->serve(request, path, rawTarget.substr(0, rawTarget.find('?')));
  return errorReply(version, http::status::not_found, "not found (no --web directory)", false);
}

Answer Router::lightsDocument(const RequestHead& request, std::string_view query) {
  int order = 5;
  std::string text;
  if (queryValue(query, "order", &text)) {
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), order);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || order < kMinShOrder ||
        order > kMaxShOrder) {
      return errorReply(request.version(), http::status::bad_request,
                        "order must be a whole number from " + std::to_string(kMinShOrder) + " to " +
                            std::to_string(kMaxShOrder),
                        true);
    }
  }
  if (const auto doc = lights_.cachedDocument(order)) return respond(request, *doc);
  // Projecting the maps takes a large fraction of a second each: done on the lights
  // worker, and the session sends the reply when it is ready.
  return Answer([this, head = request, order](ReplySink sink) {
    lights_.documentLater(order, [head, sink](std::shared_ptr<const Resource> doc) {
      Reply reply;
      try {
        reply = doc ? respond(head, *doc)
                    : errorReply(head.version(), http::status::internal_server_error, "internal error", true, true);
      } catch (const std::exception& e) {
        logDetail("internal error in a handler", e.what());
        reply = errorReply(head.version(), http::status::internal_server_error, "internal error", true, true);
      }
      sink(std::move(reply));
    });
  });
}

}  // namespace prt::serve
