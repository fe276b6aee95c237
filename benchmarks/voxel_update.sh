#!/usr/bin/env bash
# voxel_update.sh [SIZE] — what a moving object costs the voxel grid (issue 19.3): the default (only the moved
# voxels and their shadow sweep are resolved, injected and filtered: render/voxel_update.h) against
# --recompute-every-frame (the whole grid every frame, as before), on cornell at 64³ and 128³ and the hall at
# 64³ and 128³. Runs alternate (region, whole, region, whole, ...; VOXEL_UPDATE_REPEATS pairs, default 3) so
# that both see the same machine load; each run's per-pass GPU medians (FRAMES frames after WARMUP) and the
# median over the repeats are written to benchmarks/results/<device>-voxel-update.md (and .json).
#   VOXEL_UPDATE_FRAMES [48]  VOXEL_UPDATE_WARMUP [8]  VOXEL_UPDATE_REPEATS [3]
set -euo pipefail
source "$(dirname "$0")/common.sh"
size="${1:-320x180}"
frames="${VOXEL_UPDATE_FRAMES:-48}" warmup="${VOXEL_UPDATE_WARMUP:-8}" repeats="${VOXEL_UPDATE_REPEATS:-3}"
vct=./build/vct
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for case in cornell:64 cornell:128 hall:64 hall:128; do
    scene="${case%%:*}" voxels="${case##*:}"
    for ((r = 0; r < repeats; ++r)); do
        for mode in region whole; do
            flags=()
            [ "$mode" = whole ] && flags=(--recompute-every-frame)
            out="$work/$scene-$voxels-$mode-$r"
            echo "== $scene ${voxels}³ $mode ($((r + 1))/$repeats)"
            "$vct" render --scene "$scene" --size "$size" --frames "$frames" --warmup "$warmup" --voxels "$voxels" \
                "${flags[@]}" --out "$out" >/dev/null
        done
    done
done
"$PYTHON" - "$work" "$size" "$frames" "$warmup" "$repeats" <<'PY'
import json, statistics, sys, pathlib
work, size, frames, warmup, repeats = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
passes = ["voxelize", "inject", "mips"]
rows, out, device = [], {"size": size, "frames": int(frames), "warmup": int(warmup), "repeats": repeats, "cases": []}, ""
for case in ["cornell:64", "cornell:128", "hall:64", "hall:128"]:
    scene, voxels = case.split(":")
    med = {}
    for mode in ["region", "whole"]:
        runs = []
        for r in range(repeats):
            t = json.load(open(work / f"{scene}-{voxels}-{mode}-{r}" / "timings.json"))
            device = t["device"]
            p = {x["name"]: x["median_ms"] for x in t["passes"]}
            runs.append({"update": sum(p.get(n, 0.0) for n in passes), "frame": t["frame_median_ms"],
                         **{n: p.get(n, 0.0) for n in passes}})
        med[mode] = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
        med[mode]["runs"] = runs
    reg, whole = med["region"], med["whole"]
    out["cases"].append({"scene": scene, "voxels": int(voxels), "region": reg, "whole": whole})
    rows.append(f"| {scene} | {voxels}³ | {reg['voxelize']:.2f} / {reg['inject']:.2f} / {reg['mips']:.2f} | "
                f"{whole['voxelize']:.2f} / {whole['inject']:.2f} / {whole['mips']:.2f} | {reg['update']:.2f} | "
                f"{whole['update']:.2f} | **{100 * reg['update'] / whole['update']:.1f} %** | {reg['frame']:.1f} | "
                f"{100 * reg['update'] / reg['frame']:.1f} % | {whole['frame']:.1f} |")
out["device"] = device
slug = "".join(c if c.isalnum() else "-" for c in device).strip("-")
while "--" in slug: slug = slug.replace("--", "-")
res = pathlib.Path("benchmarks/results")
(res / f"{slug}-voxel-update.json").write_text(json.dumps(out, indent=2) + "\n")
md = [f"# Voxel update of a moving object: only what moved vs the whole grid ({device})", "",
      f"`benchmarks/voxel_update.sh {size}`: `vct render` at {size}, {frames} frames, GPU medians after {warmup} warm-up "
      f"frames, ms; {repeats} alternating pairs of runs, the median over them. *region*: the default (render/voxel_update.h); "
      "*whole*: `--recompute-every-frame` (every voxel every frame, the behaviour before). Both give bit-identical "
      "images (tests/static_scene_test.cpp). update = voxelize + inject + mips.", "",
      "| scene | voxels | region voxelize / inject / mips | whole voxelize / inject / mips | region update | whole update | region ÷ whole | region frame | update ÷ frame | whole frame |",
      "|---|---|---|---|---|---|---|---|---|---|", *rows, ""]
(res / f"{slug}-voxel-update.md").write_text("\n".join(md))
print("\n".join(md))
PY
