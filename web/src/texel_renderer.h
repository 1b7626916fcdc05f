// WebGL2 drawing of transfer textures (per-texel PRT, PRTT; docs/web-client.md "Transfer
// textures"): per texel pass one RGBA16F TEXTURE_2D_ARRAY per atlas (texel_texture.h), the
// atlas UVs as a vertex attribute, a depth prepass and the per-fragment shading
// (shaders/texel_prt.vert, texel_prt.frag) with the same Lighting block as the vertex path,
// and the atlas read-back in UV space for tests. Owned by GlRenderer, which holds the
// geometry buffers this class draws from.
#pragma once

#include <GLES3/gl3.h>

#include <array>
#include <span>
#include <vector>

#include "glm_types.h"
#include "prt/asset.h"
#include "prt/status.h"

namespace prt::web {

class TexelRenderer {
 public:
  // Compiles the two programs; the WebGL2 context must be current.
  Status init();
  // Uses the scene's position, albedo and index buffers (owned by the caller, alive until
  // releaseGeometry) with `atlasUv` (2 floats per vertex) and `atlases` (contiguous triangle
  // runs); drops every texel pass. The caller checks for GL errors.
  void setGeometry(GLuint positions, GLuint albedo, GLuint indices, std::span<const float> atlasUv,
                   std::span<const TextureAtlas> atlases);
  // Forgets the geometry and deletes every texel pass's textures.
  void releaseGeometry();
  // Whether setGeometry gave atlases (the scene has transfer textures).
  bool hasAtlases() const { return !atlases_.empty(); }
  const std::vector<TextureAtlas>& atlases() const { return atlases_; }

  // Packs and uploads texel pass `pass` holding `order` bands, replacing the previous pass of
  // its kind. Needs geometry; a pass that does not fit (texture size, layers, GPU memory)
  // changes nothing and says why.
  Status uploadPass(const TransferPass& pass, int order);
  // Bands the texel pass of `kind` (0 unshadowed, 1 shadowed, 2 interreflected) holds; 0 when absent.
  int passOrder(int kind) const;

  // Draws the scene from texel pass `kind` with the bound Lighting block: a depth-only prepass
  // over every triangle, then each atlas's triangles shaded where the depth is EQUAL to the
  // prepass's, so each pixel runs the per-fragment PRT once. Leaves depth test LESS with
  // depth and colour writes on. False (nothing drawn) when the pass is absent.
  bool draw(int kind, const glm::mat4& viewProjection, int displayOrder, float exposure);

  // Renders atlas `atlas` of pass `kind` in UV space (one fragment per texel whose centre a
  // triangle covers) with the same fragment shader writing linear radiance into an RGBA32F
  // target, sampling at the exact texel centres (texel_prt.frag), and reads it back: width x height x 4 floats, row y = texel row y, alpha 1 where
  // a triangle covered the texel centre, 0 elsewhere. Errors: absent pass, atlas out of range,
  // no float render targets (EXT_color_buffer_float).
  Status readAtlas(int kind, int atlas, int displayOrder, std::vector<float>* out);

 private:
  struct Program {
    GLuint id = 0;
    GLint viewProjection = -1, atlasSpace = -1, transfer = -1, layersPerChannel = -1, channels = -1, activeLayers = -1;
    GLint exposure = -1, atlasSize = -1;
  };
  struct Pass {
    std::vector<GLuint> textures;  // one per atlas
    int channels = 0, order = 0, layersPerChannel = 0;
  };
  static Status link(const char* fs, Program* out);
  static void releasePass(Pass* p);
  // texel_prt in use over pass `p` at `displayOrder` bands (clamped to what it holds); with
  // `atlas` >= 0 in UV space over that atlas (the read-back), else in the view.
  void useShading(const Pass& p, int displayOrder, float exposure, int atlas);
  void drawAtlas(std::size_t atlas) const;  // that atlas's triangles, from the bound VAO

  Program shading_, depth_;
  GLuint vao_ = 0, atlasUv_ = 0;
  GLsizei indexCount_ = 0;
  std::vector<TextureAtlas> atlases_;
  std::array<Pass, 3> passes_{};
};

}  // namespace prt::web
