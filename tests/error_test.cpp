// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <xeno/shape/box.hpp>

#include <string>

using namespace xeno;

TEST_CASE_TEMPLATE("a rejected argument throws InvalidArgument naming argument and value", T, float, double) {
    CHECK_THROWS_AS(Box<T>(T(-1), T(1), T(1)), InvalidArgument);
    CHECK_THROWS_AS(Box<T>(T(1), T(0), T(1)), std::invalid_argument);
    try {
        Box<T> b(T(1), T(1), std::numeric_limits<T>::quiet_NaN());
        FAIL("no exception");
    } catch (const InvalidArgument& e) {
        const std::string what = e.what();
        CHECK(what.find("Box") != std::string::npos);
        CHECK(what.find("half_extents.z") != std::string::npos);
        CHECK(what.find("nan") != std::string::npos);
    }
}

TEST_CASE("set_error_handler returns the previous handler and nullptr restores the default") {
    auto custom = [](const char*) { std::abort(); };
    ErrorHandler original = set_error_handler(custom);
    CHECK((original != nullptr));
    CHECK((set_error_handler(nullptr) == static_cast<ErrorHandler>(custom)));
    CHECK((set_error_handler(original) == original));
}
