#include "app/io/Progress.h"

#include <unistd.h>

#include <cmath>
#include <string>

namespace gale::app {

Progress::Progress(std::string label, int total, std::FILE* out, int interactive)
    : mLabel(std::move(label)), mTotal(total), mOut(out) {
    mInteractive = interactive < 0 ? ::isatty(::fileno(out)) != 0 : interactive != 0;
}

Progress::~Progress() { finish(); }

std::string Progress::formatDuration(double seconds) {
    char buf[64];
    if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
    if (seconds < 60.0) {
        std::snprintf(buf, sizeof buf, "%.1f s", seconds);
    } else if (seconds < 3600.0) {
        const int s = static_cast<int>(std::lround(seconds));
        std::snprintf(buf, sizeof buf, "%d min %02d s", s / 60, s % 60);
    } else {
        const int m = static_cast<int>(std::lround(seconds / 60.0));
        std::snprintf(buf, sizeof buf, "%d h %02d min", m / 60, m % 60);
    }
    return buf;
}

void Progress::step(int done, double step_ms) {
    mSum_ms += step_ms;
    ++mCount;
    const double mean_ms = mSum_ms / mCount;
    const double eta_s = mean_ms * (mTotal - done) / 1000.0;
    char buf[160];
    const int width = static_cast<int>(std::to_string(mTotal).size());
    std::snprintf(buf, sizeof buf, "%s %*d/%d  %.1f ms/%s  ETA %s", mLabel.c_str(), width, done,
                  mTotal, step_ms, mLabel.c_str(), formatDuration(eta_s).c_str());
    std::string line = buf;
    if (mInteractive) {
        // Pad over the previous, possibly longer, line.
        const size_t length = line.size();
        if (length < mLastWidth) line.append(mLastWidth - length, ' ');
        mLastWidth = length;
        std::fprintf(mOut, "\r%s", line.c_str());
    } else {
        std::fprintf(mOut, "%s\n", line.c_str());
    }
    std::fflush(mOut);
}

void Progress::finish() {
    if (mFinished) return;
    mFinished = true;
    if (mInteractive && mCount > 0) {
        std::fputc('\n', mOut);
        std::fflush(mOut);
    }
}

}  // namespace gale::app
