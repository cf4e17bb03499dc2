#pragma once
/// \file Errors.h
/// The exceptions of the command-line layer. `main` alone catches them: an InputError (bad scene,
/// image, arguments or output folder) exits with code 2, anything else with code 1.

#include <stdexcept>
#include <string>

namespace gale::app {

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
