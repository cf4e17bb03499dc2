#pragma once
// The reliability tests' view of the program: tests/GaleProcess.h runs it.

#include "GaleProcess.h"

namespace gale::reliability {

namespace fs = std::filesystem;

using gale::test::Child;
using gale::test::RunOptions;
using gale::test::RunResult;
using gale::test::TempDir;
using gale::test::countLines;
using gale::test::describeTree;
using gale::test::listTree;
using gale::test::readFile;
using gale::test::runGale;
using gale::test::sourcePath;
using gale::test::writeFile;

}  // namespace gale::reliability
