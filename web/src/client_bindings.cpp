// Embind bindings of the browser client (ClientApp): what web/shell/app.js calls.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include "client_app.h"

using emscripten::val;
using prt::web::ClientApp;

namespace {

// A Uint8Array over the reserved asset memory, for fetch() to stream into; null when the
// allocation failed (out of memory). Re-take it after any other call into the module:
// memory growth detaches old views.
val reserveAsset(ClientApp& app, double bytes) {
  if (!(bytes >= 0) || bytes > 2147483647.0) return val::null();
  std::uint8_t* p = app.reserveAsset(static_cast<std::size_t>(bytes));
  if (!p) return val::null();
  return val(emscripten::typed_memory_view(static_cast<std::size_t>(bytes), p));
}

std::string setEnvironment(ClientApp& app, const val& flat, int order) {
  return app.setEnvironment(emscripten::convertJSArrayToNumberVector<float>(flat), order);
}

val lightSH(const ClientApp& app) { return val::array(app.lightSH()); }

val project(const ClientApp& app, float x, float y, float z) { return val::array(app.project(x, y, z)); }

}  // namespace

EMSCRIPTEN_BINDINGS(prt_client) {
  emscripten::class_<ClientApp>("ClientApp")
      .constructor<std::string>()
      .function("error", &ClientApp::error)
      .function("reserveAsset", &reserveAsset)
      .function("loadAsset", &ClientApp::loadAsset)
      .function("setEnvironment", &setEnvironment)
      .function("setWhiteFurnace", &ClientApp::setWhiteFurnace)
      .function("setEnvRotation", &ClientApp::setEnvRotation)
      .function("setLightColor", &ClientApp::setLightColor)
      .function("setMode", &ClientApp::setMode)
      .function("setDisplayOrder", &ClientApp::setDisplayOrder)
      .function("setExposure", &ClientApp::setExposure)
      .function("setBackground", &ClientApp::setBackground)
      .function("orbit", &ClientApp::orbit)
      .function("pan", &ClientApp::pan)
      .function("zoom", &ClientApp::zoom)
      .function("frameScene", &ClientApp::frameScene)
      .function("render", &ClientApp::render)
      .function("lightSH", &lightSH)
      .function("project", &project)
      .function("vertexCount", &ClientApp::vertexCount)
      .function("triangleCount", &ClientApp::triangleCount)
      .function("bakedOrder", &ClientApp::bakedOrder)
      .function("displayOrder", &ClientApp::displayOrder)
      .function("mode", &ClientApp::mode)
      .function("hasPass", &ClientApp::hasPass);
}
