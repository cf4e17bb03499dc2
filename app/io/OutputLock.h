#pragma once
/// \file OutputLock.h
/// One run per output folder at a time (docs/reliability.md): FOLDER/.gale.lock holds the
/// owner's PID while a render, solve or terrain export writes there.

#include <string>

namespace gale::app {

/// Takes the lock of `folder` (which must exist) for its lifetime. A lock whose PID is running
/// refuses the run: throws InputError "WHERE: 'FOLDER' is in use by another gale run (PID N,
/// FOLDER/.gale.lock) ...". A lock whose PID is gone (a killed run) is taken over with a note
/// on stderr. The lock file is registered for removal on signals (app/io/Interrupt.h).
class OutputLock {
  public:
    OutputLock(const std::string& folder, const std::string& where);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

    /// "FOLDER/.gale.lock".
    static std::string pathFor(const std::string& folder);

  private:
    std::string mPath;
};

}  // namespace gale::app
