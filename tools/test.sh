#!/usr/bin/env bash
# Builds Substep and runs every test (the README's test command; CI runs it too):
#   1. Release: every target, every test but the long ones;
#   2. ASan/UBSan: the engine's, the loader's and the engine layer's unit tests (the program's
#      end-to-end tests and the GL ones stay Release-only: under the sanitizers they would take
#      CI past its 20 minutes on two cores);
#   3. clang 14 (Debian 12's): the engine libraries and the built-in scenes build (the whole
#      program with clang as well would take CI past its 20 minutes; build it with
#      `CXX=clang++ cmake -S . -B build-clang && cmake --build build-clang`).
# SUBSTEP_CI_STAGES picks stages (default "release clang"). The ASan/UBSan stage is not in the
# default: built from nothing it takes about 18 minutes on this project's 2-core machine, which
# with the Release stage's ~10 would take CI past its 20. Run it with
#   SUBSTEP_CI_STAGES="release asan clang" tools/test.sh     (or SUBSTEP_CI_STAGES=asan)
# Long soak and sweep cases carry the CTest labels `stability` and `soak` and run with:
#   ctest --test-dir build -L stability      ctest --test-dir build -L soak
# The fuzzer (label `fuzz`) has its own build: see tests/fuzz/CMakeLists.txt.
set -euo pipefail
cd "$(dirname "$0")/.."

stages=" ${SUBSTEP_CI_STAGES:-release clang} "
jobs="$(nproc)"
stage() { printf '\n== %s (%s)\n' "$1" "$(date -u +%H:%M:%S)"; }

tools/install-deps.sh

if [[ $stages == *" release "* ]]; then
  stage "Release: build and test"
  cmake --preset release
  cmake --build --preset release -j "$jobs"
  ctest --preset release -j "$jobs"
fi

if [[ $stages == *" asan "* ]]; then
  stage "ASan/UBSan: engine, loader and engine-layer unit tests"
  asan_tests=(
    # engine/scene: the loader (every rule), meshes, building worlds
    scene_loader_test scene_loader_json_test scene_loader_validator_test scene_loader_shapes_test
    scene_loader_bodies_test scene_loader_joints_test scene_loader_camera_test
    scene_loader_soft_bodies_test scene_test mesh_import_test shape_keys_test
    scene_loader_fuzz_replay
    # engine/ecs: the layer the sandbox goes through
    registry_test view_test body_components_test physics_system_test physics_system_changes_test
    scene_entities_test
    # engine/physics: the world, contacts and corrections
    world_test contact_test correction_test mass_properties_test heightfield_test
    distance_joint_test hinge_joint_test spherical_joint_test prismatic_joint_test fixed_joint_test
    # sandbox: whole-or-nothing outputs
    atomic_file_test output_transaction_test csv_writer_test
  )
  cmake --preset asan
  cmake --build --preset asan -j "$jobs" --target "${asan_tests[@]}"
  for test in "${asan_tests[@]}"; do
    echo "-- $test"
    if [ "$test" = scene_loader_fuzz_replay ]; then
      (cd tests/data/scenes && "../../../build-asan/tests/$test" ../../../build-asan/tests/fuzz/seeds ../../fuzz/findings)
    else
      "build-asan/tests/$test" --gtest_brief=1
    fi
  done
fi

if [[ $stages == *" clang "* ]]; then
  stage "clang: the engine libraries and the built-in scenes"
  # Build type None: no optimisation flags, since this stage checks that clang compiles the
  # code; the Release stage above is the one whose programs run.
  CC=clang CXX=clang++ cmake -S . -B build-clang -G Ninja -DCMAKE_BUILD_TYPE=None \
    -DSUBSTEP_BUILD_TESTS=OFF -DSUBSTEP_BUILD_BENCHMARKS=OFF
  cmake --build build-clang -j "$jobs" --target substep_physics substep_scene substep_ecs substep_scenes
fi
stage "done"
