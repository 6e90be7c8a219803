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
    report_invalid(std::string("xeno: ") + where + ": " + what + " (got " + format_value(value) + ")");
}

/// Rejects a non-finite value.
template <class T>
void require_finite(T value, const char* where, const char* what) {
    if (!std::isfinite(value)) report_invalid(where, (std::string(what) + " must be finite").c_str(), static_cast<double>(value));
}

/// Rejects a value that is not finite and strictly positive.
template <class T>
void require_positive(T value, const char* where, const char* what) {
    if (!(std::isfinite(value) && value > T(0)))
        report_invalid(where, (std::string(what) + " must be finite and > 0").c_str(), static_cast<double>(value));
}

/// Rejects a value that is not finite and >= 0.
template <class T>
void require_non_negative(T value, const char* where, const char* what) {
    if (!(std::isfinite(value) && value >= T(0)))
        report_invalid(where, (std::string(what) + " must be finite and >= 0").c_str(), static_cast<double>(value));
}

/// Rejects a shape size (metres) that is not finite and > 0, or outside
/// [ScalarTraits<T>::min_size, max_size].
template <class T>
void require_size(T value, const char* where, const char* what) {
    require_positive(value, where, what);
    if (value < ScalarTraits<T>::min_size || value > ScalarTraits<T>::max_size)
        report_invalid(where,
                       (std::string(what) + " must be within [" + format_value(ScalarTraits<T>::min_size) + ", " +
                        format_value(ScalarTraits<T>::max_size) + "] m in this precision")
                           .c_str(),
                       static_cast<double>(value));
}

/// Rejects a value that is not finite or whose magnitude exceeds `limit` (a documented range
/// such as ScalarTraits<T>::max_size); `unit` is appended to the limit in the message.
template <class T>
void require_at_most(T value, T limit, const char* where, const char* what, const char* unit = "") {
    if (!(std::isfinite(value) && std::abs(value) <= limit))
        report_invalid(
            where,
            (std::string(what) + " must be finite and within +-" + format_value(static_cast<double>(limit)) + unit).c_str(),
            static_cast<double>(value));
}

/// Rejects an integer count outside [low, high].
inline void require_count(int value, int low, int high, const char* where, const char* what) {
    if (value < low || value > high)
        report_invalid(
            where, (std::string(what) + " must be within [" + std::to_string(low) + ", " + std::to_string(high) + "]").c_str(),
            static_cast<double>(value));
}

/// Rejects a vector with a non-finite component, naming the first one: "position.y must be
/// finite (got nan)". Works for any type with x, y, z members (Vec3<T>).
template <class V>
void require_finite_xyz(const V& v, const char* where, const char* what) {
    const char* names[3] = {".x", ".y", ".z"};
    const decltype(v.x) values[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(values[i]))
            report_invalid(where, (std::string(what) + names[i] + " must be finite").c_str(), static_cast<double>(values[i]));
}

/// Rejects a vector whose components are not all finite and within +-limit, naming the first
/// bad one.
template <class V, class T>
void require_within_xyz(const V& v, T limit, const char* where, const char* what, const char* unit = "") {
    const char* names[3] = {".x", ".y", ".z"};
    const decltype(v.x) values[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; ++i) require_at_most(values[i], limit, where, (std::string(what) + names[i]).c_str(), unit);
}

/// Rejects an orientation quaternion (w, x, y, z members) with a non-finite component (naming
/// the first) or with every component zero. Any other quaternion is a rotation once normalised.
template <class Q>
void require_orientation(const Q& q, const char* where, const char* what) {
    const char* names[4] = {".w", ".x", ".y", ".z"};
    const decltype(q.w) values[4] = {q.w, q.x, q.y, q.z};
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(values[i]))
            report_invalid(where, (std::string(what) + names[i] + " must be finite").c_str(), static_cast<double>(values[i]));
    using S = decltype(q.w);
    if (q.w == S(0) && q.x == S(0) && q.y == S(0) && q.z == S(0))
        report_invalid(where, (std::string(what) + " must not be the zero quaternion; w").c_str(), static_cast<double>(q.w));
}

}  // namespace detail
}  // namespace xeno
