// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_render's command line (options.hpp): a hand-written loop over argv, strict about values
// (the whole text must parse, numbers must be finite and in range) so that a script's typo stops
// the run with a message instead of rendering something else.
#include "render/options.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace xeno::render {

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

/// A whole number in [low, high], the whole text.
int parse_int(const std::string& option, const std::string& text, int low, int high) {
    const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    errno = 0;
    const long value = digits ? std::strtol(text.c_str(), nullptr, 10) : 0;
    if (!digits || errno == ERANGE || value < low || value > high)
        throw OptionsError(option + ": " + quoted(text) + " is not a whole number in " + std::to_string(low) + ".." +
                           std::to_string(high));
    return static_cast<int>(value);
}

/// A finite decimal number, the whole text; positive when asked.
double parse_double(const std::string& option, const std::string& text, bool positive) {
    char* end = nullptr;
    errno = 0;
    const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    const bool ok = !text.empty() && end && *end == '\0' && errno != ERANGE && std::isfinite(value) && (!positive || value > 0);
    if (!ok) throw OptionsError(option + ": " + quoted(text) + " is not a " + (positive ? "positive " : "") + "finite number");
    return value;
}

/// WxH, each side in 16..16384.
void parse_size(const std::string& text, int& width, int& height) {
    const std::size_t x = text.find_first_of("xX");
    if (x == std::string::npos || x == 0 || x + 1 == text.size())
        throw OptionsError("--size: " + quoted(text) + " is not WIDTHxHEIGHT (e.g. 640x480)");
    try {
        width = parse_int("--size", text.substr(0, x), 16, 16384);
        height = parse_int("--size", text.substr(x + 1), 16, 16384);
    } catch (const OptionsError&) {
        throw OptionsError("--size: " + quoted(text) + " is not WIDTHxHEIGHT with each side in 16..16384 (e.g. 640x480)");
    }
}

}  // namespace

Options parse_options(int argc, const char* const* argv) {
    Options o;
    bool only_positional = false;  // after "--"
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (only_positional || arg.empty() || arg[0] != '-' || arg == "-") {
            o.scenarios.push_back(arg);
            continue;
        }
        if (arg == "--") {
            only_positional = true;
            continue;
        }
        // "--name=value" or "--name value".
        std::string value;
        bool has_inline_value = false;
        if (const std::size_t eq = arg.find('='); eq != std::string::npos && arg.rfind("--", 0) == 0) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
            has_inline_value = true;
        }
        const auto take_value = [&]() -> std::string {
            if (has_inline_value) return value;
            if (i + 1 >= argc) throw OptionsError(arg + ": needs a value");
            return argv[++i];
        };
        const auto no_value = [&]() {
            if (has_inline_value) throw OptionsError(arg + ": takes no value, got " + quoted(value));
        };

        if (arg == "--help" || arg == "-h") {
            no_value();
            o.help = true;
        } else if (arg == "--list") {
            no_value();
            o.list = true;
        } else if (arg == "--frames") {
            o.frames = parse_int(arg, take_value(), 1, 1000000);
        } else if (arg == "--fps") {
            o.fps = parse_double(arg, take_value(), true);
        } else if (arg == "--size") {
            parse_size(take_value(), o.width, o.height);
        } else if (arg == "--float") {
            no_value();
            o.use_float = true;
        } else if (arg == "--double") {
            no_value();
            o.use_float = false;
        } else if (arg == "--out") {
            o.out_dir = take_value();
            if (o.out_dir.empty()) throw OptionsError("--out: the directory name is empty");
        } else if (arg == "--contacts") {
            no_value();
            o.contacts = true;
        } else if (arg == "--orbit") {
            o.orbit_degrees = parse_double(arg, take_value(), false);
        } else if (arg == "--states") {
            o.states_path = take_value();
            if (o.states_path.empty()) throw OptionsError("--states: the file name is empty");
        } else if (arg == "--no-images") {
            no_value();
            o.images = false;
        } else {
            throw OptionsError("unknown option " + quoted(arg));
        }
    }
    return o;
}

std::vector<std::string> resolve_scenarios(const std::vector<std::string>& requested, const std::vector<std::string>& available) {
    std::vector<std::string> out;
    const auto add = [&](const std::string& name) {
        if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    };
    if (requested.empty())
        for (const std::string& name : available) add(name);
    for (const std::string& name : requested) {
        if (name == "all") {
            for (const std::string& a : available) add(a);
        } else if (std::find(available.begin(), available.end(), name) != available.end()) {
            add(name);
        } else {
            throw OptionsError("unknown scenario " + quoted(name));
        }
    }
    return out;
}

std::string usage(const std::string& program) {
    return "usage: " + program +
           " [options] [scenario ...|all]\n"
           "\n"
           "Simulates each scenario and renders it off-screen (OSMesa) to\n"
           "DIR/<scenario>/frame_0000.png ...; with ffmpeg on PATH also <scenario>.gif and .mp4.\n"
           "No scenario names (or 'all') runs every scenario.\n"
           "\n"
           "options:\n"
           "  --list           print the scenarios (name, two spaces, description) and exit\n"
           "  --frames N       frames per scenario, frame 0 is the initial state (default: the\n"
           "                   scenario's own length, seconds x fps + 1, e.g. 5.3 s for dominoes)\n"
           "  --fps F          frames per simulated second; each frame steps 1/F s (default 60)\n"
           "  --size WxH       image size in pixels (default 640x480)\n"
           "  --float          simulate in single precision\n"
           "  --double         simulate in double precision (default)\n"
           "  --out DIR        output directory (default out)\n"
           "  --contacts       draw contact points and normals\n"
           "  --orbit DEG      turn the camera this many degrees about +y over the run (default 0)\n"
           "  --states FILE    write every body's pose per frame as CSV:\n"
           "                   scenario,frame,time,body,x,y,z,qw,qx,qy,qz\n"
           "  --no-images      simulate (and write --states) without rendering anything\n"
           "  --help           print this help and exit\n"
           "\n"
           "Options also accept --name=value. Exit status: 0 success, 1 a scenario failed, 2 bad arguments.\n";
}

}  // namespace xeno::render
