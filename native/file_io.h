// Whole-file reads and atomic, non-destructive writes for the native tools' outputs.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "prt/status.h"

namespace prt {

// Reads all of `path` into *out; fails (naming the path) when it is missing, not a regular
// file (a FIFO or device is refused without blocking), unreadable, or larger than maxBytes.
// The Status code for a failed system call's errno: kNotFound for a missing path,
// kResourceExhausted for a full disk, a quota or no memory or descriptors, else kIoError.
StatusCode statusCodeForErrno(int errorNumber);

Status readFileBytes(const std::string& path, std::uint64_t maxBytes, std::vector<std::uint8_t>* out);

// Opens `path` read-only for a whole-file read and sets *fd (the caller closes it) and *size;
// fails as readFileBytes does (naming the path) before anything is read.
Status openFileForReading(const std::string& path, std::uint64_t maxBytes, int* fd, std::uint64_t* size);

// Checks that `output` may receive a new file without destroying anything else: it does not
// exist yet, or it is a regular file (a symbolic link to one counts as that file) that is
// not the same file (device and inode) as any of `inputs`. Fails naming the path otherwise:
// a device node, FIFO, socket or directory, a dangling link, or an input. Call it before
// long work so a bad -o fails at once; writeFileAtomically checks again.
Status checkOutputPath(const std::string& output, std::span<const std::string> inputs = {});

// Writes `bytes` to a new temporary file beside `path` (named `<path>.prt-partial-XXXXXX`),
// flushes it, renames it over `path` (or, when `path` is a symbolic link, over the file it
// points to, so the link survives) and flushes the directory, so that after a crash readers
// see the old file or the complete new one, never a partial one. Refuses what
// checkOutputPath refuses. The temporary is removed on failure and on SIGINT, SIGTERM and
// SIGHUP (the signal then ends the process as it would have); only SIGKILL or a power loss
// can leave one. One write at a time per process (the signal cleanup tracks one file).
Status writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes,
                           std::span<const std::string> inputs = {});

// writeFileAtomically of a file given as pieces written one after another (why: a large
// file made of arrays that live elsewhere is written without first copying them into one
// buffer, a copy that cost as much as the write for a sharded bake's 100 MB shard files).
Status writePartsAtomically(const std::string& path, std::span<const std::span<const std::uint8_t>> parts,
                            std::span<const std::string> inputs = {});

}  // namespace prt
