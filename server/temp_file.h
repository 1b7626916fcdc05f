// Anonymous temporary files: precompressed variants live in the page cache rather than in
// the heap, and go out through the same sendfile path as the files they were made from.
#pragma once

#include <string_view>

#include "open_file.h"
#include "prt/status.h"

namespace prt::serve {

// Writes `bytes` to a new file in $TMPDIR (or /tmp) that has no name (O_TMPFILE, or
// created and unlinked at once where the file system lacks it), so nothing is left behind
// however the server exits. The error names the directory.
Status writeTempFile(std::string_view bytes, FileRef* out);

}  // namespace prt::serve
