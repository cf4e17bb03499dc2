#pragma once
/// \file ParameterErrorCheck.h
/// What the library tests check about errors (docs/architecture.md, "Errors"): a bad scene value
/// throws gale::ParameterError with the scene's dotted key; a broken precondition of the calling
/// code throws std::logic_error, and never a std::invalid_argument (which the program would
/// report as bad input).

#include <gtest/gtest.h>

#include <exception>
#include <functional>
#include <stdexcept>
#include <string>

#include "base/ParameterError.h"

namespace gale::test {

/// Runs `call` and returns the ParameterError it throws; fails the test if it throws nothing or
/// anything else.
inline ParameterError thrownBy(const std::function<void()>& call) {
    try {
        call();
    } catch (const ParameterError& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw something other than a ParameterError: " << e.what();
        return ParameterError("", "", "");
    }
    ADD_FAILURE() << "threw nothing";
    return ParameterError("", "", "");
}

/// Runs `call` and returns the message of the std::logic_error it throws; fails the test if it
/// throws nothing, a std::invalid_argument (ParameterError included) or anything else.
inline std::string logicErrorOf(const std::function<void()>& call) {
    try {
        call();
    } catch (const std::invalid_argument& e) {
        ADD_FAILURE() << "a programming error thrown as bad input: " << e.what();
        return {};
    } catch (const std::logic_error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw something other than a std::logic_error: " << e.what();
        return {};
    }
    ADD_FAILURE() << "threw nothing";
    return {};
}

}  // namespace gale::test
