#pragma once
/// \file Progress.h
/// Progress of a long loop on stderr: one updating line (carriage return) on a terminal, one line
/// per step otherwise (logs and CI keep every line).

#include <chrono>
#include <cstdio>
#include <string>

namespace gale::app {

class Progress {
  public:
    /// `label` starts each line ("frame"); `total` steps. `interactive` -1 asks isatty(out).
    Progress(std::string label, int total, std::FILE* out = stderr, int interactive = -1);
    /// Reports that step `done` (1-based) finished and took step_ms milliseconds.
    void step(int done, double step_ms);
    /// Ends the updating line on a terminal. Called by the destructor if not before.
    void finish();
    ~Progress();

    /// "1.2 s", "3 min 05 s", "1 h 02 min".
    static std::string formatDuration(double seconds);

  private:
    std::string mLabel;
    int mTotal;
    std::FILE* mOut;
    bool mInteractive;
    bool mFinished = false;
    double mSum_ms = 0.0;
    int mCount = 0;
    size_t mLastWidth = 0;
};

}  // namespace gale::app
