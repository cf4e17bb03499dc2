#pragma once
/// \file ParameterError.h
/// The typed error of library code (sim, coupling, render) for a parameter out of range: it
/// carries the scene's dotted key ("solver.voxel_size_m"), the value and what was expected, so the
/// program can name the scene file and line of that key (app/scene's rethrowAsSceneError) instead
/// of guessing which key a message belongs to. It is a std::invalid_argument, so code that
/// catches those still does.

#include <cstddef>
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

    /// The same error about element `index` of the array of tables `arrayKey`: an element's
    /// validate() knows its key ("wind.gusts.peak_mps") but not its place, which the caller adds
    /// ("wind.gusts[2].peak_mps"). A key outside `arrayKey` comes back unchanged.
    ParameterError inElement(const std::string& arrayKey, size_t index) const {
        const std::string prefix = arrayKey + ".";
        if (mKey.compare(0, prefix.size(), prefix) != 0) return *this;
        return ParameterError(
            arrayKey + "[" + std::to_string(index) + "]." + mKey.substr(prefix.size()), mValue,
            mExpected);
    }

  private:
    std::string mKey, mValue, mExpected;
};

}  // namespace gale
