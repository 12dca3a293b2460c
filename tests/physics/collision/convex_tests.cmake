# Convex-mesh shapes: quickhull, the hull's mass properties and its narrowphase pairs.
physics_add_test(convex_test SOURCES collision/convex_test.cpp LIBS substep_physics)
