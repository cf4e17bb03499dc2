#pragma once
/// \file TestFiles.h
/// Files and folders for tests that run the gale program: a self-removing temporary folder and
/// whole-file reads and writes. Shared by app_tests and reliability_tests.

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace gale::test {

namespace fs = std::filesystem;

/// A new empty folder under the system temp folder, removed with everything in it at scope end.
class TempDir {
  public:
    TempDir() {
        static std::atomic<int> counter{0};
        mPath = fs::temp_directory_path() /
                ("gale_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        fs::remove_all(mPath);
        fs::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ec;
        // Folders a test made read-only must become writable again to be removed.
        for (auto it = fs::recursive_directory_iterator(mPath, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
            if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, ec);
        fs::permissions(mPath, fs::perms::owner_all, ec);
        fs::remove_all(mPath, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return mPath; }
    std::string str() const { return mPath.string(); }
    std::string operator/(const std::string& name) const { return (mPath / name).string(); }

  private:
    fs::path mPath;
};

inline std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

inline std::string sourcePath(const std::string& relative) {
    return (fs::path(GALE_SOURCE_DIR) / relative).string();
}

}  // namespace gale::test
