#pragma once
/// \file AtomicFile.h
/// Never a half file, never a lost one (docs/reliability.md): every output is written under a
/// temporary name in its destination's folder, flushed, fsync'ed and checked, and only then
/// renamed over the destination (atomic within one file system), and the folder is fsync'ed so
/// the rename survives a crash. Temporaries are registered so that every exit path this process
/// can catch (an exception, SIGINT/SIGTERM/SIGHUP) removes them; a temporary left by a killed
/// run is recognised by its name (it carries the dead run's PID) and removed by the next run.

#include <string>
#include <vector>

namespace gale::app {

/// A temporary name next to `path` that keeps its extension (so image writers still know the
/// format): "dir/.name.tmp-PID-N.ext". Registered for removal on an abrupt exit (see
/// removeRegisteredTemporaries) until commitTemporary or discardTemporary.
std::string temporaryPathFor(const std::string& path);

/// Checks that the finished temporary `tmpPath` is a non-empty file, fsyncs it, renames it to
/// `path` and fsyncs the folder. On failure removes `tmpPath` and throws std::runtime_error
/// "PATH: cannot write: REASON".
void commitTemporary(const std::string& tmpPath, const std::string& path);

/// fsyncs the non-empty file `tmpPath` (the temporary of `path`, named in the message); on
/// failure removes it and throws std::runtime_error "PATH: cannot write: REASON".
void syncTemporary(const std::string& tmpPath, const std::string& path);

/// Removes a temporary that will not be committed (no error if it is gone) and forgets it.
void discardTemporary(const std::string& tmpPath);

/// Writes `text` to `path` atomically: temporary, write (every byte checked), fsync, close
/// (checked), rename. Throws std::runtime_error "PATH: cannot write: REASON" and leaves `path`
/// as it was.
void writeTextAtomic(const std::string& path, const std::string& text);

/// Registers `path` (a temporary or a lock file) for removal by removeRegisteredTemporaries;
/// at most REGISTERED_PATHS at once (later ones are still removed on exceptions, not on
/// signals).
void registerForRemoval(const std::string& path);
/// Stops tracking `path` (it was committed, or removed).
void unregisterForRemoval(const std::string& path);
/// Unlinks every registered path, and the pending lock (setPendingLock) if it holds this
/// process's PID. Async-signal-safe: the signal handlers call it.
void removeRegisteredTemporaries();
/// A lock file about to be linked into place (OutputLock): between the link and its
/// registration a signal would leave it behind, and registering it before the link would let a
/// signal remove another run's lock. removeRegisteredTemporaries removes it only if it holds
/// this process's PID, i.e. only if the link happened.
void setPendingLock(const std::string& path);
/// Forgets the pending lock (registered, or not ours).
void clearPendingLock();
inline constexpr int REGISTERED_PATHS = 64;

/// Temporaries in `folder` (not below) left by gale runs that are no longer running: names of
/// the form ".NAME.tmp-PID-N[.ext]" or "NAME.tmpPID" whose PID is dead (or reused by a process
/// that is not ours: we cannot tell, so only PIDs that do not exist count). Empty if the folder
/// does not exist.
std::vector<std::string> staleTemporaries(const std::string& folder);

/// Removes staleTemporaries(folder) and says so on stderr (one note). Returns how many.
int removeStaleTemporaries(const std::string& folder);

}  // namespace gale::app

namespace gale::app {

/// The outputs of one run, each written to its own temporary and moved into place together
/// only when all are complete, so a failed run leaves the earlier run's outputs as they were.
/// The destructor removes every temporary not committed (the failure path).
class StagedFiles {
  public:
    StagedFiles() = default;
    ~StagedFiles();
    StagedFiles(const StagedFiles&) = delete;
    StagedFiles& operator=(const StagedFiles&) = delete;

    /// The temporary to write `path` to (temporaryPathFor).
    std::string add(const std::string& path);
    /// The writer has finished the temporary of `path`: checks it is non-empty and fsyncs it
    /// (syncTemporary); returns its size in bytes. Throws std::runtime_error naming `path`.
    double seal(const std::string& path);
    /// Renames every sealed temporary into place in the order added, fsyncs their folders,
    /// and removes the temporaries that were never sealed. Throws std::runtime_error naming
    /// the file whose rename failed (the rest are removed).
    void commit();
    /// Removes every temporary not committed (what the destructor does), now.
    void discard();
    /// Sealed files so far, in the order added.
    std::vector<std::string> sealed() const;

  private:
    struct Entry {
        std::string path, tmp;
        bool sealed = false;
    };
    std::vector<Entry> mEntries;
};

/// Writes `text` to the staged temporary of `path` (every byte checked, fsync'ed) and seals it.
/// Throws std::runtime_error "PATH: cannot write: REASON" naming `path`, not the temporary.
void writeStagedText(StagedFiles& staged, const std::string& path, const std::string& text);

/// One file a run reads or writes, and what it is for messages ("the scene", "-o").
struct RunPath {
    std::string path;
    std::string role;
};

/// Outputs never overwrite inputs or each other (docs/reliability.md): resolves every path
/// (symbolic links, "..", relative to the current folder) and throws InputError "ROLE: 'PATH' is
/// also ROLE2 ('PATH2'); ..." if an output resolves to an input or to another output.
void refuseAliases(const std::vector<RunPath>& inputs, const std::vector<RunPath>& outputs);

}  // namespace gale::app
