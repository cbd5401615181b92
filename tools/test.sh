#!/usr/bin/env bash
# Builds and runs the whole test suite twice: an optimised build with warnings
# as errors, then the same tests under AddressSanitizer and
# UndefinedBehaviorSanitizer. Exits non-zero on any failure.
#
# The sanitizer pass leaves out four tests (the asan test preset's filter in
# CMakePresets.json): the 2D and 3D resting tanks, the 60-layer volume tank
# and the showcase played to its end. Each steps thousands of particles for
# 5 to 8 simulated seconds to measure a physical outcome, which takes 1.5 to
# 4 minutes apiece under the sanitizers and would put CI (2 cores) over its 30
# minutes. They run in the optimised pass; every code path they drive runs
# under the sanitizers in the short fluid tests and in the every-scene tests
# (which step the showcase and the fluid scenes).
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
