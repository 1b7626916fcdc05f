// The GL context the client draws with: a WebGL2 context on a page's canvas in the browser
// (webgl_context.cpp), an OpenGL ES 3 context on an off-screen EGL surface natively
// (web/native/egl_context.cpp: the GPU benchmark runs the same renderer without a browser).
// One build links exactly one of the two.
#pragma once

#include <memory>
#include <string>

namespace prt::web {

struct GlContextOptions {
  std::string canvas;  // browser: CSS selector of the canvas ("#view"); unused natively
  int width = 0;       // native: size of the off-screen default framebuffer, pixels
  int height = 0;      //         (the browser's canvas has its own size)
};

class GlContext {
 public:
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Creates the context (WebGL2 / OpenGL ES 3.0 or later, depth buffer, antialiased where the
  // platform offers it) and makes it current. "" or why it failed, naming what was missing.
  std::string create(const GlContextOptions& options);
  // Makes the context current (a no-op before a successful create()).
  void makeCurrent() const;
  // Enables extension `name` where WebGL needs that step; whether the context offers it.
  bool enableExtension(const char* name) const;

 private:
  struct State;  // the platform's handles
  std::unique_ptr<State> state_;
};

}  // namespace prt::web
