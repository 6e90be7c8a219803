// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// A character controller built only on xeno's public API, and the `character` scene that shows it:
// an upright capsule (a kinematic body, so it pushes dynamic bodies and is never pushed back)
// moved by shape casts, the way game characters are moved. Each step, before World::step:
//   1. carry: standing on a kinematic body, the capsule takes that body's velocity at its feet;
//   2. move and slide: the walk is swept along; at each hit the capsule stops a skin short of the
//      obstacle and the rest of the move loses its component into it, so it slides along walls;
//   3. step up: a walk blocked by something steep is tried again lifted by the step height, then
//      put down; it is kept when it got farther and landed on walkable ground;
//   4. fall or stand: a short cast down finds the ground (a walkable slope within 45°); off the
//      ground the capsule falls under gravity;
//   5. move_kinematic(body, new pose, dt): the world moves it there during the step.
#pragma once

#include "features.hpp"
#include "scene.hpp"

#include <cmath>
#include <memory>

namespace xeno::scenes {

template <class T>
class CharacterController {
public:
    struct Settings {
        T radius = T(0.3);        ///< m
        T half_height = T(0.5);   ///< m, of the capsule's segment: 1.6 m tall in all
        T step_height = T(0.3);   ///< m: what it climbs without jumping
        T skin = T(0.01);         ///< m kept between the capsule and what it touches
        T walkable_cos = T(0.7);  ///< ground steeper than acos(0.7) ≈ 45.6° is a wall
        T gravity = T(9.81);      ///< m/s², down (−y)
    };

    /// A capsule standing on `feet` (its bottom a skin above that point).
    CharacterController(World<T>& world, const Vec3<T>& feet, const Settings& settings = {})
        : world_(world), settings_(settings) {
        BodyDef<T> d;
        d.type = BodyType::kinematic;
        d.position = feet + up() * (settings.radius + settings.half_height + settings.skin);  // a skin above
        body_ = world.create_body(Capsule<T>(settings.radius, settings.half_height), d);
    }

    BodyId body() const { return body_; }
    /// Where it stands: a skin below the bottom of the capsule (m, world).
    Vec3<T> feet() const {
        return world_.body(body_).position() - up() * (settings_.radius + settings_.half_height + settings_.skin);
    }
    bool on_ground() const { return on_ground_; }
    /// What it stands on (invalid in the air).
    BodyId ground() const { return ground_; }

    /// Moves the character for the coming step of dt seconds at `walk` (m/s, horizontal).
    void update(const Vec3<T>& walk, T dt) {
        Vec3<T> p = world_.body(body_).position();
        Vec3<T> carry = Vec3<T>::zero();
        if (on_ground_ && world_.contains(ground_) && world_.body(ground_).type() == BodyType::kinematic)
            carry = world_.body(ground_).velocity_at(feet());
        fall_speed_ = on_ground_ ? T(0) : fall_speed_ + settings_.gravity * dt;
        p = walk_with_steps(p, (walk + carry) * dt);
        p = slide(p, -up() * (fall_speed_ * dt));
        settle(p);
        world_.move_kinematic(body_, p, Quat<T>::identity(), dt);
    }

private:
    static Vec3<T> up() { return Vec3<T>::unit_y(); }
    Capsule<T> shape() const { return Capsule<T>(settings_.radius, settings_.half_height); }
    QueryFilter<T> filter() const {
        QueryFilter<T> f;
        f.ignore_body = body_;
        f.ignore_sensors = true;
        // Loose dynamic bodies do not block it: it walks into them and, being kinematic, pushes
        // them aside. It stands and collides only on static and kinematic bodies.
        f.accept = [](BodyId, const Body<T>& b) { return b.type() != BodyType::dynamic; };
        return f;
    }
    std::optional<WorldShapeCastHit<T>> cast(const Vec3<T>& from, const Vec3<T>& move) const {
        return world_.shape_cast(shape(), Transform<T>{from, Quat<T>::identity()}, move, filter());
    }
    bool walkable(const Vec3<T>& surface_normal) const { return dot(surface_normal, up()) >= settings_.walkable_cos; }

    /// Whether a capsule centred at `centre` stands on what a downward cast hit. The contact
    /// normal says so on a face; on an edge (a step's rim) it tilts towards the capsule however
    /// flat the top beyond it is, so there a short ray looks at the surface just past the edge.
    bool stands_on(const WorldShapeCastHit<T>& ground, const Vec3<T>& centre) const {
        if (walkable(-ground.hit.normal)) return true;
        Vec3<T> outward = ground.hit.point - centre;
        outward -= up() * dot(outward, up());
        if (length(outward) < T(1e-6)) return false;
        const T reach = T(2) * settings_.skin;
        Ray<T> probe;
        probe.origin = ground.hit.point + normalized(outward) * reach + up() * reach;
        probe.direction = -up();
        probe.max_distance = T(2) * reach;
        const std::optional<WorldRayHit<T>> top = world_.raycast(probe, filter());
        return top && top->body == ground.body && walkable(top->hit.normal);
    }

    /// Sweeps from p along move, sliding along what it hits (at most four times). Each cast
    /// reaches a skin beyond the move, so the capsule stops a skin short of what it meets even
    /// when the move ends right at it (a cast touching exactly at its end can report either).
    Vec3<T> slide(Vec3<T> p, Vec3<T> move) const {
        for (int i = 0; i < 4 && length(move) > T(1e-6); ++i) {
            const T reach = length(move);
            const Vec3<T> direction = move / reach;
            const std::optional<WorldShapeCastHit<T>> hit = cast(p, direction * (reach + settings_.skin));
            if (!hit) return p + move;
            const Vec3<T> n = -hit->hit.normal;    // the obstacle's surface, facing the capsule
            if (hit->hit.initially_overlapping) {  // pushed out a skin's width, then on
                p += n * settings_.skin;
                continue;
            }
            const T advance = clamp(hit->hit.fraction * (reach + settings_.skin) - settings_.skin, T(0), reach);
            p += direction * advance;
            move = direction * (reach - advance);
            move -= n * std::min(dot(move, n), T(0));  // lose the part into the obstacle
        }
        return p;
    }

    /// The walk, and if something steep blocks it on the ground, the same walk lifted by the step
    /// height and put down again, kept when it got farther and landed on walkable ground.
    Vec3<T> walk_with_steps(const Vec3<T>& p, const Vec3<T>& move) const {
        const Vec3<T> flat = slide(p, move);
        if (!on_ground_ || length(move) <= T(0)) return flat;
        const std::optional<WorldShapeCastHit<T>> blocked = cast(p, move + normalized(move) * settings_.skin);
        if (!blocked || walkable(-blocked->hit.normal)) return flat;
        const Vec3<T> lifted = slide(slide(p, up() * settings_.step_height), move);
        const std::optional<WorldShapeCastHit<T>> land = cast(lifted, -up() * (settings_.step_height + settings_.skin));
        if (!land || land->hit.initially_overlapping || !stands_on(*land, lifted)) return flat;
        const T rise = dot(land->hit.point - p, up()) + settings_.radius + settings_.half_height + settings_.skin;
        if (rise > settings_.step_height) return flat;  // the rounded bottom reached a higher rim
        const Vec3<T> landed =
            lifted - up() * std::max(land->hit.fraction * (settings_.step_height + settings_.skin) - settings_.skin, T(0));
        const auto progress = [&](const Vec3<T>& q) { return dot(q - p, move); };
        return progress(landed) > progress(flat) + T(1e-4) ? landed : flat;
    }

    /// Finds the ground under p (snapping down onto it when it was standing: stairs down, slopes).
    void settle(Vec3<T>& p) {
        const T probe = on_ground_ ? settings_.step_height : T(2) * settings_.skin;
        const std::optional<WorldShapeCastHit<T>> hit = cast(p, -up() * probe);
        on_ground_ = hit && stands_on(*hit, p);
        if (!on_ground_) {
            ground_ = BodyId{};
            return;
        }
        // A skin above the ground, up or down: the casts start that far from everything, well
        // beyond their tolerance (about 1 mm in float beside a 100 m ground box: shape_cast.hpp).
        if (hit->hit.initially_overlapping) p += up() * settings_.skin;  // sunk in (a platform rose): up and out
        else p -= up() * (hit->hit.fraction * probe - settings_.skin);
        ground_ = hit->body;
        fall_speed_ = T(0);
    }

    World<T>& world_;
    Settings settings_;
    BodyId body_, ground_;
    bool on_ground_ = false;
    T fall_speed_ = T(0);
};

/// A character walking a path: up a step onto a ledge, into a wall it slides along, and onto a
/// platform that carries it while it stands still; a few crates in the way get pushed aside.
template <class T>
Scene character(World<T>& world) {
    Scene s;
    s.ground = add_ground(world);
    add_static_box(world, Vec3<T>{T(2), T(0.125), T(2)}, Vec3<T>{T(4), T(0.125), T(0)});  // a 0.25 m step
    add_static_box(world, Vec3<T>{T(4), T(1), T(0.25)}, Vec3<T>{T(4), T(1), T(-2.5)});    // a wall along x
    BodyDef<T> pd;
    pd.type = BodyType::kinematic;
    pd.position = {T(9), T(0.125), T(0)};
    const BodyId platform = world.create_body(Box<T>(T(1.5), T(0.125), T(1.5)), pd);
    for (int i = 0; i < 3; ++i)  // beside its first steps: knocked aside
        s.bodies.push_back(add_box(world, Vec3<T>{T(0.2), T(0.2), T(0.2)},
                                   Vec3<T>{T(0.8) + T(0.4) * T(i), T(0.2), T(i % 2 == 0 ? 0.38 : -0.38)}));
    auto hero = std::make_shared<CharacterController<T>>(world, Vec3<T>{T(0), T(0), T(0)});
    s.bodies.push_back(hero->body());
    auto time = std::make_shared<T>(T(0));
    s.before_step = [&world, hero, time, platform](double step) {
        const T dt = static_cast<T>(step);
        const T t = *time;
        // The platform waits for the character, then shuttles ±2 m along z on a 6 s cycle.
        const T ride = std::max(t + dt - T(6.5), T(0));
        const T z = T(2) * std::sin(T(2) * ScalarTraits<T>::pi * ride / T(6));
        world.move_kinematic(platform, Vec3<T>{T(9), T(0.125), z}, Quat<T>::identity(), dt);
        // The walk: +x up the step (0–2.5 s), then towards the wall at 45° (slides along it, to 5 s),
        // then onto the platform (to 6.5 s), then stand and ride.
        Vec3<T> walk = Vec3<T>::zero();
        if (t < T(2.5)) walk = {T(1.5), T(0), T(0)};
        else if (t < T(5)) walk = Vec3<T>{T(1), T(0), T(-1)} * T(1.2);
        else if (t < T(6.5)) walk = {T(1.5), T(0), T(1)};
        hero->update(walk, dt);
        *time = t + dt;
    };
    s.eye = {4, 6, 12};
    s.target = {5, 0.5, 0};
    s.seconds = 12.5;  // the walk (6.5 s) and one 6 s platform ride
    return s;
}

}  // namespace xeno::scenes
