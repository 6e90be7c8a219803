// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// xeno_render: runs scenarios from the registry (scenario.hpp) and renders them off-screen.
//   xeno_render --list
//   xeno_render --frames 120 --out out vertex-face        -> out/vertex-face/frame_0000.png ...
//   xeno_render --no-images --states states.csv all        -> poses only, no GL context
// Per scenario: frame 0 is the initial state; between frames the simulation steps 1/fps seconds;
// the scenario says how long its story takes (scenes::Scene::seconds) unless --frames is given.
// With ffmpeg on PATH the frames also become <scenario>.gif (320 px wide) and <scenario>.mp4.
// Exit status: 0 success, 1 a scenario or an output failed, 2 bad command line (options.hpp).
#include "render/options.hpp"
#include "render/renderer.hpp"
#include "render/scenario.hpp"

#include <xeno/math/scalar.hpp>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace xeno::render;
using Clock = std::chrono::steady_clock;

const char* const program = "xeno_render";

double milliseconds_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// s quoted for /bin/sh.
std::string shell_quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

bool ffmpeg_available() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

/// Makes dir/name.gif (at most 320 px wide, at most 30 frames per second) and dir/name.mp4 from
/// dir/frame_%04d.png; returns false when ffmpeg failed.
bool make_videos(const fs::path& dir, const std::string& name, double fps, int width) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%g", fps);
    const std::string input = "ffmpeg -hide_banner -loglevel error -nostdin -y -framerate " + std::string(rate) + " -i " +
                              shell_quoted((dir / "frame_%04d.png").string());
    // GIF delays are whole hundredths of a second, and browsers slow down delays below 2/100 s.
    const std::string gif_rate = fps > 30 ? "fps=30," : "";
    const std::string gif = input + " -vf " +
                            shell_quoted(gif_rate + "scale=" + std::to_string(std::min(320, width)) +
                                         ":-1:flags=lanczos,split[a][b];[a]palettegen=stats_mode=diff[p];"
                                         "[b][p]paletteuse=dither=bayer:bayer_scale=4") +
                            " -loop 0 " + shell_quoted((dir / (name + ".gif")).string());
    // libx264 with yuv420p needs even dimensions.
    const std::string mp4 = input + " -vf " + shell_quoted("scale=trunc(iw/2)*2:trunc(ih/2)*2") +
                            " -c:v libx264 -preset fast -crf 20 -pix_fmt yuv420p -movflags +faststart " +
                            shell_quoted((dir / (name + ".mp4")).string());
    const bool gif_ok = std::system(gif.c_str()) == 0;
    const bool mp4_ok = std::system(mp4.c_str()) == 0;
    return gif_ok && mp4_ok;
}

/// Deletes frame_NNNN.png left by an earlier, longer run, so the videos hold this run only.
void remove_old_frames(const fs::path& dir) {
    const auto is_frame = [](const std::string& name) {  // frame_NNNN.png, four or more digits
        const std::size_t prefix = 6, suffix = 4;
        return name.size() >= prefix + 4 + suffix && name.compare(0, prefix, "frame_") == 0 &&
               name.compare(name.size() - suffix, suffix, ".png") == 0 &&
               std::all_of(name.begin() + prefix, name.end() - suffix, [](char c) { return c >= '0' && c <= '9'; });
    };
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
        if (is_frame(entry.path().filename().string())) fs::remove(entry.path(), ec);
}

/// One line of stderr per scenario, redrawn in place on a terminal; elsewhere only the last state.
class Progress {
public:
    Progress(std::string name, int total) : name_(std::move(name)), total_(total), live_(isatty(STDERR_FILENO) != 0) {}
    void update(int done) {
        if (live_) draw(done, "");
    }
    void finish(int done, const std::string& summary) {
        draw(done, summary);
        std::fputc('\n', stderr);
        std::fflush(stderr);
    }

private:
    void draw(int done, const std::string& summary) const {
        constexpr int cells = 20;
        const int filled = total_ > 0 ? done * cells / total_ : cells;
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar.append(static_cast<std::size_t>(cells - filled), '.');
        std::fprintf(stderr, "\r[%s] %s %d/%d%s", bar.c_str(), name_.c_str(), done, total_, summary.c_str());
        std::fflush(stderr);
    }
    std::string name_;
    int total_;
    bool live_;
};

struct Run {
    const Options& options;
    Renderer* renderer;  ///< null with --no-images
    std::FILE* states;   ///< null without --states
    bool ffmpeg;
};

void write_states(std::FILE* out, const std::string& scenario, int frame, double time, const std::vector<BodyState>& states,
                  bool use_float) {
    // Enough digits to read every value back exactly in the precision it was simulated in.
    const char* format = use_float ? "%s,%d,%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n"
                                   : "%s,%d,%.9g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n";
    for (const BodyState& s : states)
        std::fprintf(out, format, scenario.c_str(), frame, time, s.body, s.x, s.y, s.z, s.qw, s.qx, s.qy, s.qz);
}

/// Simulates (and renders) one scenario; throws on failure.
void run_scenario(const Run& run, const Scenario& scenario) {
    const Options& o = run.options;
    const fs::path dir = fs::path(o.out_dir) / scenario.name;
    if (run.renderer) {
        fs::create_directories(dir);
        remove_old_frames(dir);
    }
    std::unique_ptr<Simulation> sim = scenario.make(o.use_float);
    if (!sim) throw std::runtime_error("the scenario's factory returned nothing");

    // The scenario's own length (frame 0 is the start, so seconds × fps + 1 frames) unless --frames.
    const int frames = o.frames > 0 ? o.frames : 1 + static_cast<int>(std::lround(sim->seconds() * o.fps));
    Progress progress(scenario.name, frames);
    double step_ms = 0, render_ms = 0, png_ms = 0;
    const double dt = 1.0 / o.fps;
    const double orbit_total = xeno::radians(o.orbit_degrees);
    for (int frame = 0; frame < frames; ++frame) {
        if (frame > 0) {
            const Clock::time_point start = Clock::now();
            sim->step(dt);
            step_ms += milliseconds_since(start);
        }
        if (run.states) write_states(run.states, scenario.name, frame, frame * dt, sim->states(), o.use_float);
        if (run.renderer) {
            Clock::time_point start = Clock::now();
            const double turn = frames > 1 ? orbit_total * frame / (frames - 1) : 0.0;
            run.renderer->begin_frame(orbit(sim->camera(), turn));
            sim->draw(*run.renderer, o.contacts);
            run.renderer->end_frame();
            render_ms += milliseconds_since(start);

            start = Clock::now();
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.png", frame);
            const fs::path file = dir / name;
            if (!run.renderer->write_png(file.string()))
                throw std::runtime_error("cannot write " + file.string() + ": " + std::strerror(errno));
            png_ms += milliseconds_since(start);
        }
        progress.update(frame + 1);
    }

    char summary[160];
    const double n = frames, steps = std::max(1, frames - 1);
    if (run.renderer)
        std::snprintf(summary, sizeof summary, "  render %.1f ms, png %.1f ms, step %.2f ms per frame", render_ms / n, png_ms / n,
                      step_ms / steps);
    else std::snprintf(summary, sizeof summary, "  step %.2f ms per frame", step_ms / steps);
    std::string line = summary;
    if (run.renderer && run.ffmpeg) {
        const Clock::time_point start = Clock::now();
        const bool ok = make_videos(dir, scenario.name, o.fps, o.width);
        char video[64];
        std::snprintf(video, sizeof video, ", %s in %.1f s", ok ? "gif+mp4" : "ffmpeg FAILED", milliseconds_since(start) / 1000);
        line += video;
        progress.finish(frames, line);
        if (!ok) throw std::runtime_error("ffmpeg could not make " + scenario.name + ".gif/.mp4 in " + dir.string());
        return;
    }
    progress.finish(frames, line);
}

int usage_error(const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\nTry '%s --help' for the options or '%s --list' for the scenarios.\n", program,
                 message.c_str(), program, program);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    std::vector<std::string> selected;
    const std::vector<Scenario>& registry = scenarios();
    try {
        options = parse_options(argc, argv);
        if (options.help) {
            std::fputs(usage(program).c_str(), stdout);
            return 0;
        }
        if (options.list) {
            for (const Scenario& s : registry) std::printf("%s  %s\n", s.name.c_str(), s.description.c_str());
            return 0;
        }
        std::vector<std::string> names;
        for (const Scenario& s : registry) names.push_back(s.name);
        selected = resolve_scenarios(options.scenarios, names);
    } catch (const OptionsError& e) {
        return usage_error(e.what());
    }

    std::optional<Renderer> renderer;
    if (options.images) {
        try {
            renderer.emplace(options.width, options.height);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: error: %s\n", program, e.what());
            return 1;
        }
    }
    std::FILE* states = nullptr;
    if (!options.states_path.empty()) {
        const fs::path parent = fs::path(options.states_path).parent_path();
        std::error_code ec;
        if (!parent.empty()) fs::create_directories(parent, ec);
        states = std::fopen(options.states_path.c_str(), "w");
        if (!states) {
            std::fprintf(stderr, "%s: error: cannot write --states file '%s': %s\n", program, options.states_path.c_str(),
                         std::strerror(errno));
            return 1;
        }
        std::fputs("scenario,frame,time,body,x,y,z,qw,qx,qy,qz\n", states);
    }

    const Run run{options, renderer ? &*renderer : nullptr, states, renderer && ffmpeg_available()};
    int status = 0;
    for (const std::string& name : selected) {
        const auto it = std::find_if(registry.begin(), registry.end(), [&](const Scenario& s) { return s.name == name; });
        try {
            run_scenario(run, *it);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "\n%s: scenario '%s' failed: %s\n", program, name.c_str(), e.what());
            status = 1;
        }
    }
    if (states && std::fclose(states) != 0) {
        std::fprintf(stderr, "%s: error: writing '%s' failed\n", program, options.states_path.c_str());
        status = 1;
    }
    return status;
}
