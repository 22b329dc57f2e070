#!/usr/bin/env bash
# Installs every Debian package sandtin needs to build, test and run.
# Idempotent: packages already present are skipped, so a second run is instant.
# Usage: scripts/install-deps.sh   (uses sudo when not run as root)
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # geometry and maths
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev
  # files and formats (GDAL: GeoTIFF import; OpenEXR: float heightmaps; tinygltf: glTF export)
  nlohmann-json3-dev libpng-dev libgdal-dev libopenexr-dev libtinygltf-dev
  # GPU, window and UI (X11, XRandR and XTest headers: scripted runs send real X input)
  libvulkan-dev vulkan-validationlayers mesa-vulkan-drivers glslang-tools glslang-dev
  libglfw3-dev libimgui-dev libstb-dev libx11-dev libxrandr-dev libxtst-dev
  # tests: GoogleTest, a virtual X server for the editor tests, and util-linux's `script`
  # (bsdutils: a pseudo-terminal for the CLI's progress lines)
  libgtest-dev libgmock-dev xvfb xauth xdotool bsdutils
  # fuzzing and sanitizers: clang with libFuzzer and its runtimes
  clang-14 libclang-rt-14-dev
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo_cmd=(sudo)
  else
    echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq || echo "install-deps: apt-get update failed; trying the cached package lists" >&2
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
