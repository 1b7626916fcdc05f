// Reading a GL buffer back to the CPU: WebGL2 has glGetBufferSubData, OpenGL ES 3 maps the
// buffer instead. Tests, tools and benchmark fences only: both wait for the GPU.
#pragma once

#include <GLES3/gl3.h>

#include <cstddef>
#include <cstring>

#ifdef __EMSCRIPTEN__
#include <webgl/webgl2.h>  // glGetBufferSubData (WebGL2, not GLES3)
#endif

namespace prt::web {

// Copies `bytes` bytes from offset 0 of the buffer bound to `target` into `out` (caller-owned,
// at least `bytes` long; the buffer must hold that many). False when the buffer could not be
// read (natively: the map failed; `out` is then zeroed and the GL error is left set).
inline bool readBoundBuffer(GLenum target, std::size_t bytes, void* out) {
#ifdef __EMSCRIPTEN__
  glGetBufferSubData(target, 0, static_cast<GLsizeiptr>(bytes), out);
  return true;
#else
  const void* mapped = glMapBufferRange(target, 0, static_cast<GLsizeiptr>(bytes), GL_MAP_READ_BIT);
  if (!mapped) {
    std::memset(out, 0, bytes);
    return false;
  }
  std::memcpy(out, mapped, bytes);
  return glUnmapBuffer(target) == GL_TRUE;
#endif
}

}  // namespace prt::web
