// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// libFuzzer target over world construction and stepping (docs/robustness.md, "Fuzzing"). The
// bytes decode into a precision, a few settings (solver mode, sleeping, broad phase), up to eight
// bodies of any shape (sizes 1e-2 … 1e2 m, positions within 50 m, speeds up to 1e3 m/s, densities
// 1e-2 … 1e5 kg/m³, static, kinematic or dynamic) and then a script of up to 60 steps of random
// dt interleaved with creating, destroying, pushing, teleporting and re-aiming bodies. Now and
// then a value is poisoned (NaN, ±inf, negative or zero size, density, dt, velocity, a stale
// handle): the door must throw InvalidArgument, which is caught, and the world must carry on as
// if the call had not been made. After every step every body's position, orientation and
// velocities must be finite and its orientation unit; anything else traps. Inputs of odd length
// step on two workers (World::set_workers), so the parallel stages see the same hostile worlds;
// the length, not a byte, decides, so no corpus file changes meaning.
//   run:    xeno_fuzz_world -max_total_time=60 <corpus dir>
#include "decode.hpp"

#include <cstdint>
#include <limits>
#include <vector>

using namespace xeno;

namespace {

/// Calls f, which must throw InvalidArgument (the input was poisoned); anything else traps.
template <class F>
void must_reject(F&& f, const char* what) {
    try {
        f();
    } catch (const InvalidArgument&) {
        return;
    }
    fuzz::fail(what);
}

template <class T>
Vec3<T> vector(FuzzedDataProvider& in, double magnitude) {
    const Vec3<double> v{fuzz::signed_unit(in), fuzz::signed_unit(in), fuzz::signed_unit(in)};
    return (v * magnitude).cast<T>();
}

template <class T>
void check_world(const World<T>& world) {
    world.for_each_body([](BodyId, const Body<T>& b) {
        if (!(is_finite(b.position()) && is_finite(b.orientation()) && is_finite(b.linear_velocity()) &&
              is_finite(b.angular_velocity())))
            fuzz::fail("a body's state is not finite after a step");
        if (!(std::abs(length(b.orientation()) - T(1)) <= T(1e-3))) fuzz::fail("a body's orientation is not unit after a step");
    });
}

/// Creates one decoded body, poisoned or not. Returns its handle, or an invalid one when the
/// shape or the definition was (rightly) rejected.
template <class T>
BodyId create(World<T>& world, FuzzedDataProvider& in) {
    const fuzz::ShapeSpec spec = fuzz::shape_spec(in, -2, 2);
    BodyDef<T> def;
    def.type = static_cast<BodyType>(in.ConsumeIntegralInRange<int>(0, 2));
    def.position = vector<T>(in, 50.0);
    def.orientation = fuzz::rotation(in).cast<T>();
    def.linear_velocity = vector<T>(in, fuzz::log_uniform(in, -2, 3));
    def.angular_velocity = vector<T>(in, fuzz::log_uniform(in, -2, 2));
    def.density = static_cast<T>(fuzz::log_uniform(in, -2, 5));
    def.material.friction = static_cast<T>(in.ConsumeProbability<double>() * 1.5);
    def.material.restitution = static_cast<T>(in.ConsumeProbability<double>());
    def.linear_damping = static_cast<T>(in.ConsumeBool() ? 0.0 : in.ConsumeProbability<double>());
    def.gravity_scale = static_cast<T>(in.ConsumeBool() ? 1.0 : 4.0 * fuzz::signed_unit(in));
    def.fast = in.ConsumeIntegralInRange<int>(0, 7) == 0;
    def.sensor = in.ConsumeIntegralInRange<int>(0, 15) == 0;
    if (in.ConsumeBool() && in.ConsumeBool()) def.mass = static_cast<T>(fuzz::log_uniform(in, -2, 4));

    const int poisoned = in.ConsumeIntegralInRange<int>(0, 23);  // 0 … 5 poison one field
    const T bad = static_cast<T>(fuzz::poison(in));
    const std::shared_ptr<const Shape<T>> shape = fuzz::build<T>(spec);
    if (!shape) return {};
    const T non_finite = std::isfinite(bad) ? std::numeric_limits<T>::quiet_NaN() : bad;
    switch (poisoned) {
        case 0: def.position.x = non_finite; break;
        case 1: def.linear_velocity.y = non_finite; break;
        case 2: def.angular_velocity.z = non_finite; break;
        case 3: def.orientation = std::isfinite(bad) ? Quat<T>{T(0), T(0), T(0), T(0)} : Quat<T>{bad, T(0), T(0), T(0)}; break;
        case 4:
            def.density = bad;
            def.mass = T(0);
            def.type = BodyType::dynamic;
            break;  // 0, -1 or non-finite
        case 5: def.gravity_scale = non_finite; break;
        default: {
            try {
                return world.create_body(shape, def);
            } catch (const InvalidArgument&) {
                // A valid definition may still be rejected for its mass in this precision
                // (density x volume out of range): fine, and nothing may have been created.
                return {};
            }
        }
    }
    const std::size_t before = world.body_count();
    must_reject([&] { world.create_body(shape, def); }, "create_body accepted a poisoned definition");
    if (world.body_count() != before) fuzz::fail("a rejected create_body left a body behind");
    return {};
}

/// Applies a force and a torque, each accepted or refused changing nothing.
template <class T>
void push_or_refuse(Body<T>& b, const Vec3<T>& f, const Vec3<T>& t) {
    const Vec3<T> force = b.force(), torque = b.torque();
    try {
        b.apply_force(f);
    } catch (const InvalidArgument&) {
        if (!(b.force() == force)) fuzz::fail("a rejected apply_force changed the accumulated force");
    }
    try {
        b.apply_torque(t);
    } catch (const InvalidArgument&) {
        if (!(b.torque() == torque)) fuzz::fail("a rejected apply_torque changed the accumulated torque");
    }
}

template <class T>
void run(FuzzedDataProvider& in, unsigned workers) {
    WorldSettings<T> settings;
    settings.solver = in.ConsumeBool() ? SolverMode::soft_step : SolverMode::baumgarte;
    if (settings.solver == SolverMode::baumgarte) settings.velocity_iterations = 10;
    settings.allow_sleeping = in.ConsumeBool();
    settings.broad_phase = in.ConsumeBool() ? BroadPhaseKind::sweep_and_prune : BroadPhaseKind::brute_force;
    settings.substeps = in.ConsumeIntegralInRange<int>(1, 12);
    World<T> world(settings);
    world.set_workers(workers);

    std::vector<BodyId> ids;
    const int bodies = in.ConsumeIntegralInRange<int>(1, 8);
    for (int i = 0; i < bodies; ++i) {
        const BodyId id = create(world, in);
        if (id.valid()) ids.push_back(id);
    }
    auto pick = [&]() -> BodyId {  // a live or (sometimes) stale handle
        if (ids.empty()) return {};
        return ids[in.ConsumeIntegralInRange<std::size_t>(0, ids.size() - 1)];
    };

    int steps = 0;
    const int max_steps = in.ConsumeIntegralInRange<int>(1, 60);
    while (steps < max_steps) {
        const int op = in.remaining_bytes() == 0 ? 0 : in.ConsumeIntegralInRange<int>(0, 9);
        const BodyId id = pick();
        const bool live = world.contains(id);
        switch (op) {
            case 1: {  // create
                const BodyId created = create(world, in);
                if (created.valid()) ids.push_back(created);
                break;
            }
            case 2:  // destroy (a stale handle must be rejected)
                if (live) world.destroy_body(id);
                else if (!ids.empty()) must_reject([&] { world.destroy_body(id); }, "destroy_body accepted a stale handle");
                break;
            case 3:  // new velocity, maybe poisoned
                if (!live) break;
                if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
                    const T bad = static_cast<T>(fuzz::poison(in));
                    if (!std::isfinite(bad))
                        must_reject(
                            [&] {
                                world.body(id).set_linear_velocity(Vec3<T>{bad, T(0), T(0)});
                            },
                            "set_linear_velocity accepted a non-finite velocity");
                } else {
                    world.body(id).set_linear_velocity(vector<T>(in, fuzz::log_uniform(in, -2, 3)));
                    world.body(id).set_angular_velocity(vector<T>(in, fuzz::log_uniform(in, -2, 2)));
                }
                break;
            case 4:  // impulse at a point near the body
                if (!live) break;
                world.body(id).apply_impulse_at(vector<T>(in, world.body(id).is_dynamic() ? 10.0 * world.body(id).mass() : 1.0),
                                                world.body(id).position() + vector<T>(in, 1.0));
                break;
            case 5:  // force and torque for the next step
                if (!live) break;
                if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
                    // Finite but extreme (up to the largest T): accepted, and then stepped to a
                    // finite state, or rejected leaving the accumulated sums as they were.
                    Body<T>& b = world.body(id);
                    const T big =
                        static_cast<T>(static_cast<double>(std::numeric_limits<T>::max()) * in.ConsumeProbability<double>());
                    const Vec3<T> push{big, -big, in.ConsumeBool() ? big : T(0)};
                    push_or_refuse(b, push, push);
                    b.set_linear_velocity(push);  // any finite velocity is accepted; the speed cap holds it
                    break;
                }
                {
                    // A modest push may still be refused: a sum accepted earlier (above) can overflow
                    // its acceleration once the body has turned its small inertia towards it.
                    Body<T>& b = world.body(id);
                    const Vec3<T> force = vector<T>(in, b.is_dynamic() ? 100.0 * b.mass() : 1.0);
                    push_or_refuse(b, force, vector<T>(in, 10.0));
                }
                break;
            case 6:  // teleport
                if (!live) break;
                world.set_transform(id, vector<T>(in, 50.0), fuzz::rotation(in).cast<T>());
                break;
            case 7: {  // a poisoned dt or seconds: must be rejected, changing nothing
                const T bad = static_cast<T>(fuzz::poison(in));
                must_reject([&] { world.step(bad); }, "step accepted a bad dt");
                if (!(bad == T(0)))  // update(0) is no time, not an error
                    must_reject([&] { world.update(bad); }, "update accepted bad seconds");
                break;
            }
            case 8:  // update by real time: whole fixed steps
                steps += world.update(static_cast<T>(in.ConsumeProbability<double>() * 0.1));
                check_world(world);
                break;
            default: {  // one step of a random dt, from 1e-4 s to 0.1 s
                world.step(static_cast<T>(fuzz::log_uniform(in, -4, -1)));
                ++steps;
                check_world(world);
                break;
            }
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    FuzzedDataProvider in(data, size);
    const unsigned workers = size % 2 == 0 ? 1u : 2u;
    if (in.ConsumeBool()) run<float>(in, workers);
    else run<double>(in, workers);
    return 0;
}
