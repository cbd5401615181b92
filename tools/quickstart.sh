#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build,
# and render the bundled showcase level (scenes/showcase.toml: a water cannon
# on a truck puts out three fires) to a video in out/showcase/. At the scene's
# 960x540, 30 fps and 9 s the rendering takes about 20 s on two cores without
# a GPU (Mesa's lavapipe; the build comes first). Without ffmpeg, `render`
# writes PNG frames instead and says so.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=scenes/showcase.toml
out=out/showcase
tools/install-deps.sh
cmake --preset release
cmake --build --preset release --target spindrift_cli
build/release/spindrift render "$scene" --out "$out"
video="$out/$(basename "$scene" .toml).mp4"
if [[ -f $video ]]; then
  echo "spindrift: video written to $video"
else
  echo "spindrift: frames written to $out/"
fi
