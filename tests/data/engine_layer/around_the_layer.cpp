// Not compiled: sandbox code that goes around the engine layer, which
// tools/check_engine_layer.sh must reject (CTest engine_layer_check_rejects).
void teleport(LiveScene& live, BodyId id) {
    World& world = live.worldForEdits();
    world.body(id).x = Vec3::Zero();
}
