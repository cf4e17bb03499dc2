#pragma once
/// \file QuietStderr.h
/// Silences file descriptor 2 for a scope. libpng prints "libpng error: ..." to stderr on its own
/// before OpenImageIO reports the same error through geterror(); gale promises exactly one line
/// per error, so image decoding runs with stderr pointed at /dev/null. Not thread-safe: the
/// program decodes images on the main thread only.

namespace gale::app {

class QuietStderr {
  public:
    QuietStderr();
    ~QuietStderr();
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

  private:
    int mSaved = -1;
};

}  // namespace gale::app
