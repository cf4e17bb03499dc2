#include "app/io/AtomicFile.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <unordered_map>

#include "app/io/Errors.h"

namespace gale::app {

namespace fs = std::filesystem;

namespace {

/// The signal-safe registry: fixed slots of fixed size, a slot is in use when its first byte is
/// not 0. Written by the main thread only; the handler only reads.
char gRegistered[REGISTERED_PATHS][PATH_MAX];
/// setPendingLock's path, empty when none.
char gPendingLock[PATH_MAX];

[[noreturn]] void failWrite(const std::string& path, const std::string& reason,
                            const std::string& tmpPath) {
    if (!tmpPath.empty()) discardTemporary(tmpPath);
    throw std::runtime_error(path + ": cannot write: " + reason);
}

/// The folder holding `path` ("." for a bare name).
std::string folderOf(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? "." : parent.string();
}

/// fsyncs a folder so a rename in it is durable; file systems that cannot sync folders
/// (EINVAL) are fine.
void syncFolder(const std::string& folder, const std::string& path) {
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    const int r = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (r != 0 && err != EINVAL && err != EROFS)
        throw std::runtime_error(path + ": cannot write: " + std::strerror(err));
}

bool processExists(long pid) {
    if (pid <= 0 || pid > INT_MAX) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

/// The PID in a temporary's name, or -1 if the name is not one of ours.
long temporaryOwner(const std::string& name) {
    // ".NAME.tmp-PID-N[.ext]"
    size_t at = name.rfind(".tmp-");
    if (!name.empty() && name[0] == '.' && at != std::string::npos && at > 0) {
        const size_t begin = at + 5, dash = name.find('-', begin);
        if (dash == std::string::npos || dash == begin) return -1;
        const std::string pid = name.substr(begin, dash - begin);
        if (pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos) return -1;
        return std::stol(pid);
    }
    // "NAME.tmpPID" (the .vdb writer's own temporary)
    at = name.rfind(".tmp");
    if (at == std::string::npos || at == 0) return -1;
    const std::string pid = name.substr(at + 4);
    if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos)
        return -1;
    return std::stol(pid);
}

}  // namespace

void registerForRemoval(const std::string& path) {
    if (path.size() >= PATH_MAX) return;
    for (char* slot : gRegistered)
        if (slot[0] == '\0') {
            std::memcpy(slot, path.c_str(), path.size() + 1);
            return;
        }
}

void unregisterForRemoval(const std::string& path) {
    for (char* slot : gRegistered)
        if (slot[0] != '\0' && path == slot) slot[0] = '\0';
}

void setPendingLock(const std::string& path) {
    if (path.size() >= PATH_MAX) return;
    std::memcpy(gPendingLock, path.c_str(), path.size() + 1);
}

void clearPendingLock() { gPendingLock[0] = '\0'; }

namespace {

/// Whether the file at `path` holds this process's PID as its first line (async-signal-safe:
/// open, read, close and getpid only).
bool holdsOwnPid(const char* path) {
    const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    char text[32];
    const ssize_t n = ::read(fd, text, sizeof text);
    ::close(fd);
    long pid = 0;
    ssize_t i = 0;
    for (; i < n && text[i] >= '0' && text[i] <= '9'; ++i) pid = pid * 10 + (text[i] - '0');
    return i > 0 && pid == static_cast<long>(::getpid());
}

}  // namespace

void removeRegisteredTemporaries() {
    for (const char* slot : gRegistered)
        if (slot[0] != '\0') ::unlink(slot);
    if (gPendingLock[0] != '\0' && holdsOwnPid(gPendingLock)) ::unlink(gPendingLock);
}

std::string temporaryPathFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(path);
    const std::string name = "." + p.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++) + p.extension().string();
    const std::string tmp = (p.parent_path() / name).string();
    registerForRemoval(tmp);
    return tmp;
}

void discardTemporary(const std::string& tmpPath) {
    ::unlink(tmpPath.c_str());
    unregisterForRemoval(tmpPath);
}

void syncTemporary(const std::string& tmpPath, const std::string& path) {
    const int fd = ::open(tmpPath.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) failWrite(path, std::strerror(errno), tmpPath);
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size == 0) {
        ::close(fd);
        failWrite(path, "the writer left an empty file", tmpPath);
    }
    const int r = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (r != 0) failWrite(path, std::strerror(err), tmpPath);
}

void commitTemporary(const std::string& tmpPath, const std::string& path) {
    syncTemporary(tmpPath, path);
    if (::rename(tmpPath.c_str(), path.c_str()) != 0)
        failWrite(path, std::strerror(errno), tmpPath);
    unregisterForRemoval(tmpPath);
    syncFolder(folderOf(path), path);
}

namespace {

/// Writes `text` to `tmpPath` (created or truncated), fsyncs and closes it; every failure
/// removes the temporary and throws naming `path`, the file the user asked for. A stream
/// (tmpPath == path, isStreamOutput) is opened without creating or truncating, not fsync'ed and
/// never removed.
void writeWholeText(const std::string& tmpPath, const std::string& path, const std::string& text) {
    const bool stream = tmpPath == path;
    const std::string removable = stream ? std::string() : tmpPath;
    const int fd = stream ? ::open(path.c_str(), O_WRONLY | O_CLOEXEC)
                          : ::open(tmpPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) failWrite(path, std::strerror(errno), removable);
    size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = n < 0 ? errno : ENOSPC;
            ::close(fd);
            failWrite(path, std::strerror(err), removable);
        }
        done += static_cast<size_t>(n);
    }
    if (stream) {
        if (::close(fd) != 0) failWrite(path, std::strerror(errno), removable);
        return;
    }
    if (::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        failWrite(path, std::strerror(err), tmpPath);
    }
    if (::close(fd) != 0) failWrite(path, std::strerror(errno), tmpPath);
}

}  // namespace

void writeTextAtomic(const std::string& path, const std::string& text) {
    if (isStreamOutput(path)) return writeWholeText(path, path, text);
    const std::string tmp = temporaryPathFor(path);
    writeWholeText(tmp, path, text);
    if (::rename(tmp.c_str(), path.c_str()) != 0) failWrite(path, std::strerror(errno), tmp);
    unregisterForRemoval(tmp);
    syncFolder(folderOf(path), path);
}

void writeStagedText(StagedFiles& staged, const std::string& path, const std::string& text) {
    writeWholeText(staged.add(path), path, text);
    staged.seal(path);
}

std::vector<std::string> staleTemporaries(const std::string& folder) {
    std::vector<std::string> out;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const long pid = temporaryOwner(name);
        if (pid > 0 && pid != ::getpid() && !processExists(pid) && it->is_regular_file(ec))
            out.push_back(it->path().string());
    }
    return out;
}

int removeStaleTemporaries(const std::string& folder) {
    const std::vector<std::string> stale = staleTemporaries(folder);
    int removed = 0;
    for (const std::string& p : stale) removed += ::unlink(p.c_str()) == 0;
    if (removed > 0)
        std::fprintf(stderr,
                     "gale: note: removed %d temporary file%s left in %s by a run that was "
                     "stopped (e.g. %s)\n",
                     removed, removed == 1 ? "" : "s", folder.c_str(),
                     fs::path(stale.front()).filename().c_str());
    return removed;
}

}  // namespace gale::app

namespace gale::app {

StagedFiles::~StagedFiles() { discard(); }

void StagedFiles::discard() {
    for (const Entry& e : mEntries)
        if (!e.stream) discardTemporary(e.tmp);
    mEntries.clear();
}

std::string StagedFiles::add(const std::string& path) {
    if (isStreamOutput(path)) {
        mEntries.push_back({path, path, false, true});
        return path;
    }
    mEntries.push_back({path, temporaryPathFor(path), false, false});
    return mEntries.back().tmp;
}

double StagedFiles::seal(const std::string& path) {
    for (Entry& e : mEntries)
        if (e.path == path) {
            e.sealed = true;
            if (e.stream) return 0.0;  // written in place: nothing to sync or measure
            syncTemporary(e.tmp, e.path);
            std::error_code ec;
            const auto size = fs::file_size(e.tmp, ec);
            return ec ? 0.0 : static_cast<double>(size);
        }
    throw std::logic_error("StagedFiles::seal: " + path + " was not added");
}

std::vector<std::string> StagedFiles::sealed() const {
    std::vector<std::string> out;
    for (const Entry& e : mEntries)
        if (e.sealed) out.push_back(e.path);
    return out;
}

void StagedFiles::commit() {
    std::vector<Entry> entries;
    entries.swap(mEntries);
    std::vector<std::string> folders;
    for (size_t k = 0; k < entries.size(); ++k) {
        const Entry& e = entries[k];
        if (e.stream) continue;  // written in place already
        if (!e.sealed) {
            discardTemporary(e.tmp);
            continue;
        }
        if (::rename(e.tmp.c_str(), e.path.c_str()) != 0) {
            const int err = errno;
            for (size_t j = k; j < entries.size(); ++j)
                if (!entries[j].stream) discardTemporary(entries[j].tmp);
            throw std::runtime_error(e.path + ": cannot write: " + std::strerror(err));
        }
        unregisterForRemoval(e.tmp);
        const std::string folder = folderOf(e.path);
        if (folders.empty() || folders.back() != folder) {
            folders.push_back(folder);
            syncFolder(folder, e.path);
        }
    }
}

bool isStreamOutput(const std::string& path) {
    struct stat st {};
    if (path.empty() || ::stat(path.c_str(), &st) != 0) return false;
    return S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode);
}

std::vector<std::string> rasterSidecars(const std::string& path) {
    const fs::path p(path);
    std::string ext = p.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::vector<std::string> out{path + ".aux.xml", fs::path(p).replace_extension(".aux").string(),
                                 fs::path(p).replace_extension(".prj").string(),
                                 fs::path(p).replace_extension(".wld").string()};
    std::vector<std::string> worlds;
    if (ext == ".tif" || ext == ".tiff") worlds = {".tfw", ".tifw", ".tiffw"};
    if (ext == ".png") worlds = {".pgw", ".pngw"};
    if (ext == ".jpg" || ext == ".jpeg") worlds = {".jgw", ".jpgw"};
    for (const std::string& w : worlds) out.push_back(fs::path(p).replace_extension(w).string());
    return out;
}

namespace {

/// What refuseAliases knows about one path: its real name, and the file it is if it exists.
struct ResolvedPath {
    std::string real;  ///< absolute, symbolic links and ".." resolved
    bool exists = false;
    struct stat st {};
    /// One name per file: device and inode when it exists (hard links meet), else the name.
    std::string identity() const {
        if (!exists) return "path:" + real;
        return "inode:" + std::to_string(static_cast<unsigned long long>(st.st_dev)) + ":" +
               std::to_string(static_cast<unsigned long long>(st.st_ino));
    }
};

/// Resolves paths, each folder once (thousands of frames share one).
class PathResolver {
  public:
    ResolvedPath resolve(const std::string& path) {
        ResolvedPath r;
        const fs::path p(path);
        const std::string name = p.filename().string();
        std::error_code ec;
        fs::path full;
        if (name.empty() || name == "." || name == "..") {
            full = fs::weakly_canonical(fs::absolute(p, ec), ec);
            if (ec) full = fs::absolute(p).lexically_normal();
        } else {
            full =
                fs::path(folder(p.parent_path().empty() ? "." : p.parent_path().string())) / name;
            // The file itself may be a symbolic link (to an input): resolve it too.
            if (fs::is_symlink(full, ec)) {
                const fs::path target = fs::weakly_canonical(full, ec);
                if (!ec) full = target;
            }
        }
        r.real = full.string();
        r.exists = ::stat(r.real.c_str(), &r.st) == 0;
        return r;
    }

  private:
    std::string folder(const std::string& raw) {
        for (const auto& [given, resolved] : mFolders)
            if (given == raw) return resolved;
        std::error_code ec;
        std::string resolved = fs::weakly_canonical(fs::absolute(raw, ec), ec).string();
        if (ec) resolved = fs::absolute(raw).lexically_normal().string();
        mFolders.emplace_back(raw, resolved);
        return resolved;
    }
    std::vector<std::pair<std::string, std::string>> mFolders;
};

bool isStreamMode(mode_t mode) { return S_ISCHR(mode) || S_ISFIFO(mode) || S_ISSOCK(mode); }

}  // namespace

void refuseAliases(const std::vector<RunPath>& inputs, const std::vector<RunPath>& outputs) {
    PathResolver resolver;
    std::unordered_map<std::string, const RunPath*> seen;
    for (const RunPath& in : inputs)
        if (!in.path.empty()) seen.emplace(resolver.resolve(in.path).identity(), &in);
    const auto clash = [](const RunPath& out, const RunPath& other) {
        throw InputError(out.role + ": '" + out.path + "' is also " + other.role + " ('" +
                         other.path + "'); choose another output path");
    };
    for (const RunPath& out : outputs) {
        if (out.path.empty()) continue;
        const ResolvedPath r = resolver.resolve(out.path);
        if (r.exists && S_ISDIR(r.st.st_mode))
            throw InputError(out.role + ": '" + out.path +
                             "' is a folder; give the name of the file to write");
        if (r.exists && isStreamMode(r.st.st_mode)) {
            if (!out.streamable)
                throw InputError(out.role + ": '" + out.path +
                                 "' is a device, FIFO or socket; this output is written as a "
                                 "regular file (and moved into place): give a file name");
            // A stream is written in place: it may not be an input, but two outputs may share it.
            const auto it = seen.find(r.identity());
            if (it != seen.end()) clash(out, *it->second);
            continue;
        }
        if (r.exists && S_ISREG(r.st.st_mode) &&
            ((r.st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 ||
             ::access(r.real.c_str(), W_OK) != 0))
            throw InputError(out.role + ": '" + out.path +
                             "' is read-only; gale does not replace it: make it writable "
                             "(chmod u+w) or choose another output path");
        const auto [it, fresh] = seen.emplace(r.identity(), &out);
        if (!fresh) clash(out, *it->second);
    }
}

}  // namespace gale::app
