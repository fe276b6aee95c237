#!/usr/bin/python3
"""Plots the speed-against-error report (benchmarks/report.sh) from its JSON files, nothing else:

  PREFIX-pareto-SCENE.png       final sRGB PSNR (and specular PSNR) against GPU ms per frame, one point per
                                configuration, static and moving camera (the Pareto front: up and left is better);
                                with the truth (TRUTH.json, benchmarks/report.sh), a second row: sRGB PSNR of the
                                final and of the indirect light against the path-traced reference, static camera,
                                the every-pixel trace included (the upsampling's error above, the GI's below)
  PREFIX-truth.md               with the truth: per scene and configuration, ms per frame, the error against the
                                every-pixel trace and against the path-traced reference (PSNR, relMSE, ratio)
  PREFIX-convergence-SCENE.png  PSNR of diffuse, specular and final against frame number: static camera
                                (convergence), moving camera, and the cut halfway (recovery)
  PREFIX-tau.png                re-traced fraction and final sRGB PSNR against τ (moving camera, scale 4, sg)
  PREFIX-study-SCENE.png        Tokuyoshi 2015 Fig. 6: sg specular MSE over β × κ per material class (heat
                                maps), and MSE against β (κ 100) and against σ_n (normal), each normalised by
                                its optimum

Benchmark scripts only: matplotlib (Debian's python3-matplotlib) is never needed to build or test.
Usage: plot_report.py REPORT.json STUDY.json OUT_PREFIX [TRUTH.json...]
  TRUTH.json: benchmarks/report.sh's ...-report-truth-SCENE.json (configuration name -> vct compare
  --reference-dir metrics of the static camera's last frame against vct reference)
"""
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

WEIGHT_COLOURS = {"bilinear": "tab:gray", "normal": "tab:blue", "sg": "tab:red"}


def weights_of(name):
    for weights in WEIGHT_COLOURS:
        if f" {weights}" in f" {name}":
            return weights
    return None


def runs_by_scene(report):
    scenes = {}
    for run in report["runs"]:
        scenes.setdefault(run["scene"], {})[run["camera"]] = run
    return scenes


def main_configs(run):
    """The configurations of the grid (no τ sweep), reference excluded."""
    return [c for c in run["configs"] if "error" in c and "tau " not in c["name"]]


def number(value):
    """A finite float, or None (compare writes null for an infinite PSNR)."""
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def truth_points(truth, static_run):
    """(name, ms per frame, compare entry) per configuration of the truth, the every-pixel trace first; ms from
    the report's static run (the same numbers as the row above), else from the truth file."""
    ms = {c["name"]: c["frame_median_ms"] for c in static_run["configs"]} if static_run else {}
    points = []
    for name in truth.get("order", list(truth["configs"])):
        entry = truth["configs"][name]
        points.append((name, ms.get(name, entry.get("frame_median_ms")), entry))
    return points


def truth_label(truth):
    reference = truth.get("reference") or {}
    bounces = reference.get("bounces", 1)
    return (f"path-traced reference ({truth['spp']} spp, {bounces} bounce{'s' if bounces != 1 else ''}, "
            f"frame {truth['frame']}, static camera)")


def plot_truth_row(axes, truth, static_run):
    for ax, light, label in [(axes[0], "final", "final, sRGB PSNR against the path-traced reference (dB)"),
                             (axes[1], "indirect", "indirect (final − direct), sRGB PSNR against the truth (dB)")]:
        for name, ms, entry in truth_points(truth, static_run):
            psnr = number(entry["errors"][light]["psnr_srgb"])
            if psnr is None or ms is None:
                continue
            if entry["trace_scale"] == 1:  # the every-pixel trace: the GI's own error, no upsampling
                ax.scatter(ms, psnr, marker="*", s=160, color="k", zorder=3)
                ax.axhline(psnr, color="k", ls=":", lw=0.8)
                ax.axvline(ms, color="k", ls=":", lw=0.8)
                ax.annotate("every-pixel trace (scale 1)", (ms, psnr), fontsize=6, xytext=(4, -9),
                            textcoords="offset points")
                continue
            weights = weights_of(name)
            colour = WEIGHT_COLOURS.get(weights, "k")
            ax.scatter(ms, psnr, marker="o", s=60 if entry["trace_scale"] == 4 else 30, color=colour,
                       facecolors=colour if "adaptive" in name else "none")
            ax.annotate(name, (ms, psnr), fontsize=5, xytext=(3, 2), textcoords="offset points")
        ax.set_xlabel("GPU ms per frame (median; dotted: the every-pixel trace)")
        ax.set_ylabel(label)
        ax.set_title(truth_label(truth), fontsize=8)
        ax.grid(alpha=0.3)


def plot_pareto(scene, cameras, out_path, truth=None):
    rows = 2 if truth else 1
    fig, axes = plt.subplots(rows, 2, figsize=(12, 4.8 * rows), squeeze=False)
    for ax, key, label in [(axes[0][0], "final_srgb", "final, tone-mapped sRGB PSNR (dB, peak 1)"),
                           (axes[0][1], "specular", "specular indirect PSNR (dB, peak = reference max)")]:
        for camera, marker in [("static", "o"), ("moving", "^")]:
            if camera not in cameras:
                continue
            run = cameras[camera]
            reference = run["configs"][0]
            ax.axvline(reference["frame_median_ms"], color="k", ls=":" if camera == "static" else "--", lw=0.8)
            for c in main_configs(run):
                weights = weights_of(c["name"])
                scale = c["settings"]["trace_scale"]
                ax.scatter(c["frame_median_ms"], c["error"][key]["psnr"], marker=marker,
                           s=60 if scale == 4 else 30, color=WEIGHT_COLOURS.get(weights, "k"),
                           facecolors="none" if "adaptive" not in c["name"] else WEIGHT_COLOURS.get(weights, "k"))
                ax.annotate(f"{c['name']} ({camera})", (c["frame_median_ms"], c["error"][key]["psnr"]),
                            fontsize=5, xytext=(3, 2), textcoords="offset points")
        ax.set_xlabel("GPU ms per frame (median; dotted/dashed: the reference, every pixel traced)")
        ax.set_ylabel(label)
        ax.set_title("against the every-pixel trace of the same frame (the upsampling's error)", fontsize=8)
        ax.grid(alpha=0.3)
    if truth:
        plot_truth_row(axes[1], truth, cameras.get("static"))
    title = f"{scene}: error against cost (o static, ^ moving camera; large: scale 4; filled: adaptive)"
    if truth:
        title += "\nbottom: against the path-traced truth (the GI's error; ★ the every-pixel trace)"
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)
    plt.close(fig)


def fmt(value, spec):
    value = number(value)
    return "–" if value is None else format(value, spec)


def write_truth_table(report, truths, out_path):
    """Markdown: per scene and configuration, cost, the error against the every-pixel trace and against the
    truth."""
    lines = ["Static camera, last frame of the report, every configuration against a path-traced reference of "
             "that frame (`vct reference`, `vct compare --reference-dir`; docs/truth_compare.md): sRGB PSNR "
             "(tone-mapped, peak 1) and relMSE (linear HDR, the reference's noise subtracted) of the final and of "
             "the indirect light (final − direct), and Σ indirect / Σ reference indirect. \"vs every-pixel\": the "
             "report's final sRGB PSNR against the every-pixel trace (trace scale 1) of the same frame.",
             "",
             "| scene | configuration | frame ms | final PSNR vs every-pixel | final PSNR vs truth | "
             "indirect PSNR vs truth | final relMSE | indirect relMSE | indirect ratio |",
             "|---|---|---|---|---|---|---|---|---|"]
    runs = runs_by_scene(report)
    notes = []
    for scene, truth in truths.items():
        static = runs.get(scene, {}).get("static")
        upsampling = {c["name"]: c["error"]["final_srgb"]["psnr"] for c in static["configs"] if "error" in c} \
            if static else {}
        for name, ms, entry in truth_points(truth, static):
            errors = entry["errors"]
            lines.append(
                f"| {scene} | {name if entry['trace_scale'] != 1 else name + ' (every-pixel trace)'} | "
                f"{fmt(ms, '.2f')} | {fmt(upsampling.get(name), '.2f')} | "
                f"{fmt(errors['final']['psnr_srgb'], '.2f')} | {fmt(errors['indirect']['psnr_srgb'], '.2f')} | "
                f"{fmt(errors['final']['rel_mse'], '.4g')} | {fmt(errors['indirect']['rel_mse'], '.4g')} | "
                f"{fmt(entry.get('image', {}).get('indirect', {}).get('ratio'), '.3f')} |")
        first = truth["configs"][truth_points(truth, static)[0][0]]["errors"]
        seconds = truth.get("reference_seconds")
        notes.append(f"- {scene}: {truth_label(truth)}, {truth['width']}x{truth['height']}"
                     f"{f', {seconds} s' if seconds is not None else ''}; its noise, as relMSE: final "
                     f"{fmt(first['final'].get('rel_mse_noise'), '.3g')}, indirect "
                     f"{fmt(first['indirect'].get('rel_mse_noise'), '.3g')} (a relMSE within it is below what "
                     "the reference resolves).")
    with open(out_path, "w") as f:
        f.write("\n".join(lines + [""] + notes) + "\n")


def plot_convergence(scene, cameras, out_path):
    present = [c for c in ("static", "moving", "cut") if c in cameras]
    fig, axes = plt.subplots(len(present), 3, figsize=(15, 3.6 * len(present)), squeeze=False)
    for row, camera in enumerate(present):
        run = cameras[camera]
        for col, (curve, label) in enumerate([("diffuse_psnr", "diffuse PSNR"), ("specular_psnr", "specular PSNR"),
                                              ("final_srgb_psnr", "final sRGB PSNR")]):
            ax = axes[row][col]
            for c in main_configs(run):
                if c["settings"]["trace_scale"] != 4:
                    continue
                weights = weights_of(c["name"])
                ax.plot(c["curves"][curve], color=WEIGHT_COLOURS.get(weights, "k"),
                        ls="-" if "adaptive" in c["name"] else "--", lw=1, label=c["name"])
            if "cut_frame" in run:
                ax.axvline(run["cut_frame"], color="k", ls=":", lw=0.8)
            ax.set_title(f"{scene}, {camera} camera: {label}", fontsize=9)
            ax.set_xlabel("frame")
            ax.set_ylabel("dB")
            ax.grid(alpha=0.3)
            if row == 0 and col == 0:
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out_path, dpi=110)
    plt.close(fig)


def plot_tau(report, out_path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for scene, cameras in runs_by_scene(report).items():
        run = cameras.get("moving")
        if not run:
            continue
        points = [(c["settings"]["tau_used"], c["resampled_fraction_mean"], c["error"]["final_srgb"]["psnr"])
                  for c in run["configs"]
                  if "error" in c and c["settings"]["trace_scale"] == 4 and c["name"].startswith("s4 sg+adaptive")]
        points.sort()
        axes[0].plot([p[0] for p in points], [100 * p[1] for p in points], "o-", label=scene)
        axes[1].plot([p[0] for p in points], [p[2] for p in points], "o-", label=scene)
    axes[0].set_ylabel("re-traced pixels, mean over frames (%)")
    axes[1].set_ylabel("final sRGB PSNR after the last frame (dB)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("τ (moving camera, trace scale 4, sg + adaptive)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)
    plt.close(fig)


def plot_study(study, scene_json, out_path):
    betas, kappas, sigmas = study["betas"], study["kappas"], study["sigmas"]
    classes = [c for c in scene_json["classes"] if c["class"] != "all"] + \
              [c for c in scene_json["classes"] if c["class"] == "all"]
    fig, axes = plt.subplots(2, max(len(classes), 2), figsize=(4 * max(len(classes), 2), 7.5), squeeze=False)
    kappa_index = kappas.index(100) if 100 in kappas else len(kappas) // 2
    for col, c in enumerate(classes):
        ax = axes[0][col]
        grid = c["sg_specular_mse"]  # [β][κ]
        image = ax.imshow(grid, origin="lower", cmap="viridis", aspect="auto")
        ax.set_xticks(range(len(kappas)), [f"{k:g}" for k in kappas])
        ax.set_yticks(range(len(betas)), [f"{b:g}" for b in betas])
        ax.set_xlabel("κ")
        ax.set_ylabel("β")
        best = c["sg_optimum"]
        ax.set_title(f"{c['class']} ({c['pixels']:.0f} px)\nsg specular MSE, optimum β {best['beta']:g}, "
                     f"κ {best['kappa']:g}", fontsize=8)
        fig.colorbar(image, ax=ax, fraction=0.046)
    ax_beta, ax_sigma = axes[1][0], axes[1][1]
    for c in classes:
        column = [row[kappa_index] for row in c["sg_specular_mse"]]
        low = min(column)
        ax_beta.plot(betas, [v / low for v in column], "o-", label=c["class"])
        normal = c["normal_specular_mse"]
        low = min(normal)
        ax_sigma.plot(sigmas, [v / low for v in normal], "o-", label=c["class"])
    ax_beta.set_xscale("log")
    ax_beta.set_xlabel(f"β (sg, κ {kappas[kappa_index]:g})")
    ax_sigma.set_xscale("log")
    ax_sigma.set_xlabel("σ_n (normal)")
    for ax in (ax_beta, ax_sigma):
        ax.set_ylabel("specular MSE / class optimum")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for col in range(2, axes.shape[1]):
        axes[1][col].axis("off")
    fig.suptitle(f"{scene_json['scene']}: Tokuyoshi 2015 Fig. 6, upsampling alone (scale 4), "
                 "per material class")
    fig.tight_layout()
    fig.savefig(out_path, dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    report = json.load(open(sys.argv[1]))
    study = json.load(open(sys.argv[2]))
    prefix = sys.argv[3]
    truths = {}
    for path in sys.argv[4:]:
        truth = json.load(open(path))
        truths[truth["scene"]] = truth
    written = []
    for scene, cameras in runs_by_scene(report).items():
        plot_pareto(scene, cameras, f"{prefix}-pareto-{scene}.png", truths.get(scene))
        plot_convergence(scene, cameras, f"{prefix}-convergence-{scene}.png")
        written += [f"{prefix}-pareto-{scene}.png", f"{prefix}-convergence-{scene}.png"]
    plot_tau(report, f"{prefix}-tau.png")
    written.append(f"{prefix}-tau.png")
    for scene_json in study["scenes"]:
        path = f"{prefix}-study-{scene_json['scene']}.png"
        plot_study(study, scene_json, path)
        written.append(path)
    if truths:
        write_truth_table(report, truths, f"{prefix}-truth.md")
        written.append(f"{prefix}-truth.md")
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
