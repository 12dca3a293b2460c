# broadphase sources (target_sources(substep_physics PRIVATE collision/...))
target_sources(substep_physics PRIVATE
  collision/shape_bounds.cpp
  collision/aabb_tree.cpp
  collision/broadphase.cpp
)
