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
// The cap works on groups: the moving bodies joined by this step's contact rows (static bodies
// join nothing). A group that no joint holds, no torque drives and no kinematic body pushes
// exchanges energy only inside itself, so it may not end the step with more energy than it
// started with (or than the substeps left it with, when they pushed bodies out of an overlap),
// counted as the substeps' integrator keeps it (integrator_energy). When the restitution pass
// gives a group more, the pass's change to its bodies' velocities and to its rows' impulses is
// scaled back, all by one factor, to the budget. Groups with a joint, a torque or a kinematic
// body are left as they are.
#pragma once

#include "contact_solver.hpp"
#include "integrator.hpp"
#include "solver_body.hpp"

#include <algorithm>
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

/// The cap described at the top of this file, around apply_restitution: `before` finds the
/// groups and notes their bodies' velocities and their rows' impulses, `after` scales back what
/// the pass gave a group too much.
template <class T>
class ReboundEnergyCap {
public:
    /// `joints`: rows with solver body indices a and b (0: static), which exclude their groups.
    template <class JointRows>
    void before(const std::vector<ContactConstraint<T>>& rows, const std::vector<std::uint32_t>& bouncing,
                const JointRows& joints, const std::vector<SolverBody<T>>& bodies,
                const std::vector<BodyIntegration<T>>& integration, T threshold, T h) {
        members_.clear();
        saved_.clear();
        groups_.clear();
        // Most steps of a scene with restitution bounce nothing (a settled pile): then the pass
        // changes nothing and there is nothing to cap. (While 1,000 boxes rain onto a pile, with
        // landings every step, the cap takes 1.7 % of a step, measured with perf.)
        if (std::none_of(bouncing.begin(), bouncing.end(),
                         [&](std::uint32_t row) { return row_rebounds(rows[row], threshold, h); }))
            return;
        join_groups(rows, joints, integration);
        group_of_.assign(bodies.size(), none);
        for (const std::uint32_t row : bouncing) {
            const ContactConstraint<T>& c = rows[row];
            const std::uint32_t root = find(c.a != 0 ? c.a : c.b);
            if (excluded_[root]) continue;
            if (group_of_[root] == none) {
                group_of_[root] = static_cast<std::uint32_t>(groups_.size());
                groups_.push_back({});
            }
            saved_.push_back(save(row, c, group_of_[root]));
        }
        for (std::uint32_t k = 1; k < bodies.size(); ++k) {
            const std::uint32_t group = group_of_[find(k)];
            if (group != none) members_.push_back({k, group, bodies[k].v, bodies[k].w});
        }
    }

    /// `start(k)` gives solver body k's velocity and spin at the step's start, as a pair.
    template <class Start>
    void after(std::vector<ContactConstraint<T>>& rows, std::vector<SolverBody<T>>& bodies,
               const std::vector<SolverMass<T>>& masses, const std::vector<BodyIntegration<T>>& integration, const Start& start,
               T h) {
        if (groups_.empty()) return;
        for (const Member& m : members_)
            add_energy(groups_[m.group], m, bodies[m.body], masses[m.body], integration[m.body], start, h);
        for (Group& g : groups_) g.scale = scale_for(g);
        for (const Saved& s : saved_) {
            const T scale = groups_[s.group].scale;
            if (scale == T(1)) continue;
            ContactConstraint<T>& c = rows[s.row];
            for (int i = 0; i < c.count; ++i) {
                ContactConstraintPoint<T>& p = c.points[static_cast<std::size_t>(i)];
                const std::size_t k = static_cast<std::size_t>(i);
                p.normal_impulse = s.normal[k] + scale * (p.normal_impulse - s.normal[k]);
                p.step_impulse = s.step[k] + scale * (p.step_impulse - s.step[k]);
                p.max_normal_impulse = std::max(s.max_normal[k], p.normal_impulse);
            }
            c.bounce_impulse *= scale;
        }
        for (const Member& m : members_) {
            const T scale = groups_[m.group].scale;
            if (scale == T(1)) continue;
            SolverBody<T>& b = bodies[m.body];
            b.v = m.v + (b.v - m.v) * scale;
            b.w = m.w + (b.w - m.w) * scale;
        }
    }

private:
    static constexpr std::uint32_t none = ~std::uint32_t(0);
    struct Member {
        std::uint32_t body, group;
        Vec3<T> v, w;  ///< before the restitution pass
    };
    /// A group's energies, and E(s) = before + slope s + curvature s² for the velocities
    /// v_before + s Δv of all its bodies.
    struct Group {
        T at_start{}, before{}, slope{}, curvature{};
        T scale{1};  ///< of the pass's change, 1: kept whole
    };
    struct Saved {
        std::uint32_t row, group;
        std::array<T, 4> normal, step, max_normal;
    };

    std::uint32_t find(std::uint32_t k) {
        while (parent_[k] != k) k = parent_[k] = parent_[parent_[k]];
        return k;
    }

    /// Union–find over the rows between moving bodies; a group is excluded when a joint holds,
    /// a torque drives or the user moves (kinematic) any of its bodies.
    template <class JointRows>
    void join_groups(const std::vector<ContactConstraint<T>>& rows, const JointRows& joints,
                     const std::vector<BodyIntegration<T>>& integration) {
        const std::size_t n = integration.size();
        parent_.resize(n);
        for (std::uint32_t k = 0; k < n; ++k) parent_[k] = k;
        for (const ContactConstraint<T>& c : rows)
            if (c.a != 0 && c.b != 0) parent_[find(c.a)] = find(c.b);
        excluded_.assign(n, 0);
        for (const auto& j : joints) excluded_[find(j.a)] = excluded_[find(j.b)] = 1;
        for (std::uint32_t k = 1; k < n; ++k)
            if (!integration[k].dynamic || length_squared(integration[k].angular_impulse_rate) != T(0)) excluded_[find(k)] = 1;
        excluded_[find(0)] = 1;
    }

    static Saved save(std::uint32_t row, const ContactConstraint<T>& c, std::uint32_t group) {
        Saved s{row, group, {}, {}, {}};
        for (int i = 0; i < c.count; ++i) {
            const std::size_t k = static_cast<std::size_t>(i);
            s.normal[k] = c.points[k].normal_impulse;
            s.step[k] = c.points[k].step_impulse;
            s.max_normal[k] = c.points[k].max_normal_impulse;
        }
        return s;
    }

    template <class Start>
    static void add_energy(Group& g, const Member& m, const SolverBody<T>& now, const SolverMass<T>& mass,
                           const BodyIntegration<T>& in, const Start& start, T h) {
        const T kg = T(1) / mass.inv_mass;  // dynamic: inv_mass > 0
        const Mat3<T>& inertia = *in.inertia_local;
        const Quat<T> turned = now.dq * in.orientation0;
        const auto [v0, w0] = start(m.body);
        g.at_start += integrator_energy(kg, inertia, in.orientation0, v0, w0, in.acceleration, Vec3<T>::zero(), h);
        g.before += integrator_energy(kg, inertia, turned, m.v, m.w, in.acceleration, now.dp, h);
        const Vec3<T> dv = now.v - m.v;
        const Vec3<T> spin = rotate(conjugate(turned), m.w), dspin = rotate(conjugate(turned), now.w - m.w);
        g.curvature += T(0.5) * kg * length_squared(dv) + T(0.5) * dot(dspin, inertia * dspin);
        g.slope += kg * (dot(m.v, dv) + T(0.5) * h * dot(in.acceleration, dv)) + dot(dspin, inertia * spin);
    }

    /// The largest s in [0, 1] with E(s) within the budget (E(1): the pass's whole change).
    static T scale_for(const Group& g) {
        const T budget = std::max(g.at_start, g.before);
        if (!(g.before + g.slope + g.curvature > budget) || !(g.curvature > T(0))) return T(1);
        const T b = g.slope, c = g.curvature;
        const T s = (std::sqrt(std::max(b * b + T(4) * c * (budget - g.before), T(0))) - b) / (T(2) * c);
        return std::min(std::max(s, T(0)), T(1));
    }

    std::vector<std::uint32_t> parent_;    ///< per solver body: union–find over this step's rows
    std::vector<std::uint8_t> excluded_;   ///< per group root: a joint, a torque or a kinematic body
    std::vector<std::uint32_t> group_of_;  ///< per group root: index into groups_, or none
    std::vector<Group> groups_;
    std::vector<Member> members_;
    std::vector<Saved> saved_;
};

}  // namespace detail
}  // namespace xeno
