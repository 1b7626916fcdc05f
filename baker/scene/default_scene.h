// The built-in scene `prt-bake` uses when no glTF file is given: generated in code, so it
// needs no files and always matches the current Scene layout.
//
// An open room corner 4 m wide, 4 m deep and 3 m high (floor, back wall, red left wall,
// green right wall; open at the front and the top so environment light gets in) holding a
// sphere, a cube, a tall box and a torus that stand on the floor. It is chosen to show what
// transfer captures: soft shadows, contact darkening where objects meet the floor, and
// colour bleeding from the coloured walls onto the white-ish floor and sphere. Every surface
// is a fine grid (16 cells per metre) so per-vertex transfer can show gradients. For glossy
// bakes the sphere is a polished white dielectric and the torus a purple metal; the room
// and the boxes are matte (no specular part), so their shading does not follow the eye.
#pragma once

#include "baker/scene/scene.h"

namespace prt::bake {

// Returns the default scene: world space in metres, +y up, floor at y = 0, the room
// spanning x and z in [-2, 2]; about 20k vertices; unit normals pointing into the room and
// out of the objects; counter-clockwise front faces; albedo below 1 on every channel.
// Vertices on sharp edges are duplicated per face, so each keeps its face's normal.
// TEXCOORD_1 is a lightmap atlas (every surface grid its own chart, texels in proportion to
// area, gutters wide enough for `lightmapPadding` texels at a `lightmapSide`² atlas and every
// larger one; the same UVs for every side from 512 up at padding 2) so transfer textures need
// no unwrapper; TEXCOORD_0 is absent.
Scene makeDefaultScene(int lightmapSide = 512, int lightmapPadding = 2);

}  // namespace prt::bake
