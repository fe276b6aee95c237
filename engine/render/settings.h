// Everything a frame depends on besides the scene and the camera: one documented place for the tunables and
// their defaults. Each field has one row in the setting table (render/setting_table.cpp: its flag, range,
// help, panel widget, live or rebuild), from which the command line and its --help, the demo's panel and
// scripts, the JSON reports and Renderer::canApplyLive are made: a new field needs its row there. README and
// benchmarks quote these defaults. The defaults run the method: indirect light traced at 1/4 resolution per
// axis, upsampled with SG lobe weights and temporal history, low-weight pixels re-traced
// (benchmarks/README.md: the speed and error that chose trace scale 4).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>

namespace vct {

// RenderSettings::anisotropy before the device is known: chooseAnisotropy (render/gpu_scene.h) picks it.
// Not 0, which is a valid request (off).
constexpr uint32_t kAnisotropyFromDevice = ~0u;

// Default τ (RenderSettings::tau): re-trace where the weights kept less than this share of one full
// neighbourhood, the history counted in pixel-own samples (a neighbourhood's worth each).
constexpr float kDefaultResampleThreshold = 0.25f;
// RenderSettings::bounces for `--bounces all`: the voxels' gathers amortised over frames, converging to every
// bounce (docs/design.md §5.7).
constexpr uint32_t kAllBounces = 0xFFFFFFFFu;
// Bounces of indirect light by default (RenderSettings::bounces): every bounce, the closest to the path-traced
// truth, at 1.08× the one-bounce frame on cornell (docs/design.md §5.7 for the figures).
constexpr uint32_t kDefaultBounces = kAllBounces;

// Weight of a sample traced at the pixel itself in the accumulated history, in units of one fully agreeing
// spatial neighbourhood (the spatial kernel sums to 1): glsl::EXACT_SAMPLE_WEIGHT (lib/upsample_weights.glsl
// says why 64; renderer.cpp checks that the two agree).
constexpr float kExactSampleWeight = 64.0f;
// Default cap A_max on the accumulated history weight (docs/design.md §6.5, --history-cap): 8 pixel-own
// samples, so that the history never outweighs that many frames of new samples and follows changing light.
// With γ = 0.8 and one own sample every s² frames the sum stays below ~1.25 of them, so the cap binds only at
// scale 1.
constexpr float kHistoryWeightCap = 8.0f * kExactSampleWeight;

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    // Linear scale applied before tone mapping.
    float exposure = 1.0f;
    // The environment (render/environment.h, docs/design.md §5.9): an equirectangular HDR map (.exr, .hdr)
    // when `environment` names one; otherwise the procedural sky of the scene's first directional light; in a
    // scene with only point and spot lights (a closed room), the constant `ambient`. All × the intensity.
    std::string environment;
    float environmentIntensity = 1.0f;
    float environmentRotation = 0.0f;  // degrees about +y (maps only; the sky follows its light)
    float skyTurbidity = 3.0f;         // Preetham's T: 2 very clear, 3 clear, 6+ hazy
    glm::vec3 ambient{0.03f};
    // Shadow-map depth bias: constant (in depth units × 2^-24 for D32... device-defined) and slope factor.
    float shadowDepthBias = 1.25f;
    float shadowSlopeBias = 1.75f;

    // ---- global illumination (voxel cone tracing) ----
    bool gi = true;  // false: the environment, unoccluded, instead of cone-traced indirect light
    uint32_t voxelResolution = 0;  // N for the N³ grid (32..256); 0 = chosen from the scene
    // From this N up the radiance's mip 0 is sparse, in the brick atlas (docs/design.md §5.10); below, one dense
    // texture with the other mips (a cone sample between mips 0 and 1 is then one texture read, not two).
    uint32_t sparseMip0From = 256;
    // Bounces of indirect light (1: light from directly lit surfaces; N: the voxels also send on light that
    // has bounced N − 1 times, docs/design.md §5.7).
    uint32_t bounces = kDefaultBounces;
    uint32_t traceScale = 4;  // indirect light traced at 1/traceScale of the pixels per axis (1, 2, 4)
    // Turn each pixel's diffuse cones about its normal, differently every frame (docs/design.md §5.5): the
    // history averages the cone directions instead of keeping the blotches of one fixed set. On by default:
    // +0.8 dB against the path-traced truth at trace scale 4 (cornell 64³, 64 frames; +0.7 dB at 128³) for
    // 1.06× the fixed set's trace (round 16, before whole mips); the price is some turn noise in a still view
    // (a pixel's own sample comes every 16 frames at scale 4). The benchmarks that measure the upsampling
    // against the every-pixel trace run the fixed set (app/bench/benchmark_command.cpp): with turned cones
    // trace scale 1 is a history itself.
    bool coneRotation = true;
    bool coneJitter = false;
    // Voxels reflect the lights in their specular lobes as well (glossy-to-diffuse transport, docs/design.md
    // §5.11); off: Lambertian voxels of the diffuse albedo, what `vct reference --secondary diffuse` renders, so
    // that the cone tracer's error can be measured apart from the glossy transport's.
    bool voxelGlossy = true;
    // Cones end where they pass from one closed region of the static grid into another (render/voxel_regions.h),
    // where the scene needs it (VoxelRegions::needed).
    bool voxelRegions = true;
    std::string voxelCache;  // OpenVDB file holding the static voxelization (vct voxelize); empty: compute it
    // Diagnostic: run every pass every frame, also those whose output did not change (shadow, voxel grid,
    // G-buffer and direct light of a static scene and camera); the image must be the same as without (the test
    // of skipping them).
    bool recomputeEveryFrame = false;

    // ---- spatio-temporal upsampling and adaptive re-tracing (docs/design.md §6.7) ----
    enum class Weights { Bilinear, Normal, Sg };  // kWeightsNames in this order
    Weights weights = Weights::Sg;                // bilateral guide: none, depth × normal, depth × SG lobe
    float beta = 20.0f;                           // SG lobe weight exponent β
    float kappa = 100.0f;                         // SG smoothing kernel sharpness κ
    float sigmaN = 0.1f;                          // normal weight σ_n (σ_n² = 0.01)
    float diffuseSharpness =
        2.0f;              // sg diffuse lobe sharpness λ_d (SG fit of the cosine lobe; the Fig. 6 study)
    float gamma = 0.8f;    // temporal history decay γ
    bool temporal = true;  // reproject and accumulate last frame's result
    float tau = kDefaultResampleThreshold;  // re-trace pixels whose sum of weights is below τ
    bool adaptive = true;                   // adaptive re-tracing of low-weight pixels at full resolution
    // Cap A_max on the accumulated history weight, in pixel-own samples (A_max / kExactSampleWeight).
    float historyCap = kHistoryWeightCap / kExactSampleWeight;
    // Write the per-pixel sum of weights image (FrameTargets::weightSum) for --aux and the weights / resample
    // views; off, upsample skips that store (nothing in the frame reads it).
    bool writeWeightSum = false;
    // How the upsample pass maps work to invocations (shaders/upsample.comp, docs/design.md §6.8): one per low-res
    // cell with its samples in registers (cell: fast on a CPU device, where an invocation is a SIMD lane and
    // shared memory is gathered per lane), one per pixel with the workgroup's samples in shared memory (pixel:
    // fast on a GPU); auto picks by device type. The images are the same.
    enum class UpsampleLayout { Auto, Cell, Pixel };  // kUpsampleLayoutNames in this order
    UpsampleLayout upsampleLayout = UpsampleLayout::Auto;
    // How the cone-tracing passes (trace, re-trace, the voxel gathers) map cones to invocations (lib/cone_trace.glsl,
    // docs/design.md §5.5): a pixel's or voxel's cones one after the other in one invocation (pixel: fast on a CPU
    // device, where an invocation is a SIMD lane and a pixel's lanes would diverge), or one invocation per cone,
    // combined through shared memory (cone: on a GPU a pass that traces few pixels waits on one invocation's chain
    // of texture reads, which this shortens 6–7×); auto picks by device type. The images are the same.
    enum class TraceLayout { Auto, Pixel, Cone };  // kTraceLayoutNames in this order
    TraceLayout traceLayout = TraceLayout::Auto;

    // ---- material filtering ----
    bool toksvig = true;     // normal-map mip length → effective roughness (docs/design.md §4.1)
    bool specularAA = true;  // geometric specular anti-aliasing from normal derivatives (docs/design.md §4.2)
    // Diagnostic: sample every material texture at level 0 (bilinear, no mips, no anisotropy). A render
    // supersampled this way and box-filtered down is the ground truth that texture filtering approximates.
    bool textureLod0 = false;
    // Anisotropic filtering of material textures: 0 (off), 2, 4, 8 or 16 samples. The Renderer replaces
    // kAnisotropyFromDevice with chooseAnisotropy's choice: afterwards it holds what the sampler uses.
    uint32_t anisotropy = kAnisotropyFromDevice;
};

// The weights' names on the command line and in the JSON reports, indexed by RenderSettings::Weights.
inline constexpr const char* kWeightsNames[] = {"bilinear", "normal", "sg"};
inline const char* weightsName(RenderSettings::Weights weights) {
    return kWeightsNames[size_t(weights)];
}

inline constexpr const char* kUpsampleLayoutNames[] = {"auto", "cell", "pixel"};
inline constexpr const char* kTraceLayoutNames[] = {"auto", "pixel", "cone"};

// Largest κ (--kappa): glsl::SG_MAX_KAPPA, the largest fp16 value, since the trace stores each sample's
// smoothed sharpness λ̄ ≤ κ in a 16-bit float (lib/upsample_weights.glsl; tests/upsample_weights_test.cpp
// checks that the two agree). The shaders clamp a larger κ to it; the command line and the demo reject one.
constexpr float kMaxKappa = 65504.0f;
// τ in use: RenderSettings::tau (a τ of 0 or less, which the command line and the demo refuse, the default).
inline float resampleThreshold(const RenderSettings& settings) {
    return settings.tau > 0.0f ? settings.tau : kDefaultResampleThreshold;
}

}  // namespace vct
