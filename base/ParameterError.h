#pragma once
/// \file ParameterError.h
/// The typed error of library code (sim, coupling, render) for a parameter out of range: it
/// carries the scene's dotted key ("solver.voxel_size_m"), the value and what was expected, so the
/// program can name the scene file and line of that key (app/scene's rethrowAsSceneError) instead
/// of guessing which key a message belongs to. It is a std::invalid_argument, so code that
/// catches those still does.

#include <stdexcept>
#include <string>
#include <utility>

namespace gale {

class ParameterError : public std::invalid_argument {
  public:
    /// what() reads "KEY: EXPECTED (got VALUE)".
    ParameterError(std::string key, std::string value, std::string expected)
        : std::invalid_argument(key + ": " + expected + " (got " + value + ")"),
          mKey(std::move(key)),
          mValue(std::move(value)),
          mExpected(std::move(expected)) {}

    /// The scene's dotted key, e.g. "solver.memory_limit_mb".
    const std::string& key() const { return mKey; }
    /// The offending value as the user would write it (in the key's unit).
    const std::string& value() const { return mValue; }
    /// What the key must be, e.g. "must be > 0".
    const std::string& expected() const { return mExpected; }

  private:
    std::string mKey, mValue, mExpected;
};

}  // namespace gale
