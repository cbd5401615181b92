#!/usr/bin/env bash
# Builds the Debian packages of spindrift with CPack (no root needed) and
# checks what they hold with dpkg-deb -c:
#   libspindrift-dev: the public headers, the library, the CMake package, the pkg-config file;
#   spindrift:        the command line tool.
# Usage: tools/make-deb.sh [build-dir]   (default build/release, configured
# with the release preset if it is not there yet). The packages install under
# /usr with the build's library folder (lib/ for a build configured with the
# default prefix; configure with -DCMAKE_INSTALL_PREFIX=/usr for Debian's
# lib/x86_64-linux-gnu/). They land in <build-dir>/packages/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
jobs=${JOBS:-$(nproc)}
if [[ ! -f $build/CMakeCache.txt ]]; then
  cmake --preset release -B "$build"
fi
cmake --build "$build" -j "$jobs" --target spindrift spindrift_cli
out=$(cd "$build" && pwd)/packages
rm -rf "$out"
(cd "$build" && cpack -G DEB -B "$out")

status=0
check() {  # check <deb> <regex that some path must match>...
  local deb=$1; shift
  local listing; listing=$(dpkg-deb -c "$deb" | awk '{print $6}')
  for pattern in "$@"; do
    if ! grep -Eq "$pattern" <<<"$listing"; then
      echo "make-deb: $(basename "$deb") has no path matching $pattern" >&2
      status=1
    fi
  done
}
lib=$(ls "$out"/libspindrift-dev_*.deb)
tool=$(ls "$out"/spindrift_*.deb)
for deb in "$lib" "$tool"; do
  echo "=== $(basename "$deb")"
  dpkg-deb -f "$deb" Package Version Architecture Depends
  dpkg-deb -c "$deb"
done
check "$lib" '^\./usr/include/spindrift/world\.h$' '^\./usr/include/spindrift/export\.h$' \
  '^\./usr/include/spindrift/version\.h$' '^\./usr/lib/(x86_64-linux-gnu/)?libspindrift\.(a|so)$' \
  '^\./usr/lib/.*cmake/spindrift/spindriftConfig\.cmake$' '^\./usr/lib/.*cmake/spindrift/spindriftTargets\.cmake$' \
  '^\./usr/lib/.*pkgconfig/spindrift\.pc$'
check "$tool" '^\./usr/bin/spindrift$'
# Each file in one package only, and nothing of src/ anywhere.
if dpkg-deb -c "$tool" | awk '{print $6}' | grep -Eq '^\./usr/(include|lib)/.'; then
  echo "make-deb: the tool's package holds library files" >&2; status=1
fi
if dpkg-deb -c "$lib" | awk '{print $6}' | grep -Eq '^\./usr/bin/.|/src/'; then
  echo "make-deb: the library's package holds the tool or sources" >&2; status=1
fi
if [[ -z $(dpkg-deb -f "$tool" Depends) ]]; then
  echo "make-deb: the tool's package lists no run-time dependencies" >&2; status=1
fi
((status == 0)) && echo "make-deb: packages in $out checked"
exit $status
