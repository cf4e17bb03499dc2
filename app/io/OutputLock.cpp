#include "app/io/OutputLock.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"

namespace gale::app {

std::string OutputLock::pathFor(const std::string& folder) {
    return (std::filesystem::path(folder) / ".gale.lock").string();
}

namespace {

/// The PID written in the lock file, -1 if unreadable.
long lockOwner(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return -1;
    long pid = -1;
    if (std::fscanf(f, "%ld", &pid) != 1) pid = -1;
    std::fclose(f);
    return pid;
}

bool running(long pid) {
    if (pid <= 0 || pid > INT_MAX) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

}  // namespace

OutputLock::OutputLock(const std::string& folder, const std::string& where)
    : mPath(pathFor(folder)) {
    // The PID is written to a temporary first and linked into place, so the lock never exists
    // without its PID. Two tries: the second after taking over a stale lock.
    const std::string tmp = temporaryPathFor(mPath);
    {
        const std::string text = std::to_string(::getpid()) + "\n";
        const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        const bool ok = fd >= 0 && ::write(fd, text.data(), text.size()) == ssize_t(text.size());
        const int err = errno;
        if (fd >= 0) ::close(fd);
        if (!ok) {
            discardTemporary(tmp);
            throw std::runtime_error(mPath + ": cannot write: " + std::strerror(err));
        }
    }
    setPendingLock(mPath);
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (::link(tmp.c_str(), mPath.c_str()) == 0) {
            registerForRemoval(mPath);
            clearPendingLock();
            discardTemporary(tmp);
            return;
        }
        const int err = errno;
        clearPendingLock();
        if (err != EEXIST) {
            discardTemporary(tmp);
            throw InputError(where + ": '" + folder + "': cannot create the lock file " + mPath +
                             ": " + std::strerror(err));
        }
        const long owner = lockOwner(mPath);
        if (running(owner)) {
            discardTemporary(tmp);
            throw InputError(where + ": '" + folder + "' is in use by another gale run (PID " +
                             std::to_string(owner) + ", lock " + mPath +
                             "); wait for it to finish, or write elsewhere");
        }
        if (owner < 0) {
            discardTemporary(tmp);
            throw InputError(where + ": '" + folder + "' has a lock file " + mPath +
                             " without a PID; remove it if no gale run writes there");
        }
        std::fprintf(stderr,
                     "gale: note: taking over %s from PID %ld, which is no longer running\n",
                     mPath.c_str(), owner);
        ::unlink(mPath.c_str());
        setPendingLock(mPath);
    }
    clearPendingLock();
    discardTemporary(tmp);
    throw InputError(where + ": '" + folder + "': the lock " + mPath +
                     " was taken by another run at the same time");
}

OutputLock::~OutputLock() {
    ::unlink(mPath.c_str());
    unregisterForRemoval(mPath);
}

}  // namespace gale::app
