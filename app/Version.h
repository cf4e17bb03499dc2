#pragma once
/// \file Version.h
/// The program's version, as printed by `gale --version` and written into run reports. Keep in step
/// with project(VERSION) in the top-level CMakeLists.txt.

namespace gale::app {
inline constexpr const char* GALE_VERSION = "0.1.0";
}  // namespace gale::app
