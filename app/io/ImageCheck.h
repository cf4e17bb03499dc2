#pragma once
/// \file ImageCheck.h
/// Image writers (libpng, giflib through OpenImageIO) do not all report a failed write: on a
/// full disk they can finish "successfully" with a cut file. So every image gale writes is read
/// back whole before it is moved into place.

#include <string>

namespace gale::app {

/// Reads every subimage of the finished temporary `tmpPath` (of output `path`) and checks its
/// size (`width` x `height` pixels; -1 for any). `writerErrno` is errno as the writer left it
/// (0 if it did not set one): a cut file is almost always a failed write, whose reason it holds.
/// Throws std::runtime_error "PATH: cannot write: REASON (it does not read back whole)".
/// libpng's own stderr line is silenced (one line per error).
void verifyImageFile(const std::string& tmpPath, const std::string& path, int width, int height,
                     int writerErrno);

}  // namespace gale::app
