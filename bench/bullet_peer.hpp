// SPDX-FileCopyrightText: 2026 The xeno authors
// SPDX-License-Identifier: MIT
//
// Bullet's side of xeno_step_bench: the pyramid of scenes::pyramid (examples/scenes/stacks.hpp)
// rebuilt in a btDiscreteDynamicsWorld, stepped and measured the way the bench's pyramid_row
// measures xeno, so the two engines' ms/step, worst move and top sag print side by side from one
// process on one machine. Bullet runs with its defaults (btDbvtBroadphase, the sequential-impulse
// solver's 10 iterations, split impulse, default margins) plus what the scene itself fixes: sizes,
// masses, friction, restitution, gravity, the step and no sleeping.
#pragma once

#if XENO_HAVE_BULLET

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

namespace bullet_peer {

// The bench compares xeno float with Bullet: Debian's libbullet is built in single precision, and
// a header compiled with BT_USE_DOUBLE_PRECISION would not match the library's layout anyway.
static_assert(sizeof(btScalar) == sizeof(float), "bullet_peer compares xeno float with single-precision Bullet");

/// One pyramid run's numbers, defined as pyramid_row in step_bench.cpp defines xeno's.
struct PyramidRun {
    std::size_t boxes = 0;
    double ms_per_step = 0;        ///< wall time of stepSimulation alone, per step
    double contacts_per_step = 0;  ///< manifolds with at least one point (xeno's StepStats::contacts)
    double points_per_step = 0;    ///< manifold points, all of which Bullet's solver takes as rows
    double worst_move = 0;         ///< m: the largest distance of a box's centre from where it was placed
    double top_sag = 0;            ///< m: how far the top box's centre went down
    int missed_steps = 0;          ///< stepSimulation calls that did not run exactly one substep (should be 0)
};

/// Bullet's objects for one scene, in an order that lets the defaults tear it down: the world is
/// declared last so it is destroyed first, while the bodies, broadphase and dispatcher its
/// destructor still touches (removing each body's broadphase proxy) are alive.
struct Scene {
    std::unique_ptr<btDefaultCollisionConfiguration> config;
    std::unique_ptr<btCollisionDispatcher> dispatcher;
    std::unique_ptr<btDbvtBroadphase> broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::unique_ptr<btRigidBody> ground;
    std::vector<std::unique_ptr<btRigidBody>> boxes;  ///< creation order, as scenes::Scene::bodies: the top box is last
    std::unique_ptr<btDiscreteDynamicsWorld> world;
};

inline Scene make_scene(const btVector3& gravity) {
    Scene s;
    s.config = std::make_unique<btDefaultCollisionConfiguration>();
    s.dispatcher = std::make_unique<btCollisionDispatcher>(s.config.get());
    s.broadphase = std::make_unique<btDbvtBroadphase>();
    s.solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    s.world = std::make_unique<btDiscreteDynamicsWorld>(s.dispatcher.get(), s.broadphase.get(), s.solver.get(), s.config.get());
    s.world->setGravity(gravity);
    return s;
}

/// A box shape whose outer faces lie `half` from its centre, as xeno's Box. We keep btBoxShape's
/// default collision margin (0.04 m; setSafeMargin leaves it, being under a tenth of 0.5 m): the
/// constructor stores the half extents minus the margin and every query adds the margin back, so
/// the box stays 1 m across (box–box pairs go to btBoxBoxDetector on the full extents; only
/// GJK-based pairs see the margin, as edges rounded by 4 cm).
inline btCollisionShape* add_box_shape(Scene& s, const btVector3& half) {
    s.shapes.push_back(std::make_unique<btBoxShape>(half));
    return s.shapes.back().get();
}

/// A body at `position` with no motion state (Bullet then moves the body's own transform, the
/// one read back), mass 0 for a static body.
inline std::unique_ptr<btRigidBody> make_body(btCollisionShape* shape, btScalar mass, const btVector3& position) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(position);
    // xeno's default material on every body. Bullet combines a pair's friction as the product
    // (0.6 × 0.6 = 0.36) where xeno takes the geometric mean (0.6): the per-body value is the
    // scene's, the pair's value differs, and the comparison says so rather than retune Bullet.
    info.m_friction = btScalar(0.6);
    info.m_restitution = btScalar(0);
    auto body = std::make_unique<btRigidBody>(info);
    // Sleeping is off in xeno's pyramid rows (no_sleep()): a sleeping pyramid would cost nothing.
    body->setActivationState(DISABLE_DEACTIVATION);
    return body;
}

/// scenes::pyramid(world, base): a static ground box (half size max(50, base), 0.5 thick, top face
/// at y = 0) and rows of unit boxes (1,000 kg: density 1000 kg/m³), row r holding base - r boxes
/// 1 m apart centred on x = 0 at height 0.5 + r, z = 0, placed exactly touching and at rest.
inline Scene pyramid(int base, const btVector3& gravity) {
    Scene s = make_scene(gravity);
    const btScalar ground_half = btScalar(std::max(50, base));
    s.ground =
        make_body(add_box_shape(s, btVector3(ground_half, btScalar(0.5), ground_half)), 0, btVector3(0, btScalar(-0.5), 0));
    s.world->addRigidBody(s.ground.get());
    btCollisionShape* cube = add_box_shape(s, btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
    for (int row = 0; row < base; ++row) {
        const int n = base - row;
        for (int j = 0; j < n; ++j) {
            const btScalar x = btScalar(j) - btScalar(n - 1) * btScalar(0.5);
            s.boxes.push_back(make_body(cube, btScalar(1000), btVector3(x, btScalar(0.5) + btScalar(row), 0)));
            s.world->addRigidBody(s.boxes.back().get());
        }
    }
    return s;
}

/// Adds this step's manifolds with points and their points to the running sums.
inline void count_contacts(const btCollisionDispatcher& dispatcher, double& contacts, double& points) {
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        const int n = dispatcher.getManifoldByIndexInternal(i)->getNumContacts();
        contacts += n > 0 ? 1 : 0;
        points += n;
    }
}

/// Builds the pyramid, runs `steps` steps of 1/60 s and measures it. stepSimulation(dt, 1, dt)
/// runs exactly one fixed substep of dt per call, as World::step(dt) does; only that call is
/// timed, so counting the manifolds afterwards does not weigh on Bullet's ms/step.
inline PyramidRun run_pyramid(int base, int steps, const btVector3& gravity) {
    using clock_type = std::chrono::steady_clock;
    Scene s = pyramid(base, gravity);
    std::vector<btVector3> placed;
    for (const auto& box : s.boxes) placed.push_back(box->getWorldTransform().getOrigin());

    const btScalar dt = btScalar(1) / btScalar(60);
    PyramidRun run;
    run.boxes = s.boxes.size();
    clock_type::duration stepping{};
    for (int i = 0; i < steps; ++i) {
        const auto start = clock_type::now();
        const int substeps = s.world->stepSimulation(dt, 1, dt);
        stepping += clock_type::now() - start;
        if (substeps != 1) ++run.missed_steps;
        count_contacts(*s.dispatcher, run.contacts_per_step, run.points_per_step);
    }
    run.ms_per_step = std::chrono::duration<double, std::milli>(stepping).count() / steps;
    run.contacts_per_step /= steps;
    run.points_per_step /= steps;

    for (std::size_t i = 0; i < placed.size(); ++i)
        run.worst_move = std::max(run.worst_move, double((s.boxes[i]->getWorldTransform().getOrigin() - placed[i]).length()));
    run.top_sag = double(placed.back().y() - s.boxes.back()->getWorldTransform().getOrigin().y());
    return run;
}

}  // namespace bullet_peer

#endif  // XENO_HAVE_BULLET
