#!/usr/bin/env bash
# Installs what vct needs to build and run on Debian 12 (bookworm): all from Debian's packages.
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools   # Vulkan (lavapipe), shaders
  libglfw3-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev libopenexr-dev
  libopenvdb-dev libopenvdb-tools libboost-iostreams-dev                     # voxel export (vdb_print in tests)
  libimgui-dev                                                               # the demo's panel (+ backend sources)
  libembree-dev libtbb-dev                                                   # the path-traced reference
  libgtest-dev xvfb xauth                                                    # tests, headless window
  clang-format git                                                           # the format check (Debian 12: version 14)
)
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
[ ${#missing[@]} -eq 0 ] && exit 0
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
