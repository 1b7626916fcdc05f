// The directory trees the server tests serve: assets built with the shared writer
// (encodeAsset), broken assets, environment maps, web files, and symlinks that lead out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/asset.h"

namespace prt::serve::test {

// A valid encoded asset: `vertices` vertices in a strip, order `order`, an unshadowed and
// an interreflected pass with smooth (compressible) coefficients that depend on `seed`,
// baked (nominally) for `lighting`.
std::vector<std::uint8_t> makeAssetBytes(int vertices, int order, std::uint32_t seed, const std::string& name,
                                         const LightingInfo& lighting = {});

// A Radiance RGBE (.hdr) image of width x height holding one colour.
std::string makeRgbeImage(int width, int height, float r, float g, float b);

void writeFile(const std::string& path, const std::string& bytes);
void writeFile(const std::string& path, const std::vector<std::uint8_t>& bytes);
std::string readFile(const std::string& path);

struct TestTree {
  std::string dir;      // holds everything below
  std::string root;     // --root: room.prt, sub/small.prt, corrupt.prt, truncated.prt,
                        //   escape.prt (symlink out), sky.hdr, bad.hdr, damaged.exr,
                        //   sub/notimage.exr, studio.exr (blender-data)
  std::string web;      // --web: index.html, app.js, module.mjs, core.wasm, ...
  std::string outside;  // next to the roots: secret.txt and secret.prt
  std::vector<std::uint8_t> room;   // the bytes of root/room.prt (about 1.8 MB)
  std::vector<std::uint8_t> small;  // the bytes of root/sub/small.prt (local-sphere lighting)
  std::string bigJs;                // web/big.js
  std::string huge;                 // web/huge.bin: 24 MB of noise, more than socket buffers hold
  bool hasExr = false;              // blender-data's studio.exr was found and copied
};

// Builds a fresh tree in a new directory under `parent` (created if missing). Trees are
// removed when the test process exits (kept when PRT_KEEP_TEST_TREES is set).
TestTree makeTestTree(const std::string& parent);

}  // namespace prt::serve::test
