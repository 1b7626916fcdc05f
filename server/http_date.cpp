#include "http_date.h"

#include <ctime>

namespace prt::serve {

std::string_view httpDateNow() {
  // Per thread, so formatting needs no lock; strftime runs at most once a second.
  thread_local std::time_t cachedSecond = -1;
  thread_local char text[40];
  thread_local std::size_t length = 0;
  const std::time_t now = std::time(nullptr);
  if (now != cachedSecond) {
    std::tm tm{};
    gmtime_r(&now, &tm);
    length = std::strftime(text, sizeof text, "%a, %d %b %Y %H:%M:%S GMT", &tm);
    cachedSecond = now;
  }
  return {text, length};
}

}  // namespace prt::serve
