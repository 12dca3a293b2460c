#!/usr/bin/env bash
# Builds Substep and runs every test (the README's test command; CI runs it through .ci/run).
# Installs what it needs; safe to run again (each stage reuses its build folder).
#   1. release (gcc, build/): every target, every test but the long ones (labels stability and
#      soak), the program's end-to-end, capture and GL tests among them;
#   2. asan (clang 14, build-asan/): the whole program, `substep`, built once with clang (the
#      check that the project builds with Debian 12's clang) with AddressSanitizer and
#      UndefinedBehaviorSanitizer at -O1 without -g, and under it the unit tests that matter:
#      the loader (every rule, the fuzz seeds and findings), the engine layer, the world,
#      contacts, corrections and joints, the soft bodies' element kernels (four lanes and eight
#      alike under clang too), and the sandbox's whole-or-nothing outputs.
# Both stages fit CI's 20 minutes from a fresh clone on two cores: the release stage about
# 10-12 minutes, the asan stage about 7 (746 s of CPU to build; docs/STABILITY.md, "Continuous
# integration", has the measures and how the wall time was estimated). Without a compiler launcher (CI, a fresh
# clone) both precompile Eigen for the libraries, and the release stage one header for
# every test program (SUBSTEP_PRECOMPILE_HEADERS); a build folder
# configured with ccache keeps its settings.
# SUBSTEP_CI_STAGES picks stages (default "release asan"; "clang" is another name for asan).
# Long soak and sweep cases carry the CTest labels `stability` and `soak` and run with:
#   ctest --test-dir build -L stability      ctest --test-dir build -L soak -j2
# The fuzzer (label `fuzz`) has its own build: see tests/fuzz/CMakeLists.txt.
set -euo pipefail
cd "$(dirname "$0")/.."

stages=" ${SUBSTEP_CI_STAGES:-release asan} "
stages="${stages/ clang / asan }"
jobs="$(nproc)"
stage() { printf '\n== %s (%s)\n' "$1" "$(date -u +%H:%M:%S)"; }

# ON unless the build folder already compiles through a launcher such as ccache (which caches
# precompiled-header builds only with extra sloppiness settings).
precompile() {
  if grep -qs '^CMAKE_CXX_COMPILER_LAUNCHER:[A-Z]*=.\+' "$1/CMakeCache.txt"; then
    echo OFF
  else
    echo ON
  fi
}

tools/install-deps.sh

if [[ $stages == *" release "* ]]; then
  stage "release: build and test"
  cmake --preset release -DSUBSTEP_PRECOMPILE_HEADERS="$(precompile build)"
  cmake --build --preset release -j "$jobs"
  ctest --preset release -j "$jobs"
fi

if [[ $stages == *" asan "* ]]; then
  stage "asan: the whole program with clang and the sanitizers, the unit tests that matter"
  asan_tests=(
    # engine/scene: the loader (every rule), meshes, building worlds
    scene_loader_test scene_loader_json_test scene_loader_validator_test scene_loader_shapes_test
    scene_loader_bodies_test scene_loader_joints_test scene_loader_camera_test
    scene_loader_soft_bodies_test scene_test mesh_import_test shape_keys_test
    scene_loader_fuzz_replay
    # engine/ecs: the layer the sandbox goes through
    registry_test view_test body_components_test physics_system_test physics_system_changes_test
    scene_entities_test
    # engine/physics: the world, contacts and corrections; the soft kernels' lanes alike
    world_test contact_test correction_test mass_properties_test heightfield_test heightfield_turns_test
    distance_joint_test hinge_joint_test spherical_joint_test prismatic_joint_test fixed_joint_test
    soft_element_batch_test soft_shape_matching_test soft_rigid_mode_test soft_attachment_run_test
    soft_candidate_skips_test
    soft_still_contacts_test
    # sandbox: whole-or-nothing outputs
    atomic_file_test output_transaction_test csv_writer_test
  )
  cmake --preset asan -DSUBSTEP_PRECOMPILE_HEADERS="$(precompile build-asan)"
  cmake --build --preset asan -j "$jobs" --target substep "${asan_tests[@]}"
  for test in "${asan_tests[@]}"; do
    echo "-- $test"
    if [ "$test" = scene_loader_fuzz_replay ]; then
      (cd tests/data/scenes && "../../../build-asan/tests/$test" ../../../build-asan/tests/fuzz/seeds ../../fuzz/findings)
    else
      "build-asan/tests/$test" --gtest_brief=1
    fi
  done
  # The program itself under the sanitizers: a scene file through the loader, world and outputs.
  build-asan/bin/substep run assets/scenes/soft_bodies.json --frames 10 --csv build-asan/soft_bodies.csv >/dev/null
fi
stage "done"
