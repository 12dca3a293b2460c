# Convex-mesh shapes: quickhull, the mesh shape factory and the hull's narrowphase pairs.
target_sources(substep_physics PRIVATE
  collision/convex_hull.cpp
  collision/convex_mesh_shape.cpp
  collision/collide_convex.cpp
)
