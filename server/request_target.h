// Turning an HTTP request target into a path that can be resolved under a directory
// without ever leaving it: the one gate every file-serving URL goes through.
#pragma once

#include <string>
#include <string_view>

#include "prt/status.h"

namespace prt::serve {

struct RequestTarget {
  std::string path;   // percent-decoded, starts with '/', validated segment by segment
  std::string query;  // raw (still encoded), without the '?'
};

// Splits an origin-form target ("/a/b?x=1") and percent-decodes its path. Rejects
// (kInvalidArgument, message for the log) anything that could name a file outside the
// directory the path is resolved against or that no file name holds: other target forms,
// raw bytes outside visible ASCII,
// malformed %-escapes, NUL and other control bytes, backslashes, "." and ".." segments
// (also when they arrive as %2e%2e), and empty segments ("//", also via %2f), which would
// turn the rest into an absolute path. A trailing '/' is kept (a directory index).
Status parseTarget(std::string_view target, RequestTarget* out);

// The value of `key` in an application/x-www-form-urlencoded query (the first occurrence,
// percent-decoded); false when absent or malformed.
bool queryValue(std::string_view query, std::string_view key, std::string* value);

// Percent-encodes everything in `segment` except RFC 3986 unreserved characters, so a file
// name can be put into a URL path segment.
std::string encodePathSegment(std::string_view segment);

}  // namespace prt::serve
