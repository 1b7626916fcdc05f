// Compiling and linking GLSL ES 3.00 programs (shared by every GL class of the client).
#pragma once

#include <GLES3/gl3.h>

#include <cstddef>
#include <string>

#include "prt/status.h"

namespace prt::web {

// Compiles and links `vs` + `fs` into *out. `feedback`: name of a varying to capture with
// transform feedback (separate attribs), or nullptr. Errors carry the driver's log.
Status linkProgram(const char* vs, const char* fs, GLuint* out, const char* feedback = nullptr);
// The same with `feedbackCount` varyings captured interleaved into one buffer, in that order.
Status linkProgram(const char* vs, const char* fs, GLuint* out, const char* const* feedback, int feedbackCount);

// `source` (GLSL ES 3.00, its first line the #version directive) with `defines` (whole
// lines, e.g. "#define BANDS 5\n") inserted after the version line: one shader file, linked
// per compile-time constant.
std::string withDefines(const char* source, const std::string& defines);

// Binds the program's uniform block `name` (if it has one) to binding point `binding`.
void bindUniformBlock(GLuint program, const char* name, GLuint binding);

// Points vertex attributes 5 (vec4: f0 rgb, Phong exponent) and 6 (float: f90) of the bound
// vertex array into the ARRAY_BUFFER bound now, `floatsPerVertex` floats a vertex: the
// specular material layout of both glossy paths (glossy_texture.h, kGlossySpecularFloats).
void specularAttributePointers(GLsizei floatsPerVertex);

// Texture parameters for texelFetch-only textures (no filtering, no wrapping).
void setNearestClamp(GLenum target);

// The GL error the calls since the last check left (glGetError) as a Status: ok when none;
// out of memory says what did not fit ("the GPU is out of memory for <memoryFor>"), any
// other error its code and what was being done ("WebGL error N while <during>").
Status glErrorStatus(const char* memoryFor, const char* during);

// A buffer object of `bytes` bytes (from `data`, or uninitialised when null), STATIC_DRAW,
// left bound to `target`.
GLuint makeBuffer(GLenum target, const void* data, std::size_t bytes);

// The transfer textures' row layout (kTransferTextureWidth wide) for the bound program's texel
// fetches: its uTextureMask and uTextureShift uniforms at these locations.
void setTextureLayout(GLint maskLocation, GLint shiftLocation);

// Copies `rows` rows of kTransferTextureWidth float texels (`format` GL_RGBA or GL_RGB) from
// `buffer` into `texture`, GPU to GPU (a pixel-unpack copy, no read-back); leaves texture
// unit 0 active.
void copyBufferToTexture(GLuint buffer, GLuint texture, int rows, GLenum format = GL_RGBA);

}  // namespace prt::web
