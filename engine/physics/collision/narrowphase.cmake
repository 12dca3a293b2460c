# narrowphase sources (target_sources(substep_physics PRIVATE collision/...))
target_sources(substep_physics PRIVATE
  collision/narrowphase.cpp
  collision/collide_sphere.cpp
  collision/collide_capsule.cpp
  collision/collide_box.cpp
  collision/collide_box_box.cpp
  collision/collide_cylinder.cpp
)
# The general convex pair: support functions, GJK/EPA, the clipped manifold, and convex shapes
# against triangle meshes, heightfields and spline tubes through it.
target_sources(substep_physics PRIVATE
  collision/convex_support.cpp
  collision/gjk_epa.cpp
  collision/convex_manifold.cpp
  collision/collide_convex_triangles.cpp
  collision/collide_convex_spline.cpp
)
