#!/usr/bin/python3
"""The ground-truth report (benchmarks/truth.sh) from its `vct compare --reference-dir` JSONs, nothing else:

  OUT/truth.md                   per scene and reference: whole-image ratios, tone-mapped PSNRs and relMSE per
                                 voxel resolution x trace scale; per surface x voxel resolution x scale the
                                 indirect / diffuse / specular ratios
  OUT/truth_ratios.png           per-surface indirect ratio (vct / reference) against voxel resolution, a line at 1
                                 (one-bounce reference; solid: trace scale 1, dashed: the others)
  OUT/truth_error_vs_voxels.png  indirect sRGB PSNR and relMSE against voxel resolution, per scene, scale and
                                 reference (the relMSE panel also shows the reference's own noise term, dotted)
  OUT/truth_maps-SCENE.png       the log2 indirect ratio maps side by side (voxels x scale, one-bounce reference)
  OUT/maps/STEM/log2_*.png       the ratio maps, copied from where `vct compare --maps` wrote them

Each JSON's "config" (added by truth.sh) names its scene, voxels, trace_scale and reference_kind; a JSON without
one is understood from its file name, truth-SCENE-vVOXELS-sSCALE-vs-KIND.json. The Markdown is written even
without matplotlib (Debian's python3-matplotlib, for the plots only; never needed to build or test).
Usage: plot_truth.py OUT_DIR TRUTH.json...
"""
import json
import os
import re
import shutil
import sys

KIND_LABELS = {"1": "one-bounce reference", "all": "all-bounce reference",
               "diffuse": "one-bounce reference, diffuse secondary vertices, against vct's Lambertian voxels "
                          "(--voxel-glossy off): the cone tracer's own error"}
KIND_ORDER = ["1", "all", "diffuse"]
RATIO_TICKS = [1 / 16, 1 / 8, 1 / 4, 0.5, 0.6, 0.7, 0.8, 0.9, 1, 1.1, 1.25, 1.5, 2, 3, 4, 8, 16]
KIND_STYLES = {"1": "-", "all": "--", "diffuse": ":"}
NAME_PATTERN = re.compile(r"truth-(?P<scene>.+)-v(?P<voxels>\d+)-s(?P<trace_scale>\d+)-vs-(?P<reference_kind>[^.]+)\.json$")


def load(paths):
    runs = []
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        config = dict(data.get("config") or {})
        match = NAME_PATTERN.search(os.path.basename(path))
        if match:
            for key, value in match.groupdict().items():
                config.setdefault(key, int(value) if key in ("voxels", "trace_scale") else value)
        if not all(k in config for k in ("scene", "voxels", "trace_scale", "reference_kind")):
            print(f"plot_truth.py: {path}: no config and not named truth-SCENE-vV-sT-vs-KIND.json: skipped",
                  file=sys.stderr)
            continue
        config["reference_kind"] = str(config["reference_kind"])
        runs.append({"path": path, "stem": os.path.splitext(os.path.basename(path))[0], "config": config,
                     "data": data})
    return runs


def group(runs):
    """{scene: {kind: [run, ...] sorted by (scale, voxels)}}, scenes and kinds in a stable order."""
    scenes = {}
    for run in runs:
        c = run["config"]
        scenes.setdefault(c["scene"], {}).setdefault(c["reference_kind"], []).append(run)
    for kinds in scenes.values():
        for kind_runs in kinds.values():
            kind_runs.sort(key=lambda r: (r["config"]["trace_scale"], r["config"]["voxels"]))
    return scenes


def kinds_in_order(kinds):
    return sorted(kinds, key=lambda k: KIND_ORDER.index(k) if k in KIND_ORDER else len(KIND_ORDER))


def num(value, fmt="{:.3f}"):
    return "–" if value is None else fmt.format(value)


def psnr(error):
    # null in the JSON: identical images (MSE 0: an infinite PSNR) or no pixel (MSE null too).
    if error["psnr_srgb"] is not None:
        return f"{error['psnr_srgb']:.2f}"
    return "∞" if error["mse_srgb"] == 0 else "–"


def config_label(c):
    return f"{c['voxels']}³ s{c['trace_scale']}"


def markdown(scenes):
    lines = ["# vct against ground truth", ""]
    first = next(iter(next(iter(scenes.values())).values()))[0]
    c, d = first["config"], first["data"]
    lines += [
        f"Device: {c.get('device', '?')}. Frame {d['width']}×{d['height']}; vct after {c.get('frames', '?')} frames, "
        f"the references path-traced at the frame vct writes ({c.get('frame', '?')}) with {c.get('spp', '?')} spp "
        f"(`benchmarks/truth.sh`). Definitions: `docs/truth_compare.md`.",
        "",
        "Ratios are Σ lum(vct) / Σ lum(reference) over the pixels of a surface (1 = the same light); *indirect* is "
        "final − direct, *diffuse* and *specular* the demodulated incoming indirect light. PSNR on the tone-mapped "
        "sRGB image (peak 1), over the non-background pixels. relMSE on linear HDR, mean ((v − r)² − var r) / "
        "(r² + 10⁻³): the reference's noise subtracted, so values within ± *noise* of 0 are below what the "
        "reference resolves. – : no reference light (a null in the JSON).",
        "",
    ]
    for scene, kinds in scenes.items():
        for kind in kinds_in_order(kinds):
            runs = kinds[kind]
            ref = runs[0]["data"].get("reference", {})
            lines += [f"## {scene}: {KIND_LABELS.get(kind, kind)}", ""]
            if ref:
                lines += ["Reference: " + ", ".join(f"{k} {json.dumps(v)}" for k, v in sorted(ref.items())), ""]
            lines += ["| voxels | scale | indirect | diffuse | specular | direct | PSNR final | PSNR indirect | "
                      "PSNR diffuse | PSNR specular | relMSE final | relMSE indirect | noise (indirect) | "
                      "ref. PSNR indirect | PSNR indirect without ref. noise | vct ms/frame |",
                      "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
                      " ---: | ---: | ---: |"]
            for run in runs:
                d, cfg = run["data"], run["config"]
                image, errors = d["image"], d["errors"]
                lines.append(
                    f"| {cfg['voxels']}³ | {cfg['trace_scale']} | "
                    + " | ".join(num(image[q]["ratio"]) for q in ("indirect", "diffuse", "specular", "direct"))
                    + " | " + " | ".join(psnr(errors[q]) for q in ("final", "indirect", "diffuse",
                                                                                "specular"))
                    + f" | {num(errors['final']['rel_mse'], '{:.3g}')} | {num(errors['indirect']['rel_mse'], '{:.3g}')}"
                    + f" | {num(errors['indirect']['rel_mse_noise'], '{:.2g}')}"
                    + f" | {num(errors['indirect'].get('psnr_srgb_reference'), '{:.2f}')}"
                    + f" | {num(errors['indirect'].get('psnr_srgb_without_reference_noise'), '{:.2f}')}"
                    + f" | {num(cfg.get('frame_median_ms'), '{:.1f}')} |")
            lines += ["", "Per surface, indirect / diffuse / specular ratio (reference noise on the sums in the "
                      "third column):", ""]
            header = "| surface | pixels | ref. noise ind / diff / spec | " + " | ".join(
                config_label(r["config"]) for r in runs) + " |"
            lines += [header, "| --- | ---: | ---: |" + " ---: |" * len(runs)]
            surfaces = {}
            for i, run in enumerate(runs):
                for s in run["data"]["surfaces"]:
                    surfaces.setdefault(s["id"], {"surface": s, "cells": [None] * len(runs)})["cells"][i] = s
            for sid in sorted(surfaces):
                s = surfaces[sid]["surface"]
                noise = " / ".join(num(s[q]["reference_noise"] and 100 * s[q]["reference_noise"], "{:.1f}%")
                                   for q in ("indirect", "diffuse", "specular"))
                cells = [" / ".join(num(cell[q]["ratio"], "{:.2f}") for q in ("indirect", "diffuse", "specular"))
                         if cell else "" for cell in surfaces[sid]["cells"]]
                lines.append(f"| {sid} {s['name']} | {s['pixels']} | {noise} | " + " | ".join(cells) + " |")
            lines.append("")
    return "\n".join(lines)


def copy_maps(runs, out_dir):
    for run in runs:
        for source in run["data"].get("maps", []):
            if not source.endswith(".png"):
                continue
            target_dir = os.path.join(out_dir, "maps", run["stem"])
            target = os.path.join(target_dir, os.path.basename(source))
            if os.path.abspath(source) == os.path.abspath(target):
                continue
            if not os.path.exists(source):
                if not os.path.exists(target):
                    print(f"plot_truth.py: {source} is gone: not copied", file=sys.stderr)
                continue
            os.makedirs(target_dir, exist_ok=True)
            shutil.copyfile(source, target)
            run.setdefault("copied", {})[os.path.basename(source)] = target


def main_kind(kinds):
    return "1" if "1" in kinds else kinds_in_order(kinds)[0]


def plot_ratios(scenes, out_path, plt):
    from matplotlib.ticker import FuncFormatter

    fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.5), squeeze=False)
    for ax, (scene, kinds) in zip(axes[0], scenes.items()):
        kind = main_kind(kinds)
        runs = kinds[kind]
        by_surface = {}
        for run in runs:
            for s in run["data"]["surfaces"]:
                entry = by_surface.setdefault(s["id"], {"name": s["name"], "pixels": s["pixels"], "points": {}})
                entry["points"].setdefault(run["config"]["trace_scale"], []).append(
                    (run["config"]["voxels"], s["indirect"]["ratio"]))
        # The 10 largest surfaces (by pixels), so that the legend stays readable.
        shown = sorted(by_surface.items(), key=lambda item: -item[1]["pixels"])[:10]
        colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for index, (sid, entry) in enumerate(shown):
            colour = colours[index % len(colours)]
            for scale, points in sorted(entry["points"].items()):
                points = sorted(p for p in points if p[1] is not None and p[1] > 0)
                if not points:
                    continue
                ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", color=colour,
                        ls="-" if scale == 1 else "--", label=f"{sid} {entry['name']}" if scale == 1 or
                        1 not in entry["points"] else None)
        ax.axhline(1.0, color="k", lw=0.8)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log", base=2)
        low, high = ax.get_ylim()
        ticks = [t for t in RATIO_TICKS if low <= t <= high]
        if len(ticks) < 3:  # a narrow range: five evenly spaced ticks instead
            ticks = [float(f"{low + (high - low) * k / 4:.3g}") for k in range(5)]
        ax.set_yticks(ticks, minor=False)
        ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:.3g}"))
        ax.yaxis.set_minor_formatter(FuncFormatter(lambda y, _: ""))
        voxels = sorted({r["config"]["voxels"] for r in runs})
        ax.set_xticks(voxels, [f"{v}³" for v in voxels])
        ax.set_xlabel("voxel resolution")
        ax.set_ylabel("indirect ratio Σ lum(vct) / Σ lum(reference)")
        ax.set_title(f"{scene} ({KIND_LABELS.get(kind, kind)})\nsolid: trace scale 1, dashed: 4", fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)
    plt.close(fig)


def plot_errors(scenes, out_path, plt):
    fig, axes = plt.subplots(2, len(scenes), figsize=(5.5 * len(scenes), 8), squeeze=False)
    scale_colours = {}
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for col, (scene, kinds) in enumerate(scenes.items()):
        top, bottom = axes[0][col], axes[1][col]
        voxels = set()
        for kind in kinds_in_order(kinds):
            by_scale = {}
            for run in kinds[kind]:
                by_scale.setdefault(run["config"]["trace_scale"], []).append(run)
            for scale, runs in sorted(by_scale.items()):
                colour = scale_colours.setdefault(scale, colours[len(scale_colours) % len(colours)])
                runs.sort(key=lambda r: r["config"]["voxels"])
                xs = [r["config"]["voxels"] for r in runs]
                voxels.update(xs)
                label = f"scale {scale}, {KIND_LABELS.get(kind, kind)}"
                points = [(x, r["data"]["errors"]["indirect"]["psnr_srgb"]) for x, r in zip(xs, runs)]
                points = [p for p in points if p[1] is not None]
                top.plot([p[0] for p in points], [p[1] for p in points], marker="o", color=colour,
                         ls=KIND_STYLES.get(kind, "-"), label=label)
                rel = [(x, r["data"]["errors"]["indirect"]["rel_mse"]) for x, r in zip(xs, runs)]
                rel = [p for p in rel if p[1] is not None]
                bottom.plot([p[0] for p in rel], [p[1] for p in rel], marker="o", color=colour,
                            ls=KIND_STYLES.get(kind, "-"), label=label)
                noise = [(x, r["data"]["errors"]["indirect"]["rel_mse_noise"]) for x, r in zip(xs, runs)]
                noise = [p for p in noise if p[1] is not None]
                bottom.plot([p[0] for p in noise], [p[1] for p in noise], color="grey", ls=":", lw=0.8)
        for ax in (top, bottom):
            ax.set_xscale("log", base=2)
            ax.set_xticks(sorted(voxels), [f"{v}³" for v in sorted(voxels)])
            ax.set_xlabel("voxel resolution")
            ax.grid(alpha=0.3)
        top.set_ylabel("indirect (final − direct), tone-mapped sRGB PSNR (dB)")
        top.set_title(scene)
        top.legend(fontsize=6)
        bottom.axhline(0.0, color="k", lw=0.8)
        bottom.set_ylabel("indirect relMSE, reference noise subtracted\n(dotted grey: the noise term)")
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)
    plt.close(fig)


def plot_maps(scene, runs, out_path, plt):
    from matplotlib.colors import LinearSegmentedColormap

    maps = [(r, r.get("copied", {}).get("log2_indirect.png")) for r in runs]
    maps = [(r, path) for r, path in maps if path and os.path.exists(path)]
    if not maps:
        return False
    scales = sorted({r["config"]["trace_scale"] for r, _ in maps})
    voxels = sorted({r["config"]["voxels"] for r, _ in maps})
    fig, axes = plt.subplots(len(scales), len(voxels), figsize=(4 * len(voxels), 2.6 * len(scales) + 0.6),
                             squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for run, path in maps:
        ax = axes[scales.index(run["config"]["trace_scale"])][voxels.index(run["config"]["voxels"])]
        ax.imshow(plt.imread(path), interpolation="nearest")
        ratio = run["data"]["image"]["indirect"]["ratio"]
        ax.set_title(f"{config_label(run['config'])}: indirect ratio {num(ratio)}", fontsize=8)
    colours = LinearSegmentedColormap.from_list("truth", [(0, 0, 1), (1, 1, 1), (1, 0, 0)])
    bar = fig.colorbar(plt.cm.ScalarMappable(cmap=colours, norm=plt.Normalize(-2, 2)), ax=axes.ravel().tolist(),
                       shrink=0.8)
    bar.set_label("log2(lum vct / lum reference), indirect (black: background)")
    fig.suptitle(f"{scene}: where vct has too much (red) or too little (blue) indirect light", fontsize=10)
    fig.savefig(out_path, dpi=130)
    plt.close(fig)
    return True


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out_dir = sys.argv[1]
    os.makedirs(out_dir, exist_ok=True)
    runs = load(sys.argv[2:])
    if not runs:
        print("plot_truth.py: no usable JSON", file=sys.stderr)
        return 1
    scenes = group(runs)
    copy_maps(runs, out_dir)
    with open(os.path.join(out_dir, "truth.md"), "w") as f:
        f.write(markdown(scenes) + "\n")
    written = ["truth.md"]
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("python3-matplotlib is needed for the plots: apt-get install -y python3-matplotlib", file=sys.stderr)
        return 1
    plot_ratios(scenes, os.path.join(out_dir, "truth_ratios.png"), plt)
    plot_errors(scenes, os.path.join(out_dir, "truth_error_vs_voxels.png"), plt)
    written += ["truth_ratios.png", "truth_error_vs_voxels.png"]
    for scene, kinds in scenes.items():
        name = f"truth_maps-{re.sub(r'[^A-Za-z0-9_.-]', '-', scene)}.png"
        if plot_maps(scene, kinds[main_kind(kinds)], os.path.join(out_dir, name), plt):
            written.append(name)
    print(f"plot_truth.py: wrote {', '.join(written)} in {out_dir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
