# Sourced by the benchmark scripts: the repository root, the runtime dir, Debian's python3 (matplotlib comes
# from python3-matplotlib, for plots only), and the device slug that names result files.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
PYTHON=/usr/bin/python3
[ -x "$PYTHON" ] || PYTHON=python3
mkdir -p benchmarks/results

# device_slug REPORT.json: the report's device name as a file-name prefix ("llvmpipe-LLVM-15-0-6-256-bits").
device_slug() {
    "$PYTHON" -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"])' "$1" |
        tr -cs 'A-Za-z0-9' '-' | sed 's/-*$//'
}

# flags_suffix ARGS...: extra flags as a file-name suffix ("--trace-scale 2" → "-trace-scale-2"; none → ""), so that
# configurations measured side by side do not overwrite each other's results.
flags_suffix() {
    local flags
    flags="$(echo "$*" | tr -cs 'A-Za-z0-9' '-' | sed 's/^-*//; s/-*$//')"
    echo "${flags:+-$flags}"
}

# cached_reference DIR ARGS...: `$vct reference ARGS... --out DIR`, unless DIR already holds a reference made with
# the same ARGS (recorded in DIR.settings); the wall time goes to DIR.seconds.
cached_reference() {
    local dir="$1" stamp start
    shift
    stamp="$*"
    if [ -f "$dir/reference.json" ] && [ "$(cat "$dir.settings" 2>/dev/null)" = "$stamp" ]; then
        echo "reusing $dir"
        return
    fi
    echo "== vct reference $* -> $dir"
    start=$SECONDS
    "$vct" reference "$@" --out "$dir"
    echo "$((SECONDS - start))" >"$dir.seconds"
    echo "$stamp" >"$dir.settings"
}
