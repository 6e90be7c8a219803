// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// An off-screen OpenGL renderer for the examples: OSMesa (Mesa's llvmpipe, no display, no GPU)
// draws lit, flat-shaded triangles, lines and point markers over a sky gradient and a ground grid
// on y = 0, into a 4x multisampled framebuffer that is resolved into a CPU buffer each frame and
// can be written as PNG. World units are metres, y is up (docs/conventions.md, "Units and axes").
//
// One frame:  begin_frame(camera)  -> clears, draws sky and ground
//             draw_triangle/line/point ... -> appended to per-type batches (no GL calls)
//             end_frame()          -> one buffer upload and one draw call per batch, MSAA resolve,
//                                     glFinish; pixels() then holds the image, top row first.
// Triangles are lit by their geometric normal (counter-clockwise seen from the front), one
// directional light plus a sky/ground ambient term; lines and points are unlit. Lines win depth
// ties against triangles (the filled geometry is pushed back by a polygon offset) so body edges stay
// visible. Points are round camera-facing discs, drawn again faintly through whatever hides them.
//
// Only this file's .cpp includes the OSMesa and GL headers. DebugDraw<T> output (draw_shape, a
// world's debug drawing) reaches a Renderer through DrawAdapter<T> for T = float or double.
#pragma once

#include <xeno/debug_draw.hpp>
#include <xeno/math/vec3.hpp>

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace xeno::render {

/// A perspective camera looking from position at target; y up unless `up` says otherwise.
struct Camera {
    f64::Vec3 position{6, 4, 8};    ///< metres, world frame
    f64::Vec3 target{0, 0.5, 0};    ///< metres: the point at the image centre
    f64::Vec3 up{0, 1, 0};          ///< world direction shown as up in the image (need not be unit)
    double fov_y_degrees = 45;      ///< vertical field of view
    double near = 0.05, far = 500;  ///< clip distances in metres, 0 < near < far
};

/// The camera with its position turned about the target by angle (radians, right-handed about +y).
Camera orbit(const Camera& camera, double angle_radians);

/// Off-screen OpenGL renderer on an OSMesa context (see the file comment). Non-copyable.
class Renderer {
public:
    /// Creates a width × height RGBA context (core profile 3.3, else the legacy context) and a
    /// 4x MSAA framebuffer. Throws std::runtime_error when OSMesa or the framebuffer fails, or when
    /// a size is outside [1, 16384].
    Renderer(int width, int height);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    int width() const;
    int height() const;

    /// Starts a frame seen by camera: clears to the sky gradient, draws the ground grid on y = 0,
    /// empties the batches. Throws std::invalid_argument for a degenerate camera (position equal
    /// to target, non-finite values, near/far not 0 < near < far, fov outside (0, 180)).
    void begin_frame(const Camera& camera);
    /// A filled triangle, counter-clockwise seen from the front, lit by its own normal; colour
    /// alpha < 1 draws it translucent (after the opaque ones, unsorted).
    void draw_triangle(const f32::Vec3& a, const f32::Vec3& b, const f32::Vec3& c, Color color);
    /// A line segment (edges, normals), unlit, drawn over coincident faces.
    void draw_line(const f32::Vec3& a, const f32::Vec3& b, Color color);
    /// A round marker of diameter size (metres) facing the camera (contact points).
    void draw_point(const f32::Vec3& p, float size, Color color);
    /// The same calls in double precision (converted to float); braced lists pick the float ones.
    template <class T, class = std::enable_if_t<std::is_same_v<T, double>>>
    void draw_triangle(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, Color color) {
        draw_triangle(f32::Vec3(a), f32::Vec3(b), f32::Vec3(c), color);
    }
    template <class T, class = std::enable_if_t<std::is_same_v<T, double>>>
    void draw_line(const Vec3<T>& a, const Vec3<T>& b, Color color) {
        draw_line(f32::Vec3(a), f32::Vec3(b), color);
    }
    template <class T, class = std::enable_if_t<std::is_same_v<T, double>>>
    void draw_point(const Vec3<T>& p, T size, Color color) {
        draw_point(f32::Vec3(p), static_cast<float>(size), color);
    }
    /// Draws the batches, resolves the multisampled image and waits for it: pixels() is ready.
    void end_frame();

    /// The last finished frame: width × height RGBA bytes, rows from the top of the image down.
    const std::vector<unsigned char>& pixels() const;
    /// Writes the last frame as an 8-bit RGB PNG (fast zlib level); false if the file can't be written.
    bool write_png(const std::string& path) const;
    /// World point → (pixel x from the left, pixel y from the top, window depth in [0, 1]) with the
    /// camera of the current (or last) frame; pixel centres are at .5. Depth outside [0, 1] or a
    /// point behind the camera means it is not visible.
    f64::Vec3 project(const f64::Vec3& world) const;

    /// Number of triangles, lines and points drawn in the last frame (for statistics).
    std::size_t triangle_count() const;
    std::size_t line_count() const;
    std::size_t point_count() const;
    /// The GL_VERSION and GL_RENDERER strings of the context, e.g. "4.5 (Core Profile) Mesa 22.3.6".
    std::string gl_description() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Forwards a DebugDraw<T> (draw_shape, a world's debug drawing) to a Renderer, in float.
template <class T>
class DrawAdapter : public DebugDraw<T> {
public:
    explicit DrawAdapter(Renderer& out) : out_(out) {}
    void draw_triangle(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c, Color color) override {
        out_.draw_triangle(f32::Vec3(a), f32::Vec3(b), f32::Vec3(c), color);
    }
    void draw_line(const Vec3<T>& a, const Vec3<T>& b, Color color) override {
        out_.draw_line(f32::Vec3(a), f32::Vec3(b), color);
    }
    void draw_point(const Vec3<T>& p, T size, Color color) override {
        out_.draw_point(f32::Vec3(p), static_cast<float>(size), color);
    }

private:
    Renderer& out_;
};

}  // namespace xeno::render
