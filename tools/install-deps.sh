#!/usr/bin/env bash
# Installs spindrift's build and test dependencies from Debian 12 packages.
# Only what is missing is installed; safe to run again.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git
  libglm-dev libtbb-dev libtomlplusplus-dev libcli11-dev libfmt-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libvulkan-dev glslc mesa-vulkan-drivers vulkan-validationlayers
  libbox2d-dev libglfw3-dev libimgui-dev
  ffmpeg xvfb xauth
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "spindrift: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -ne 0 ]] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "spindrift: all dependencies present"
fi
