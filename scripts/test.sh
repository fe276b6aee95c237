#!/usr/bin/env bash
# The test command (README, .ci/run): installs dependencies, checks the formatting (scripts/check-format.sh),
# builds with warnings as errors (the build also rejects an include that goes up a layer), runs every test
# (CPU math, glTF loading, headless renders with the validation layer, bad input).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/check-format.sh
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVCT_WERROR=ON
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
