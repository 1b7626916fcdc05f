// What a browser may do with the documents under --web (HTML, and SVG, which can hold
// scripts too): the Content-Security-Policy written for the web client's page, no framing
// by other sites (clickjacking), and no Referer leaving the page.
#pragma once

#include <boost/beast/http/empty_body.hpp>
#include <boost/beast/http/message.hpp>

#include <string_view>

namespace prt::serve {

// The policy, from what web/shell loads: module scripts from the server itself and the
// wasm they compile ('wasm-unsafe-eval', which allows WebAssembly compilation and nothing
// else: no 'unsafe-eval'); lil-gui's injected <style> ('unsafe-inline' styles only); its
// icon font and the page's icon as data: URLs; fetches to the same origin; no plugins, no
// <base>, no form posts, no framing.
inline constexpr std::string_view kContentSecurityPolicy =
    "default-src 'self'; script-src 'self' 'wasm-unsafe-eval'; style-src 'self' 'unsafe-inline'; "
    "img-src 'self' data:; font-src 'self' data:; connect-src 'self'; object-src 'none'; base-uri 'none'; "
    "form-action 'none'; frame-ancestors 'none'";

// True for the media types a browser renders as a document that can run scripts.
bool isDocumentType(std::string_view contentType);

// Adds Content-Security-Policy, X-Frame-Options and Referrer-Policy to `head` when
// `contentType` is a document type; leaves other responses alone.
void addDocumentPolicy(std::string_view contentType, boost::beast::http::response<boost::beast::http::empty_body>& head);

}  // namespace prt::serve
