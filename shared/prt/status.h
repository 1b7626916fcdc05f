// Status: the error type every fallible entry point of the shared library returns.
// No exceptions cross shared/ boundaries, so the same code behaves identically in
// native builds and in Emscripten builds compiled without exception support.
#pragma once

#include <string>
#include <utility>

namespace prt {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // a parameter is outside its documented range (order, size, direction)
  kSizeMismatch,     // a buffer is too small or sizes disagree
  kNotFinite,        // an input value is NaN or infinite
  // Decoding untrusted bytes (prt/asset.h):
  kTruncated,         // the data ends before the structure it declares
  kBadMagic,          // not this format at all
  kBadVersion,        // a format version this reader cannot read
  kChecksumMismatch,  // stored and computed checksums differ: damaged in storage or transit
  kCorrupt,           // checksums pass but the content is inconsistent or out of range
  // Native callers (baker, server); shared/ itself never returns these:
  kUsage,              // a command line that does not parse (unknown flag, missing value)
  kNotFound,           // a named file, directory or resource does not exist
  kIoError,            // the operating system refused a read or write (permissions, EIO)
  kUnavailable,        // a service is not there now (port in use, no GPU context); may pass later
  kResourceExhausted,  // out of memory, disk space or a configured limit
  kInternal,           // a bug: an invariant of this program does not hold
};

// Returns a stable lower-case name for a code ("ok", "invalid argument", ...).
const char* statusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;  // ok
  static Status ok() { return Status(); }
  static Status error(StatusCode code, std::string message) {
    Status s;
    s.code_ = code;
    s.message_ = std::move(message);
    return s;
  }

  bool isOk() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  // Human-readable message naming the problem; empty when ok.
  const std::string& message() const { return message_; }
  // "<code name>: <message>", or "ok".
  std::string toString() const;

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

}  // namespace prt

// Returns from the enclosing function with the Status of `expr` when it is not ok.
// `expr` is evaluated once. The enclosing function must return prt::Status.
#define PRT_RETURN_IF_ERROR(expr)                                   \
  do {                                                              \
    if (::prt::Status prt_status_ = (expr); !prt_status_.isOk()) {  \
      return prt_status_;                                           \
    }                                                               \
  } while (false)
