#!/usr/bin/env bash
# Builds and runs the whole test suite twice: an optimised build with warnings
# as errors, then the same tests under AddressSanitizer and
# UndefinedBehaviorSanitizer. Exits non-zero on any failure.
#
# The sanitizer pass leaves out 60 tests (the asan test preset's filter in
# CMakePresets.json), which would put CI (2 cores) over its 30 minutes (a
# clean run with only the first nine left out took 31 minutes, 11 of them the
# sanitizer tests); all of them run in the optimised pass:
# - the 2D and 3D resting tanks, the 2D and 3D volume tanks, the three
#   floating boxes and the showcase played to its end: each steps thousands
#   of particles for 5 to 8 simulated seconds to measure a physical outcome,
#   0.5 to 4 minutes apiece under the sanitizers;
# - every bundled scene at one and at two threads compared bit for bit (4
#   minutes under the sanitizers);
# - second runs of host code the sanitizers already see once, each 15 to 35 s
#   under them, most of it lavapipe and the validation layer compiling
#   shaders: the render and sprite-look tests drawing a Vulkan world (their
#   CPU-world twins run, through the same renderer, and so do the Vulkan
#   world's reference image and scene comparisons of `default`, `bees` and
#   `sparks`), ten more CPU-against-Vulkan scene comparisons (the trails and
#   sub-emitters of `comets` and `fireworks` run under the sanitizers in
#   tests/gpu/trail_test.cpp and sub_emitter_test.cpp), three of the
#   four integrators of the gale scene on both backends (explicit Euler
#   runs), the campfire's and the effects close-up's
#   Vulkan reference images (their CPU twins run), the showcase's two
#   reference images at 3 and 8 s (the same code drew the other scenes'
#   frames, and SceneBuild runs the showcase), the 3D dam break's
#   reference image (tests/render/screen_fluid_test.cpp draws the same
#   passes), the run-to-run determinism test (the one-against-two-threads
#   test runs the same code), the non-finite removal and the emitter on a
#   spinning body on the device (their CPU twins run), one of the two Vulkan sort-order tests, the viewer's
#   pour-and-remove script (the other viewer tests run), and the trails'
#   history on both backends (53 s under the sanitizers; the CPU trail
#   writes run in the other trail tests, the device's trail buffers in the
#   Vulkan half of Trails.RibbonCoversTheLastStepsOfThePathOnBothBackends),
#   the device fluid's tank at rest, 2D and 3D dam breaks and jet into a
#   box against the CPU (its world, lists, grid and transfer tests run the
#   same driver under them, its jet's births test the births), and its
#   static tank of bodies, floating box, jet pushing a crate, the
#   showcase's first 1.5 s against the CPU and the moved bodies' contacts
#   listed in the CPU's order (its kinematic paddle, the bodies' gather and
#   the carry run the same body passes, still and moving, under them); and
#   the CPU's launches into tanks without energy
#   gained or particles lost (61 s under the sanitizers; the crates pushing
#   no particle through a wall run the same launches under them); and the
#   sloshing tanks' period against linear theory (34 s under them: 2D and
#   3D fluids without sleeping for four periods; the sleeping wave test
#   runs the same 2D tank under them, and the short 3D fluid tests the 3D
#   solver). A clean
#   run of 2026-12-06 with 55 left out took 31 minutes.
# Under the sanitizers every code path they drive still runs: the short fluid
# tests, SceneBuild.EverySceneBuildsAndRuns (every bundled scene, the showcase
# and the fluid tanks included, for 2 s) and the two-thread determinism tests
# of single scenes.
#
# LeakSanitizer ignores what Mesa's lavapipe allocates and keeps
# (tools/lsan.supp, which says why); our own Vulkan objects are checked by
# the validation layer when each device is destroyed.
#
# The sanitizer build keeps line tables only (-g1, the asan preset): reports
# still give file and line, and the heaviest file (src/effects/emitter_step.cpp)
# compiles in 44 s of CPU instead of 77 s with full -g.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
jobs=$(nproc)
for preset in release asan; do
  echo "=== spindrift tests: $preset ==="
  cmake --preset "$preset"
  cmake --build --preset "$preset" -j "$jobs"
  ctest --preset "$preset" -j "$jobs"
done
