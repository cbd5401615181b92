#!/usr/bin/env bash
# Makes the pictures of docs/rendering.md and docs/tutorial.md with the
# project's own command: one frame of scenes/fluid_splash.toml at t = 1 s for
# each Sprinkle splat step (spindrift render --fluid-steps N), the 2D dam
# break at t = 2 s and the 3D one at t = 1 s as the liquid surface and as
# splats, the showcase level
# at three moments, the campfire's smoke three ways, the comets' trails and
# the fireworks built up in three steps. Run after a build (cmake --build --preset release).
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
# The 3D dam break at t = 1 s as the screen-space liquid and as splats.
"$cli" render scenes/fluid_dam_break_3d.toml --out "$tmp/screen" --start 1.0 --frames 1 --format png \
  --width 480 --height 270 --quiet
cp "$tmp/screen/frame_00000.png" "$out/dam-break-3d-surface.png"
"$cli" render scenes/fluid_dam_break_3d.toml --out "$tmp/splats3d" --start 1.0 --frames 1 --format png \
  --fluid-steps 7 --width 480 --height 270 --quiet
cp "$tmp/splats3d/frame_00000.png" "$out/dam-break-3d-splats.png"
# The showcase level (docs/tutorial.md) at three moments.
for t in 1.5 4.0 8.9; do
  "$cli" render scenes/showcase.toml --out "$tmp/showcase-$t" --start "$t" --frames 1 --format png \
    --width 640 --height 360 --quiet
  cp "$tmp/showcase-$t/frame_00000.png" "$out/showcase-$t.png"
done
# The campfire (docs/rendering.md, "Sprites"): its smoke with weighted blended
# OIT and soft edges as the scene has it, sorted back to front instead, and
# with hard edges; the variants are copies of the scene with one key changed.
ln -s "$PWD/scenes/data" "$tmp/data"
sed 's/^blend = "oit".*/blend = "alpha"/' scenes/campfire.toml > "$tmp/campfire-sorted.toml"
sed 's/^soft_distance = .*//' scenes/campfire.toml > "$tmp/campfire-hard.toml"
for variant in campfire "$tmp/campfire-sorted" "$tmp/campfire-hard"; do
  scene="$variant.toml"
  [ "$variant" = campfire ] && scene=scenes/campfire.toml
  name=$(basename "$variant")
  "$cli" render "$scene" --out "$tmp/$name" --start 3.0 --frames 1 --format png --width 480 --height 270 --quiet
  cp "$tmp/$name/frame_00000.png" "$out/$name.png"
done
# Trails (docs/rendering.md, "Trails"): the comets at t = 3 s.
"$cli" render scenes/comets.toml --out "$tmp/comets" --start 3.0 --frames 1 --format png --width 640 --height 360 \
  --quiet
cp "$tmp/comets/frame_00000.png" "$out/comets.png"
# Fireworks (docs/tutorial-fireworks.md), built up as the tutorial does: the
# rockets alone, then with the burst, then the whole scene with its crackle;
# the first two are the scene cut before the named emitter.
awk '/^name = "burst"/ { exit } { print }' scenes/fireworks.toml | sed '$d' > "$tmp/fireworks-rockets.toml"
awk '/^name = "crackle"/ { exit } { print }' scenes/fireworks.toml | sed '$d' > "$tmp/fireworks-burst.toml"
cp scenes/fireworks.toml "$tmp/fireworks.toml"
for name in fireworks-rockets fireworks-burst fireworks; do
  "$cli" render "$tmp/$name.toml" --out "$tmp/$name" --start 3.0 --frames 1 --format png --width 640 --height 360 \
    --quiet
  cp "$tmp/$name/frame_00000.png" "$out/$name.png"
done
echo "wrote $out/splat-step-{1..7}.png, $out/dam-break-{,3d-}{surface,splats}.png, $out/showcase-{1.5,4.0,8.9}.png," \
  "$out/campfire{,-sorted,-hard}.png, $out/comets.png and $out/fireworks{-rockets,-burst,}.png"
