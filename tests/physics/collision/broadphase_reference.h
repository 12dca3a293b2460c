#pragma once
// The broadphase's reference for its tests (broadphase_test.cpp, broadphase_sleeping_test.cpp):
// the pairing boxes as broadphase.h documents them and an O(n²) brute force over them, and random
// scenes that change frame after frame as a running world's do.

#include "physics/collision/broadphase.h"
#include "physics/collision/shape_bounds.h"
#include "physics/world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <vector>

namespace substep::test_broadphase {

inline constexpr double kDt = 1.0 / 60.0;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline Quat randomOrientation(std::mt19937& rng) {
    std::normal_distribution<double> normal;
    return Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
}

/// The pairing box as the broadphase documents it, computed here on its own.
inline Aabb pairingBox(const Body& body, double dt, double k, const BroadphaseSettings& settings) {
    const Aabb tight = shapeBounds(body.shape, body.userPosition(), body.userOrientation());
    double speed = 0.0;
    if (body.rotates()) {
        speed += body.omega.norm() * (body.userOrigin.norm() + shapeReach(body.shape));
    }
    Vec3 sweep = Vec3::Zero();
    if (!settings.sweptGrowth) {
        speed += body.v.norm();
    } else if ((k * dt * body.v).norm() <= settings.maxGrowth) {
        sweep = k * dt * body.v;
    } else {
        speed = kInf;  // a runaway sweep: the clamped growth on every side
    }
    double growth = std::abs(k * dt) * speed;
    if (!(growth <= settings.maxGrowth)) growth = settings.maxGrowth;
    // The tight box at the start and at the end of the sweep, and all between.
    Aabb box = tight.inflated(growth + settings.margin);
    box.grow(Aabb{box.min + sweep, box.max + sweep});
    return box;
}

inline bool takesPart(const Body& body, double dt, double k, const BroadphaseSettings& settings) {
    if (!body.alive || !body.collide || body.shape.type == ShapeType::None) return false;
    if (body.shape.type == ShapeType::Plane) return true;
    // A body whose pose is not finite has no box.
    const Aabb box = pairingBox(body, dt, k, settings);
    return box.min.allFinite() && box.max.allFinite();
}

/// Every pair i < j by the rules, tested directly.
inline std::vector<BodyPair> bruteForcePairs(std::span<const Body> bodies, double dt, double k,
                                             const BroadphaseSettings& settings) {
    std::vector<BodyPair> pairs;
    std::vector<Aabb> boxes;
    std::vector<bool> inPlay;
    for (const Body& body : bodies) {
        boxes.push_back(pairingBox(body, dt, k, settings));
        inPlay.push_back(takesPart(body, dt, k, settings));
    }
    for (uint32_t i = 0; i < bodies.size(); ++i) {
        for (uint32_t j = i + 1; j < bodies.size(); ++j) {
            const Body& a = bodies[i];
            const Body& b = bodies[j];
            if (!inPlay[i] || !inPlay[j]) continue;
            if (!a.isDynamic() && !b.isDynamic()) continue;
            const bool planeA = a.shape.type == ShapeType::Plane;
            const bool planeB = b.shape.type == ShapeType::Plane;
            if (planeA && planeB) continue;
            if (planeA || planeB) {
                const Body& plane = planeA ? a : b;
                const Body& other = planeA ? b : a;
                if (!other.isDynamic()) continue;
                // The lowest corner of the box along the plane normal.
                const Aabb& box = boxes[planeA ? j : i];
                double lowest = kInf;
                for (int c = 0; c < 8; ++c) {
                    const Vec3 corner(c & 1 ? box.max.x() : box.min.x(),
                                      c & 2 ? box.max.y() : box.min.y(),
                                      c & 4 ? box.max.z() : box.min.z());
                    lowest = std::min(lowest, plane.shape.normal.dot(corner));
                }
                if (lowest <= plane.shape.offset + 1e-12) pairs.push_back({i, j});
                continue;
            }
            if (boxes[i].overlaps(boxes[j])) {
                pairs.push_back({i, j});
            }
        }
    }
    return pairs;
}

inline std::vector<BodyPair> toVector(std::span<const BodyPair> pairs) {
    return {pairs.begin(), pairs.end()};
}

inline Body makeTestBody(const Shape& shape, const Vec3& position, bool isStatic,
                         const Quat& orientation = Quat::Identity()) {
    Body body = makeBody({.shape = shape,
                          .type = isStatic ? BodyType::Static : BodyType::Dynamic,
                          .mass = 1.0,
                          .position = position,
                          .orientation = orientation});
    return body;
}

/// A random mix of spheres, boxes, capsules (some static), a static mesh, two planes, bodies
/// that do not collide and dead slots, with random velocities.
inline std::vector<Body> randomScene(std::mt19937& rng, int count) {
    std::uniform_real_distribution<double> position(-3.0, 3.0);
    std::uniform_real_distribution<double> size(0.0, 0.6);
    std::uniform_real_distribution<double> speed(-4.0, 4.0);
    std::uniform_int_distribution<int> pick(0, 99);
    std::vector<Body> bodies;
    bodies.push_back(Body{});  // the world's anchor: ShapeType::None
    bodies.back().alive = true;
    bodies.push_back(makeTestBody(planeShape(Vec3::UnitY(), -2.5), Vec3::Zero(), true));
    bodies.push_back(makeTestBody(planeShape(Vec3(1, 1, 0).normalized(), 3.0), Vec3::Zero(), true));
    for (int i = 0; i < count; ++i) {
        const Vec3 p(position(rng), position(rng), position(rng));
        const int kind = pick(rng) % 3;
        const Shape shape =
            kind == 0   ? sphereShape(0.05 + 0.5 * size(rng))
            : kind == 1 ? boxShape(Vec3(size(rng), size(rng), size(rng)) + Vec3::Constant(0.01))
                        : capsuleShape(0.05 + 0.3 * size(rng), size(rng));
        const bool isStatic = pick(rng) < 20;
        Body body = makeTestBody(shape, p, isStatic, randomOrientation(rng));
        if (!isStatic) {
            body.v = Vec3(speed(rng), speed(rng), speed(rng));
            body.omega = Vec3(speed(rng), speed(rng), speed(rng));
        }
        if (pick(rng) < 5) body.collide = false;
        if (pick(rng) < 5) body = Body{};  // a dead slot
        body.generation = static_cast<uint32_t>(bodies.size());
        bodies.push_back(body);
    }
    // A static mesh whose builder filled its local bounds.
    Body mesh = makeTestBody(boxShape(Vec3::Ones()), Vec3(0, -2, 0), true);
    mesh.shape = Shape{.type = ShapeType::Mesh};
    mesh.shape.localBounds = {Vec3(-3, -0.5, -3), Vec3(3, 0.2, 3)};
    mesh.generation = static_cast<uint32_t>(bodies.size());
    bodies.push_back(mesh);
    return bodies;
}

/// Moves the scene on by one frame and changes some slots the way a running world does.
inline void advance(std::mt19937& rng, std::vector<Body>& bodies, uint32_t& nextGeneration) {
    std::uniform_int_distribution<int> pick(0, 999);
    std::uniform_real_distribution<double> position(-3.0, 3.0);
    for (size_t i = 3; i < bodies.size(); ++i) {
        Body& body = bodies[i];
        if (body.isDynamic()) {
            body.x += body.v * kDt;
            integrateRotation(body.q, body.omega * kDt);
            // Keep the scene inside its region so pairs keep happening.
            for (int a = 0; a < 3; ++a) {
                if (std::abs(body.x[a]) > 3.5)
                    body.v[a] = -std::copysign(std::abs(body.v[a]), body.x[a]);
            }
        }
        const int event = pick(rng);
        if (event < 5) {
            body = Body{};  // destroyed
        } else if (event < 10 && !body.alive) {
            // The slot is reused by a new body.
            body = makeTestBody(sphereShape(0.2), Vec3(position(rng), position(rng), position(rng)),
                                false);
            body.v = Vec3(1, 0, 0);
            body.generation = nextGeneration++;
        } else if (event < 15 && body.alive) {
            body.collide = !body.collide;
        } else if (event < 18 && body.alive && body.type == BodyType::Static) {
            body.x += Vec3(0.3, 0, 0);  // a static body moved by hand
        } else if (event < 20 && body.alive && body.shape.type != ShapeType::Mesh) {
            // Made static (or dynamic again).
            body.invMass = body.isDynamic() ? 0.0 : 1.0;
        }
    }
}

}  // namespace substep::test_broadphase
