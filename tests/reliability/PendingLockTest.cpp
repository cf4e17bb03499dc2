/// \file PendingLockTest.cpp
/// The lock a run is about to link into place (app/io/AtomicFile.h, setPendingLock): a signal's
/// clean-up removes it when the link happened (the file holds this process's PID) and never
/// when it is another run's lock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "TestFiles.h"
#include "app/io/AtomicFile.h"

namespace gale::app {
namespace {

using gale::test::TempDir;
using gale::test::writeFile;
namespace fs = std::filesystem;

TEST(PendingLock, TheSignalCleanUpRemovesItOnlyWhenItHoldsThisProcesssPid) {
    TempDir dir;
    const std::string ours = dir / "ours.lock";
    const std::string theirs = dir / "theirs.lock";
    const std::string empty = dir / "empty.lock";
    writeFile(ours, std::to_string(::getpid()) + "\n");
    // PID 1 is never a gale run's; a longer number that starts with our PID is not ours either.
    writeFile(theirs, "1\n");
    writeFile(empty, "");

    setPendingLock(theirs);
    removeRegisteredTemporaries();
    EXPECT_TRUE(fs::exists(theirs)) << "another run's lock removed";
    writeFile(theirs, std::to_string(::getpid()) + "7\n");
    removeRegisteredTemporaries();
    EXPECT_TRUE(fs::exists(theirs)) << "a lock whose PID only starts with ours removed";

    setPendingLock(empty);
    removeRegisteredTemporaries();
    EXPECT_TRUE(fs::exists(empty)) << "a lock without a PID removed";

    setPendingLock(ours);
    clearPendingLock();
    removeRegisteredTemporaries();
    EXPECT_TRUE(fs::exists(ours)) << "a cleared pending lock still removed";

    setPendingLock(ours);
    removeRegisteredTemporaries();
    EXPECT_FALSE(fs::exists(ours)) << "this run's own pending lock left behind";
    clearPendingLock();
}

}  // namespace
}  // namespace gale::app
