#!/usr/bin/env bash
# Builds Substep and runs every test (the README's test command; CI runs it too).
# Long soak and sweep cases carry the CTest label `stability` and run with:
#   ctest --test-dir build -L stability
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh
cmake --preset release
cmake --build --preset release -j "$(nproc)"
ctest --preset release -j "$(nproc)"
