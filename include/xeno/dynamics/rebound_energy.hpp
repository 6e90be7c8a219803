// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A bounce gives back at most the energy the body brought (docs/solver-design.md, "Restitution",
// "Energy of a spinning bounce"). The restitution pass drives each point's v_n to −e times its
// approach, measured at anchors fixed for the whole step and for a spinning body from the step's
// start: a box or a cylinder tumbling at 10 rad/s turns 0.17 rad in a step at 60 Hz, its corners'
// approach is then off by metres per second, and with e = 1 such a body left the floor with up to
// 18 % more energy than it fell with (a capsule with friction 0.5: 25 %), bounce after bounce.
//
// The cap: a body whose contacts this step are all with static bodies, that no joint holds and
// no torque drives, may not end the step with more energy than it started with (or than the
// substeps left it with, when they pushed it out of an overlap), counted as the substeps'
// integrator keeps it (integrator_energy). When the restitution pass gives it more, the pass's
// change to that body's velocities and to its rows' impulses is scaled back to the budget.
// Bodies that touch other moving bodies exchange energy with them within the step and are left
// as they are.
#pragma once

#include "contact_solver.hpp"
#include "integrator.hpp"
#include "solver_body.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace xeno {
namespace detail {

/// A body's energy as a substep's semi-implicit Euler keeps it in free flight: with v += a h,
/// then x += v h, the sum ½v² − a·x + ½ h a·v is exact from substep to substep (contact_solver.hpp,
/// set_rebounds), so that, times the mass, plus the spin's ½ ω·I ω in the body frame. dp: the
/// position change since the step began; `orientation`: the body's orientation now.
template <class T>
T integrator_energy(T mass, const Mat3<T>& inertia_local, const Quat<T>& orientation, const Vec3<T>& v, const Vec3<T>& w,
                    const Vec3<T>& a, const Vec3<T>& dp, T h) {
    const Vec3<T> spin = rotate(conjugate(orientation), w);
    const T linear = T(0.5) * length_squared(v) + T(0.5) * h * dot(a, v) - dot(a, dp);
    return mass * linear + T(0.5) * dot(spin, inertia_local * spin);
}

/// The cap described at the top of this file, around apply_restitution: `before` notes the
/// bodies it watches and their rows' impulses, `after` scales back what the pass gave too much.
template <class T>
class ReboundEnergyCap {
public:
    /// `joints`: rows with solver body indices a and b (0: static), which couple their bodies.
    template <class JointRows>
    void before(const std::vector<ContactConstraint<T>>& rows, const std::vector<std::uint32_t>& bouncing,
                const JointRows& joints, const std::vector<SolverBody<T>>& bodies,
                const std::vector<BodyIntegration<T>>& integration) {
        watched_.clear();
        saved_.clear();
        if (bouncing.empty()) return;
        coupled_.assign(bodies.size(), 0);
        for (const ContactConstraint<T>& c : rows)
            if (c.a != 0 && c.b != 0) coupled_[c.a] = coupled_[c.b] = 1;
        for (const auto& j : joints) coupled_[j.a] = coupled_[j.b] = 1;
        watch_.assign(bodies.size(), none);
        for (const std::uint32_t row : bouncing) {
            const ContactConstraint<T>& c = rows[row];
            const std::uint32_t body = c.a == 0 ? c.b : c.b == 0 ? c.a : 0;
            if (body == 0 || coupled_[body] || !integration[body].dynamic ||
                length_squared(integration[body].angular_impulse_rate) != T(0))
                continue;
            if (watch_[body] == none) {
                watch_[body] = static_cast<std::uint32_t>(watched_.size());
                watched_.push_back({body, bodies[body].v, bodies[body].w});
            }
            saved_.push_back(save(row, c));
        }
    }

    /// `start(k)` gives solver body k's velocity and spin at the step's start, as a pair.
    template <class Start>
    void after(std::vector<ContactConstraint<T>>& rows, std::vector<SolverBody<T>>& bodies,
               const std::vector<SolverMass<T>>& masses, const std::vector<BodyIntegration<T>>& integration, const Start& start,
               T h) {
        for (Watched& w : watched_) w.scale = scale_for(w, bodies[w.body], masses[w.body], integration[w.body], start, h);
        for (const Saved& s : saved_) {
            ContactConstraint<T>& c = rows[s.row];
            const Watched& w = watched_[watch_[c.a == 0 ? c.b : c.a]];
            if (w.scale == T(1)) continue;
            for (int i = 0; i < c.count; ++i) {
                ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
                const std::size_t k = static_cast<std::size_t>(i);
                p.normal_impulse = s.normal[k] + w.scale * (p.normal_impulse - s.normal[k]);
                p.step_impulse = s.step[k] + w.scale * (p.step_impulse - s.step[k]);
                p.max_normal_impulse = std::max(s.max_normal[k], p.normal_impulse);
            }
            c.bounce_impulse *= w.scale;
        }
        for (const Watched& w : watched_) {
            if (w.scale == T(1)) continue;
            SolverBody<T>& b = bodies[w.body];
            b.v = w.v + (b.v - w.v) * w.scale;
            b.w = w.w + (b.w - w.w) * w.scale;
        }
    }

private:
    static constexpr std::uint32_t none = ~std::uint32_t(0);
    struct Watched {
        std::uint32_t body;
        Vec3<T> v, w;  ///< before the restitution pass
        T scale{1};    ///< of the pass's change, 1: kept whole
    };
    struct Saved {
        std::uint32_t row;
        std::array<T, 4> normal, step, max_normal;
    };

    static Saved save(std::uint32_t row, const ContactConstraint<T>& c) {
        Saved s{row, {}, {}, {}};
        for (int i = 0; i < c.count; ++i) {
            const std::size_t k = static_cast<std::size_t>(i);
            s.normal[k] = c.points[k].normal_impulse;
            s.step[k] = c.points[k].step_impulse;
            s.max_normal[k] = c.points[k].max_normal_impulse;
        }
        return s;
    }

    /// The largest s in [0, 1] with E(v_before + s Δv, ω_before + s Δω) within the budget: E is
    /// E_before + B s + C s² along that line, C ≥ 0.
    template <class Start>
    static T scale_for(const Watched& w, const SolverBody<T>& now, const SolverMass<T>& mass, const BodyIntegration<T>& in,
                       const Start& start, T h) {
        if (!(mass.inv_mass > T(0))) return T(1);
        const T m = T(1) / mass.inv_mass;
        const Mat3<T>& inertia = *in.inertia_local;
        const Quat<T> turned = now.dq * in.orientation0;
        const auto [v0, w0] = start(w.body);
        const T at_start = integrator_energy(m, inertia, in.orientation0, v0, w0, in.acceleration, Vec3<T>::zero(), h);
        const T before = integrator_energy(m, inertia, turned, w.v, w.w, in.acceleration, now.dp, h);
        const T after = integrator_energy(m, inertia, turned, now.v, now.w, in.acceleration, now.dp, h);
        const T budget = std::max(at_start, before);
        if (!(after > budget)) return T(1);
        const Vec3<T> dv = now.v - w.v;
        const Vec3<T> spin = rotate(conjugate(turned), w.w), dspin = rotate(conjugate(turned), now.w - w.w);
        const T c = T(0.5) * m * length_squared(dv) + T(0.5) * dot(dspin, inertia * dspin);
        const T b = m * (dot(w.v, dv) + T(0.5) * h * dot(in.acceleration, dv)) + dot(dspin, inertia * spin);
        if (!(c > T(0))) return T(1);
        const T s = (std::sqrt(std::max(b * b + T(4) * c * (budget - before), T(0))) - b) / (T(2) * c);
        return std::min(std::max(s, T(0)), T(1));
    }

    std::vector<std::uint8_t> coupled_;  ///< per solver body: a row or joint with another moving body
    std::vector<std::uint32_t> watch_;   ///< per solver body: index into watched_, or none
    std::vector<Watched> watched_;
    std::vector<Saved> saved_;
};

}  // namespace detail
}  // namespace xeno
