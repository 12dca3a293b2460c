#!/usr/bin/env bash
# Builds Substep and runs its main job (the README's first command). Until the renderer lands,
# the gallery runs headless: every built-in scene is simulated and summarised.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

substep=build/bin/substep
echo
echo "Substep gallery, simulated headless (build/bin/substep run SCENE for one scene):"
"$substep" scenes | while read -r name _; do
  echo
  "$substep" run "$name" --seconds 2
done
