#include "app/io/AtomicFile.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace gale::app {

namespace fs = std::filesystem;

std::string temporaryPathFor(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const fs::path p(path);
    const std::string name = "." + p.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++) + p.extension().string();
    return (p.parent_path() / name).string();
}

void commitTemporary(const std::string& tmpPath, const std::string& path) {
    std::error_code ec;
    fs::rename(tmpPath, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmpPath, ignored);
        throw std::runtime_error(path + ": cannot write: " + ec.message());
    }
}

void writeTextAtomic(const std::string& path, const std::string& text) {
    const std::string tmp = temporaryPathFor(path);
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
    const bool wrote = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int err = errno;
    const bool closed = std::fclose(f) == 0;
    if (!wrote || !closed) {
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": cannot write: " + std::strerror(wrote ? errno : err));
    }
    commitTemporary(tmp, path);
}

}  // namespace gale::app
