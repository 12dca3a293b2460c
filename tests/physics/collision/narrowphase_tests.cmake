# narrowphase tests (physics_add_test(...))
physics_add_test(narrowphase_test SOURCES collision/narrowphase_test.cpp LIBS substep_physics)
physics_add_test(cylinder_test SOURCES collision/cylinder_test.cpp LIBS substep_physics)
