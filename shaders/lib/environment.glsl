// The environment (docs/design.md §5.9): an equirectangular radiance map with a mip chain prefiltered by solid
// angle, seen by the background, by cones that leave the voxel grid, by direct light with GI off and by the
// path-traced reference. This header holds the mapping and the cone's mip, shared by GLSL and C++
// (lib/cpp_glsl.h); lib/environment_sample.glsl reads the map on the GPU, engine/render/environment.h on the CPU.
//
// Layout: u = azimuth, v = polar angle from +y (row 0 is the zenith, the last row the nadir). A map is turned
// about +y by `rotation` (radians, --environment-rotation): it is looked up at the direction turned back.
#ifndef VCT_ENVIRONMENT_GLSL
#define VCT_ENVIRONMENT_GLSL

#include "lib/constants.glsl"

// Unit direction d → (u, v) in [0, 1]²: φ = atan2(d.x, −d.z) − rotation (u = 0.5 looks along −z, glTF's
// default camera view), θ = acos(d.y).
VCT_INLINE vec2 equirectUv(vec3 d, float rotation) {
    const float phi = atan(d.x, -d.z) - rotation;
    return vec2(fract(phi * (0.5f * INV_PI) + 0.5f), acos(clamp(d.y, -1.0f, 1.0f)) * INV_PI);
}

// The inverse: (u, v) → unit direction.
VCT_INLINE vec3 equirectDirection(vec2 uv, float rotation) {
    const float phi = (uv.x - 0.5f) * (2.0f * PI) + rotation;
    const float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// The mip level whose texels are as wide as a cone of half-angle atan(tanHalfAngle): a level-0 texel spans
// 2π/width of azimuth, level m 2^m times that, and the cone's footprint 2·θ. Fractional (trilinear between
// levels); never below 0. A 60° diffuse cone on a 256-wide map reads level 5.4 (texels of 45°).
VCT_INLINE float environmentMip(float tanHalfAngle, float width) {
    const float halfAngle = atan(max(tanHalfAngle, 0.0f));
    return max(log2(max(halfAngle * width * INV_PI, 1e-6f)), 0.0f);
}

#endif  // VCT_ENVIRONMENT_GLSL
