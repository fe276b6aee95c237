#!/usr/bin/python3
"""Plots the speed-against-error report (benchmarks/report.sh) from its JSON files, nothing else:

  PREFIX-pareto-SCENE.png       final sRGB PSNR (and specular PSNR) against GPU ms per frame, one point per
                                configuration, static and moving camera (the Pareto front: up and left is better)
  PREFIX-convergence-SCENE.png  PSNR of diffuse, specular and final against frame number: static camera
                                (convergence), moving camera, and the cut halfway (recovery)
  PREFIX-tau.png                re-traced fraction and final sRGB PSNR against τ (moving camera, scale 4, sg)
  PREFIX-study-SCENE.png        Tokuyoshi 2015 Fig. 6: sg specular MSE over β × κ per material class (heat
                                maps), and MSE against β (κ 100) and against σ_n (normal), each normalised by
                                its optimum

Benchmark scripts only: matplotlib (Debian's python3-matplotlib) is never needed to build or test.
Usage: plot_report.py REPORT.json STUDY.json OUT_PREFIX
"""
import json
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


def plot_pareto(scene, cameras, out_path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, key, label in [(axes[0], "final_srgb", "final, tone-mapped sRGB PSNR (dB, peak 1)"),
                           (axes[1], "specular", "specular indirect PSNR (dB, peak = reference max)")]:
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
        ax.grid(alpha=0.3)
    fig.suptitle(f"{scene}: error against cost (o static, ^ moving camera; large: scale 4; filled: adaptive)")
    fig.tight_layout()
    fig.savefig(out_path, dpi=130)
    plt.close(fig)


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
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    report = json.load(open(sys.argv[1]))
    study = json.load(open(sys.argv[2]))
    prefix = sys.argv[3]
    written = []
    for scene, cameras in runs_by_scene(report).items():
        plot_pareto(scene, cameras, f"{prefix}-pareto-{scene}.png")
        plot_convergence(scene, cameras, f"{prefix}-convergence-{scene}.png")
        written += [f"{prefix}-pareto-{scene}.png", f"{prefix}-convergence-{scene}.png"]
    plot_tau(report, f"{prefix}-tau.png")
    written.append(f"{prefix}-tau.png")
    for scene_json in study["scenes"]:
        path = f"{prefix}-study-{scene_json['scene']}.png"
        plot_study(study, scene_json, path)
        written.append(path)
    print("wrote " + ", ".join(written))


if __name__ == "__main__":
    main()
