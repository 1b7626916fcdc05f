// Reader of Radiance RGBE pictures (.hdr, .pic).
//
// Our own rather than stb_image's: the stb_image in Debian 12 loops forever on a run-length
// count of 0, which a truncated or corrupt file easily holds, and it pads short files with
// zeros instead of reporting them.
#pragma once

#include <cstdio>

#include "prt/image.h"
#include "prt/status.h"

namespace prt {

// Decodes the RGBE picture `file` holds from its current position to linear float RGB in
// `out` (row 0 at the top). Supports FORMAT=32-bit_rle_rgbe with the standard "-Y H +X W"
// layout, scanlines flat, in old-style or in new-style run-length encoding; EXPOSURE is
// ignored, as most readers do. Errors (kInvalidArgument) describe the problem, not the
// file. Allocates only after the header passes: each side in [1, kMaxImageSide].
Status readRadianceHdr(std::FILE* file, RgbImage* out);

}  // namespace prt
