#pragma once
/// \file Interrupt.h
/// SIGINT, SIGTERM and SIGHUP handled alike by every verb that writes (render, solve, terrain;
/// docs/reliability.md). Two modes:
/// - at once (while nothing complete is on disk: reading, building, solving): the handler
///   removes the registered temporaries and lock (app/io/AtomicFile.h), prints the stage's
///   message and exits with 128 + the signal (130, 143, 129);
/// - deferred (while outputs are written): the handler only records the signal; the verb
///   finishes the file in hand, keeps what is complete, writes its report and returns
///   interruptExitCode().

#include <string>

namespace gale::app {

/// Installs the handlers; starts in the "at once" mode with `stage` as the message ("while
/// building the scene: nothing written"). When the scope ends the handlers stay, deferred: a
/// signal after the verb's work is recorded and the process exits with the verb's status.
class InterruptScope {
  public:
    explicit InterruptScope(const char* stage);
    ~InterruptScope();
    InterruptScope(const InterruptScope&) = delete;
    InterruptScope& operator=(const InterruptScope&) = delete;

    /// The "at once" mode with a new message; if a signal came while deferred, acts on it now.
    /// `stage` must outlive the scope (a string literal).
    void exitAtOnce(const char* stage);
    /// The deferred mode: signals are only recorded (see interruptSignal).
    void defer();
};

/// The signal caught while deferred (SIGINT, SIGTERM or SIGHUP), 0 if none.
int interruptSignal();

/// 128 + interruptSignal(): 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP.
int interruptExitCode();

/// "SIGINT", "SIGTERM", "SIGHUP" (or "signal N").
const char* interruptSignalName();

/// For a signal that came after the run's work was complete, while its outputs were moved into
/// place: flushes stdout, says on stderr "gale: interrupted (SIGTERM) while writing; the run had
/// finished and OUTPUT and REPORT are complete" (`report` may be empty) and returns
/// interruptExitCode(). The outputs and report stay those of a complete run.
int reportInterruptedWhileWriting(const std::string& output, const std::string& report);

}  // namespace gale::app
