#pragma once
// Running the gale program as a user does, and watching what it leaves on disk: a child process
// with its own working folder, environment additions and a time limit, whose exit code or signal,
// stdout and stderr are kept apart. Every test executable that runs the program uses this one.

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "TestFiles.h"

namespace gale::test {

namespace fs = std::filesystem;

/// Every path under `folder` (relative to it) with its size; empty if `folder` does not exist.
inline std::map<std::string, uintmax_t> listTree(const std::string& folder) {
    std::map<std::string, uintmax_t> out;
    std::error_code ec;
    if (!fs::exists(folder, ec)) return out;
    for (auto it = fs::recursive_directory_iterator(folder, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const std::string rel = fs::relative(it->path(), folder, ec).string();
        out[rel] = it->is_regular_file(ec) ? it->file_size(ec) : 0;
    }
    return out;
}

inline std::string describeTree(const std::map<std::string, uintmax_t>& tree) {
    std::string s;
    for (const auto& [name, size] : tree) s += "  " + name + " (" + std::to_string(size) + " B)\n";
    return s.empty() ? "  (nothing)\n" : s;
}

/// How a run of the program ended.
struct RunResult {
    int exitCode = -1;  ///< -1 if it did not exit normally
    int signal = 0;     ///< the signal that ended it, 0 if none
    bool timedOut = false;
    std::string out;
    std::string err;
    std::string describe() const {
        std::string s =
            timedOut ? "timed out"
            : signal ? "killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")"
                     : "exit code " + std::to_string(exitCode);
        return s + "\n--- stdout:\n" + out + "--- stderr:\n" + err;
    }
};

struct RunOptions {
    std::string cwd;                                       ///< empty: this process's folder
    std::vector<std::pair<std::string, std::string>> env;  ///< added to (or replacing in) ours
    std::vector<std::string> wrapper;  ///< programs put before gale (e.g. setpriv ...)
    double timeout_s = 300.0;
};

/// A started child process writing its stdout and stderr to files in a private folder.
class Child {
  public:
    Child(const std::vector<std::string>& args, const RunOptions& options) {
        std::vector<std::string> argv = options.wrapper;
        argv.push_back(GALE_EXE);
        argv.insert(argv.end(), args.begin(), args.end());
        mOutPath = mCapture / "out";
        mErrPath = mCapture / "err";
        // The capture folder must be writable by a wrapped child running as another user.
        ::chmod(mCapture.str().c_str(), 0777);
        mPid = ::fork();
        if (mPid == 0) {
            if (!options.cwd.empty() && ::chdir(options.cwd.c_str()) != 0) ::_exit(126);
            for (const auto& [k, v] : options.env) ::setenv(k.c_str(), v.c_str(), 1);
            const int in = ::open("/dev/null", O_RDONLY);
            const int out = ::open(mOutPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
            const int err = ::open(mErrPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
            if (in < 0 || out < 0 || err < 0) ::_exit(126);
            ::dup2(in, 0), ::dup2(out, 1), ::dup2(err, 2);
            std::vector<char*> cargv;
            for (std::string& a : argv) cargv.push_back(a.data());
            cargv.push_back(nullptr);
            ::execvp(cargv[0], cargv.data());
            ::_exit(127);
        }
        mStart = std::chrono::steady_clock::now();
    }
    ~Child() {
        if (mPid > 0 && !mReaped) {
            ::kill(mPid, SIGKILL);
            int status;
            ::waitpid(mPid, &status, 0);
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    pid_t pid() const { return mPid; }
    void signal(int sig) const { ::kill(mPid, sig); }
    std::string errSoFar() const { return readFile(mErrPath); }

    /// Waits for the child to end (killing it after `timeout_s`) and returns how it ended.
    RunResult wait(double timeout_s) {
        RunResult r;
        int status = 0;
        for (;;) {
            const pid_t p = ::waitpid(mPid, &status, WNOHANG);
            if (p == mPid) break;
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
            if (elapsed > timeout_s) {
                ::kill(mPid, SIGKILL);
                ::waitpid(mPid, &status, 0);
                r.timedOut = true;
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        mReaped = true;
        if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
        if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
        r.out = readFile(mOutPath);
        r.err = readFile(mErrPath);
        return r;
    }

  private:
    TempDir mCapture;
    std::string mOutPath, mErrPath;
    pid_t mPid = -1;
    bool mReaped = false;
    std::chrono::steady_clock::time_point mStart;
};

/// Runs gale with `args` to the end.
inline RunResult runGale(const std::vector<std::string>& args, const RunOptions& options = {}) {
    Child child(args, options);
    return child.wait(options.timeout_s);
}

inline int countLines(const std::string& text) {
    int n = 0;
    for (char c : text) n += (c == '\n');
    return n;
}

/// Runs gale with `args` to the end in folder `cwd`.
inline RunResult runGale(const std::vector<std::string>& args, const std::string& cwd) {
    RunOptions options;
    options.cwd = cwd;
    return runGale(args, options);
}

}  // namespace gale::test
