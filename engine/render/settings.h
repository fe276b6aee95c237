// Everything a frame depends on besides the scene and the camera: one documented place for the tunables.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace vct {

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    // Linear scale applied before tone mapping.
    float exposure = 1.0f;
    // Constant ambient radiance standing in for indirect light until cone tracing replaces it; also the
    // radiance of the background, so that the two agree.
    glm::vec3 ambient{0.03f};
    // Shadow-map depth bias: constant (in depth units × 2^-24 for D32... device-defined) and slope factor.
    float shadowDepthBias = 1.25f;
    float shadowSlopeBias = 1.75f;

    // ---- global illumination (voxel cone tracing) ----
    bool gi = true;                // false: the constant ambient term instead of cone-traced indirect light
    uint32_t voxelResolution = 0;  // N for the N³ grid (32..256); 0 = chosen from the scene
    uint32_t traceScale = 1;       // indirect light traced at 1/traceScale of the pixels per axis (1, 2, 4)

    // ---- material filtering ----
    bool toksvig = true;     // normal-map mip length → effective roughness (DESIGN §3.2)
    bool specularAA = true;  // geometric specular anti-aliasing from normal derivatives (seed 000)
};

}  // namespace vct
