#!/usr/bin/env bash
# Checks that the sandbox reaches the physics world only through the engine layer (DESIGN.md:
# "the ECS physics system is the one place that creates, changes, steps and destroys World
# objects"). The compiler already holds most of it: SceneInstance, LiveScene and PhysicsSystem
# hand the sandbox a const World only. This catches the ways round that: a World of its own, a
# non-const World reference or pointer, a const_cast, or a call that only a mutable World has.
#   tools/check_engine_layer.sh [DIR ...]   (default: sandbox)
set -euo pipefail
cd "$(dirname "$0")/.."
dirs=("$@")
[ ${#dirs[@]} -eq 0 ] && dirs=(sandbox)
pattern='const_cast<[^>]*World|(^|[^a-zA-Z_:])World(\s*[&*]|\s+[a-z_]+\s*[({=;]|\s*\()|[wW]orld_?(\(\))?\.(step|setSettings|createBody|createJoint|destroyBody|destroyJoint|updateJoint|setBodyPose|setBodyVelocity|setBodySurface|requestRepair|body|joint)\([^)]*\)\s*(\.[a-zA-Z]+\s*)?(=[^=]|\+=|-=|;)'
# `const World&` is the read-only view the layer hands out; drop it before matching.
found=$(grep -rnE --include='*.cpp' --include='*.h' "$pattern" "${dirs[@]}" |
        grep -vE 'const World\s*[&*]' | grep -vE '^\S+:\s*[0-9]+:\s*//' || true)
if [ -n "$found" ]; then
    echo "the sandbox reaches the World around the engine layer:"
    echo "$found"
    exit 1
fi
echo "engine layer: the sandbox goes through components and the physics system"
