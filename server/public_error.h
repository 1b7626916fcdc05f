// What a response body may say about a failure on the server's side. File-system paths
// outside what the URL already says (absolute paths, the roots) and the library text that
// carries them stay in the server's log: a client learns which file failed and roughly
// why, never where the server keeps it.
#pragma once

#include <string>
#include <string_view>

namespace prt::serve {

// `detail` made safe to send: a leading "'<absPath>': " (how the image loader names the
// file) is dropped and other mentions of `absPath` become `relPath`. If what is left still
// holds `root` (unless it is "/") or anything that looks like an absolute path (a '/' opening a word),
// `fallback` is returned instead.
std::string publicMessage(std::string_view detail, std::string_view absPath, std::string_view relPath,
                          std::string_view root, std::string_view fallback);

// True when `text` holds something that looks like an absolute path: a '/' at the start or
// after a space, quote, bracket, '=' or ':' that is followed by a path character.
bool mentionsAbsolutePath(std::string_view text);

// Writes "prt-serve: <what>: <detail>" to stderr (one stdio call), so the operator keeps
// the detail a response leaves out.
void logDetail(std::string_view what, std::string_view detail);

}  // namespace prt::serve
