// Which part of the server answers a request: the API documents, the content-addressed
// assets and their parts, the light previews, or the web client's files.
#pragma once

#include <memory>
#include <string_view>

#include "catalogue.h"
#include "light_library.h"
#include "reply.h"
#include "respond.h"
#include "static_files.h"

namespace prt::serve {

class Router {
 public:
  // `web` may be null (no --web): then only the API and the assets are served.
  Router(Catalogue& catalogue, LightLibrary& lights, StaticFiles* web);

  // The answer to a complete request head: a reply, or (for a lights document not made
  // yet) work that delivers one later from the lights worker. Never throws: an unexpected
  // failure inside a handler becomes 500 (and the connection is closed).
  Answer handle(const RequestHead& request) noexcept;

 private:
  Answer route(const RequestHead& request);
  Answer lightsDocument(const RequestHead& request, std::string_view query);

  Catalogue& catalogue_;
  LightLibrary& lights_;
  StaticFiles* web_;
};

}  // namespace prt::serve
