#pragma once
/// \file OutputFolder.h
/// The folder a render writes into, checked before any frame is drawn.

#include <cstdint>
#include <string>
#include <vector>

namespace gale::app {

struct OutputFolderStatus {
    std::string folder;     ///< as given (relative to the current directory)
    bool exists = false;    ///< false: render will create it (and its missing parents)
    int existingFiles = 0;  ///< files already in it
    std::vector<std::string> staleFrames;  ///< files named like this run's frames, beyond its last
    double freeBytes = -1.0;               ///< space available on its file system, -1 if unknown
};

/// Checks, without creating anything, that `folder` is a folder or can be created: it is not a
/// file, and its nearest existing ancestor is a folder we may write into. `where` names the
/// source of the folder in messages ("knoll.toml:40: output.folder" or "-o"). `prefix` and
/// `frames` find frames of an earlier, longer run. Throws InputError.
OutputFolderStatus checkOutputFolder(const std::string& folder, const std::string& where,
                                     const std::string& prefix, int frames);

/// Creates `folder` (and parents) and proves it writable by creating and removing a file in it.
/// Returns true if it created the folder. Throws InputError naming `where` and the reason.
bool prepareOutputFolder(const std::string& folder, const std::string& where);

/// "<folder>/<prefix>_0007.png".
std::string framePath(const std::string& folder, const std::string& prefix, int frame);

}  // namespace gale::app
