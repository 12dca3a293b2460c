#!/usr/bin/env bash
# Builds Substep and runs its main job (the README's first command).
#   With a display ($DISPLAY set): the interactive window, `substep view [SCENE]`.
#   Without one, or while the window is not built: the gallery, every built-in scene rendered
#   headless (EGL, OSMesa as fallback) to build/gallery/SCENE/frame_NNNNN.png at a telling frame.
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

# The frame that shows what a scene is about (60 frames = 1 s at the usual dt); scenes not
# listed get frame 60.
telling_frame() {
  case "$1" in
    pendula | pendulum3) echo 45 ;;   # mid-swing
    rope100) echo 50 ;;               # the rope falling, curled
    chain100) echo 120 ;;
    *) echo 60 ;;
  esac
}

gallery=build/gallery
size="${SUBSTEP_SIZE:-1280x720}"
mkdir -p "$gallery"
echo
echo "Substep gallery, rendered headless at $size (build/bin/substep render SCENE --frames LIST --out DIR):"
failed=0
while read -r name _; do
  frame=$(telling_frame "$name")
  if "$substep" render "$name" --frames "$frame" --out "$gallery/$name" --size "$size" >/dev/null; then
    printf '  %-12s %s\n' "$name" "$gallery/$name/frame_$(printf '%05d' "$frame").png"
  else
    failed=1
  fi
done < <("$substep" scenes)
echo
echo "Images are in $(pwd)/$gallery"
exit "$failed"
