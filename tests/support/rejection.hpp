// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// What a call that should be refused threw, for the bad-input and limits tests
// (docs/conventions.md, "Errors").
#pragma once

#include <xeno/error.hpp>

#include <doctest/doctest.h>

#include <exception>
#include <functional>
#include <string>

namespace xeno::test {

/// The message of the InvalidArgument that f throws, "accepted" if it throws nothing, and a note
/// if it throws something else.
inline std::string rejection(const std::function<void()>& f) {
    try {
        f();
    } catch (const InvalidArgument& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("not an InvalidArgument: ") + e.what();
    }
    return "accepted";
}

}  // namespace xeno::test

/// Checks that the expression is rejected with a message containing both fragments (typically the
/// function and the argument).
#define CHECK_REJECTED(expression, where, what)                                            \
    do {                                                                                   \
        const std::string message_ = ::xeno::test::rejection([&] { (void)(expression); }); \
        INFO(#expression << "  ->  " << message_);                                         \
        CHECK(message_.find(where) != std::string::npos);                                  \
        CHECK(message_.find(what) != std::string::npos);                                   \
    } while (false)
