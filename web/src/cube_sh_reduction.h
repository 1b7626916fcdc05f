// GPU projection of the light cube onto SH (docs/web-client.md): a weight table (basis x
// exact texel solid angle from the shared cubeShWeightRows, 4 coefficients per RGBA32F
// texel, one array layer per coefficient group) and two reduction passes: pass 1 sums each
// face row against its weights into partial sums (R, G, B as three render targets), pass 2
// sums the partials into the 16 x 3 cube-SH texture (packLighting layout). No readback.
#pragma once

#include <GLES3/gl3.h>

#include <cstddef>

#include "cube_faces.h"
#include "prt/status.h"

namespace prt::web {

class CubeShReduction {
 public:
  // Larger tables (e.g. 512^2 faces at order 7 or 8) are refused: the CPU path serves them.
  inline static constexpr std::size_t kMaxWeightTableBytes = std::size_t{256} << 20;

  Status init();
  // Builds the weight table and partial-sum targets for faces of `size` at SH `order`
  // (1..8), unless they are already built for these. Needs float render targets.
  Status prepare(int size, int order);
  // Projects the atlas `cubeTexture` into `cubeShFramebuffer` (16 x 3 RGBA32F), reading
  // only rects[f] of face f (everything outside must be black). Leaves the default
  // framebuffer bound and depth testing off.
  void run(GLuint cubeTexture, GLuint cubeShFramebuffer, const FaceRect (&rects)[6]);

  // Bytes of the weight table now allocated (for the docs and the report).
  std::size_t weightBytes() const;

 private:
  void release();
  GLuint sumRowsProgram_ = 0, sumBlocksProgram_ = 0, vao_ = 0;
  GLint rowsCube_ = -1, rowsWeights_ = -1, rowsSize_ = -1, rowsGroups_ = -1, rowsRects_ = -1;
  GLint blocksPartial_ = -1, blocksSize_ = -1, blocksGroups_ = -1;
  GLuint weights_ = 0, partial_ = 0, partialFramebuffer_ = 0;
  int size_ = 0, order_ = 0, groups_ = 0;
};

}  // namespace prt::web
