#!/usr/bin/env bash
# Installs the Debian packages the way a user would, `apt install ./*.deb`,
# and checks them from outside the source tree: the tool validates and runs
# a bundled scene, and the examples configure, build and run against the
# installed package with find_package(spindrift) and no prefix hint. Then it
# removes the packages again (it also does so when a check fails).
#
# Needs root or sudo (apt), and changes the system's /usr while it runs, so it
# is a script, not a test in the suite (which must not write outside its
# build folder). Usage: tools/test-deb.sh [build-dir]   (default
# build/deb, configured with -DCMAKE_INSTALL_PREFIX=/usr so the library lands
# in Debian's lib/<multiarch>/ folder).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${1:-build/deb}
jobs=${JOBS:-$(nproc)}
sudo_cmd=()
[[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)

if [[ ! -f $build/CMakeCache.txt ]]; then
  cmake --preset release -B "$build" -DCMAKE_INSTALL_PREFIX=/usr -DSPINDRIFT_BUILD_TESTS=OFF -DSPINDRIFT_BUILD_BENCH=OFF
fi
JOBS=$jobs tools/make-deb.sh "$build"
packages=$(cd "$build/packages" && pwd)

for name in libspindrift-dev spindrift; do
  if dpkg-query -W -f='${Status}' "$name" 2>/dev/null | grep -q "install ok installed"; then
    echo "test-deb: $name is already installed; remove it first" >&2
    exit 1
  fi
done

work=$(mktemp -d)
cleanup() {
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get remove -y -qq libspindrift-dev spindrift >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT

echo "=== apt install ./libspindrift-dev_*.deb ./spindrift_*.deb"
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq \
  "$packages"/libspindrift-dev_*.deb "$packages"/spindrift_*.deb

echo "=== the tool from /usr/bin"
[[ $(command -v spindrift) == /usr/bin/spindrift ]] || { echo "test-deb: spindrift is not /usr/bin/spindrift" >&2; exit 1; }
spindrift --version
spindrift validate "$root/scenes/fluid_boxes.toml"
spindrift run "$root/scenes/fluid_boxes.toml" --out "$work/run" --seconds 0.5 --format csv
ls "$work/run" | grep -q '^summary\.json$' || { echo "test-deb: run wrote no summary.json" >&2; exit 1; }

echo "=== pkg-config"
pkg-config --exists spindrift
pkg-config --modversion spindrift

for example in particle_effect fluid_crates render_png; do
  echo "=== examples/$example against the installed package"
  cmake -S "$root/examples/$example" -B "$work/$example" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$work/$example" -j "$jobs" >/dev/null
  grep -q '^spindrift_DIR:PATH=/usr/lib/' "$work/$example/CMakeCache.txt" ||
    { echo "test-deb: $example did not find the package under /usr/lib" >&2; exit 1; }
  if [[ $example == render_png ]]; then
    "$work/$example/$example" "$root/examples/render_png/scene.toml" "$work/frame.png"
    [[ -s $work/frame.png ]] || { echo "test-deb: render_png wrote no frame" >&2; exit 1; }
  else
    "$work/$example/$example"
  fi
done
echo "test-deb: the packages install with apt, and the tool and the examples work from them"
