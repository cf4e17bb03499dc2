#include "app/io/OutputFolder.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"

namespace gale::app {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& where, const std::string& folder,
                       const std::string& reason) {
    throw InputError(where + ": '" + folder + "' " + reason);
}

}  // namespace

std::string framePath(const std::string& folder, const std::string& prefix, int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "_%04d.png", frame);
    return (fs::path(folder) / (prefix + name)).string();
}

OutputFolderStatus checkOutputFolder(const std::string& folder, const std::string& where,
                                     const std::string& prefix, int frames) {
    OutputFolderStatus status;
    status.folder = folder;
    if (folder.empty()) throw InputError(where + ": the output folder is empty");
    std::error_code ec;
    fs::path existing = fs::path(folder);
    const fs::file_status st = fs::status(existing, ec);
    if (fs::exists(st)) {
        if (!fs::is_directory(st)) fail(where, folder, "is a file, not a folder");
        status.exists = true;
        if (::access(folder.c_str(), W_OK | X_OK) != 0)
            fail(where, folder, std::string("is not writable: ") + std::strerror(errno));
        const std::string head = prefix + "_", tail = ".png";
        for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
            ++status.existingFiles;
            const std::string name = e.path().filename().string();
            if (name.size() <= head.size() + tail.size() ||
                name.compare(0, head.size(), head) != 0 ||
                name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
                continue;
            const std::string digits =
                name.substr(head.size(), name.size() - head.size() - tail.size());
            if (digits.size() < 4 || digits.size() > 9 ||
                digits.find_first_not_of("0123456789") != std::string::npos)
                continue;
            if (std::stol(digits) >= frames) status.staleFrames.push_back(name);
        }
    } else {
        // Walk up to the nearest existing ancestor: it must be a writable folder.
        fs::path p = fs::absolute(existing, ec).lexically_normal();
        while (p.has_parent_path() && p != p.root_path()) {
            p = p.parent_path();
            const fs::file_status a = fs::status(p, ec);
            if (!fs::exists(a)) continue;
            if (!fs::is_directory(a))
                fail(where, folder, "cannot be created: '" + p.string() + "' is a file");
            if (::access(p.c_str(), W_OK | X_OK) != 0)
                fail(where, folder,
                     "cannot be created in '" + p.string() + "': " + std::strerror(errno));
            existing = p;
            break;
        }
    }
    const fs::space_info space = fs::space(existing, ec);
    if (!ec) status.freeBytes = static_cast<double>(space.available);
    return status;
}

bool prepareOutputFolder(const std::string& folder, const std::string& where) {
    std::error_code ec;
    const bool created = fs::create_directories(folder, ec);
    if (ec) fail(where, folder, "cannot be created: " + ec.message());
    if (!fs::is_directory(folder, ec)) fail(where, folder, "is a file, not a folder");
    // Prove it writable the only reliable way: write a file there.
    const std::string probe = temporaryPathFor((fs::path(folder) / "probe").string());
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) fail(where, folder, std::string("is not writable: ") + std::strerror(errno));
    std::fclose(f);
    fs::remove(probe, ec);
    return created;
}

}  // namespace gale::app
