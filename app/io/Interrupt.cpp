#include "app/io/Interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

#include "app/io/AtomicFile.h"

namespace gale::app {
namespace {

constexpr int SIGNALS[] = {SIGINT, SIGTERM, SIGHUP};
volatile sig_atomic_t gSignal = 0;
volatile sig_atomic_t gDeferred = 0;
const char* volatile gStage = "";

void say(const char* text) { (void)!::write(STDERR_FILENO, text, std::strlen(text)); }

const char* nameOf(int sig) {
    switch (sig) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        default:
            return "a signal";
    }
}

/// Everything here is async-signal-safe: unlink, write, _exit.
[[noreturn]] void exitNow(int sig) {
    removeRegisteredTemporaries();
    say("gale: interrupted (");
    say(nameOf(sig));
    say(") ");
    say(gStage);
    say("\n");
    ::_exit(128 + sig);
}

extern "C" void onSignal(int sig) {
    if (gSignal == 0) gSignal = sig;
    if (!gDeferred) exitNow(sig);
}

}  // namespace

InterruptScope::InterruptScope(const char* stage) {
    gSignal = 0;
    gStage = stage;
    gDeferred = 0;
    struct sigaction sa {};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    for (int s : SIGNALS) sigaddset(&sa.sa_mask, s);  // one handler at a time
    for (int s : SIGNALS) sigaction(s, &sa, nullptr);
}

InterruptScope::~InterruptScope() {
    // The verb is done and its outputs are in place. A signal from here until the process exits
    // is only recorded, so the exit status stays the verb's: the default action, restored here,
    // would kill a finished run (status 143 and no message) in the moment before it exits.
    gDeferred = 1;
}

void InterruptScope::exitAtOnce(const char* stage) {
    gStage = stage;
    gDeferred = 0;
    if (gSignal != 0) exitNow(gSignal);
}

void InterruptScope::defer() { gDeferred = 1; }

int interruptSignal() { return gSignal; }

int interruptExitCode() { return gSignal == 0 ? 0 : 128 + gSignal; }

const char* interruptSignalName() { return nameOf(gSignal); }

int reportInterruptedWhileWriting(const std::string& output, const std::string& report) {
    std::string files = output;
    if (!files.empty() && !report.empty()) files += " and ";
    files += report;
    std::fflush(stdout);
    std::fprintf(stderr, "gale: interrupted (%s) while writing; the run had finished%s%s%s\n",
                 interruptSignalName(), files.empty() ? "" : " and ", files.c_str(),
                 files.empty() ? "" : " are complete");
    return interruptExitCode();
}

}  // namespace gale::app
