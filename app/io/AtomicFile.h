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
/// as it was. A stream destination (isStreamOutput: /dev/null, /dev/full, a FIFO) is written in
/// place, every byte checked, and never replaced.
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

    /// The temporary to write `path` to (temporaryPathFor); for a stream destination
    /// (isStreamOutput: /dev/null, a FIFO) `path` itself, written in place and never renamed,
    /// synced or removed.
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
        bool stream = false;  ///< tmp == path: written in place
    };
    std::vector<Entry> mEntries;
};

/// Writes `text` to the staged temporary of `path` (every byte checked, fsync'ed) and seals it.
/// Throws std::runtime_error "PATH: cannot write: REASON" naming `path`, not the temporary.
void writeStagedText(StagedFiles& staged, const std::string& path, const std::string& text);

/// One file a run reads or writes, and what it is for messages: the key or flag it came from and
/// its part ("-o (the .vdb field)", "scene.toml:4: terrain.dem (the DEM)").
struct RunPath {
    std::string path;
    std::string role;
    /// An output that may be a stream: when `path` is a character device, FIFO or socket (e.g.
    /// /dev/null, /dev/stdout) it is written in place as a stream (isStreamOutput) instead of
    /// being replaced. Only for writers that go through StagedFiles or writeTextAtomic (text:
    /// reports, CSV, SVG); outputs whose writer renames its own temporary over the destination
    /// (OpenVDB, GDAL, images) leave it false and a stream destination is refused.
    bool streamable = false;
};

/// Whether `path` (after symbolic links) exists and is a character device, FIFO or socket: an
/// output written as a stream, never replaced. False for regular files, folders, missing paths.
bool isStreamOutput(const std::string& path);

/// The guard of every verb (docs/reliability.md, "Outputs never overwrite inputs"): before any
/// work, resolves every path a run reads and writes to its real file (symbolic links, "..",
/// relative to the current folder, and hard links by device and inode) and throws InputError,
/// naming both paths and the key or flag each came from, when
/// - an output resolves to an input or to another output of the same run:
///   "ROLE: 'PATH' is also ROLE2 ('PATH2'); choose another output path";
/// - an output exists and is read-only (no write permission bit, or not writable by this user):
///   "ROLE: 'PATH' is read-only; gale does not replace it: ...";
/// - an output exists as a device, FIFO or socket and is not `streamable`;
/// - an output exists as a folder.
/// Empty paths are skipped. Streams (isStreamOutput) are not compared with each other (two
/// outputs to /dev/null are fine) but are compared with the inputs. Cheap for many outputs in
/// one folder: each folder is resolved once, each file stat'ed once.
/// @code
///   std::vector<RunPath> inputs = sceneInputs(scene);
///   inputs.push_back({o.pointsPath, "the points file"});
///   for (const std::string& v : o.vdbPaths) inputs.push_back({v, "--vdb"});
///   refuseAliases(inputs, {{o.outPath, "-o (the probe CSV)", /*streamable=*/true}});
/// @endcode
void refuseAliases(const std::vector<RunPath>& inputs, const std::vector<RunPath>& outputs);

/// The sidecar files GDAL reads beside a raster `path` (they may not exist): its .aux.xml, .prj,
/// and world files (.wld, .tfw/.tifw for a .tif, .pgw/.pngw for a .png, .jgw for a .jpg, .aux).
/// Inputs for refuseAliases; outputs of a raster writer that writes them.
std::vector<std::string> rasterSidecars(const std::string& path);

}  // namespace gale::app
