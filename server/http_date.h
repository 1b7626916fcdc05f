// The Date header value (RFC 9110 §5.6.7 IMF-fixdate), formatted once a second per thread.
#pragma once

#include <string_view>

namespace prt::serve {

// "Sun, 06 Nov 1994 08:49:37 GMT" for now; valid until the calling thread's next call.
std::string_view httpDateNow();

}  // namespace prt::serve
