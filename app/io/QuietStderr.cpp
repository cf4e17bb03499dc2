#include "app/io/QuietStderr.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>

namespace gale::app {

QuietStderr::QuietStderr() {
    std::fflush(stderr);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null < 0) return;  // then messages stay visible: harmless
    mSaved = ::dup(2);
    if (mSaved >= 0) ::dup2(null, 2);
    ::close(null);
}

QuietStderr::~QuietStderr() {
    if (mSaved < 0) return;
    std::fflush(stderr);
    ::dup2(mSaved, 2);
    ::close(mSaved);
}

}  // namespace gale::app
