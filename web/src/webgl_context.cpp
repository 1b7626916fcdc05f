// GlContext in the browser: a WebGL2 context through Emscripten's html5 API.
#include "gl_context.h"

#include <emscripten/html5.h>

namespace prt::web {

struct GlContext::State {
  EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle = 0;
};

GlContext::GlContext() : state_(std::make_unique<State>()) {}
GlContext::~GlContext() = default;

std::string GlContext::create(const GlContextOptions& options) {
  EmscriptenWebGLContextAttributes attrs;
  emscripten_webgl_init_context_attributes(&attrs);
  attrs.majorVersion = 2;
  attrs.minorVersion = 0;
  attrs.antialias = true;
  attrs.depth = true;
  attrs.preserveDrawingBuffer = true;  // screenshots and tests read the canvas after a frame
  state_->handle = emscripten_webgl_create_context(options.canvas.c_str(), &attrs);
  if (state_->handle <= 0) {
    state_->handle = 0;
    return "WebGL2 is not available in this browser (context creation failed)";
  }
  emscripten_webgl_make_context_current(state_->handle);
  return "";
}

void GlContext::makeCurrent() const {
  if (state_->handle > 0) emscripten_webgl_make_context_current(state_->handle);
}

bool GlContext::enableExtension(const char* name) const {
  return state_->handle > 0 && emscripten_webgl_enable_extension(state_->handle, name);
}

}  // namespace prt::web
