// The path-traced reference (`vct reference`): an unbiased CPU path tracer on Embree 3 that renders exactly
// the scene vct renders (same Scene at the same time, camera, pixel grid, punctual lights, materials, BRDF
// from shaders/lib/brdf.glsl compiled as C++, the same environment map) and writes its result in vct's own units,
// so that it compares pixel for pixel with `vct render --aux`.
//
// What each buffer estimates at a pixel (box filter over the pixel: every sample jitters its primary ray):
//   direct            emission + Σ punctual lights · f · cos · visibility (every light shadowed by a ray);
//   the
//                     environment where the primary ray escapes (vct's background)
//   diffuse_indirect  D = (1/π) ∫ L_ind(l) (n·l) dl: the cosine-weighted mean incoming indirect radiance,
//   what
//                     the trace pass's 6 diffuse cones return. One cosine-distributed ray per sample (the
//                     estimator is L_ind of that ray).
//   specular_indirect S = ∫ f_s(v, l) L_ind(l) (n·l) dl / (F0·scale + bias): the incoming indirect radiance
//                     weighted by the specular lobe, normalised by the lobe's own albedo (integrateDFG at
//                     (n·v, roughness), the function vct's DFG table holds, interpolated on a fine grid):
//                     what the specular cone returns before composite multiplies it by specularDfg. One
//                     GGX-distributed ray per sample.
//   final             direct + occlusion·albedo·D + specularDfg(F0, DFG)·S: vct's composite formula applied
//   to
//                     the reference's own buffers, per sample, so a difference in `final` is a difference in
//                     direct, D or S and nothing else.
// L_ind is the radiance arriving along a ray that leaves the surface: the emission and reflected light of the
// surface it hits (NEE to every light, then --bounces − 1 further BRDF-sampled bounces), or the environment
// if it escapes. --bounces 0 leaves D = S = 0; 1 is what vct's cones estimate; kUnlimitedBounces is full GI
// (Russian roulette after 3 bounces: unbiased).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "render/environment.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace vct::reference {

constexpr int kUnlimitedBounces = -1;

// How surfaces hit by indirect rays reflect light. Full: the glTF BRDF (evalBrdf) everywhere, the truth.
// Diffuse: Lambert with the diffuse albedo only, albedo/π · E, which is what vct's voxels store: the truth
// without glossy-to-diffuse transport, so that an error can be split into what the cones get wrong and what
// the voxels do not model. The primary hit always uses the full BRDF.
enum class SecondaryBrdf { Full, Diffuse };

struct ReferenceSettings {
    uint32_t width = 320;
    uint32_t height = 180;
    uint64_t seed = 1;
    int bounces = 1;  // 0, N ≥ 1 or kUnlimitedBounces
    SecondaryBrdf secondary = SecondaryBrdf::Full;
    glm::vec3 environment{0.03f};  // constant radiance of rays that escape (RenderSettings::ambient)
    // The environment map (render/environment.h: sceneEnvironment, what vct renders with); replaces
    // `environment` when set. Importance-sampled with MIS when it has more than one texel.
    std::shared_ptr<const EnvironmentMap> environmentMap;
    uint32_t threads = 0;  // 0: every hardware thread
};

// One row of the surface table: the (instance, primitive) pairs the primary rays can hit. Ids index it.
struct Surface {
    std::string name;  // "<node or mesh name>/<material name>", e.g. "room/red"
    int node = -1;
    uint32_t primitive = 0;
    uint32_t material = 0;
};

// A per-pixel RGB image (width × height, row-major, top row first) as the mean of the samples so far, and the
// variance of that mean per channel, estimated from two independent halves of the samples (even and odd
// sample indices): var ≈ (mean_even − mean_odd)² / 4.
struct EstimateImage {
    std::vector<glm::vec3> mean;
    std::vector<glm::vec3> variance;
};

struct ReferenceImages {
    uint32_t width = 0, height = 0, samplesPerPixel = 0;
    EstimateImage final, direct, diffuseIndirect, specularIndirect;
    EstimateImage indirect;          // final − direct per sample: the indirect light leaving the surface
    std::vector<int32_t> surfaceId;  // primary hit at the pixel centre; -1: background
};

struct ReferenceStats {
    uint64_t rays = 0;     // primary, indirect and shadow rays
    double seconds = 0.0;  // wall time spent in addSamples
    double raysPerSecond() const { return seconds > 0.0 ? double(rays) / seconds : 0.0; }
};

class PathTracer {
  public:
    // Builds the Embree scene of `scene` at `timeSeconds` (instances, lights) seen from `camera`. Throws
    // vct::Error for a scene it cannot trace (too many triangles; see the limit in the .cpp).
    PathTracer(const Scene& scene, float timeSeconds, const CameraView& camera,
               const ReferenceSettings& settings);
    ~PathTracer();
    PathTracer(const PathTracer&) = delete;
    PathTracer& operator=(const PathTracer&) = delete;

    // Adds `samples` more samples to every pixel (progressive: results are identical to one call with the
    // sum, for a seed, whatever the thread count). `progress` (may be empty) is called with the fraction
    // done, from one worker thread at a time. `cancel`, when another thread sets it, stops at the next row
    // and returns false: the images are then incomplete until restart().
    bool addSamples(uint32_t samples, const std::function<void(float)>& progress = {},
                    const std::atomic<bool>* cancel = nullptr);
    // Drops every sample and starts again from `camera` (the scene and its time stay): the demo's progressive
    // view after the camera moved. Also what a cancelled addSamples leaves to be done.
    void restart(const CameraView& camera);
    uint32_t samplesPerPixel() const;
    ReferenceImages images() const;
    const std::vector<Surface>& surfaces() const;
    const ReferenceStats& stats() const;
    const ReferenceSettings& settings() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace vct::reference
