#!/usr/bin/env bash
# Installs GI Workbench's build and test dependencies from Debian 12 packages.
# Idempotent: packages already present are skipped; apt-get runs only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build
  libglfw3-dev libimgui-dev libstb-dev libglm-dev libtinygltf-dev libopenimageio-dev openimageio-tools
  libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev libepoxy-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libembree-dev libtbb-dev libeigen3-dev
  xvfb xauth xdotool assimp-testmodels
  chromium
  clang libclang-rt-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
