#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build,
# and run the bundled default scene, writing particle caches and a summary to
# out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake --preset release
cmake --build --preset release --target spindrift_cli
build/release/spindrift run scenes/default.toml --out out/default --every 60
echo "spindrift: caches and summary.json written to out/default/"
