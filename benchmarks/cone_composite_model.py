#!/usr/bin/env python3
"""How much a cone march reads of an opaque sphere that covers part of the cone (docs/design.md §5.6, round 22).

An ideal march: every step's opacity is the exact share of the cone's rays that meet the sphere within the step's
depth range (perfect prefiltering along the cone, no voxels, no mips), composited front to back as trace.comp does,
as if the steps' coverages were independent. The exact answer is the share of the cone's rays that meet the sphere
at all. A solid object that stays in the footprint for k steps is counted k times: 1 − Π(1 − c_i) instead of the
union of the c_i. The step is 0.75 of the footprint (CONE_STEP_SCALE), the half-angle 30° (the diffuse cones).

Usage: benchmarks/cone_composite_model.py   (python3-numpy)
"""
import numpy as np

HALF_ANGLE = np.radians(30.0)
STEP_SCALE = 0.75
RAYS = 20000


def cone_rays(rng):
    """Unit directions spread uniformly over the cone about +z."""
    cos_theta = 1.0 - rng.random(RAYS) * (1.0 - np.cos(HALF_ANGLE))
    sin_theta = np.sqrt(1.0 - cos_theta**2)
    phi = 2.0 * np.pi * rng.random(RAYS)
    return np.stack([sin_theta * np.cos(phi), sin_theta * np.sin(phi), cos_theta], 1)


def march(rays, centre, radius):
    """(exact share of rays meeting the sphere, what the independent composite reads)."""
    b = rays @ centre
    disc = b * b - (centre @ centre - radius * radius)
    hit = disc > 0.0
    root = np.sqrt(np.maximum(disc, 0.0))
    enter = np.where(hit, b - root, np.inf)
    leave = np.where(hit, b + root, -np.inf)
    opacity, t = 0.0, 0.05
    while t < 4.0 and opacity < 0.999:
        step = STEP_SCALE * max(2.0 * np.tan(HALF_ANGLE) * t, 0.01)
        coverage = np.mean((enter < t + 0.5 * step) & (leave > t - 0.5 * step))
        opacity += (1.0 - opacity) * coverage
        t += step
    return hit.mean(), opacity


def main():
    rays = cone_rays(np.random.default_rng(4))
    print("| sphere centre (cone along +z) | radius | exact share | independent composite | ratio |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for centre, radius in [((0, 0, 1.5), 0.5), ((0.5, 0, 1.5), 0.4), ((0.8, 0, 1.5), 0.5), ((0, 0, 1.0), 0.2)]:
        exact, read = march(rays, np.array(centre, float), radius)
        print(f"| {centre} | {radius} | {exact:.3f} | {read:.3f} | {read / exact:.2f} |")


if __name__ == "__main__":
    main()
