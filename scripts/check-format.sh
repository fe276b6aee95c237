#!/usr/bin/env bash
# The format check (scripts/test.sh, ctest format_check): fails, naming the files and lines, when a tracked
# C++ or GLSL file is not as clang-format 14 writes it. C++ follows .clang-format, the shaders
# shaders/.clang-format (GLSL keeps its include order). `scripts/check-format.sh --fix` formats them instead.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format="${CLANG_FORMAT:-$(command -v clang-format-14 || echo clang-format)}"
if ! version="$("$clang_format" --version 2>/dev/null)"; then
    echo "check-format: $clang_format not found (install clang-format 14: scripts/install-deps.sh)" >&2
    exit 1
fi
case "$version" in
    *"version 14."*) ;;
    *) echo "check-format: needs clang-format 14 (others format differently), found: $version" >&2; exit 1 ;;
esac

# Being changed on another branch (the GI tracer) when the formatting commit was made: not formatted yet, so
# not checked. Empty this list once that work is merged and formatted.
excluded=(
    shaders/lib/cone.glsl shaders/lib/cone_trace.glsl shaders/lib/voxel.glsl shaders/lib/shared.h
    shaders/inject.comp shaders/voxel_mips.comp shaders/trace.comp shaders/resample.comp shaders/voxel_view.comp
    engine/render/voxel_grid.h engine/render/voxel_grid.cpp engine/render/renderer.h engine/render/renderer.cpp
    engine/render/settings.h engine/render/setting_table.h engine/render/setting_table.cpp
    engine/passes/inject_pass.h engine/passes/inject_pass.cpp engine/passes/voxel_mips_pass.h
    engine/passes/voxel_mips_pass.cpp engine/passes/trace_pass.h engine/passes/trace_pass.cpp
    engine/passes/resample_pass.h engine/passes/resample_pass.cpp engine/passes/voxel_view_pass.h
    engine/passes/voxel_view_pass.cpp
    tests/cone_test.cpp tests/voxel_test.cpp tests/reference_test.cpp
)
# Likewise files that branch adds: in shaders/ and engine/passes/ only these were formatted. Remove this list
# (check every file there) together with the one above.
formatted_in_shaders_and_passes=(
    engine/passes/composite_pass.cpp engine/passes/composite_pass.h engine/passes/direct_pass.cpp
    engine/passes/direct_pass.h engine/passes/gbuffer_pass.cpp engine/passes/gbuffer_pass.h
    engine/passes/shadow_pass.cpp engine/passes/shadow_pass.h engine/passes/upsample_pass.cpp
    engine/passes/upsample_pass.h engine/passes/voxelize_pass.cpp engine/passes/voxelize_pass.h
    shaders/composite.comp shaders/direct.comp shaders/gbuffer.frag shaders/gbuffer.vert shaders/lib/brdf.glsl
    shaders/lib/color.glsl shaders/lib/constants.glsl shaders/lib/cpp_glsl.h shaders/lib/gbuffer_read.glsl
    shaders/lib/indirect_pack.glsl shaders/lib/lights.glsl shaders/lib/toksvig.glsl
    shaders/lib/upsample_guide.glsl shaders/lib/upsample_weights.glsl shaders/shadow.vert shaders/upsample.comp
    shaders/voxel_resolve.comp shaders/voxelize.comp
)

declare -A skip=() formatted=()
for f in "${excluded[@]}"; do skip[$f]=1; done
for f in "${formatted_in_shaders_and_passes[@]}"; do formatted[$f]=1; done
files=()
while IFS= read -r f; do
    [ -n "${skip[$f]:-}" ] && continue
    case "$f" in shaders/* | engine/passes/*) [ -z "${formatted[$f]:-}" ] && continue ;; esac
    files+=("$f")
done < <(git ls-files -- '*.cpp' '*.h' '*.glsl' '*.comp' '*.vert' '*.frag' '*.geom')

if [ "${1:-}" = "--fix" ]; then
    "$clang_format" -i "${files[@]}"
    exit 0
fi
if ! "$clang_format" --dry-run --Werror "${files[@]}"; then
    echo "check-format: the files above are not formatted; run scripts/check-format.sh --fix" >&2
    exit 1
fi
echo "check-format: ${#files[@]} files formatted"
