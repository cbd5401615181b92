#!/usr/bin/env bash
# Makes the pictures of docs/rendering.md with the project's own command: one
# frame of scenes/fluid_splash.toml at t = 1 s for each Sprinkle splat step
# (spindrift render --fluid-steps N). Run after a build (cmake --build --preset release).
set -euo pipefail
cd "$(dirname "$0")/.."
cli=build/release/spindrift
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
for n in 1 2 3 4 5 6 7; do
  "$cli" render scenes/fluid_splash.toml --out "$tmp/step$n" --start 1.0 --frames 1 --format png \
    --fluid-steps "$n" --width 480 --height 270 --quiet
  cp "$tmp/step$n/frame_00000.png" "$out/splat-step-$n.png"
done
echo "wrote $out/splat-step-{1..7}.png"
