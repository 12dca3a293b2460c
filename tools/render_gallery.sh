#!/usr/bin/env bash
# Renders every built-in scene at the frame that shows what it is about, headless, to
# OUTDIR/SCENE.png, and prints where each went. Used by tools/run.sh (build/gallery) and for the
# README's pictures (docs/gallery):
#   tools/render_gallery.sh OUTDIR [WxH] [SCENE ...]
# Needs a built build/bin/substep. Exit 1 if any scene failed to render.
set -euo pipefail
cd "$(dirname "$0")/.."

out="${1:?usage: tools/render_gallery.sh OUTDIR [WxH] [SCENE ...]}"
size="${2:-1280x720}"
shift $(( $# >= 2 ? 2 : 1 ))
substep=build/bin/substep

# The frame that shows what a scene is about (60 frames = 1 s at the usual dt); others get 60.
telling_frame() {
  case "$1" in
    pendula | pendulum3) echo 45 ;;  # mid-swing
    rope100) echo 50 ;;              # the rope falling, curled
    chain100 | bunny_chain) echo 120 ;;
    marbles_on_wire) echo 12 ;;      # just lifted out of the wires, spread along the track
    cradle) echo 40 ;;               # the far marble leaving, the others at rest
    coin) echo 60 ;;                 # rolling on its rim, tilted
    joint_types) echo 150 ;;         # every joint resting on its limit or target
    twisted_rope) echo 1500 ;;       # 25 s: turned 8 times, coiled
    rolling_balls) echo 600 ;;       # 10 s: circulating, marbles queued at the lift and on it
    *) echo 60 ;;
  esac
}

scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  while read -r name _; do scenes+=("$name"); done < <("$substep" scenes)
fi

mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0
for name in "${scenes[@]}"; do
  frame=$(telling_frame "$name")
  if "$substep" render "$name" --frames "$frame" --out "$work/$name" --size "$size" >/dev/null; then
    mv "$work/$name/frame_$(printf '%05d' "$frame").png" "$out/$name.png"
    printf '  %-16s %s (frame %s)\n' "$name" "$out/$name.png" "$frame"
  else
    failed=1
  fi
done
exit "$failed"
