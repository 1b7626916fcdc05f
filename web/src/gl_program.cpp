#include "gl_program.h"

#include "transfer_texture.h"

#include <string>

namespace prt::web {
namespace {

Status compile(GLenum type, const char* source, GLuint* out) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    return Status::error(StatusCode::kInvalidArgument, std::string("shader compile failed: ") + log);
  }
  *out = s;
  return Status::ok();
}

}  // namespace

Status linkProgram(const char* vs, const char* fs, GLuint* out, const char* feedback) {
  return feedback ? linkProgram(vs, fs, out, &feedback, 1) : linkProgram(vs, fs, out, nullptr, 0);
}

Status linkProgram(const char* vs, const char* fs, GLuint* out, const char* const* feedback, int feedbackCount) {
  GLuint v = 0, f = 0;
  if (Status s = compile(GL_VERTEX_SHADER, vs, &v); !s.isOk()) return s;
  if (Status s = compile(GL_FRAGMENT_SHADER, fs, &f); !s.isOk()) {
    glDeleteShader(v);
    return s;
  }
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  // One varying: separate attribs (its own buffer); several: interleaved into one buffer.
  if (feedbackCount > 0) {
    glTransformFeedbackVaryings(p, feedbackCount, feedback, feedbackCount == 1 ? GL_SEPARATE_ATTRIBS : GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    glDeleteProgram(p);
    return Status::error(StatusCode::kInvalidArgument, std::string("program link failed: ") + log);
  }
  *out = p;
  return Status::ok();
}

std::string withDefines(const char* source, const std::string& defines) {
  std::string out(source);
  const std::size_t afterVersion = out.find('\n');
  out.insert(afterVersion == std::string::npos ? out.size() : afterVersion + 1, defines);
  return out;
}

void bindUniformBlock(GLuint program, const char* name, GLuint binding) {
  const GLuint index = glGetUniformBlockIndex(program, name);
  if (index != GL_INVALID_INDEX) glUniformBlockBinding(program, index, binding);
}

void specularAttributePointers(GLsizei floatsPerVertex) {
  const GLsizei stride = floatsPerVertex * static_cast<GLsizei>(sizeof(float));
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 4, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(6, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(4 * sizeof(float)));
}

void setNearestClamp(GLenum target) {
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

Status glErrorStatus(const char* memoryFor, const char* during) {
  const GLenum err = glGetError();
  if (err == GL_NO_ERROR) return Status::ok();
  return Status::error(StatusCode::kInvalidArgument, err == GL_OUT_OF_MEMORY
                                                         ? std::string("the GPU is out of memory for ") + memoryFor
                                                         : "WebGL error " + std::to_string(err) + " while " + during);
}

GLuint makeBuffer(GLenum target, const void* data, std::size_t bytes) {
  GLuint b = 0;
  glGenBuffers(1, &b);
  glBindBuffer(target, b);
  glBufferData(target, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
  return b;
}

void setTextureLayout(GLint maskLocation, GLint shiftLocation) {
  glUniform1i(maskLocation, kTransferTextureWidth - 1);
  glUniform1i(shiftLocation, kTransferTextureShift);
}

void copyBufferToTexture(GLuint buffer, GLuint texture, int rows, GLenum format) {
  glActiveTexture(GL_TEXTURE0);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffer);
  glBindTexture(GL_TEXTURE_2D, texture);
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kTransferTextureWidth, rows, format, GL_FLOAT, nullptr);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}

}  // namespace prt::web
