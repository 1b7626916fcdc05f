// A small CPU triangle rasteriser for the scene thumbnails (thumbnail.h): z-buffered,
// colours interpolated linearly in screen space (Gouraud), no GL. The server has no GPU, and
// a thumbnail is a few hundred thousand samples, so a scanline-free bounding-box loop with
// edge functions is enough. Pure computation: no I/O, no allocation beyond the target.
#pragma once

#include <vector>

#include "prt/vec3.h"

namespace prt::serve {

// One projected vertex: x right and y down in pixels (pixel (i, j) covers [i, i+1) x [j, j+1),
// its sample at the centre), depth > 0 (smaller is nearer) and the colour to interpolate.
struct RasterVertex {
  float x = 0, y = 0;
  float depth = 0;
  Rgb colour;
};

// A colour and depth buffer with a coverage mask; every pixel starts uncovered (colour 0,
// depth +infinity).
struct RasterTarget {
  int width = 0, height = 0;
  std::vector<Rgb> colour;         // width * height, row 0 at the top
  std::vector<float> depth;        // width * height
  std::vector<unsigned char> covered;  // 1 where some triangle won the depth test

  // A cleared target of width x height (both >= 1; the caller bounds them).
  RasterTarget(int width, int height);
};

// Draws triangle (a, b, c), either winding (no culling: the page does not cull either):
// every pixel whose centre lies inside (top-left rule on shared edges, so a mesh leaves no
// gaps and covers no centre twice) and whose interpolated depth (1/depth interpolated, exact
// under perspective) is nearer than what the pixel holds gets the screen-space barycentric
// blend of the three colours. Triangles with a non-finite coordinate, a depth <= 0 or no
// area draw nothing, so untrusted vertex data cannot make it misbehave.
void drawTriangle(RasterTarget& target, const RasterVertex& a, const RasterVertex& b, const RasterVertex& c);

}  // namespace prt::serve
