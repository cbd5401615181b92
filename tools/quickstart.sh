#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build,
# and render the bundled showcase scene to a video in out/showcase/. The size
# is kept small (960x540, 30 fps, 4 s) so that it takes under two minutes on
# a machine without a GPU (Mesa's lavapipe). Without ffmpeg, `render` writes
# PNG frames instead and says so.
set -euo pipefail
cd "$(dirname "$0")/.."
# The scene to show; scenes/showcase.toml replaces it once it exists.
scene=scenes/fluid_dam_break_2d.toml
out=out/showcase
tools/install-deps.sh
cmake --preset release
cmake --build --preset release --target spindrift_cli
build/release/spindrift render "$scene" --out "$out" --width 960 --height 540 --fps 30 --seconds 4
video="$out/$(basename "$scene" .toml).mp4"
if [[ -f $video ]]; then
  echo "spindrift: video written to $video"
else
  echo "spindrift: frames written to $out/"
fi
