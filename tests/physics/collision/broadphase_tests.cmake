# broadphase tests (physics_add_test(...))
physics_add_test(broadphase_test SOURCES collision/broadphase_test.cpp LIBS substep_physics)
physics_add_test(broadphase_sleeping_test SOURCES collision/broadphase_sleeping_test.cpp LIBS substep_physics)
