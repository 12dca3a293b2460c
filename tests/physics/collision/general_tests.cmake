# The general convex pair: GJK/EPA against brute force, the manifold, convex shapes on meshes,
# heightfields and splines, and the narrowphase table with no empty cell.
physics_add_test(gjk_epa_test SOURCES collision/gjk_epa_test.cpp LIBS substep_physics)
physics_add_test(convex_manifold_test SOURCES collision/convex_manifold_test.cpp LIBS substep_physics)
