#pragma once
/// \file Errors.h
/// The exceptions and exit codes of the command-line layer. `main` alone catches: an InputError
/// (bad scene, image, arguments or output folder) exits with code 2, anything else with code 1.
/// A run that worked but did not reach its goal (a solve that did not converge, a benchmark that
/// missed its target) is not an exception: its verb returns EXIT_UNMET.

#include <stdexcept>
#include <string>

namespace gale::app {

/// Exit codes of every verb (README, docs/cli.md and each --help say the same).
inline constexpr int EXIT_OK = 0;
inline constexpr int EXIT_FAILURE_INTERNAL = 1;  ///< a runtime failure: I/O, GL context, memory
inline constexpr int EXIT_BAD_INPUT = 2;         ///< scene, image, arguments, output folder
/// The run completed and wrote its outputs, but did not converge or missed its stated target.
inline constexpr int EXIT_UNMET = 3;
/// Ctrl-C (128 + SIGINT); SIGTERM and SIGHUP exit 143 and 129 (128 + the signal,
/// app/io/Interrupt.h).
inline constexpr int EXIT_INTERRUPTED = 130;

/// Bad input from the user: the message is complete and printed as it is, on one line.
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A scene file error: `FILE:LINE: section.key: reason (got VALUE)`, or `FILE:LINE:COL: reason`
/// for TOML syntax errors.
class SceneError : public InputError {
  public:
    using InputError::InputError;
};

/// An image that cannot serve as a heightmap or grass texture: `PATH: reason`.
class ImageError : public InputError {
  public:
    using InputError::InputError;
};

}  // namespace gale::app
