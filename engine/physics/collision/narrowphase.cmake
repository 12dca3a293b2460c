# narrowphase sources (target_sources(substep_physics PRIVATE collision/...))
target_sources(substep_physics PRIVATE
  collision/narrowphase.cpp
  collision/collide_sphere.cpp
  collision/collide_capsule.cpp
  collision/collide_box.cpp
  collision/collide_box_box.cpp
  collision/collide_cylinder.cpp
)
