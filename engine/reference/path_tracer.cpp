#include "reference/path_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "reference/ray_scene.h"
#include "reference/rng.h"
#include "render/environment_sampler.h"
#include "render/scene_lights.h"
#include "render/shader_math.h"

namespace vct::reference {

namespace {

using glm::vec2;
using glm::vec3;

enum Buffer { kFinal, kDirect, kDiffuse, kSpecular, kIndirect, kBufferCount };

// The split-sum DFG values (F0·scale + bias = the specular lobe's albedo) the reference demodulates with and
// composes `final` with: integrateDFG, the function vct's table holds, on a grid whose corners are exactly
// n·v and perceptual roughness 0 and 1 (vct's texture puts texel centres half a texel inside, so it clamps at
// roughness 1; that alone moved S by 2–3 % on rough surfaces). Bilinear between grid points: within 0.2 % of
// the integral (Reference.FurnaceGivesTheGeometricSeries).
constexpr uint32_t kDfgSteps = 128;

const std::vector<vec2>& dfgGrid() {
    static const std::vector<vec2> grid = [] {
        std::vector<vec2> values(size_t(kDfgSteps + 1) * (kDfgSteps + 1));
        for (uint32_t row = 0; row <= kDfgSteps; ++row)
            for (uint32_t col = 0; col <= kDfgSteps; ++col)
                values[size_t(row) * (kDfgSteps + 1) + col] =
                    glsl::integrateDFG(float(col) / float(kDfgSteps),
                                       glsl::alphaFromPerceptual(float(row) / float(kDfgSteps)), 1024);
        return values;
    }();
    return grid;
}

vec2 dfgLookup(float NoV, float perceptualRoughness) {
    const std::vector<vec2>& grid = dfgGrid();
    const float x = std::clamp(NoV, 0.0f, 1.0f) * float(kDfgSteps);
    const float y = std::clamp(perceptualRoughness, 0.0f, 1.0f) * float(kDfgSteps);
    const uint32_t x0 = std::min(uint32_t(x), kDfgSteps - 1), y0 = std::min(uint32_t(y), kDfgSteps - 1);
    const float tx = x - float(x0), ty = y - float(y0);
    auto at = [&](uint32_t i, uint32_t j) { return grid[size_t(j) * (kDfgSteps + 1) + i]; };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx),
                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

// After this many bounces of unlimited GI, paths continue with probability max(throughput) (Russian
// roulette).
constexpr int kRouletteDepth = 3;
// The primary specular lobe is also combined with the environment's sampling from this α up (below it D_GGX
// is a spike that only the lobe's own rays can meet).
constexpr float kMinAlphaEnvironmentMis = 1e-3f;
// A hard stop for unlimited paths that roulette keeps alive (a furnace of albedo 1): never reached in
// practice.
constexpr int kMaxDepth = 1024;

// From the frame around unit n that the diffuse cones use (lib/cone.glsl, Duff et al. 2017) to world space.
vec3 toWorld(vec3 local, vec3 n) {
    return glsl::coneTangent(n) * local.x + glsl::coneBitangent(n) * local.y + n * local.z;
}

// Cosine-distributed direction around n: pdf = (n·l)/π (Malley's method).
vec3 sampleCosine(vec2 u, vec3 n) {
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * glsl::PI * u.y;
    return toWorld(vec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))), n);
}

float maxComponent(vec3 c) {
    return std::max(c.x, std::max(c.y, c.z));
}

// A surface seen from direction v (unit, towards the viewer), with its material.
struct Shading {
    SurfacePoint s;
    vec3 v;
};

}  // namespace

struct PathTracer::Impl {
    const Scene& scene;
    ReferenceSettings settings;
    float timeSeconds;
    MaterialEvaluator materials;
    RayScene rays;
    std::vector<gpu::GpuLight> lights;
    // What escaping rays see (ReferenceSettings::environmentMap, or the constant `environment`), and its
    // importance sampling. A map of more than one texel is also sampled as a light (next-event estimation
    // combined with BSDF sampling by the balance heuristic, docs/design.md §9.2); a constant one only by the
    // BSDF's rays (the cosine lobe already is its best strategy), exactly as before maps existed.
    EnvironmentMap environment;
    std::unique_ptr<EnvironmentSampler> environmentSampler;
    bool sampleEnvironment = false;
    std::vector<Surface> surfaces;
    std::unique_ptr<tbb::task_arena> arena;

    CameraView camera;
    glm::mat4 invViewProj{1.0f};
    uint32_t spp = 0;
    std::vector<glm::dvec3> sums[kBufferCount][2];  // per buffer, per half (even, odd sample indices)
    std::vector<int32_t> surfaceId;
    ReferenceStats stats;
    float offset = 1e-4f;

    Impl(const Scene& s, float t, const CameraView& c, const ReferenceSettings& r)
        : scene(s), settings(r), timeSeconds(t), materials(s), rays(s, t, materials) {
        std::vector<glm::quat> rotations;
        const std::vector<glm::mat4> world = scene.evaluate(t, &rotations);
        lights = sceneLights(scene, world, rotations);
        environment =
            settings.environmentMap ? *settings.environmentMap : constantEnvironment(settings.environment);
        environmentSampler = std::make_unique<EnvironmentSampler>(environment);
        sampleEnvironment = environment.width() * environment.height() > 1;
        for (const RayGeometry& g : rays.geometries())
            surfaces.push_back({g.name, g.node, g.primitive, g.material});
        // Rays leave a surface this far along its face normal: well above float rounding at the scene's
        // scale, well below any feature vct's voxels resolve.
        offset = 2e-5f * rays.extent();
        arena = std::make_unique<tbb::task_arena>(settings.threads == 0 ? tbb::task_arena::automatic
                                                                        : int(settings.threads));
        restart(c);
    }

    // The camera ray through image position (px, py) in pixels (0..width, 0..height, y down), as the
    // G-buffer's rasterisation sees it: from the near plane to the far plane through the inverse
    // view-projection.
    bool cameraRay(float px, float py, vec3& origin, vec3& direction, float& length) const {
        const vec2 ndc(px / float(settings.width) * 2.0f - 1.0f, py / float(settings.height) * 2.0f - 1.0f);
        const glm::vec4 nearPoint = invViewProj * glm::vec4(ndc, 0.0f, 1.0f);
        const glm::vec4 farPoint = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
        origin = vec3(nearPoint) / nearPoint.w;
        const vec3 delta = vec3(farPoint) / farPoint.w - origin;
        length = glm::length(delta);
        if (!(length > 0.0f) || !std::isfinite(length)) return false;
        direction = delta / length;
        return true;
    }

    void restart(const CameraView& c) {
        camera = c;
        const float aspect = float(settings.width) / float(settings.height);
        invViewProj = glm::inverse(camera.projection(aspect) * camera.view);
        spp = 0;
        const size_t pixels = size_t(settings.width) * settings.height;
        for (auto& buffer : sums)
            for (auto& half : buffer) half.assign(pixels, glm::dvec3(0.0));
        // The surface at each pixel centre: what the per-surface sums of the comparison group by.
        surfaceId.assign(pixels, -1);
        arena->execute([&] {
            tbb::parallel_for(
                tbb::blocked_range<uint32_t>(0, settings.height),
                [&](const tbb::blocked_range<uint32_t>& rows) {
                    for (uint32_t y = rows.begin(); y < rows.end(); ++y)
                        for (uint32_t x = 0; x < settings.width; ++x) {
                            vec3 origin, direction;
                            float length;
                            if (!cameraRay(float(x) + 0.5f, float(y) + 0.5f, origin, direction, length))
                                continue;
                            const RayHit hit = rays.intersect(origin, direction, 0.0f, length, true);
                            if (hit.hit) surfaceId[size_t(y) * settings.width + x] = int32_t(hit.geometry);
                        }
                });
        });
    }

    // A ray leaving surface s along unit l starts on the side of the surface that l points to.
    vec3 spawnOrigin(const SurfacePoint& s, vec3 l) const {
        return s.position + (glm::dot(s.faceNormal, l) >= 0.0f ? s.faceNormal : -s.faceNormal) * offset;
    }

    // The BRDF of a surface hit by an indirect ray (SecondaryBrdf), times n·l.
    vec3 secondaryBrdfCosine(const Shading& x, vec3 l) const {
        if (settings.secondary == SecondaryBrdf::Diffuse)
            return glsl::diffuseAlbedo(x.s.baseColor, x.s.metallic) * glsl::INV_PI *
                   glsl::saturate(glm::dot(x.s.normal, l));
        return glsl::evalBrdfCosine(x.s.normal, x.v, l, x.s.baseColor, x.s.metallic, x.s.perceptualRoughness);
    }

    // Next-event estimation: every punctual light, shadowed by a ray; `primary` picks the full BRDF.
    vec3 directLight(const Shading& x, bool primary, uint64_t& rayCount) const {
        vec3 sum(0.0f);
        for (const gpu::GpuLight& light : lights) {
            const glsl::IncidentLight incident = glsl::incidentLight(light, x.s.position);
            if (maxComponent(incident.radiance) <= 0.0f) continue;
            const vec3 l = incident.towardsLight;
            const vec3 f = primary ? glsl::evalBrdfCosine(x.s.normal, x.v, l, x.s.baseColor, x.s.metallic,
                                                          x.s.perceptualRoughness)
                                   : secondaryBrdfCosine(x, l);
            if (maxComponent(f) <= 0.0f) continue;
            ++rayCount;
            if (rays.occluded(spawnOrigin(x.s, l), l, 0.0f, incident.distance - 2.0f * offset)) continue;
            sum += incident.radiance * f;
        }
        return sum;
    }

    // Samples the next direction of an indirect path at x: returns false where the path ends; `weight` is
    // f·cos/pdf. Full: a one-sample mixture of cosine and GGX half-vector sampling, weighted by the mixture's
    // pdf (the balance heuristic of the two strategies). Diffuse: cosine sampling of the Lambert lobe.
    // `pdf`: the solid-angle pdf of l (for MIS with the environment's sampling).
    bool sampleSecondary(const Shading& x, Pcg32& rng, vec3& l, vec3& weight, float& pdfOut) const {
        const vec3 n = x.s.normal;
        const vec3 albedo = glsl::diffuseAlbedo(x.s.baseColor, x.s.metallic);
        if (settings.secondary == SecondaryBrdf::Diffuse) {
            l = sampleCosine(rng.uniform2(), n);
            weight = albedo;
            pdfOut = std::max(glm::dot(n, l), 0.0f) * glsl::INV_PI;
            return glm::dot(l, x.s.faceNormal) > 0.0f && maxComponent(albedo) > 0.0f;
        }
        const float pSpecular = specularChoice(x);
        const float alpha = secondaryAlpha(x);
        const float choice = rng.uniform();
        const vec2 u = rng.uniform2();
        if (choice < pSpecular) {
            const vec3 h = toWorld(glsl::importanceSampleGGX(u, alpha), n);
            l = 2.0f * glm::dot(x.v, h) * h - x.v;
        } else {
            l = sampleCosine(u, n);
        }
        const float NoL = glm::dot(n, l);
        if (NoL <= 0.0f || glm::dot(l, x.s.faceNormal) <= 0.0f) return false;
        const float pdf = secondaryPdf(x, l);
        pdfOut = pdf;
        if (!(pdf > 0.0f)) return false;
        weight = glsl::evalBrdfCosine(n, x.v, l, x.s.baseColor, x.s.metallic, x.s.perceptualRoughness) / pdf;
        return maxComponent(weight) > 0.0f && std::isfinite(maxComponent(weight));
    }

    // The share of the specular strategy in the secondary mixture, and the α it samples (the α evalBrdf
    // uses: sampling the very lobe it evaluates keeps f/pdf bounded).
    static float specularChoice(const Shading& x) {
        const vec3 albedo = glsl::diffuseAlbedo(x.s.baseColor, x.s.metallic);
        const vec3 f0 = glsl::f0FromMetallic(x.s.baseColor, x.s.metallic);
        const float specularWeight = glsl::luminance(f0);
        const float diffuseWeight = glsl::luminance(albedo) * (1.0f - specularWeight);
        const float total = specularWeight + diffuseWeight;
        return total > 0.0f ? std::clamp(specularWeight / total, 0.05f, 0.95f) : 0.5f;
    }
    static float secondaryAlpha(const Shading& x) {
        return std::max(glsl::alphaFromPerceptual(x.s.perceptualRoughness), glsl::MIN_ALPHA_PUNCTUAL);
    }
    // The solid-angle pdf with which sampleSecondary draws l.
    float secondaryPdf(const Shading& x, vec3 l) const {
        const vec3 n = x.s.normal;
        const float NoL = glm::dot(n, l);
        if (NoL <= 0.0f) return 0.0f;
        if (settings.secondary == SecondaryBrdf::Diffuse) return NoL * glsl::INV_PI;
        const float pSpecular = specularChoice(x);
        const float alpha = secondaryAlpha(x);
        const vec3 h = glm::normalize(x.v + l);
        const float NoH = glsl::saturate(glm::dot(n, h));
        const float VoH = glm::dot(x.v, h);
        const float pdfSpecular = VoH > 0.0f ? glsl::D_GGX(NoH, alpha) * NoH / (4.0f * VoH) : 0.0f;
        return (1.0f - pSpecular) * NoL * glsl::INV_PI + pSpecular * pdfSpecular;
    }

    // The environment seen by a BSDF-sampled ray that escaped along `direction`, drawn with solid-angle pdf
    // `bsdfPdf` (0: the vertex did not also sample the environment, weight 1): the balance heuristic's share.
    vec3 escapedRadiance(vec3 direction, float bsdfPdf) const {
        const vec3 radiance = environment.radiance(direction);
        if (!(bsdfPdf > 0.0f)) return radiance;
        return radiance * (bsdfPdf / (bsdfPdf + environmentSampler->pdf(direction)));
    }

    // One environment sample leaving surface point s, unoccluded and above the face; pdf 0 when it is not.
    EnvironmentSampler::Sample environmentLightSample(const SurfacePoint& s, Pcg32& rng,
                                                      uint64_t& rayCount) const {
        EnvironmentSampler::Sample e = environmentSampler->sample(rng.uniform2());
        if (!(e.pdf > 0.0f) || glm::dot(e.direction, s.faceNormal) <= 0.0f ||
            glm::dot(e.direction, s.normal) <= 0.0f)
            return {};
        ++rayCount;
        if (rays.occluded(spawnOrigin(s, e.direction), e.direction, 0.0f,
                          std::numeric_limits<float>::infinity()))
            return {};
        return e;
    }

    // Next-event estimation of the environment at a secondary vertex, weighted against the BSDF's own rays.
    vec3 environmentLight(const Shading& x, Pcg32& rng, uint64_t& rayCount) const {
        const EnvironmentSampler::Sample e = environmentLightSample(x.s, rng, rayCount);
        if (!(e.pdf > 0.0f)) return vec3(0.0f);
        return secondaryBrdfCosine(x, e.direction) * e.radiance / (e.pdf + secondaryPdf(x, e.direction));
    }

    // Radiance arriving at `origin` along unit `direction` from the first surface hit (its emission, its
    // reflection of the lights and, with bounces left, of further indirect light) or from the environment.
    // `directionPdf`: the pdf the caller's BSDF sampling drew `direction` with, when the caller also sampled
    // the environment (0 when it did not). The environment counts like emission: light it sends reaches the
    // origin after as many bounces as the path has vertices before it escapes.
    vec3 indirectRadiance(vec3 origin, vec3 direction, float directionPdf, Pcg32& rng,
                          uint64_t& rayCount) const {
        vec3 radiance(0.0f), throughput(1.0f);
        for (int depth = 1; depth <= kMaxDepth; ++depth) {
            ++rayCount;
            const RayHit hit =
                rays.intersect(origin, direction, 0.0f, std::numeric_limits<float>::infinity(), false);
            if (!hit.hit) {
                radiance += throughput * escapedRadiance(direction, directionPdf);
                break;
            }
            const Shading x{rays.surfaceAt(hit, direction), -direction};
            radiance += throughput * (x.s.emission + directLight(x, false, rayCount));
            if (settings.bounces != kUnlimitedBounces && depth >= settings.bounces) break;
            if (sampleEnvironment) radiance += throughput * environmentLight(x, rng, rayCount);
            vec3 l, weight;
            float pdf = 0.0f;
            if (!sampleSecondary(x, rng, l, weight, pdf)) break;
            directionPdf = sampleEnvironment ? pdf : 0.0f;
            throughput *= weight;
            if (settings.bounces == kUnlimitedBounces && depth >= kRouletteDepth) {
                const float survive = std::min(maxComponent(throughput), 0.95f);
                if (rng.uniform() >= survive) break;
                throughput /= survive;
            }
            origin = spawnOrigin(x.s, l);
            direction = l;
        }
        return radiance;
    }

    // One sample of one pixel: adds final, direct, D and S into the half `sample & 1`.
    void samplePixel(uint32_t x, uint32_t y, uint32_t sample, uint64_t& rayCount) {
        const size_t pixel = size_t(y) * settings.width + x;
        Pcg32 rng = sampleRng(settings.seed, pixel, sample);
        const vec2 jitter = rng.uniform2();
        vec3 final(0.0f), direct(0.0f), diffuse(0.0f), specular(0.0f), indirect(0.0f);
        vec3 origin, direction;
        float length;
        RayHit hit;
        if (cameraRay(float(x) + jitter.x, float(y) + jitter.y, origin, direction, length)) {
            ++rayCount;
            hit = rays.intersect(origin, direction, 0.0f, length, true);
        }
        if (!hit.hit) {
            direct = final =
                environment.radiance(direction);  // the background, as vct's direct pass writes it
        } else {
            const Shading x0{rays.surfaceAt(hit, direction), -direction};
            const SurfacePoint& s = x0.s;
            direct = s.emission + directLight(x0, true, rayCount);
            const vec3 n = s.normal;
            // n·v as composite reads the DFG table, and a view vector that has it (a normal-mapped n can face
            // away).
            const float NoV = std::max(glm::dot(n, x0.v), glsl::MIN_N_DOT_V);
            vec3 v = x0.v;
            if (glm::dot(n, v) < glsl::MIN_N_DOT_V) {
                vec3 side = v - n * glm::dot(n, v);
                const float sideLength = glm::length(side);
                side = sideLength > 1e-6f ? side / sideLength : glsl::coneTangent(n);
                v = side * std::sqrt(1.0f - NoV * NoV) + n * NoV;
            }
            const vec2 dfg = dfgLookup(NoV, s.perceptualRoughness);
            const vec3 f0 = glsl::f0FromMetallic(s.baseColor, s.metallic);
            if (settings.bounces != 0) {
                // D: one cosine-distributed ray; its radiance is an unbiased estimate of (1/π)∫L cos.
                const vec3 ld = sampleCosine(rng.uniform2(), n);
                const float pdfD = sampleEnvironment ? std::max(glm::dot(n, ld), 0.0f) * glsl::INV_PI : 0.0f;
                if (glm::dot(ld, s.faceNormal) > 0.0f)
                    diffuse = indirectRadiance(spawnOrigin(s, ld), ld, pdfD, rng, rayCount);
                // S: one GGX half vector (pdf D·(n·h)); f_s·cos/pdf = F·V·4(n·l)(v·h)/(n·h) (D cancels,
                // finite at α = 0), divided by the lobe's albedo F0·scale + bias.
                const float alpha = glsl::alphaFromPerceptual(s.perceptualRoughness);
                const vec3 h = toWorld(glsl::importanceSampleGGX(rng.uniform2(), alpha), n);
                const float VoH = glm::dot(v, h);
                const vec3 ls = 2.0f * VoH * h - v;
                const float NoL = glm::dot(n, ls);
                const vec3 lobeAlbedo = f0 * dfg.x + dfg.y;
                // Below this α the lobe is (nearly) a delta: only its own ray can find the environment.
                const bool specularMis = sampleEnvironment && alpha >= kMinAlphaEnvironmentMis;
                if (NoL > 0.0f && VoH > 0.0f && glm::dot(ls, s.faceNormal) > 0.0f &&
                    maxComponent(lobeAlbedo) > 0.0f) {
                    const float NoH = std::max(glm::dot(n, h), 1e-8f);
                    const vec3 lobe = glsl::F_Schlick(f0, VoH) * glsl::V_SmithGGXCorrelated(NoV, NoL, alpha) *
                                      4.0f * NoL * VoH / NoH;
                    const float pdfS = specularMis ? glsl::D_GGX(NoH, alpha) * NoH / (4.0f * VoH) : 0.0f;
                    specular = lobe / glm::max(lobeAlbedo, vec3(1e-6f)) *
                               indirectRadiance(spawnOrigin(s, ls), ls, pdfS, rng, rayCount);
                }
                // The environment sampled as a light for D and S (one shadow ray for both), each weighted
                // against its own BSDF strategy by the balance heuristic.
                if (sampleEnvironment) {
                    const EnvironmentSampler::Sample e = environmentLightSample(s, rng, rayCount);
                    if (e.pdf > 0.0f) {
                        const float NoLe = glm::dot(n, e.direction);
                        diffuse += NoLe * glsl::INV_PI * e.radiance / (e.pdf + NoLe * glsl::INV_PI);
                        const vec3 he = glm::normalize(v + e.direction);
                        const float VoHe = glm::dot(v, he);
                        const float NoHe = glsl::saturate(glm::dot(n, he));
                        if (specularMis && VoHe > 0.0f && maxComponent(lobeAlbedo) > 0.0f) {
                            const float d = glsl::D_GGX(NoHe, alpha);
                            const vec3 fCos = glsl::F_Schlick(f0, VoHe) *
                                              glsl::V_SmithGGXCorrelated(NoV, NoLe, alpha) * d * NoLe;
                            const float pdfLobe = d * NoHe / (4.0f * VoHe);
                            specular +=
                                fCos / glm::max(lobeAlbedo, vec3(1e-6f)) * e.radiance / (e.pdf + pdfLobe);
                        }
                    }
                }
            }
            // Kept apart rather than taken as final − direct: a highlight of a punctual light on a
            // near-mirror reaches 10⁸ in one sample, where float subtraction would lose the indirect light
            // entirely.
            indirect = s.occlusion * glsl::diffuseAlbedo(s.baseColor, s.metallic) * diffuse +
                       glsl::specularDfg(f0, dfg) * specular;
            final = direct + indirect;
        }
        const int half = int(sample & 1u);
        sums[kFinal][half][pixel] += glm::dvec3(final);
        sums[kDirect][half][pixel] += glm::dvec3(direct);
        sums[kDiffuse][half][pixel] += glm::dvec3(diffuse);
        sums[kSpecular][half][pixel] += glm::dvec3(specular);
        sums[kIndirect][half][pixel] += glm::dvec3(indirect);
    }
};

PathTracer::PathTracer(const Scene& scene, float timeSeconds, const CameraView& camera,
                       const ReferenceSettings& settings)
    : impl_(std::make_unique<Impl>(scene, timeSeconds, camera, settings)) {}

PathTracer::~PathTracer() = default;

void PathTracer::restart(const CameraView& camera) {
    impl_->restart(camera);
}

bool PathTracer::addSamples(uint32_t samples, const std::function<void(float)>& progress,
                            const std::atomic<bool>* cancel) {
    Impl& impl = *impl_;
    const auto start = std::chrono::steady_clock::now();
    const uint32_t first = impl.spp;
    const uint32_t height = impl.settings.height;
    std::atomic<uint32_t> rowsDone{0};
    std::atomic<uint64_t> rayCount{0};
    std::atomic<bool> cancelled{false};
    std::mutex progressMutex;
    impl.arena->execute([&] {
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height, 1),
                          [&](const tbb::blocked_range<uint32_t>& rows) {
                              for (uint32_t y = rows.begin(); y < rows.end(); ++y) {
                                  if (cancel && cancel->load(std::memory_order_relaxed)) {
                                      cancelled = true;
                                      return;
                                  }
                                  uint64_t localRays = 0;
                                  for (uint32_t x = 0; x < impl.settings.width; ++x)
                                      for (uint32_t s = 0; s < samples; ++s)
                                          impl.samplePixel(x, y, first + s, localRays);
                                  rayCount += localRays;
                                  const uint32_t done = ++rowsDone;
                                  if (progress) {
                                      std::lock_guard<std::mutex> lock(progressMutex);
                                      progress(float(done) / float(height));
                                  }
                              }
                          });
    });
    impl.stats.rays += rayCount.load();
    impl.stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (cancelled) return false;
    impl.spp += samples;
    return true;
}

uint32_t PathTracer::samplesPerPixel() const {
    return impl_->spp;
}

ReferenceImages PathTracer::images() const {
    const Impl& impl = *impl_;
    ReferenceImages out;
    out.width = impl.settings.width;
    out.height = impl.settings.height;
    out.samplesPerPixel = impl.spp;
    out.surfaceId = impl.surfaceId;
    const double n = double(impl.spp);
    const double nEven = double((impl.spp + 1) / 2), nOdd = double(impl.spp / 2);
    EstimateImage* images[kBufferCount] = {&out.final, &out.direct, &out.diffuseIndirect,
                                           &out.specularIndirect, &out.indirect};
    const size_t pixels = size_t(out.width) * out.height;
    for (int b = 0; b < kBufferCount; ++b) {
        EstimateImage& image = *images[b];
        image.mean.assign(pixels, vec3(0.0f));
        image.variance.assign(pixels, vec3(0.0f));
        if (impl.spp == 0) continue;
        for (size_t p = 0; p < pixels; ++p) {
            const glm::dvec3 even = impl.sums[b][0][p], odd = impl.sums[b][1][p];
            image.mean[p] = vec3((even + odd) / n);
            if (nOdd > 0.0) {
                // var(mean_even − mean_odd) = σ²(1/n_even + 1/n_odd) and var(mean) = σ²/n.
                const glm::dvec3 difference = even / nEven - odd / nOdd;
                image.variance[p] = vec3(difference * difference / (n * (1.0 / nEven + 1.0 / nOdd)));
            }
        }
    }
    return out;
}

const std::vector<Surface>& PathTracer::surfaces() const {
    return impl_->surfaces;
}
const ReferenceStats& PathTracer::stats() const {
    return impl_->stats;
}
const ReferenceSettings& PathTracer::settings() const {
    return impl_->settings;
}

}  // namespace vct::reference
