/// Scene files, the `camera` reader of the loader (scene_loader_sections.h): the initial view,
/// `{position, target, fov}`.

#include "scene/scene_loader_sections.h"

namespace substep::scene_loader {

void readCamera(const Node& node, SceneReading& reading) {
    const Validator& v = reading.validator;
    const ObjectReader obj(v, node, "an object {\"position\", \"target\", \"fov\"}");
    obj.allowOnly({"position", "target", "fov"});
    SceneCamera camera;
    if (auto p = obj.get("position")) camera.position = v.vec3(*p, within(kMaxCoordinate));
    if (auto t = obj.get("target")) camera.target = v.vec3(*t, within(kMaxCoordinate));
    if (auto f = obj.get("fov")) {
        camera.fov =
            v.number(*f, {.lo = 0, .hi = kPi, .loOpen = true, .hiOpen = true, .hiText = "pi"});
    }
    if ((camera.target - camera.position).norm() <= kDirectionEpsilon) {
        v.fail(obj.has("target") ? obj.pathOf("target") : obj.pathOf("position"),
               "the camera target must differ from its position");
    }
    reading.scene.camera = camera;
}

}  // namespace substep::scene_loader
