// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// How xeno reports bad input, once for the whole library (docs/conventions.md, "Errors").
//
// Every public entry point that takes user data (shape builders, body creation, settings,
// World::step) checks it before use. A rejected value throws xeno::InvalidArgument, derived from
// std::invalid_argument, whose message names the function, the argument and the value, e.g.
//     xeno: Box: half_extents.x must be finite and > 0 (got -1)
// Built without exceptions (-fno-exceptions) the same checks call the error handler instead; the
// default handler prints the message to stderr and aborts. A replacement handler must not return
// (it may exit, longjmp to a recovery point, or abort); if it returns, xeno aborts.
// Inner loops never re-check: they rely on what was accepted at the door.
#pragma once

#include "config.hpp"
#include "math/scalar.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace xeno {

/// The one exception type xeno throws: a rejected argument; what() names argument and value.
class InvalidArgument : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

/// Called with the message when exceptions are off; must not return.
using ErrorHandler = void (*)(const char* message);

namespace detail {

inline void default_error_handler(const char* message) {
    std::fprintf(stderr, "%s\n", message);
    std::abort();
}

inline ErrorHandler& error_handler_slot() {
    static ErrorHandler handler = &default_error_handler;
    return handler;
}

}  // namespace detail

/// Installs the handler used when xeno is built without exceptions; returns the previous one.
/// Passing nullptr restores the default (print and abort).
inline ErrorHandler set_error_handler(ErrorHandler handler) {
    ErrorHandler previous = detail::error_handler_slot();
    detail::error_handler_slot() = handler ? handler : &detail::default_error_handler;
    return previous;
}

namespace detail {

/// Reports a rejected input: throws InvalidArgument, or calls the handler without exceptions.
[[noreturn]] inline void report_invalid(const std::string& message) {
#if XENO_HAS_EXCEPTIONS
    throw InvalidArgument(message);
#else
    error_handler_slot()(message.c_str());
    std::abort();  // a handler that returns would let invalid data into the library
#endif
}

/// Formats a number for an error message with enough digits to see what went wrong.
inline std::string format_value(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9g", value);
    return buffer;
}

/// "xeno: <where>: <what> (got <value>)".
[[noreturn]] inline void report_invalid(const char* where, const char* what, double value) {
    report_invalid(std::string("xeno: ") + where + ": " + what + " (got " + format_value(value) +
                   ")");
}

/// Rejects a non-finite value.
template <class T>
void require_finite(T value, const char* where, const char* what) {
    if (!std::isfinite(value))
        report_invalid(where, (std::string(what) + " must be finite").c_str(),
                       static_cast<double>(value));
}

/// Rejects a value that is not finite and strictly positive.
template <class T>
void require_positive(T value, const char* where, const char* what) {
    if (!(std::isfinite(value) && value > T(0)))
        report_invalid(where, (std::string(what) + " must be finite and > 0").c_str(),
                       static_cast<double>(value));
}

/// Rejects a value that is not finite and >= 0.
template <class T>
void require_non_negative(T value, const char* where, const char* what) {
    if (!(std::isfinite(value) && value >= T(0)))
        report_invalid(where, (std::string(what) + " must be finite and >= 0").c_str(),
                       static_cast<double>(value));
}

/// Rejects a shape size (metres) that is not finite and > 0, or outside
/// [ScalarTraits<T>::min_size, max_size].
template <class T>
void require_size(T value, const char* where, const char* what) {
    require_positive(value, where, what);
    if (value < ScalarTraits<T>::min_size || value > ScalarTraits<T>::max_size)
        report_invalid(where, (std::string(what) + " must be within [" + format_value(ScalarTraits<T>::min_size) + ", " +
                               format_value(ScalarTraits<T>::max_size) + "] m in this precision")
                                  .c_str(),
                       static_cast<double>(value));
}

}  // namespace detail
}  // namespace xeno
