// WebGL2 drawing of transfer textures (per-texel PRT, PRTT; docs/web-client.md "Transfer
// textures"): per texel pass one RGBA16F TEXTURE_2D_ARRAY per atlas (texel_texture.h), the
// atlas UVs as a vertex attribute, a depth prepass and the per-fragment shading
// (shaders/texel_prt.vert, texel_prt.frag) with the same Lighting block as the vertex path,
// and the atlas read-back in UV space for tests; and the glossy term by TPFL (the visibility
// pass as one more set of texture arrays, the per-frame product matrix P(L) as a small RGBA32F
// texture, texel_glossy.h), reflecting about the asset's texel normals where normal maps turned
// them (one RGBA16F texture per atlas). Owned by GlRenderer, which holds the geometry buffers this class
// draws from.
#pragma once

#include <GLES3/gl3.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "glm_types.h"
#include "prt/asset.h"
#include "prt/status.h"
#include "texel_glossy.h"

namespace prt::web {

// What one texel draw shades: the terms, the display order, the eye of the glossy term.
struct TexelShading {
  int displayOrder = 1;
  float exposure = 1.0f;
  bool diffuse = true;       // the diffuse texel pass
  bool glossy = false;       // the TPFL glossy term (drawn only with a visibility pass and a product)
  glm::vec3 eye{0.0f};       // world space
  bool fresnel = true;
  bool positions = false;    // tests, atlas read-back only: write the fragment's world position instead
};

class TexelRenderer {
 public:
  // Compiles the two programs; the WebGL2 context must be current.
  Status init();
  // Uses the scene's position, albedo and index buffers (owned by the caller, alive until
  // releaseGeometry) with `atlasUv` (2 floats per vertex) and `atlases` (contiguous triangle
  // runs); drops every texel pass. The caller checks for GL errors.
  void setGeometry(GLuint positions, GLuint albedo, GLuint normals, GLuint indices, std::span<const float> atlasUv,
                   std::span<const TextureAtlas> atlases);
  // Forgets the geometry and deletes every texel pass's textures.
  void releaseGeometry();
  // Uploads the asset's texel normals (BakedAsset::texelNormals with its texelCoverage) as one
  // RGBA16F texture per atlas (packTexelNormals), which the glossy term then reflects about
  // instead of the interpolated vertex normal; empty codes drop them. Needs geometry; nothing
  // changes on error (a count that disagrees with the atlases, a side over MAX_TEXTURE_SIZE).
  Status setShadingNormals(std::span<const std::int16_t> codes, std::span<const std::uint8_t> coverage);
  // Whether the glossy term has stored shading normals.
  bool hasShadingNormals() const { return !normals_.empty(); }
  // Whether setGeometry gave atlases (the scene has transfer textures).
  bool hasAtlases() const { return !atlases_.empty(); }
  const std::vector<TextureAtlas>& atlases() const { return atlases_; }

  // Packs and uploads texel pass `pass` holding `order` bands, replacing the previous pass of
  // its kind. Needs geometry; a pass that does not fit (texture size, layers, GPU memory)
  // changes nothing and says why.
  Status uploadPass(const TransferPass& pass, int order);
  // Bands the texel pass of `kind` (0 unshadowed, 1 shadowed, 2 interreflected) holds; 0 when absent.
  int passOrder(int kind) const;

  // Packs and uploads the TPFL visibility pass (form kVisibility, 1 channel) holding `order`
  // bands, with one specular material per vertex (attributes 5 and 6 of the texel draw),
  // replacing the previous one. Same limits and errors as uploadPass; nothing changes on error.
  Status uploadVisibility(const TransferPass& pass, int order, std::span<const SpecularMaterial> specular);
  // Bands of the visibility pass on the GPU; 0 when absent.
  int visibilityOrder() const { return visibility_.order; }
  // Remakes P_c(L) for `bands` (1 .. 8) product bands from `lighting` (bands^2 RGB, the bound
  // Lighting block's first coefficients) and uploads it: 48 bands^2 ceil(m^2/4) bytes, m the
  // product's transfer order from the visibility order. Needs a visibility pass.
  Status setProductLighting(std::span<const Rgb> lighting, int bands);
  // Bands of the uploaded product (0: none yet); the caller remakes it when they or the lighting change.
  int productBands() const { return product_.bands; }

  // Draws the scene from texel pass `kind` with the bound Lighting block: a depth-only prepass
  // over every triangle, then each atlas's triangles shaded where the depth is EQUAL to the
  // prepass's, so each pixel runs the per-fragment PRT once. Leaves depth test LESS with
  // depth and colour writes on. False (nothing drawn) when the pass is absent.
  bool draw(int kind, const glm::mat4& viewProjection, const TexelShading& shading);

  // Renders atlas `atlas` of pass `kind` in UV space (one fragment per texel whose centre a
  // triangle covers) with the same fragment shader and `shading`'s terms and eye (exposure
  // ignored; shading.positions: the world positions instead) writing linear radiance into an RGBA32F
  // target, sampling at the exact texel centres (texel_prt.frag), and reads it back: width x height x 4 floats, row y = texel row y, alpha 1 where
  // a triangle covered the texel centre, 0 elsewhere. Errors: absent pass, atlas out of range,
  // no float render targets (EXT_color_buffer_float).
  Status readAtlas(int kind, int atlas, const TexelShading& shading, std::vector<float>* out);

 private:
  struct Program {
    GLuint id = 0;
    GLint viewProjection = -1, atlasSpace = -1, transfer = -1, layersPerChannel = -1, channels = -1, activeLayers = -1;
    GLint exposure = -1, atlasSize = -1;
    GLint diffuse = -1, glossy = -1, visibility = -1, product = -1, visibilityLayers = -1, bands = -1, fresnel = -1, eye = -1;
    GLint writePosition = -1, normals = -1, shadingNormals = -1;
    GLint shY00 = -1, shK1 = -1, shA = -1, shB = -1;
  };
  struct Pass {
    std::vector<GLuint> textures;  // one per atlas
    int channels = 0, order = 0, layersPerChannel = 0;
  };
  static Status link(const char* fs, Program* out);
  static void releasePass(Pass* p);
  // texel_prt in use over pass `p` at shading.displayOrder bands (clamped to what it holds); with
  // `atlas` >= 0 in UV space over that atlas (the read-back), else in the view.
  void useShading(const Pass& p, const TexelShading& shading, int atlas);
  bool glossyReady() const { return visibility_.order > 0 && product_.bands > 0; }
  void drawAtlas(std::size_t atlas) const;  // that atlas's triangles, from the bound VAO
  void bindAtlas(const Pass& p, std::size_t atlas) const;
  void unbindTextures() const;

  Program shading_, depth_;
  GLuint vao_ = 0, atlasUv_ = 0;
  GLsizei indexCount_ = 0;
  std::size_t vertexCount_ = 0;
  std::vector<TextureAtlas> atlases_;
  std::array<Pass, 3> passes_{};
  Pass visibility_;              // the TPFL visibility vectors, 1 channel
  GLuint specular_ = 0;          // (f0 r, g, b, s, f90) per vertex, attributes 5 and 6
  GLuint productTexture_ = 0;    // P_c(L), RGBA32F
  std::vector<GLuint> normals_;  // per atlas, RGBA16F TEXTURE_2D shading normals; empty without
  TpflProductTexture product_;   // its CPU side (the sizes; the floats until the next upload)
  ShTripleProduct tensor_;       // C restricted to the product's bands and transfer order
};

}  // namespace prt::web
