#pragma once
/// The render system: a scene's entities as a RenderScene. Every entity with a Transform and a
/// Collider (or a RenderMaterial mesh) is drawn at its Transform in its RenderMaterial's colour;
/// the ground is the scene's plane, or a reference floor under the bodies; the physics core's
/// debug draw list (physics/debug_draw.h: joint links, frames, limits, forces and torques,
/// contacts, broadphase boxes, centres of mass, velocities), which the physics system hands out,
/// becomes lines. It reads components only: what
/// the physics system wrote back after the last step. What stays fixed over a rendering (camera,
/// ground, force scale) is decided once from the initial state, so frames of one scene line up.

#include "physics/debug_draw.h"
#include "render/render_scene.h"
#include "scene/scene.h"

#include <map>
#include <memory>
#include <vector>

namespace substep {

/// Which debug overlays to draw.
struct DrawingOptions {
    bool jointFrames = true;  ///< each joint's axes on both bodies (a red, b green, c blue) and its limits
    bool jointForces = true;  ///< the joint's force on body 1, scaled to the scene
    bool jointTorques = false;  ///< the joint's torque on body 1 (the right-hand rule's axis)
    /// Contact points with their normals: off by default, since a pile of bodies turns them
    /// into a thicket that hides the scene (the viewer offers them as a toggle).
    bool contacts = false;
    // Off by default (issue 20): the views a developer turns on to see the collision and motion.
    bool bounds = false;         ///< the broadphase's box of each body
    bool centresOfMass = false;  ///< a cross at each moving body's centre of mass, along its principal axes
    bool velocities = false;     ///< each moving body's v and ω as arrows (ω with an arc of its sense)
    /// Multiplies every arrow's scale (forces, torques, velocities) and the length they are
    /// clipped to, as the panel's slider sets it; 1 is the scene's own.
    float arrowScale = 1.0f;
};

/// A scene's camera as the renderer takes it (y up).
render::Camera renderCamera(const SceneCamera& camera);

class SceneDrawing {
  public:
    /// Fixes the camera (the scene's own, else one that frames the bodies of `scene` for an image
    /// of the given aspect ratio), the ground and the scales of the overlays.
    SceneDrawing(const SceneDescription& description, SceneInstance& scene, float aspect,
                 const DrawingOptions& options = {});

    /// The scene's current state to draw: each entity with a Transform and a shape (its
    /// Collider's, or its RenderMaterial's mesh, which wins) and each soft body's surface, in its
    /// RenderMaterial's colour (a palette colour by entity without one), hidden when the
    /// material says so.
    render::RenderScene draw(SceneInstance& scene);

    /// Changes the overlays: what stays fixed (camera, ground, the scene's scales) stays.
    void setOptions(const DrawingOptions& options) { options_ = options; }
    const DrawingOptions& options() const { return options_; }
    /// The debug options drawWorld is given for the current overlays (scales times arrowScale).
    DebugDrawOptions debugOptions() const;

    const render::Camera& camera() const { return camera_; }

  private:
    void addBodies(const ecs::Registry& registry, render::RenderScene& scene);
    /// Each soft body's surface as the physics system hands it out, shaded like bodies.
    void addSoftBodies(const ecs::PhysicsSystem& physics, render::RenderScene& scene);
    /// The physics core's draw list (physics/debug_draw.h) of the layers the options select.
    void addDebugLines(const ecs::PhysicsSystem& physics, render::RenderScene& scene);
    std::shared_ptr<const render::MeshData> meshFor(const Shape& shape);
    std::shared_ptr<const render::MeshData> meshFor(const std::shared_ptr<const TriangleMesh>& mesh);

    DrawingOptions options_;
    render::Camera camera_;
    std::optional<render::Ground> ground_;
    float markerLength_ = 0.1f;  ///< joint frame axes and contact normals (m)
    float forceScale_ = 0.0f;    ///< m per N
    float torqueScale_ = 0.0f;   ///< m per N m
    float velocityScale_ = 0.0f;         ///< m per m/s
    float angularVelocityScale_ = 0.0f;  ///< m per rad/s
    float longestArrow_ = 1.0f;  ///< force arrows are clipped to this (m)
    DebugDrawList debugList_;    ///< kept across frames for its storage
    std::vector<render::Vec3f> softPoints_;  ///< a soft surface's points, kept for their storage
    std::vector<uint32_t> softIndices_;      ///< its triangles' indices, likewise
    /// Render meshes built from shape data, by the address of that data (shared between bodies).
    std::map<const void*, std::shared_ptr<const render::MeshData>> meshes_;
};

/// The colour body `index` is drawn in: static bodies a neutral grey, moving ones from a palette.
render::Colour bodyColour(std::size_t index, bool isStatic);

}  // namespace substep
