// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// The OSMesa renderer (renderer.hpp). Facts it relies on (docs/tooling.md, "OSMesa"):
//  - OSMesaCreateContextAttribs with a 3.3 core profile gives llvmpipe's 4.5 core context; the
//    legacy OSMesaCreateContextExt gives 4.5 compatibility, where the same #version 330 shaders
//    and VAOs work, so it is a usable fallback.
//  - OSMesa's own framebuffer has no multisampling, llvmpipe's FBOs do (up to 4 samples): draw
//    into a 4x FBO, blit to framebuffer 0.
//  - OSMesa copies into the client buffer only when glFinish runs with framebuffer 0 bound: the
//    frame ends with the blit, then glFinish, and the MSAA FBO is bound again at the next frame.
//  - OSMESA_Y_UP = 0 makes row 0 of the buffer the top of the image, as PNG wants.
// Camera matrices are built in double (OpenGL conventions: right-handed view space looking down
// -z, clip z in [-w, w]) and sent to GL as float; project() uses the double ones.
#include "render/renderer.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <stdexcept>

namespace xeno::render {

namespace {

/// A 4×4 matrix, column-major as OpenGL reads it: m[column * 4 + row].
using Mat4d = std::array<double, 16>;

Mat4d multiply(const Mat4d& a, const Mat4d& b) {
    Mat4d r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += a[static_cast<std::size_t>(k * 4 + row)] * b[static_cast<std::size_t>(c * 4 + k)];
            r[static_cast<std::size_t>(c * 4 + row)] = sum;
        }
    return r;
}

std::array<float, 16> to_float(const Mat4d& m) {
    std::array<float, 16> r{};
    for (std::size_t i = 0; i < 16; ++i) r[i] = static_cast<float>(m[i]);
    return r;
}

/// Orthonormal camera basis: right, up, forward (towards the target).
struct CameraBasis {
    f64::Vec3 right, up, forward;
};

CameraBasis camera_basis(const Camera& camera) {
    const f64::Vec3 forward = normalized(camera.target - camera.position);
    f64::Vec3 right = cross(forward, camera.up);
    // Degenerate case: up parallel to the view direction; any perpendicular will do.
    if (length_squared(right) < 1e-12 * std::max(1.0, length_squared(camera.up))) right = any_perpendicular(forward);
    right = normalized(right);
    return {right, cross(right, forward), forward};
}

/// The view matrix (world → eye; eye looks down -z) of gluLookAt.
Mat4d view_matrix(const Camera& camera, const CameraBasis& b) {
    const f64::Vec3& p = camera.position;
    return {b.right.x,        b.up.x,        -b.forward.x,      0,  //
            b.right.y,        b.up.y,        -b.forward.y,      0,  //
            b.right.z,        b.up.z,        -b.forward.z,      0,  //
            -dot(b.right, p), -dot(b.up, p), dot(b.forward, p), 1};
}

/// gluPerspective: vertical field of view, aspect = width / height.
Mat4d projection_matrix(const Camera& camera, double aspect) {
    const double f = 1.0 / std::tan(radians(camera.fov_y_degrees) / 2);
    const double n = camera.near, fa = camera.far;
    return {f / aspect, 0, 0,
            0,  //
            0,          f, 0,
            0,  //
            0,          0, (fa + n) / (n - fa),
            -1,  //
            0,          0, 2 * fa * n / (n - fa),
            0};
}

void validate(const Camera& camera) {
    const bool finite = is_finite(camera.position) && is_finite(camera.target) && is_finite(camera.up) &&
                        std::isfinite(camera.fov_y_degrees) && std::isfinite(camera.near) && std::isfinite(camera.far);
    if (!finite) throw std::invalid_argument("xeno::render::Camera: every value must be finite");
    if (!(length(camera.target - camera.position) > 1e-9))
        throw std::invalid_argument("xeno::render::Camera: position and target must differ");
    if (!(length(camera.up) > 0)) throw std::invalid_argument("xeno::render::Camera: up must not be zero");
    if (!(camera.fov_y_degrees > 0 && camera.fov_y_degrees < 180))
        throw std::invalid_argument("xeno::render::Camera: fov_y_degrees must be in (0, 180), got " +
                                    std::to_string(camera.fov_y_degrees));
    if (!(camera.near > 0 && camera.far > camera.near))
        throw std::invalid_argument("xeno::render::Camera: need 0 < near < far, got near " + std::to_string(camera.near) +
                                    ", far " + std::to_string(camera.far));
}

// Shaders: GLSL 3.30 core, valid in both the core and the compatibility context.
// Shading constants shared by the sky, the ground and the bodies, so that far geometry fades into
// exactly the sky's horizon colour.
constexpr const char* shading_common = R"(
const vec3 zenith_color = vec3(0.30, 0.50, 0.82);
const vec3 horizon_color = vec3(0.80, 0.86, 0.93);
uniform vec3 u_camera;   // eye position, world
uniform vec2 u_fog;      // fog start and end distance, metres
vec3 apply_fog(vec3 color, vec3 world) {
    float f = smoothstep(u_fog.x, u_fog.y, distance(world, u_camera));
    return mix(color, horizon_color, f);
}
)";

constexpr const char* lit_vertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
uniform mat4 u_view_proj;
out vec3 v_world;
out vec3 v_normal;
out vec4 v_color;
void main() {
    v_world = a_position;
    v_normal = a_normal;
    v_color = a_color;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
)";

// One directional light (Lambert) plus a hemispheric ambient: faces turned up get the sky's
// light, faces turned down a darker ground bounce, so every face of a box has its own shade.
constexpr const char* lit_fragment = R"(
in vec3 v_world;
in vec3 v_normal;
in vec4 v_color;
uniform vec3 u_light;    // unit, towards the light
out vec4 out_color;
void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;   // a face seen from behind is lit as the side we see
    float diffuse = max(dot(n, u_light), 0.0);
    vec3 ambient = mix(vec3(0.20, 0.19, 0.18), vec3(0.36, 0.38, 0.42), 0.5 + 0.5 * n.y);
    vec3 color = v_color.rgb * (ambient + 0.72 * diffuse * vec3(1.0, 0.97, 0.92));
    out_color = vec4(apply_fog(color, v_world), v_color.a);
}
)";

constexpr const char* flat_vertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;
uniform mat4 u_view_proj;
out vec3 v_world;
out vec4 v_color;
void main() {
    v_world = a_position;
    v_color = a_color;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
)";

constexpr const char* flat_fragment = R"(
in vec3 v_world;
in vec4 v_color;
out vec4 out_color;
void main() { out_color = vec4(apply_fog(v_color.rgb, v_world), v_color.a); }
)";

// Planar shadows: opaque triangles flattened onto y = 0 along the light, drawn once per pixel
// (stencil) as a translucent dark layer on the ground, fading with the fog.
constexpr const char* shadow_vertex = R"(
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_proj;
uniform vec3 u_light;    // unit, towards the light, y > 0
out vec3 v_world;
void main() {
    v_world = vec3(a_position.x - u_light.x * a_position.y / u_light.y, 0.0,
                   a_position.z - u_light.z * a_position.y / u_light.y);
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
)";

constexpr const char* shadow_fragment = R"(
in vec3 v_world;
out vec4 out_color;
void main() {
    float fade = 1.0 - smoothstep(u_fog.x, u_fog.y, distance(v_world, u_camera));
    out_color = vec4(0.0, 0.0, 0.0, 0.28 * fade);
}
)";

constexpr const char* point_vertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_offset;   // corner of the disc's square, in [-1, 1]^2
layout(location = 2) in vec4 a_color;
uniform mat4 u_view_proj;
out vec2 v_offset;
out vec4 v_color;
void main() {
    v_offset = a_offset;
    v_color = a_color;
    gl_Position = u_view_proj * vec4(a_position, 1.0);
}
)";

constexpr const char* point_fragment = R"(
in vec2 v_offset;
in vec4 v_color;
uniform float u_alpha_scale;
out vec4 out_color;
void main() {
    float r = length(v_offset);
    float w = fwidth(r);
    float coverage = 1.0 - smoothstep(1.0 - w, 1.0, r);
    if (coverage <= 0.0) discard;
    // A darker rim makes a marker readable on a face of its own colour.
    vec3 color = mix(v_color.rgb, v_color.rgb * 0.35, smoothstep(0.62, 0.75, r));
    out_color = vec4(color, v_color.a * coverage * u_alpha_scale);
}
)";

// The sky: a full-screen triangle; each pixel's view ray is rebuilt from the camera basis and its
// elevation picks the colour between horizon and zenith.
constexpr const char* sky_vertex = R"(
out vec2 v_ndc;
void main() {
    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
    v_ndc = p;
    gl_Position = vec4(p, 1.0, 1.0);
}
)";

constexpr const char* sky_fragment = R"(
in vec2 v_ndc;
uniform vec3 u_right;    // camera right, scaled by tan(fov_x / 2)
uniform vec3 u_up;       // camera up, scaled by tan(fov_y / 2)
uniform vec3 u_forward;  // unit
out vec4 out_color;
void main() {
    vec3 ray = normalize(u_forward + v_ndc.x * u_right + v_ndc.y * u_up);
    float elevation = max(ray.y, 0.0);
    out_color = vec4(mix(horizon_color, zenith_color, pow(elevation, 0.55)), 1.0);
}
)";

constexpr const char* ground_vertex = R"(
layout(location = 0) in vec2 a_corner;   // in [-1, 1]^2
uniform mat4 u_view_proj;
uniform vec3 u_ground;   // centre x, centre z, half size (metres)
out vec3 v_world;
void main() {
    v_world = vec3(u_ground.x + a_corner.x * u_ground.z, 0.0, u_ground.y + a_corner.y * u_ground.z);
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}
)";

// The ground: a plane slightly darker than the horizon with lines every metre (stronger every 5 m,
// tinted along the x and z axes). Lines are drawn analytically, a pixel wide, and fade out with
// distance and where they would be closer together than a few pixels (no moiré).
constexpr const char* ground_fragment = R"(
in vec3 v_world;
out vec4 out_color;
float grid_line(vec2 p, float spacing) {
    vec2 q = p / spacing;
    vec2 w = fwidth(q);
    vec2 d = abs(fract(q - 0.5) - 0.5) / max(w, vec2(1e-6));   // distance to a line, in pixels
    float line = 1.0 - min(min(d.x, d.y), 1.0);
    float density = max(w.x, w.y);                              // grid cells per pixel
    return line * (1.0 - smoothstep(0.15, 0.45, density));
}
void main() {
    vec2 p = v_world.xz;
    float dist = distance(v_world, u_camera);
    float fade = 1.0 - smoothstep(15.0, 70.0, dist);
    vec3 color = vec3(0.60, 0.62, 0.63);
    color = mix(color, vec3(0.42, 0.44, 0.46), 0.55 * fade * grid_line(p, 1.0));
    color = mix(color, vec3(0.36, 0.38, 0.40), 0.60 * fade * grid_line(p, 5.0));
    vec2 w = fwidth(p);
    vec2 axis = 1.0 - min(abs(p) / max(w, vec2(1e-6)) / 1.5, 1.0);
    color = mix(color, vec3(0.72, 0.36, 0.34), 0.7 * fade * axis.y);   // the x axis (z = 0)
    color = mix(color, vec3(0.34, 0.44, 0.74), 0.7 * fade * axis.x);   // the z axis (x = 0)
    out_color = vec4(apply_fog(color, v_world), 1.0);
}
)";

GLuint compile_shader(GLenum kind, const char* body, bool with_common, const char* name) {
    const char* sources[3] = {"#version 330 core\n", with_common ? shading_common : "", body};
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 3, sources, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("xeno::render::Renderer: the ") + name + " shader does not compile: " + log);
    }
    return shader;
}

GLuint link_program(const char* vertex, const char* fragment, bool vertex_common, const char* name) {
    const GLuint vs = compile_shader(GL_VERTEX_SHADER, vertex, vertex_common, name);
    GLuint fs = 0;
    try {
        fs = compile_shader(GL_FRAGMENT_SHADER, fragment, true, name);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        throw std::runtime_error(std::string("xeno::render::Renderer: the ") + name + " shader does not link: " + log);
    }
    return program;
}

/// One vertex layout, one VAO, one streaming VBO: the batch is uploaded and drawn once per frame.
struct Batch {
    GLuint vao = 0, vbo = 0;
    GLsizei stride = 0;  ///< floats per vertex
    std::vector<float> data;

    /// components: float count of each attribute, in location order.
    void create(std::initializer_list<GLint> components) {
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &vbo);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        stride = 0;
        for (GLint c : components) stride += c;
        GLuint location = 0;
        std::size_t offset = 0;
        for (GLint c : components) {
            glEnableVertexAttribArray(location);
            glVertexAttribPointer(location, c, GL_FLOAT, GL_FALSE,
                                  static_cast<GLsizei>(stride * static_cast<GLsizei>(sizeof(float))),
                                  reinterpret_cast<const void*>(offset * sizeof(float)));
            offset += static_cast<std::size_t>(c);
            ++location;
        }
        glBindVertexArray(0);
    }
    void destroy() {
        if (vbo) glDeleteBuffers(1, &vbo);
        if (vao) glDeleteVertexArrays(1, &vao);
        vao = vbo = 0;
    }
    GLsizei vertex_count() const { return static_cast<GLsizei>(data.size() / static_cast<std::size_t>(stride)); }
    /// Sends this frame's vertices to GL (once per frame).
    void upload() const {
        if (data.empty()) return;
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(), GL_STREAM_DRAW);
    }
    /// Draws what upload() sent; nothing when empty.
    void draw(GLenum mode) const {
        if (data.empty()) return;
        glBindVertexArray(vao);
        glDrawArrays(mode, 0, vertex_count());
    }
};

void push(std::vector<float>& out, const f32::Vec3& v) {
    out.push_back(v.x);
    out.push_back(v.y);
    out.push_back(v.z);
}
void push(std::vector<float>& out, Color c) {
    out.push_back(c.r);
    out.push_back(c.g);
    out.push_back(c.b);
    out.push_back(c.a);
}

}  // namespace

Camera orbit(const Camera& camera, double angle_radians) {
    // Rotation about +y: x' = x cos + z sin, z' = -x sin + z cos (right-handed).
    const double c = std::cos(angle_radians), s = std::sin(angle_radians);
    const f64::Vec3 d = camera.position - camera.target;
    Camera out = camera;
    out.position = camera.target + f64::Vec3{d.x * c + d.z * s, d.y, -d.x * s + d.z * c};
    return out;
}

struct Renderer::Impl {
    int width = 0, height = 0;
    std::vector<unsigned char> pixels;  ///< OSMesa's colour buffer: RGBA, top row first
    OSMesaContext context = nullptr;
    GLint samples = 0;
    GLuint fbo = 0, color_rb = 0, depth_rb = 0;
    GLuint lit = 0, flat = 0, point = 0, sky = 0, ground = 0, shadow = 0;  ///< programs
    GLuint empty_vao = 0, ground_vao = 0, ground_vbo = 0;
    Batch opaque, translucent, lines, points;
    std::size_t triangles_drawn = 0, lines_drawn = 0, points_drawn = 0;

    Camera camera;
    CameraBasis basis{};
    Mat4d view_proj{};
    std::array<float, 16> view_proj_f{};
    std::array<float, 2> fog{};

    void make_current() {
        if (OSMesaGetCurrentContext() != context && !OSMesaMakeCurrent(context, pixels.data(), GL_UNSIGNED_BYTE, width, height))
            throw std::runtime_error("xeno::render::Renderer: OSMesaMakeCurrent failed");
    }
    void create_framebuffer();
    void create_programs();
    void release();
    void set_common_uniforms(GLuint program) const;
};

void Renderer::Impl::create_framebuffer() {
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    // 4x where the driver has it (llvmpipe); else (softpipe) a plain FBO, without anti-aliasing.
    for (GLint wanted : {std::min<GLint>(4, max_samples), GLint(0)}) {
        glGenFramebuffers(1, &fbo);
        glGenRenderbuffers(1, &color_rb);
        glGenRenderbuffers(1, &depth_rb);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glBindRenderbuffer(GL_RENDERBUFFER, color_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, wanted, GL_RGBA8, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb);
        glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, wanted, GL_DEPTH24_STENCIL8, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        while (glGetError() != GL_NO_ERROR) {
        }
        if (status == GL_FRAMEBUFFER_COMPLETE) {
            samples = wanted;
            return;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteRenderbuffers(1, &color_rb);
        glDeleteRenderbuffers(1, &depth_rb);
        glDeleteFramebuffers(1, &fbo);
        fbo = color_rb = depth_rb = 0;
        if (wanted == 0) {
            char hex[16];
            std::snprintf(hex, sizeof hex, "0x%04x", status);
            throw std::runtime_error(std::string("xeno::render::Renderer: the off-screen framebuffer is incomplete (status ") +
                                     hex + ", size " + std::to_string(width) + "x" + std::to_string(height) + ")");
        }
    }
}

void Renderer::Impl::create_programs() {
    lit = link_program(lit_vertex, lit_fragment, false, "lit triangle");
    flat = link_program(flat_vertex, flat_fragment, false, "line");
    point = link_program(point_vertex, point_fragment, false, "point");
    sky = link_program(sky_vertex, sky_fragment, false, "sky");
    ground = link_program(ground_vertex, ground_fragment, false, "ground");
    shadow = link_program(shadow_vertex, shadow_fragment, false, "shadow");

    opaque.create({3, 3, 4});
    translucent.create({3, 3, 4});
    lines.create({3, 4});
    points.create({3, 2, 4});
    glGenVertexArrays(1, &empty_vao);

    const float corners[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    glGenVertexArrays(1, &ground_vao);
    glGenBuffers(1, &ground_vbo);
    glBindVertexArray(ground_vao);
    glBindBuffer(GL_ARRAY_BUFFER, ground_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
}

void Renderer::Impl::release() {
    if (!context) return;
    if (OSMesaGetCurrentContext() == context || OSMesaMakeCurrent(context, pixels.data(), GL_UNSIGNED_BYTE, width, height)) {
        opaque.destroy();
        translucent.destroy();
        lines.destroy();
        points.destroy();
        for (GLuint program : {lit, flat, point, sky, ground, shadow})
            if (program) glDeleteProgram(program);
        if (ground_vbo) glDeleteBuffers(1, &ground_vbo);
        for (GLuint vao : {empty_vao, ground_vao})
            if (vao) glDeleteVertexArrays(1, &vao);
        if (fbo) glDeleteFramebuffers(1, &fbo);
        if (color_rb) glDeleteRenderbuffers(1, &color_rb);
        if (depth_rb) glDeleteRenderbuffers(1, &depth_rb);
    }
    OSMesaDestroyContext(context);
    context = nullptr;
}

void Renderer::Impl::set_common_uniforms(GLuint program) const {
    glUseProgram(program);
    const GLint view_proj_location = glGetUniformLocation(program, "u_view_proj");
    if (view_proj_location >= 0) glUniformMatrix4fv(view_proj_location, 1, GL_FALSE, view_proj_f.data());
    glUniform3f(glGetUniformLocation(program, "u_camera"), static_cast<float>(camera.position.x),
                static_cast<float>(camera.position.y), static_cast<float>(camera.position.z));
    glUniform2f(glGetUniformLocation(program, "u_fog"), fog[0], fog[1]);
}

Renderer::Renderer(int width, int height) : impl_(std::make_unique<Impl>()) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw std::runtime_error("xeno::render::Renderer: image size must be within 1..16384, got " + std::to_string(width) +
                                 "x" + std::to_string(height));
    Impl& r = *impl_;
    r.width = width;
    r.height = height;
    r.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);

    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    r.context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!r.context) r.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);  // compatibility profile
    if (!r.context)
        throw std::runtime_error(
            "xeno::render::Renderer: OSMesa could not create a GL context (neither a 3.3 core "
            "nor a legacy one); is libOSMesa (Mesa's llvmpipe) installed?");
    try {
        if (!OSMesaMakeCurrent(r.context, r.pixels.data(), GL_UNSIGNED_BYTE, width, height))
            throw std::runtime_error("xeno::render::Renderer: OSMesaMakeCurrent failed for a " + std::to_string(width) + "x" +
                                     std::to_string(height) + " RGBA buffer");
        OSMesaPixelStore(OSMESA_Y_UP, 0);
        const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        int major = 0;
        if (!version || std::sscanf(version, "%d", &major) != 1 || major < 3)
            throw std::runtime_error(std::string("xeno::render::Renderer: needs OpenGL 3.3, the context offers ") +
                                     (version ? version : "nothing"));
        r.create_framebuffer();
        r.create_programs();
        const GLenum error = glGetError();
        if (error != GL_NO_ERROR)
            throw std::runtime_error("xeno::render::Renderer: OpenGL error " + std::to_string(error) + " while setting up");
    } catch (...) {
        r.release();
        throw;
    }
}

Renderer::~Renderer() { impl_->release(); }

int Renderer::width() const { return impl_->width; }
int Renderer::height() const { return impl_->height; }
const std::vector<unsigned char>& Renderer::pixels() const { return impl_->pixels; }
std::size_t Renderer::triangle_count() const { return impl_->triangles_drawn; }
std::size_t Renderer::line_count() const { return impl_->lines_drawn; }
std::size_t Renderer::point_count() const { return impl_->points_drawn; }

std::string Renderer::gl_description() const {
    impl_->make_current();
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return std::string(version ? version : "?") + ", " + (renderer ? renderer : "?") +
           (impl_->samples > 0 ? ", " + std::to_string(impl_->samples) + "x MSAA" : ", no MSAA");
}

void Renderer::begin_frame(const Camera& camera) {
    validate(camera);
    Impl& r = *impl_;
    r.make_current();
    r.camera = camera;
    r.basis = camera_basis(camera);
    const double aspect = static_cast<double>(r.width) / static_cast<double>(r.height);
    r.view_proj = multiply(projection_matrix(camera, aspect), view_matrix(camera, r.basis));
    r.view_proj_f = to_float(r.view_proj);
    r.opaque.data.clear();
    r.translucent.data.clear();
    r.lines.data.clear();
    r.points.data.clear();

    // The ground reaches towards the horizon; fog hides its edge before the far plane cuts it.
    const double ground_half = std::min(0.9 * camera.far, 300.0);
    const double fog_end = std::min(0.8 * ground_half, 200.0);
    r.fog = {static_cast<float>(0.2 * fog_end), static_cast<float>(fog_end)};

    glBindFramebuffer(GL_FRAMEBUFFER, r.fbo);
    glViewport(0, 0, r.width, r.height);
    glDepthMask(GL_TRUE);
    glStencilMask(0xff);
    glClearDepth(1.0);
    glClearStencil(0);
    // No colour clear: the ground and then the sky cover every pixel.
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);

    // Ground, centred under the camera, pushed back in depth so that edges lying on it stay visible.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    r.set_common_uniforms(r.ground);
    glUniform3f(glGetUniformLocation(r.ground, "u_ground"), static_cast<float>(camera.position.x),
                static_cast<float>(camera.position.z), static_cast<float>(ground_half));
    glBindVertexArray(r.ground_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_POLYGON_OFFSET_FILL);

    // Sky at the far plane, only where the ground left the depth cleared (no shading under it).
    glDepthMask(GL_FALSE);
    glUseProgram(r.sky);
    const double tan_y = std::tan(radians(camera.fov_y_degrees) / 2), tan_x = tan_y * aspect;
    const f64::Vec3 right = r.basis.right * tan_x, up = r.basis.up * tan_y;
    glUniform3f(glGetUniformLocation(r.sky, "u_right"), static_cast<float>(right.x), static_cast<float>(right.y),
                static_cast<float>(right.z));
    glUniform3f(glGetUniformLocation(r.sky, "u_up"), static_cast<float>(up.x), static_cast<float>(up.y),
                static_cast<float>(up.z));
    glUniform3f(glGetUniformLocation(r.sky, "u_forward"), static_cast<float>(r.basis.forward.x),
                static_cast<float>(r.basis.forward.y), static_cast<float>(r.basis.forward.z));
    glBindVertexArray(r.empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
}

void Renderer::draw_triangle(const f32::Vec3& a, const f32::Vec3& b, const f32::Vec3& c, Color color) {
    const f32::Vec3 normal = normalized_or(cross(b - a, c - a), f32::Vec3::unit_y());
    std::vector<float>& out = color.a < 1.0f ? impl_->translucent.data : impl_->opaque.data;
    for (const f32::Vec3* v : {&a, &b, &c}) {
        push(out, *v);
        push(out, normal);
        push(out, color);
    }
}

void Renderer::draw_line(const f32::Vec3& a, const f32::Vec3& b, Color color) {
    std::vector<float>& out = impl_->lines.data;
    push(out, a);
    push(out, color);
    push(out, b);
    push(out, color);
}

void Renderer::draw_point(const f32::Vec3& p, float size, Color color) {
    const Impl& r = *impl_;
    const float radius = 0.5f * size;
    // Pulled towards the eye by its radius, so a marker on a surface is not cut by it.
    const f32::Vec3 eye(r.camera.position);
    const f32::Vec3 centre = p + normalized_or(eye - p, f32::Vec3::zero()) * radius;
    const f32::Vec3 right = f32::Vec3(r.basis.right) * radius, up = f32::Vec3(r.basis.up) * radius;
    const float corners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
    std::vector<float>& out = impl_->points.data;
    for (const auto& k : corners) {
        push(out, centre + right * k[0] + up * k[1]);
        out.push_back(k[0]);
        out.push_back(k[1]);
        push(out, color);
    }
}

void Renderer::end_frame() {
    Impl& r = *impl_;
    r.make_current();
    glBindFramebuffer(GL_FRAMEBUFFER, r.fbo);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // keeps alpha at 1
    const f32::Vec3 light = normalized(f32::Vec3{0.3f, 0.85f, 0.45f});                          // towards the light
    for (const Batch* batch : {&r.opaque, &r.translucent, &r.lines, &r.points}) batch->upload();

    // 1. Opaque triangles, pushed back a little in depth so edges on them win.
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 1.0f);
    r.set_common_uniforms(r.lit);
    glUniform3f(glGetUniformLocation(r.lit, "u_light"), light.x, light.y, light.z);
    r.opaque.draw(GL_TRIANGLES);
    glDisable(GL_POLYGON_OFFSET_FILL);

    // 2. Their shadows on the ground: where the ground is visible, each pixel darkened once.
    glEnable(GL_BLEND);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    r.set_common_uniforms(r.shadow);
    glUniform3f(glGetUniformLocation(r.shadow, "u_light"), light.x, light.y, light.z);
    r.opaque.draw(GL_TRIANGLES);
    glDisable(GL_STENCIL_TEST);

    // 3. Lines, depth-tested but not written, about a pixel wide at 480 rows.
    glLineWidth(std::max(1.0f, static_cast<float>(r.height) / 400.0f));
    r.set_common_uniforms(r.flat);
    r.lines.draw(GL_LINES);

    // 4. Translucent triangles, unsorted, after everything opaque.
    glEnable(GL_POLYGON_OFFSET_FILL);
    r.set_common_uniforms(r.lit);
    r.translucent.draw(GL_TRIANGLES);
    glDisable(GL_POLYGON_OFFSET_FILL);

    // 5. Points: first faintly through everything (hidden contacts stay findable), then solid.
    r.set_common_uniforms(r.point);
    const GLint alpha_scale = glGetUniformLocation(r.point, "u_alpha_scale");
    glDisable(GL_DEPTH_TEST);
    glUniform1f(alpha_scale, 0.3f);
    r.points.draw(GL_TRIANGLES);
    glEnable(GL_DEPTH_TEST);
    glUniform1f(alpha_scale, 1.0f);
    r.points.draw(GL_TRIANGLES);
    glBindVertexArray(0);
    glDepthMask(GL_TRUE);

    r.triangles_drawn = static_cast<std::size_t>(r.opaque.vertex_count() + r.translucent.vertex_count()) / 3;
    r.lines_drawn = static_cast<std::size_t>(r.lines.vertex_count()) / 2;
    r.points_drawn = static_cast<std::size_t>(r.points.vertex_count()) / 6;

    // Resolve into OSMesa's buffer; glFinish must see framebuffer 0 bound (docs/tooling.md,
    // "OSMesa").
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, r.width, r.height, 0, 0, r.width, r.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();
}

f64::Vec3 Renderer::project(const f64::Vec3& world) const {
    const Impl& r = *impl_;
    const Mat4d& m = r.view_proj;
    double clip[4];
    for (std::size_t row = 0; row < 4; ++row)
        clip[row] = m[row] * world.x + m[4 + row] * world.y + m[8 + row] * world.z + m[12 + row];
    const double w = clip[3];
    // Behind the eye (w <= 0): report a depth outside [0, 1] so callers see it is not visible.
    if (!(w > 0)) return {0, 0, -1};
    const double x = clip[0] / w, y = clip[1] / w, z = clip[2] / w;
    return {(x + 1) / 2 * r.width, (1 - y) / 2 * r.height, (z + 1) / 2};
}

namespace {

/// libpng's error path: longjmp back into write_rgba_png (only C objects live across it).
bool write_rgba_png(const char* path, int width, int height, const unsigned char* rgba) {
    std::FILE* file = std::fopen(path, "wb");
    if (!file) return false;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(png ? &png : nullptr, info ? &info : nullptr);
        std::fclose(file);
        return false;
    }
    png_init_io(png, file);
    // Speed over size: zlib level 2 and one cheap filter (a 640x480 frame in a few ms).
    png_set_compression_level(png, 2);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_set_filler(png, 0, PNG_FILLER_AFTER);  // rows are RGBA; the alpha byte is dropped
    for (int y = 0; y < height; ++y) png_write_row(png, rgba + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 4);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return std::fclose(file) == 0;
}

}  // namespace

bool Renderer::write_png(const std::string& path) const {
    return write_rgba_png(path.c_str(), impl_->width, impl_->height, impl_->pixels.data());
}

}  // namespace xeno::render
