#!/usr/bin/env bash
# The main job (README): installs dependencies, builds, renders the built-in default scene headless into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
build/vct render --scene cornell --size 1280x720 --frames 30 --out out "$@"
