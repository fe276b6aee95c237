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

files=()
while IFS= read -r f; do
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
