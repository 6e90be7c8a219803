// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The command line of xeno_render, parsed into a plain struct so that it can be tested without
// running anything. Scripts rely on these names and defaults (see usage()). Every rejected argument
// throws OptionsError whose message names the option and the bad value; main prints it with a hint
// to use --help or --list and exits with status 2.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace xeno::render {

/// A command-line argument that cannot be accepted; what() names it and the bad value.
class OptionsError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Everything the command line can say.
struct Options {
    std::vector<std::string> scenarios;  ///< positional names as given ("all" included); empty = all
    int frames = 0;   ///< images (and state rows) per scenario, frame 0 = initial state; 0 = the scenario's own length
    double fps = 60;  ///< frames per simulated second: each frame steps 1/fps s
    int width = 640, height = 480;  ///< image size in pixels
    bool use_float = false;         ///< --float: World<float>; default double
    std::string out_dir = "out";    ///< frames go to out_dir/<scenario>/frame_0000.png ...
    bool contacts = false;          ///< draw contact points and normals
    double orbit_degrees = 0;       ///< the camera turns this far about +y over the run
    std::string states_path;        ///< CSV of every body's pose per frame; empty = none
    bool images = true;             ///< false with --no-images: no OSMesa context, no files but states
    bool list = false;              ///< --list: print the scenarios and exit
    bool help = false;              ///< --help: print usage and exit
};

/// Parses argv[1 .. argc); options may be given as "--frames 30" or "--frames=30".
/// Throws OptionsError for unknown options, missing or bad values.
Options parse_options(int argc, const char* const* argv);

/// The scenario names to run, in the order given, without repeats: "all" (or no names at all)
/// stands for every available scenario. Throws OptionsError naming the first unknown name.
std::vector<std::string> resolve_scenarios(const std::vector<std::string>& requested, const std::vector<std::string>& available);

/// The --help text, with program as the command name.
std::string usage(const std::string& program);

}  // namespace xeno::render
