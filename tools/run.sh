#!/usr/bin/env bash
# Builds Substep and runs its main job (the README's first command).
#   With a display ($DISPLAY set): the interactive window, `substep view [SCENE]`.
#   Without one, or while the window is not built: the gallery, every built-in scene rendered
#   headless (EGL, OSMesa as fallback) to build/gallery/SCENE.png at a telling frame.
# Arguments go to `substep view` (a scene name or file). SUBSTEP_SIZE=WxH sets the image size.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

substep=build/bin/substep

# With a display, the window; when it cannot open (no OpenGL 3.3 on that display, a bad scene)
# `substep view` says why on stderr, exits 2, and the gallery below is rendered instead.
if [ -n "${DISPLAY:-}" ]; then
  if "$substep" view "$@"; then
    exit 0
  fi
  echo "run.sh: the interactive viewer could not run; rendering the gallery instead"
fi

gallery=build/gallery
size="${SUBSTEP_SIZE:-1280x720}"
echo
echo "Substep gallery, rendered headless at $size (build/bin/substep render SCENE --frames N --out DIR):"
failed=0
tools/render_gallery.sh "$gallery" "$size" || failed=1
echo
echo "Images are in $(pwd)/$gallery"
exit "$failed"
