#pragma once
/// \file AtomicFile.h
/// Never a half file (STYLE, errors): write to a temporary name in the destination's folder, then
/// rename over the destination, which POSIX makes atomic within one file system.

#include <string>

namespace gale::app {

/// A temporary name next to `path` that keeps its extension (so image writers still know the
/// format): "dir/.name.tmp-PID-N.ext".
std::string temporaryPathFor(const std::string& path);

/// Renames `tmpPath` to `path`; on failure removes `tmpPath` and throws std::runtime_error naming
/// `path`.
void commitTemporary(const std::string& tmpPath, const std::string& path);

/// Writes `text` to `path` atomically. Throws std::runtime_error naming the path.
void writeTextAtomic(const std::string& path, const std::string& text);

}  // namespace gale::app
