// GlContext natively: an OpenGL ES 3 context on an off-screen EGL pbuffer, for running the
// client's renderer without a browser (the GPU frame-time benchmark, prt-gpu-frames).
//
// Displays are tried in this order, so one binary runs on a headless GPU server (NVIDIA's
// EGL offers its GPUs as devices, no X or Wayland needed) and on a CPU-only machine (Mesa's
// software device, or its surfaceless platform):
//   1. each device of EGL_EXT_device_enumeration, through EGL_EXT_platform_device;
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless);
//   3. the default display.
// The first that initialises and gives a 3.x context with a pbuffer of the asked size wins.
#include "gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include <cstring>
#include <string>
#include <vector>

namespace prt::web {

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

std::vector<EGLDisplay> candidateDisplays() {
  std::vector<EGLDisplay> out;
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (getPlatformDisplay && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices && queryDevices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back(d);
      }
    }
  }
  if (getPlatformDisplay && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back(d);
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) out.push_back(d);
  return out;
}

struct EglHandles {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
};

// A 3.x context with a width x height pbuffer on `display` (initialised here), made current;
// "" or why not. Multisampled (4x, as the browser's antialiased canvas) where offered.
std::string tryDisplay(EGLDisplay display, int width, int height, EglHandles* out) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return "eglInitialize failed";
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    eglTerminate(display);
    return "no OpenGL ES API";
  }
  EGLConfig config = nullptr;
  EGLint found = 0;
  for (EGLint samples : {4, 0}) {
    const EGLint attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT,
                                 EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                                 EGL_DEPTH_SIZE, 24, EGL_SAMPLE_BUFFERS, samples > 0 ? 1 : 0, EGL_SAMPLES, samples,
                                 EGL_NONE};
    if (eglChooseConfig(display, attributes, &config, 1, &found) && found == 1) break;
  }
  if (found != 1) {
    eglTerminate(display);
    return "no RGBA8 + depth pbuffer config for OpenGL ES 3";
  }
  const EGLint surfaceAttributes[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
  EGLSurface surface = eglCreatePbufferSurface(display, config, surfaceAttributes);
  if (surface == EGL_NO_SURFACE) {
    eglTerminate(display);
    return "eglCreatePbufferSurface failed";
  }
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, surface, surface, context)) {
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglDestroySurface(display, surface);
    eglTerminate(display);
    return "no OpenGL ES 3 context";
  }
  *out = {display, context, surface};
  return "";
}

}  // namespace

struct GlContext::State : EglHandles {};

GlContext::GlContext() : state_(std::make_unique<State>()) {}

GlContext::~GlContext() {
  if (state_->display == EGL_NO_DISPLAY) return;
  eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(state_->display, state_->context);
  eglDestroySurface(state_->display, state_->surface);
  eglTerminate(state_->display);
}

std::string GlContext::create(const GlContextOptions& options) {
  if (options.width <= 0 || options.height <= 0) return "the off-screen surface needs a width and height above 0";
  std::string why;
  for (EGLDisplay display : candidateDisplays()) {
    EglHandles h;
    const std::string e = tryDisplay(display, options.width, options.height, &h);
    if (e.empty()) {
      static_cast<EglHandles&>(*state_) = h;
      return "";
    }
    why += (why.empty() ? "" : "; ") + e;
  }
  return "no EGL display gave an OpenGL ES 3 context (" + (why.empty() ? std::string("no display found") : why) + ")";
}

void GlContext::makeCurrent() const {
  if (state_->display != EGL_NO_DISPLAY) eglMakeCurrent(state_->display, state_->surface, state_->surface, state_->context);
}

bool GlContext::enableExtension(const char* name) const {
  // OpenGL ES has no enabling step: an extension listed is on. EXT_color_buffer_float is core
  // in ES 3.2 and listed by every 3.0+ driver that renders to float targets.
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

}  // namespace prt::web
