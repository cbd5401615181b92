#!/usr/bin/env bash
# Makes the pictures of docs/rendering.md and docs/tutorial.md with the
# project's own command: one frame of scenes/fluid_splash.toml at t = 1 s for
# each Sprinkle splat step (spindrift render --fluid-steps N), the 2D dam
# break at t = 2 s as the liquid surface and as splats, and the showcase level
# at three moments. Run after a build (cmake --build --preset release).
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
# The two fluid styles side by side (docs/rendering.md, "Liquid surface").
"$cli" render scenes/fluid_dam_break_2d.toml --out "$tmp/surface" --start 2.0 --frames 1 --format png \
  --width 480 --height 270 --quiet
cp "$tmp/surface/frame_00000.png" "$out/dam-break-surface.png"
"$cli" render scenes/fluid_dam_break_2d.toml --out "$tmp/splats" --start 2.0 --frames 1 --format png \
  --fluid-steps 7 --width 480 --height 270 --quiet
cp "$tmp/splats/frame_00000.png" "$out/dam-break-splats.png"
# The showcase level (docs/tutorial.md) at three moments.
for t in 1.5 4.0 8.9; do
  "$cli" render scenes/showcase.toml --out "$tmp/showcase-$t" --start "$t" --frames 1 --format png \
    --width 640 --height 360 --quiet
  cp "$tmp/showcase-$t/frame_00000.png" "$out/showcase-$t.png"
done
echo "wrote $out/splat-step-{1..7}.png, $out/dam-break-{surface,splats}.png and $out/showcase-{1.5,4.0,8.9}.png"
