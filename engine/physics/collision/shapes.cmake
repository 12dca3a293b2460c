# Curved and complex collision shapes: spline tubes, triangle meshes, heightfields and their
# pair functions (collide_curved.h).
target_sources(substep_physics PRIVATE
  collision/static_bvh.cpp
  collision/cubic_segment.cpp
  collision/spline_tube.cpp
  collision/mesh_collider.cpp
  collision/heightfield.cpp
  collision/heightfield_sphere.cpp
  collision/triangle_contact.cpp
  collision/collide_spline.cpp
  collision/collide_mesh.cpp
)
