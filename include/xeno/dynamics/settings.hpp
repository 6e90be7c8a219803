// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// WorldSettings<T>: every tunable of the solver in one struct, in SI units for bodies of 0.1–10 m
// (docs/conventions.md, "Units and axes"). docs/solver.md explains each and how the defaults were
// chosen; the numbers follow Box2D v3's soft step (docs/solver-design.md, "Defaults") with 8
// substeps, contacts at 90 Hz (the cap of 3/16 of the substep rate), rows between moving bodies
// damped at a ratio of 3 and rows on static ground at 10 (docs/solver.md, "What 8 substeps still
// fails": one ratio for all contacts either left a 1,000:1 pair of boxes rocking or let the
// 820-box pyramid creep; 12 substeps held both, for 1.5 times the sweeps).
#pragma once

#include "../broadphase/kind.hpp"
#include "../error.hpp"
#include "../math/vec3.hpp"

#include <algorithm>
#include <limits>

namespace xeno {

/// How contacts remove overlap. Both use sequential impulses with warm starting, accumulated
/// impulse clamping and Coulomb friction; they differ in how position error is fed back.
enum class SolverMode {
    /// Substeps with soft (spring–damper) contact rows, a relax pass without bias and a
    /// restitution pass (Catto, "Solver2D", 2024; Box2D v3). The default: see docs/solver.md.
    soft_step,
    /// One step, rigid rows with a Baumgarte bias beyond the slop, then relax iterations without
    /// bias (the classic "PGS + Baumgarte" of Box2D v2.x with split-impulse style relaxing).
    baumgarte,
};

/// Solver and world settings. Lengths in metres, speeds in m/s, times in seconds.
template <class T>
struct WorldSettings {
    Vec3<T> gravity{T(0), T(-9.81), T(0)};  ///< m/s², world frame (y up)
    T fixed_time_step = T(1) / T(60);       ///< s: the step update() takes
    int max_steps_per_update = 8;           ///< update() drops simulated time beyond this many steps

    SolverMode solver = SolverMode::soft_step;
    int substeps = 8;                ///< soft step: solver substeps per step
    int velocity_iterations = 1;     ///< biased iterations per substep (soft step) or per step (baumgarte: 10 recommended)
    int relax_iterations = 1;        ///< unbiased iterations after each substep (baumgarte: per step)
    int first_relax_iterations = 3;  ///< soft step: the same after a step's first substep, whose warm start carries
                                     ///< the last step's impulses; a load released between steps sheds them here
    int joint_iterations = 4;        ///< sweeps over the joints per contact sweep: joints are few, and one
                                     ///< sweep lets a door rebound 7 % off its stop (four: under 1 %)
    T contact_hertz = T(90);         ///< soft step: contact stiffness as a frequency, capped at 3/16 of the substep rate
    T contact_damping_ratio = T(3);  ///< soft step: contacts between moving bodies, over-damped (10 creeps a big pyramid)
    T static_contact_damping_ratio = T(10);  ///< soft step: contacts with static or kinematic bodies, heavily over-damped
                                             ///< (at 3 a heavy box rocked for ever on a light one, 700:1 and up)
    T static_contact_hertz_scale = T(1);     ///< contacts with static or kinematic bodies are this much stiffer (Box2D: 2;
                                             ///< measured here, 2 lets a box 5–200 times heavier rock forever on a light one)
    T joint_hertz = T(120);                  ///< soft step: joint stiffness, capped at 1/4 of the substep rate
    T joint_damping_ratio = T(2);
    T baumgarte = T(0.2);                ///< baumgarte mode: fraction of the overlap removed per step
    T max_push_out_speed = T(3);         ///< m/s: cap on the speed at which overlap is removed
    T linear_slop = T(0.005);            ///< m: overlap tolerated without correction (baumgarte) and contact tolerance
    T speculative_distance = T(0.02);    ///< m: gap below which contacts exist before touching (plus the approach of one step)
    T contact_match_distance = T(0.02);  ///< m: a new contact point within this of an old one inherits its impulses
    /// m/s: slower approaches do not bounce (resting boxes stay put); nor, whatever the setting, do
    /// approaches slower than twice a substep's pull, 2 g h (detail::bounce_threshold)
    T restitution_threshold = T(1);
    T max_linear_speed = T(400);  ///< m/s: speed cap against tunnelling (lifted for fast bodies by CCD)
    T max_rotation_per_step = T(0.25) * ScalarTraits<T>::pi;  ///< rad per step
    bool warm_starting = true;                                ///< reuse last step's impulses as the first guess
    /// A pair whose contact anchors moved less than a tenth of linear_slop since its manifold was
    /// made re-measures the points instead of colliding again (docs/collision.md, "Reusing a
    /// manifold"); false collides every pair every step.
    bool reuse_contacts = true;

    // Sleeping (islands whose bodies stay slow for sleep_time sleep; see docs/features.md).
    bool allow_sleeping = true;
    T sleep_linear_speed = T(0.05);   ///< m/s
    T sleep_angular_speed = T(0.05);  ///< rad/s
    T sleep_time = T(0.5);            ///< s

    BroadPhaseKind broad_phase = BroadPhaseKind::sweep_and_prune;
    /// Most broad-phase pairs (with a dynamic side) a step collides and solves. Beyond it (a
    /// crowd: 3,000 bodies spawned at one point overlap in 4.5 million pairs) the pairs of the
    /// crowded bodies are thinned, each body keeping a share, so a step's time and memory stay
    /// bounded while the crowd pushes itself apart (docs/robustness.md, "Crowds"). 131,072 pairs
    /// is about 40,000 bodies resting in piles; StepStats::dropped_pairs says when it was hit.
    int max_contact_pairs = 1 << 17;
};

namespace detail {

/// Upper bounds of the settings and of World::step's dt (docs/robustness.md, "Range of T"): beyond
/// them a step either takes minutes (counts) or leaves the range of T (times and lengths).
struct SettingsLimits {
    static constexpr int max_substeps = 64;
    static constexpr int max_iterations = 256;  ///< velocity_iterations and both relax_iterations
    static constexpr int max_joint_iterations = 64;
    static constexpr int max_steps_per_update = 1000;
    static constexpr int max_contact_pairs = 1 << 30;
};

/// The largest length (m), speed (m/s) or acceleration (m/s²) a setting may have: 10⁶ in float
/// (the shape size limit), 10³⁰ in double. Measured on a pile of every shape kind: a float
/// speculative_distance of 10⁶ keeps it finite and 10³⁰ turns it NaN; in double 10³⁵ is
/// finite and 10⁴⁰ NaN (the narrow phase inflates every pair by it).
template <class T>
constexpr T max_setting_length() {
    return T(std::is_same_v<T, float> ? 1e6 : 1e30);
}

/// The speed (m/s) a body flagged `fast` is held below: 10⁶ in float, 10¹⁰ in double. Up to it a
/// fast body lands on a face at rest, within a millimetre of the surface, with the impact sweeps
/// below; at 10³⁰ (the double cap until December 7) it slid off at 10⁴ m/s or sank through the
/// ground (docs/features.md, "Continuous detection").
template <class T>
constexpr T max_fast_speed() {
    return T(std::is_same_v<T, float> ? 1e6 : 1e10);
}

/// Impact sweeps: a contact point that approaches faster than impact_sweep_speed (m/s) at the
/// start of a step makes every substep of that step run extra biased sweeps, impact_sweeps_per_decade
/// for each factor of ten beyond it (at most max_impact_sweeps in all). One Gauss–Seidel sweep
/// over a face's points leaves a share of the approach uneven between them, and that share is
/// a fraction of the speed: harmless at the speeds gravity gives, at 10⁵ m/s a cone landing on
/// its base went 4 cm into the floor and was thrown 6 cm up. Slower impacts (every ordinary
/// scene, a bullet at 1,000 m/s) are solved exactly as before.
inline constexpr double impact_sweep_speed = 1000;
inline constexpr int impact_sweeps_per_decade = 5;
inline constexpr int max_impact_sweeps = 48;

/// Biased sweeps per substep for a step whose fastest approach is `approach` (m/s, ≥ 0).
template <class T>
int biased_sweeps(int velocity_iterations, T approach) {
    int sweeps = velocity_iterations;
    for (double speed = impact_sweep_speed; static_cast<double>(approach) > speed && sweeps < max_impact_sweeps; speed *= 10)
        sweeps = std::min(sweeps + impact_sweeps_per_decade, max_impact_sweeps);
    return sweeps;
}

/// The largest mass (kg) a dynamic body may have: a body at the largest speed setting keeps a
/// finite momentum with room for an impulse that reverses it, twice over (8.5·10³¹ kg in float,
/// 4.5·10²⁷⁷ in double). A float body of 8·10³⁷ kg landing at 7 m/s took an infinite impulse,
/// and the step was discarded: it froze in mid-air.
template <class T>
constexpr T max_mass() {
    return std::numeric_limits<T>::max() / (T(4) * max_setting_length<T>());
}

/// The longest step (s) World::step and fixed_time_step accept: 1 s, sixty times the default.
/// Measured on a pile of every shape kind, float steps stayed finite up to 10⁷ s and double up to
/// 10²⁰ s, but a body at the speed cap then moves far beyond the size range per step.
template <class T>
constexpr T max_time_step() {
    return T(1);
}

/// The contact frequency a substep of h seconds allows: at most 3/16 of the substep rate (ωh ≤ 1.18;
/// 90 Hz at the default 8 substeps). Stiffer than that, one sweep per substep no longer damps a
/// stack's contacts (docs/solver.md, "Fewer sweeps: measured, not taken", has the measurements;
/// 1/8 held the same stacks at 12 substeps).
template <class T>
T capped_contact_hertz(const WorldSettings<T>& s, T h) {
    return std::min(s.contact_hertz, T(0.1875) / h);
}

/// Joint limits are contacts in angle, at the contacts' frequency but always this heavily damped
/// (the default static_contact_damping_ratio), whatever the contacts' ratios: a limb landing on its stop
/// is caught by the damper. With the limits at a contact ratio of 2 or 3 a ragdoll dropped on a
/// step swung up to 7.5° past its cones (docs/solver.md, "Joint limits").
inline constexpr double limit_damping_ratio = 10;

/// The one check of a WorldSettings (constructor, set_settings, set_gravity, restore_snapshot).
template <class T>
void validate(const WorldSettings<T>& s) {
    const char* w = "WorldSettings";
    const T big = max_setting_length<T>();  // lengths (m), speeds (m/s) and accelerations (m/s²)
    require_within_xyz(s.gravity, big, w, "gravity", " m/s^2");
    require_positive(s.fixed_time_step, w, "fixed_time_step");
    require_at_most(s.fixed_time_step, max_time_step<T>(), w, "fixed_time_step", " s");
    require_count(s.max_steps_per_update, 1, SettingsLimits::max_steps_per_update, w, "max_steps_per_update");
    if (s.solver != SolverMode::soft_step && s.solver != SolverMode::baumgarte)
        report_invalid(w, "solver must be SolverMode::soft_step or baumgarte", static_cast<double>(s.solver));
    if (s.broad_phase != BroadPhaseKind::brute_force && s.broad_phase != BroadPhaseKind::sweep_and_prune &&
        s.broad_phase != BroadPhaseKind::aabb_tree)
        report_invalid(w, "broad_phase must be BroadPhaseKind::brute_force, sweep_and_prune or aabb_tree",
                       static_cast<double>(s.broad_phase));
    require_count(s.substeps, 1, SettingsLimits::max_substeps, w, "substeps");
    require_count(s.velocity_iterations, 1, SettingsLimits::max_iterations, w, "velocity_iterations");
    require_count(s.relax_iterations, 0, SettingsLimits::max_iterations, w, "relax_iterations");
    require_count(s.first_relax_iterations, 0, SettingsLimits::max_iterations, w, "first_relax_iterations");
    require_count(s.joint_iterations, 1, SettingsLimits::max_joint_iterations, w, "joint_iterations");
    require_count(s.max_contact_pairs, 1, SettingsLimits::max_contact_pairs, w, "max_contact_pairs");
    require_positive(s.contact_hertz, w, "contact_hertz");
    require_non_negative(s.contact_damping_ratio, w, "contact_damping_ratio");
    require_non_negative(s.static_contact_damping_ratio, w, "static_contact_damping_ratio");
    require_positive(s.static_contact_hertz_scale, w, "static_contact_hertz_scale");
    require_positive(s.joint_hertz, w, "joint_hertz");
    require_non_negative(s.joint_damping_ratio, w, "joint_damping_ratio");
    require_non_negative(s.baumgarte, w, "baumgarte");
    require_positive(s.max_push_out_speed, w, "max_push_out_speed");
    require_at_most(s.max_push_out_speed, big, w, "max_push_out_speed", " m/s");
    require_non_negative(s.linear_slop, w, "linear_slop");
    require_at_most(s.linear_slop, big, w, "linear_slop", " m");
    require_non_negative(s.speculative_distance, w, "speculative_distance");
    require_at_most(s.speculative_distance, big, w, "speculative_distance", " m");
    require_positive(s.contact_match_distance, w, "contact_match_distance");
    require_at_most(s.contact_match_distance, big, w, "contact_match_distance", " m");
    require_non_negative(s.restitution_threshold, w, "restitution_threshold");
    require_positive(s.max_linear_speed, w, "max_linear_speed");
    require_at_most(s.max_linear_speed, big, w, "max_linear_speed", " m/s");
    require_positive(s.max_rotation_per_step, w, "max_rotation_per_step");
    require_non_negative(s.sleep_linear_speed, w, "sleep_linear_speed");
    require_non_negative(s.sleep_angular_speed, w, "sleep_angular_speed");
    require_non_negative(s.sleep_time, w, "sleep_time");
}
}  // namespace detail

namespace f32 {
using WorldSettings = xeno::WorldSettings<float>;
}
namespace f64 {
using WorldSettings = xeno::WorldSettings<double>;
}

}  // namespace xeno
