// One line per request on stderr: who, what, the status, the body bytes sent and how long
// it took, e.g. `127.0.0.1:51234 GET /api/scenes 200 1873 412us`.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace prt::serve {

struct AccessRecord {
  std::string_view peer;    // "address:port"
  std::string_view method;  // "-" when the request could not be parsed
  std::string_view target;  // as received; "-" when unknown
  unsigned status = 0;
  std::uint64_t bytes = 0;   // body bytes actually sent
  std::int64_t micros = 0;   // from the complete request head to the last byte sent
};

// The log line for `record`, newline included. Bytes of the method and target outside
// printable ASCII, spaces, quotes and backslashes become \xHH (a request cannot forge a
// log line or split a field), and targets are cut at 512 bytes.
std::string formatAccessLine(const AccessRecord& record);

class AccessLog {
 public:
  // `enabled` false (--quiet) makes write() a no-op.
  explicit AccessLog(bool enabled) : enabled_(enabled) {}
  bool enabled() const { return enabled_; }
  // Writes the line with one stdio call, so lines from different threads never interleave.
  void write(const AccessRecord& record) const;

 private:
  bool enabled_;
};

}  // namespace prt::serve
