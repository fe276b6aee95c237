// The upsampling weights (shaders/lib/upsample_weights.glsl, docs/design.md §6, Tokuyoshi 2015 §4) on the CPU,
// through the same header upsample.comp compiles: the spherical-Gaussian lobes, the lobe-aware weight and its
// properties (range, symmetry, identity, monotonic in angle and in sharpness mismatch, reduction to the normal
// weight for equal sharpness), the hard cases of docs/design.md §7, the plane weight, the tent kernel and the
// jitter sequence. Random sweeps use a fixed seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/packing.hpp>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "render/settings.h"
#include "render/shader_math.h"

namespace {

using namespace vct::glsl;

const float kBeta = SG_DEFAULT_BETA;
const float kKappa = SG_DEFAULT_KAPPA;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr double kPi = 3.14159265358979323846;

float weight(vec4 a, vec4 b) {
    return lobeWeight(a, b, kBeta, kKappa);
}

// 1/λ that gives the smoothed sharpness λ̄ (inverse of smoothedSharpness): 1/λ = 1/λ̄ − 1/κ.
float invLambdaFor(float smoothed) {
    return 1.0f / smoothed - 1.0f / kKappa;
}

// Every weight must be a number in [0, 1].
::testing::AssertionResult isWeight(float w) {
    if (std::isfinite(w) && w >= 0.0f && w <= 1.0f) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "weight " << w << " is not in [0, 1]";
}

bool isFiniteVec(vec4 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// fp16 storage of a lobe (or a normal): every component rounded through a half float.
vec4 roundHalf(vec4 v) {
    return glm::unpackHalf4x16(glm::packHalf4x16(v));
}
vec3 roundHalf(vec3 v) {
    return vec3(roundHalf(vec4(v, 0.0f)));
}

struct Rng {
    std::mt19937 gen{20150403u};
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen); }
    // Uniform on the sphere (Archimedes: z uniform, azimuth uniform), in double for an accurately unit result.
    vec3 unitVector() {
        const double z = std::uniform_real_distribution<double>(-1.0, 1.0)(gen);
        const double phi = std::uniform_real_distribution<double>(0.0, 2.0 * kPi)(gen);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        return vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
    }
    // A unit vector orthogonal to unit a.
    vec3 orthogonalTo(vec3 a) {
        for (;;) {
            const glm::dvec3 da(a), c = glm::cross(da, glm::dvec3(unitVector()));
            if (glm::length(c) > 1e-3) return vec3(glm::normalize(c));
        }
    }
};

// The unit vector at angle theta from unit a, in the plane spanned by a and t (unit, orthogonal to a).
vec3 rotated(vec3 a, vec3 t, double theta) {
    return vec3(glm::normalize(std::cos(theta) * glm::dvec3(a) + std::sin(theta) * glm::dvec3(t)));
}

// Tokuyoshi 2015 §4.2 (docs/design.md §6.3) evaluated independently, in double: λ̄ = λκ/(λ+κ),
// w = (2√(λ̄a λ̄b)/(λ̄a+λ̄b))^β · exp(β λ̄a λ̄b/(λ̄a+λ̄b) (ξa·ξb − 1)).
double seedWeight(vec4 a, vec4 b) {
    const double lambdaA = 1.0 / double(a.w), lambdaB = 1.0 / double(b.w);
    const double la = lambdaA * kKappa / (lambdaA + kKappa), lb = lambdaB * kKappa / (lambdaB + kKappa);
    // ξa·ξb − 1 as −½‖ξa − ξb‖² (equal for unit axes; the float axes are unit only to ~1e-7, which the
    // exponent, up to ~βκ/2, would amplify into a 1e-4 difference).
    const glm::dvec3 d = glm::dvec3(vec3(a)) - glm::dvec3(vec3(b));
    const double cosMinusOne = -0.5 * glm::dot(d, d);
    return std::pow(2.0 * std::sqrt(la * lb) / (la + lb), double(kBeta)) *
           std::exp(double(kBeta) * la * lb / (la + lb) * cosMinusOne);
}

// --- smoothed sharpness and the lobes --------------------------------------------------------------------------

TEST(UpsampleWeights, SmoothedSharpnessIsBoundedByKappa) {
    EXPECT_EQ(smoothedSharpness(0.0f, kKappa), kKappa);  // a mirror
    EXPECT_EQ(smoothedSharpness(-0.0f, kKappa), kKappa);
    EXPECT_EQ(smoothedSharpness(-1.0f, kKappa), kKappa);  // a negative 1/λ (bad data) is clamped to a mirror
    EXPECT_EQ(smoothedSharpness(kInf, kKappa), 0.0f);     // a uniform lobe
    EXPECT_NEAR(smoothedSharpness(0.09f, kKappa), 10.0f, 1e-5f);
    // λ̄ = λκ/(λ+κ) for finite λ.
    for (float lambda : {1e-3f, 0.5f, 2.0f, 10.0f, 100.0f, 1e4f, 1e7f})
        EXPECT_NEAR(smoothedSharpness(1.0f / lambda, kKappa), lambda * kKappa / (lambda + kKappa),
                    1e-5f * kKappa);
    // In [0, κ] and non-increasing in 1/λ over the whole float range.
    float previous = kKappa;
    for (float inv = 1e-30f; inv < 1e38f; inv *= 3.0f) {
        const float s = smoothedSharpness(inv, kKappa);
        EXPECT_GE(s, 0.0f);
        EXPECT_LE(s, kKappa);
        EXPECT_LE(s, previous) << "1/λ = " << inv;
        previous = s;
    }
}

TEST(UpsampleWeights, SpecularLobeIsTheReflectedWarpedNdf) {
    Rng rng;
    for (int i = 0; i < 500; ++i) {
        const vec3 n = rng.unitVector();
        vec3 v = rng.unitVector();
        if (dot(n, v) < 0.0f) v = -v;
        if (dot(n, v) < 1e-3f) continue;
        const float alpha = rng.uniform(0.0f, 1.0f);
        const vec4 lobe = specularLobe(n, v, alpha);
        ASSERT_TRUE(isFiniteVec(lobe));
        EXPECT_NEAR(length(vec3(lobe)), 1.0f, 1e-5f);
        const vec3 r = reflect(-v, n);
        EXPECT_NEAR(length(vec3(lobe) - r), 0.0f, 1e-5f) << "n·v = " << dot(n, v);
        // 1/λ = 2α²·n·v: λ = λ_h / (4 n·v) with λ_h = 2/α².
        EXPECT_NEAR(lobe.w, 2.0f * alpha * alpha * dot(n, v), 1e-6f);
    }
    // Head-on view: the axis is the normal, 1/λ = 2α².
    const vec4 headOn = specularLobe(vec3(0, 0, 1), vec3(0, 0, 1), 0.5f);
    EXPECT_NEAR(length(vec3(headOn) - vec3(0, 0, 1)), 0.0f, 1e-6f);
    EXPECT_FLOAT_EQ(headOn.w, 0.5f);
    // Rougher is wider (larger 1/λ); grazing is sharper (λ ∝ 1/n·v).
    EXPECT_LT(specularLobe(vec3(0, 0, 1), vec3(0, 0, 1), 0.2f).w,
              specularLobe(vec3(0, 0, 1), vec3(0, 0, 1), 0.4f).w);
    EXPECT_LT(specularLobe(vec3(0, 0, 1), normalize(vec3(1, 0, 0.1f)), 0.5f).w, headOn.w);
}

TEST(UpsampleWeights, SpecularLobeHardCasesAreFinite) {
    const vec3 n(0, 0, 1);
    // α = 0: a mirror, 1/λ = 0 exactly (λ̄ = κ); α = 1: the widest lobe, 1/λ = 2·n·v.
    const vec3 v = normalize(vec3(0.3f, -0.2f, 0.9f));
    EXPECT_EQ(specularLobe(n, v, 0.0f).w, 0.0f);
    EXPECT_EQ(smoothedSharpness(specularLobe(n, v, 0.0f).w, kKappa), kKappa);
    EXPECT_FLOAT_EQ(specularLobe(n, v, 1.0f).w, 2.0f * dot(n, v));
    EXPECT_FLOAT_EQ(specularLobe(n, v, 2.0f).w, 2.0f * dot(n, v));  // α clamped to 1
    EXPECT_EQ(specularLobe(n, v, -1.0f).w, 0.0f);                   // and to 0
    // n·v = 0 (grazing) and n·v < 0 (back-facing normal-map normals): unit axis, finite positive 1/λ (the n·v
    // floor), for every roughness.
    const vec3 views[] = {vec3(1, 0, 0), normalize(vec3(1, 1, 0)), normalize(vec3(1, 0, -0.01f)),
                          normalize(vec3(0.2f, 0.1f, -1.0f)), vec3(0, 0, -1)};
    for (const vec3& view : views) {
        for (float alpha : {0.0f, 1e-4f, 0.3f, 1.0f}) {
            const vec4 lobe = specularLobe(n, view, alpha);
            ASSERT_TRUE(isFiniteVec(lobe)) << "alpha " << alpha;
            EXPECT_NEAR(length(vec3(lobe)), 1.0f, 1e-5f);
            EXPECT_GE(lobe.w, 0.0f);
            EXPECT_LE(lobe.w, 2.0f * alpha * alpha * SG_MIN_NOV * 1.0001f);
            EXPECT_TRUE(isWeight(weight(lobe, lobe)));
            EXPECT_FLOAT_EQ(weight(lobe, lobe), 1.0f);
            // With n·v clamped to 0 the reflection degenerates to −v (continuous at n·v = 0).
            EXPECT_NEAR(length(vec3(lobe) + view), 0.0f, 1e-5f);
        }
    }
    // fp16-rounded inputs (G-buffer normals and views) still give a finite, unit-axis lobe.
    Rng rng;
    for (int i = 0; i < 200; ++i) {
        const vec3 nh = roundHalf(rng.unitVector()), vh = roundHalf(rng.unitVector());
        const vec4 lobe = specularLobe(nh, vh, roundHalf(vec3(rng.uniform(0.0f, 1.0f))).x);
        ASSERT_TRUE(isFiniteVec(lobe));
        EXPECT_NEAR(length(vec3(lobe)), 1.0f, 1e-5f);
    }
}

TEST(UpsampleWeights, DiffuseLobeIsTheNormalWithFixedSharpness) {
    const vec3 n = normalize(vec3(1, -2, 3));
    const vec4 d = diffuseLobe(n);
    EXPECT_EQ(vec3(d), n);
    EXPECT_FLOAT_EQ(d.w, 1.0f / SG_DIFFUSE_SHARPNESS);
}

// --- the lobe-aware weight: properties --------------------------------------------------------------------------

TEST(UpsampleWeights, LobeWeightRangeSymmetryIdentity) {
    Rng rng;
    for (int i = 0; i < 3000; ++i) {
        // Views on the whole sphere: n·v < 0 included (back-facing normal-map normals).
        const vec3 na = rng.unitVector(), nb = rng.unitVector(), va = rng.unitVector(), vb = rng.unitVector();
        const float ra = rng.uniform(0.0f, 1.0f), rb = rng.uniform(0.0f, 1.0f);
        const vec4 lobes[] = {specularLobe(na, va, ra * ra), specularLobe(nb, vb, rb * rb), diffuseLobe(na),
                              diffuseLobe(nb)};
        for (const vec4& a : lobes) {
            EXPECT_FLOAT_EQ(weight(a, a), 1.0f);
            for (const vec4& b : lobes) {
                const float w = weight(a, b);
                ASSERT_TRUE(isWeight(w));
                EXPECT_EQ(w, weight(b, a));  // exactly symmetric
            }
        }
    }
}

TEST(UpsampleWeights, LobeWeightMatchesSeedFormula) {
    Rng rng;
    for (int i = 0; i < 2000; ++i) {
        const vec3 a = rng.unitVector(), t = rng.orthogonalTo(a);
        const vec3 b = rotated(a, t, rng.uniform(0.0f, 0.6f));
        const vec4 la(a, rng.uniform(1e-3f, 2.0f)), lb(b, rng.uniform(1e-3f, 2.0f));
        const double reference = seedWeight(la, lb);
        EXPECT_NEAR(weight(la, lb), reference, 1e-5 * reference + 1e-30);
    }
}

TEST(UpsampleWeights, LobeWeightDecreasesWithAngle) {
    Rng rng;
    const float fixedInv[] = {0.0f, 1e-3f, 0.01f, 0.09f, 0.5f, 2.0f, 100.0f};
    for (int i = 0; i < 200; ++i) {
        const vec3 a = rng.unitVector(), t = rng.orthogonalTo(a);
        // Fixed sharpnesses: equal pairs from the list and random (unequal) pairs.
        const float invA = i < 7 ? fixedInv[i] : rng.uniform(0.0f, 2.0f);
        const float invB = i < 7 ? fixedInv[i] : rng.uniform(0.0f, 2.0f);
        float previous = weight(vec4(a, invA), vec4(a, invB));
        for (int degrees = 1; degrees <= 180; ++degrees) {
            const vec3 b = rotated(a, t, degrees * kPi / 180.0);
            const float w = weight(vec4(a, invA), vec4(b, invB));
            ASSERT_TRUE(isWeight(w));
            // Non-increasing; strictly decreasing until exp underflows.
            if (previous > 1e-30f) {
                EXPECT_LT(w, previous) << degrees << "° 1/λ " << invA << ", " << invB;
            } else {
                EXPECT_LE(w, previous) << degrees << "° 1/λ " << invA << ", " << invB;
            }
            previous = w;
        }
    }
    // Mirrors at 90° are rejected completely (exponent −βκ/2 underflows to 0, no NaN).
    EXPECT_EQ(weight(vec4(0, 0, 1, 0.0f), vec4(1, 0, 0, 0.0f)), 0.0f);
    EXPECT_EQ(weight(vec4(0, 0, 1, 0.0f), vec4(0, 0, -1, 0.0f)), 0.0f);
}

TEST(UpsampleWeights, LobeWeightDecreasesWithSharpnessMismatch) {
    Rng rng;
    for (float smoothedA : {0.5f, 2.0f, 10.0f, 50.0f}) {
        const vec3 axis = rng.unitVector();
        const vec4 a(axis, invLambdaFor(smoothedA));
        // The mismatch factor is (2√r/(1+r))^β for r = λ̄b/λ̄a, whichever side of 1.
        for (float r : {0.25f, 0.5f, 0.9f, 1.0f, 1.1f, 2.0f}) {
            if (smoothedA * r >= kKappa) continue;
            const double expected = std::pow(2.0 * std::sqrt(double(r)) / (1.0 + r), double(kBeta));
            EXPECT_NEAR(weight(a, vec4(axis, invLambdaFor(smoothedA * r))), expected,
                        1e-4 * expected + 1e-30);
        }
        // Sharper b (1/λb from 1/λa down to 0, a mirror) and wider b (up to 1/λ = 1e6): both decrease.
        float previous = 1.0f;
        for (float f = 0.9f; f > 1e-3f; f *= 0.8f) {
            const float w = weight(a, vec4(axis, a.w * f));
            ASSERT_TRUE(isWeight(w));
            EXPECT_LT(w, previous) << "λ̄a " << smoothedA << " 1/λb = " << a.w * f;
            previous = w;
        }
        EXPECT_LE(weight(a, vec4(axis, 0.0f)), previous);
        previous = 1.0f;
        for (float f = 1.1f; a.w * f < 1e6f; f *= 1.25f) {
            const float w = weight(a, vec4(axis, a.w * f));
            ASSERT_TRUE(isWeight(w));
            if (previous > 1e-30f) {
                EXPECT_LT(w, previous) << "λ̄a " << smoothedA << " 1/λb = " << a.w * f;
            } else {
                EXPECT_LE(w, previous);
            }
            previous = w;
        }
    }
}

TEST(UpsampleWeights, EqualSharpnessReducesToNormalWeight) {
    // Equal λ̄: w = exp(β λ̄/2 (ξa·ξb − 1)) = normalWeight with 1/σ² = β λ̄/2. For β = 20, σ² = 0.01, κ = 100:
    // λ̄ = 10, i.e. 1/λ = 1/10 − 1/100 = 0.09.
    ASSERT_EQ(kBeta, 20.0f);
    ASSERT_EQ(kKappa, 100.0f);
    ASSERT_EQ(NORMAL_WEIGHT_DEFAULT_SIGMA2, 0.01f);
    const float inv = 0.09f;
    ASSERT_NEAR(kBeta * smoothedSharpness(inv, kKappa) / 2.0f, 1.0f / NORMAL_WEIGHT_DEFAULT_SIGMA2, 1e-3f);
    // The diffuse lobes (fixed λ_d) compare like normals with σ² = 2/(β λ̄_d).
    const float diffuseSigma2 = 2.0f / (kBeta * smoothedSharpness(1.0f / SG_DIFFUSE_SHARPNESS, kKappa));
    Rng rng;
    for (int i = 0; i < 50; ++i) {
        const vec3 na = rng.unitVector(), t = rng.orthogonalTo(na);
        for (double degrees : {0.0, 0.1, 0.5, 1.0, 2.0, 5.0, 8.0, 12.0, 20.0, 30.0, 45.0, 90.0, 180.0}) {
            const vec3 nb = rotated(na, t, degrees * kPi / 180.0);
            const float wn = normalWeight(na, nb, NORMAL_WEIGHT_DEFAULT_SIGMA2);
            EXPECT_NEAR(weight(vec4(na, inv), vec4(nb, inv)), wn, 1e-5f * wn + 1e-37f) << degrees << "°";
            const float wd = normalWeight(na, nb, diffuseSigma2);
            EXPECT_NEAR(weight(diffuseLobe(na), diffuseLobe(nb)), wd, 1e-5f * wd + 1e-37f) << degrees << "°";
        }
    }
    // normalWeight itself: exp((na·nb − 1)/σ²), 1 for equal normals.
    EXPECT_EQ(normalWeight(vec3(0, 0, 1), vec3(0, 0, 1), 0.01f), 1.0f);
    EXPECT_NEAR(normalWeight(vec3(0, 0, 1), rotated(vec3(0, 0, 1), vec3(1, 0, 0), 0.1), 0.01f),
                std::exp((std::cos(0.1) - 1.0) / 0.01), 1e-5);
    EXPECT_TRUE(isWeight(normalWeight(vec3(0, 0, 1), vec3(0, 0, -1), 0.0f)));  // σ² = 0 is floored
}

TEST(UpsampleWeights, LobeWeightSeesWhatNormalWeightMisses) {
    // Tokuyoshi 2015 Fig. 1: same normal, other roughness or view — the normal weight is 1, the lobe weight not.
    const vec3 n(0, 0, 1), v = normalize(vec3(0.5f, 0, 1));
    EXPECT_EQ(normalWeight(n, n, NORMAL_WEIGHT_DEFAULT_SIGMA2), 1.0f);
    EXPECT_LT(weight(specularLobe(n, v, 0.05f), specularLobe(n, v, 0.3f)), 0.5f);
    EXPECT_LT(weight(specularLobe(n, v, 0.05f), specularLobe(n, normalize(vec3(-0.5f, 0, 1)), 0.05f)), 0.01f);
    // Rough lobes tolerate a view change that mirror-like ones reject.
    const vec3 v2 = normalize(vec3(0.45f, 0.05f, 1));
    EXPECT_GT(weight(specularLobe(n, v, 0.5f), specularLobe(n, v2, 0.5f)),
              weight(specularLobe(n, v, 0.02f), specularLobe(n, v2, 0.02f)));
}

// --- the lobe-aware weight: hard cases (docs/design.md §7) -------------------------------------------------------

TEST(UpsampleWeights, LobeWeightHardCasesAreFinite) {
    const vec3 n(0, 0, 1);
    std::vector<vec4> lobes;
    const vec3 views[] = {vec3(0, 0, 1), normalize(vec3(1, 0, 1)), vec3(1, 0, 0) /* n·v = 0 */,
                          normalize(vec3(0, 1, -0.2f)) /* n·v < 0 */, vec3(0, 0, -1)};
    for (const vec3& view : views)
        for (float alpha : {0.0f, 1e-6f, 0.5f, 1.0f}) lobes.push_back(specularLobe(n, view, alpha));
    lobes.push_back(diffuseLobe(n));
    lobes.push_back(diffuseLobe(-n));
    const vec3 axes[] = {n, normalize(vec3(1, 2, 3)), -n};
    // 1/λ = 0 (λ → ∞, mirror), tiny, ordinary, huge and infinite (λ → 0).
    for (const vec3& axis : axes)
        for (float inv : {0.0f, 1e-30f, 1e-8f, 0.09f, 2.0f, 1e4f, 1e19f, 1e30f, 3e38f, kInf})
            lobes.push_back(vec4(axis, inv));
    // fp16 storage of every lobe: slightly non-unit axes, 1/λ rounded (tiny → 0, huge → inf).
    const size_t count = lobes.size();
    for (size_t i = 0; i < count; ++i) lobes.push_back(roundHalf(lobes[i]));
    for (const vec4& a : lobes)
        for (const vec4& b : lobes) {
            const float w = weight(a, b);
            ASSERT_TRUE(isWeight(w)) << "a = (" << a.x << "," << a.y << "," << a.z << "," << a.w << ") b = ("
                                     << b.x << "," << b.y << "," << b.z << "," << b.w << ")";
            EXPECT_EQ(w, weight(b, a));
        }
    // Both lobes uniform (λ̄ = 0): identical whatever the axes.
    EXPECT_EQ(weight(vec4(n, kInf), vec4(-n, kInf)), 1.0f);
    // One uniform, one not: the mismatch factor is 0.
    EXPECT_EQ(weight(vec4(n, kInf), vec4(n, 0.5f)), 0.0f);
    EXPECT_EQ(weight(vec4(n, kInf), vec4(n, 0.0f)), 0.0f);
    // Two mirrors along the same axis: identical.
    EXPECT_EQ(weight(vec4(n, 0.0f), vec4(n, 0.0f)), 1.0f);
    // Identical lobes weigh 1 over the reachable range of 1/λ (specularLobe gives ≤ 2, fp16 ≤ 65504).
    for (float inv : {0.0f, 1e-30f, 1e-8f, 1e-4f, 0.09f, 0.5f, 2.0f, 65504.0f, 1e8f})
        EXPECT_FLOAT_EQ(weight(vec4(axes[1], inv), vec4(axes[1], inv)), 1.0f) << "1/λ = " << inv;
    // fp16-rounded identical lobes still weigh 1, and rounding a lobe barely changes its weight to the original.
    Rng rng;
    for (int i = 0; i < 500; ++i) {
        const vec3 nn = rng.unitVector(), v = rng.unitVector();
        const vec4 lobe = specularLobe(nn, v, rng.uniform(0.0f, 1.0f));
        const vec4 stored = roundHalf(lobe);
        EXPECT_FLOAT_EQ(weight(stored, stored), 1.0f);
        const float w = weight(lobe, stored);
        ASSERT_TRUE(isWeight(w));
        EXPECT_GT(w, 0.9f) << "1/λ = " << lobe.w;
    }
}

// κ large enough to overflow the guide's fp16 storage (issue 9): the trace stores λ̄ ≤ κ in a half float,
// whose largest finite value is 65504. κ is clamped there (SG_MAX_KAPPA) and the command line rejects more,
// so the stored λ̄ is finite for any κ and any lobe, and the weights against it are weights.
TEST(UpsampleWeights, HugeKappaKeepsTheStoredSharpnessFinite) {
    EXPECT_EQ(vct::kMaxKappa, SG_MAX_KAPPA);
    EXPECT_EQ(roundHalf(vec3(SG_MAX_KAPPA)).x, SG_MAX_KAPPA);  // the largest half float
    // Before the clamp: cornell's floor stripe of roughness 0.05 (α = 0.0025, n·v ≈ 0.5) at κ = 1e6 gave
    // λ̄ ≈ 1.4e5, stored as +inf.
    const float floorInv = 2.0f * 0.0025f * 0.0025f * 0.5f;
    EXPECT_TRUE(std::isinf(roundHalf(vec3(1e6f / (1.0f + 1e6f * floorInv))).x));
    const vec3 n(0, 0, 1);
    Rng rng;
    for (float kappa : {100.0f, 65504.0f, 65600.0f, 1e5f, 1e6f, 1e30f, kInf}) {
        std::vector<vec4>
            lobes;  // axis, λ̄ as the trace stores it (fp16) and as the upsample computes it (fp32)
        for (float inv : {0.0f, 1e-30f, 1e-8f, floorInv, 1e-3f, 0.5f, 2.0f}) {
            const vec3 axis = rng.unitVector();
            const float smoothed = smoothedSharpness(inv, kappa);
            ASSERT_TRUE(std::isfinite(smoothed)) << "κ " << kappa << " 1/λ " << inv;
            EXPECT_LE(smoothed, SG_MAX_KAPPA);
            EXPECT_LE(smoothed, kappa);
            const float stored = roundHalf(vec3(smoothed)).x;
            ASSERT_TRUE(std::isfinite(stored)) << "κ " << kappa << " 1/λ " << inv;
            lobes.push_back(vec4(axis, stored));
            lobes.push_back(vec4(axis, smoothed));
            lobes.push_back(vec4(n, stored));
        }
        for (const vec4& a : lobes)
            for (const vec4& b : lobes) {
                const float w = exp(lobeLogWeightSmoothed(vec3(a), a.w, vec3(b), b.w, kBeta));
                ASSERT_TRUE(isWeight(w)) << "κ " << kappa << ": λ̄ " << a.w << " vs " << b.w;
            }
        // A mirror's stored λ̄ against the same lobe computed in fp32 (a sample against its own pixel): 1 to
        // within the fp16 rounding of λ̄ (relative 2⁻¹¹, a ratio term of −β·δ²/8).
        const float mirror = smoothedSharpness(0.0f, kappa);
        EXPECT_GT(exp(lobeLogWeightSmoothed(n, roundHalf(vec3(mirror)).x, n, mirror, kBeta)), 0.9999f)
            << kappa;
    }
}

// A NaN lobe (issue 9): a NaN axis or sharpness, and an infinite sharpness (what fp16 storage made of λ̄ >
// 65504: ln ratio = inf − inf), weighs exactly 0 against anything, in both orders, never 1 or NaN. The old
// form took min(NaN, 0), which a GPU may evaluate to 0: ln ratio = 0, the weight of equal sharpness (1 for
// equal axes).
TEST(UpsampleWeights, NanOrInfiniteLobeWeighsZero) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const vec3 n(0, 0, 1), other = normalize(vec3(1, 2, 3));
    const vec3 nanAxis(nan, 0.0f, 1.0f);
    for (float good : {1e-30f, 0.5f, 3.0f, 100.0f, SG_MAX_KAPPA}) {
        for (const vec3& axis : {n, other}) {
            for (float bad : {nan, kInf}) {
                EXPECT_EQ(exp(lobeLogWeightSmoothed(n, bad, axis, good, kBeta)), 0.0f)
                    << bad << " vs " << good;
                EXPECT_EQ(exp(lobeLogWeightSmoothed(axis, good, n, bad, kBeta)), 0.0f)
                    << good << " vs " << bad;
                EXPECT_EQ(lobeWeightSmoothed(n, bad, axis, good, kBeta), 0.0f);
            }
            EXPECT_EQ(exp(lobeLogWeightSmoothed(nanAxis, good, axis, good, kBeta)), 0.0f);
            EXPECT_EQ(exp(lobeLogWeightSmoothed(axis, good, nanAxis, good, kBeta)), 0.0f);
        }
        // Through the inverse-sharpness form: a NaN 1/λ, or a NaN in the stored lobe.
        EXPECT_EQ(weight(vec4(n, nan), vec4(n, 0.5f)), 0.0f);
        EXPECT_EQ(weight(vec4(nanAxis, 0.5f), vec4(n, 0.5f)), 0.0f);
    }
    // Two NaN or two infinite lobes: 0 as well (nothing to compare), never NaN.
    EXPECT_EQ(exp(lobeLogWeightSmoothed(n, nan, n, nan, kBeta)), 0.0f);
    EXPECT_EQ(exp(lobeLogWeightSmoothed(n, kInf, n, kInf, kBeta)), 0.0f);
    EXPECT_EQ(exp(lobeLogWeightSmoothed(n, kInf, other, kInf, kBeta)), 0.0f);
}

// A zero view vector (issue 9): a surface point at the camera. viewDirection gives the normal there (a
// head-on view), so the guide's specular lobe and the specular cone stay finite; elsewhere it is normalize().
TEST(UpsampleWeights, ZeroViewVectorGivesAFiniteLobe) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const vec3 n = normalize(vec3(0.2f, 1.0f, -0.3f));
    for (const vec3& toCamera :
         {vec3(0.0f), vec3(-0.0f), vec3(1e-20f, 0.0f, 0.0f), vec3(1e-38f, 1e-40f, 0.0f), vec3(nan),
          vec3(kInf, 0.0f, 0.0f), vec3(3e38f, 3e38f, 0.0f)}) {
        const vec3 v = viewDirection(toCamera, n);
        EXPECT_EQ(v, n) << toCamera.x;
        for (float alpha : {0.0f, 0.3f, 1.0f}) {
            const vec4 lobe = specularLobe(n, v, alpha);
            ASSERT_TRUE(isFiniteVec(lobe));
            EXPECT_FLOAT_EQ(weight(lobe, lobe), 1.0f);
            ASSERT_TRUE(isFiniteVec(vec4(specularConeDirection(n, v), specularConeTanHalf(alpha))));
        }
    }
    // The general case is normalize(), down to tiny but representable distances.
    for (const vec3& toCamera :
         {vec3(1, 2, 3), vec3(0, 0, -1e-12f), vec3(1e18f, -1e18f, 1e18f), vec3(1e-7f, 0, 0)}) {
        const vec3 v = viewDirection(toCamera, n);
        EXPECT_NEAR(length(v - normalize(toCamera)), 0.0f, 1e-6f);
    }
}

// Known defect (reported to the header's owner, not fixed here): for two identical lobes with a huge 1/λ the
// product λ̄a·λ̄b underflows, so the mismatch factor 2√(λ̄a λ̄b)/(λ̄a+λ̄b) drops from 1 to 0: with denormals
// flushed (GPU, -ffast-math) w(a, a) = 0 from 1/λ ≈ 1e19; on the CPU it degrades from ≈ 1e20 (0.82 at 1e22)
// and is 0 from ≈ 1e23 — while 1/λ = ∞ (λ̄ = 0 exactly) gives 1. Not reachable from specularLobe (1/λ ≤ 2) or
// fp16 storage (≤ 65504), only from bad data. The scale-free form r = min(λ̄a, λ̄b)/max(λ̄a, λ̄b),
// factor = 2√r/(1 + r) is exactly 1 for equal sharpness, symmetric, and passes this and every test above.
TEST(UpsampleWeights, IdenticalVeryWideLobesWeighOne) {
    for (float inv : {1e19f, 1e24f, 1e30f, 3e38f}) {
        const vec4 lobe(0, 0, 1, inv);
        EXPECT_FLOAT_EQ(weight(lobe, lobe), 1.0f) << "1/λ = " << inv;
    }
}

// --- plane weight ------------------------------------------------------------------------------------------------

TEST(UpsampleWeights, PlaneWeight) {
    const vec3 n = normalize(vec3(1, 2, -2)), p(0.3f, -1.0f, 4.0f);
    const vec3 u = normalize(cross(n, vec3(0, 0, 1))), w = cross(n, u);
    const float dist = 5.0f;
    // On the plane: 1, wherever in the plane.
    EXPECT_EQ(planeWeight(n, p, p, dist), 1.0f);
    for (float s : {0.01f, 0.5f, 3.0f, 50.0f})
        EXPECT_NEAR(planeWeight(n, p, p + s * u - 0.7f * s * w, dist), 1.0f, 1e-5f);
    // Off the plane: decreasing with the distance, on either side; independent of the in-plane offset.
    float previous = 1.0f;
    for (float h = 0.005f; h < 2.0f; h *= 1.3f) {
        const float wz = planeWeight(n, p, p + h * n, dist);
        ASSERT_TRUE(isWeight(wz));
        if (previous > 1e-30f) {
            EXPECT_LT(wz, previous) << "h = " << h;
        }
        EXPECT_NEAR(planeWeight(n, p, p - h * n, dist), wz, 1e-5f);
        EXPECT_NEAR(planeWeight(n, p, p + h * n + 0.8f * u + 1.3f * w, dist), wz, 1e-4f);
        // exp(−(h / (σ_z·dist))²)
        const double expected = std::exp(-std::pow(double(h) / (double(PLANE_WEIGHT_SIGMA) * dist), 2.0));
        EXPECT_NEAR(wz, expected, 1e-5);
        previous = wz;
    }
    // The tolerance follows the camera distance: twice as far, twice the offset, the same weight.
    EXPECT_NEAR(planeWeight(n, p, p + 0.1f * n, 5.0f), planeWeight(n, p, p + 0.2f * n, 10.0f), 1e-6f);
    // The weight is symmetric in p and q when both share the normal.
    EXPECT_FLOAT_EQ(planeWeight(n, p, p + 0.1f * n, dist), planeWeight(n, p + 0.1f * n, p, dist));
    // cameraDistance 0 (and negative): finite, 1 on the plane, 0 off it.
    for (float d0 : {0.0f, -1.0f}) {
        EXPECT_EQ(planeWeight(n, p, p, d0), 1.0f);
        EXPECT_TRUE(isWeight(planeWeight(n, p, p + 0.01f * n, d0)));
        EXPECT_EQ(planeWeight(n, p, p + 0.01f * n, d0), 0.0f);
    }
    // Far-off samples underflow to 0, not NaN.
    EXPECT_EQ(planeWeight(n, p, p + 1e30f * n, dist), 0.0f);
}

// --- tent kernel ---------------------------------------------------------------------------------------------------

TEST(UpsampleWeights, TentKernelIsAPartitionOfUnity) {
    Rng rng;
    for (int radius : {1, 2}) {
        const float r = float(radius);
        for (int i = 0; i < 200; ++i) {
            // A full-res pixel at fractional low-res position f; samples at the integer low-res positions.
            const vec2 f(rng.uniform(-4.0f, 4.0f), rng.uniform(-4.0f, 4.0f));
            const ivec2 base(int(std::floor(f.x)), int(std::floor(f.y)));
            double sum = 0.0;
            for (int y = base.y - radius - 1; y <= base.y + radius + 1; ++y)
                for (int x = base.x - radius - 1; x <= base.x + radius + 1; ++x) {
                    const float k = tentKernel(vec2(float(x), float(y)) - f, r);
                    ASSERT_GE(k, 0.0f);
                    sum += k;
                }
            EXPECT_NEAR(sum, 1.0, 1e-5) << "r = " << radius << " at " << f.x << ", " << f.y;
        }
        // Aligned with a sample: r = 1 is the identity (bilinear), r = 2 spreads over 3×3 samples.
        EXPECT_FLOAT_EQ(tentKernel(vec2(0.0f), r), 1.0f / (r * r));
        // Zero at and beyond the radius, on each axis.
        for (float beyond : {r, r + 1e-3f, r + 0.5f, 10.0f * r}) {
            EXPECT_EQ(tentKernel(vec2(beyond, 0.0f), r), 0.0f);
            EXPECT_EQ(tentKernel(vec2(0.0f, -beyond), r), 0.0f);
            EXPECT_EQ(tentKernel(vec2(-beyond, 0.3f), r), 0.0f);
        }
        EXPECT_GT(tentKernel(vec2(r - 1e-3f, 0.0f), r), 0.0f);
        // Separable and even.
        EXPECT_FLOAT_EQ(tentKernel(vec2(0.3f, -0.6f), r), tentKernel(vec2(-0.3f, 0.6f), r));
        EXPECT_FLOAT_EQ(tentKernel(vec2(0.3f, -0.6f), r) * tentKernel(vec2(0.0f), r),
                        tentKernel(vec2(0.3f, 0.0f), r) * tentKernel(vec2(0.0f, -0.6f), r));
    }
}

// --- the forms the upsample pass evaluates: prepared sharpness, scaled plane, B-spline kernel ------------------

TEST(UpsampleWeights, PreparedLobeWeightMatchesTheDefinition) {
    // lobeLogWeightPrepared (ln 2 + ½(ln λ̄a + ln λ̄b) − ln(λ̄a + λ̄b), harmonic term 1/(1/λ̄a + 1/λ̄b)) against
    // Tokuyoshi 2015's formula in double, over random lobes and sharpnesses across the range [κ/(1+2κ), κ].
    Rng rng;
    for (int i = 0; i < 2000; ++i) {
        const vec3 a = rng.unitVector(), b = rng.unitVector();
        const float la = kKappa * rng.uniform(0.005f, 1.0f), lb = kKappa * rng.uniform(0.005f, 1.0f);
        const double ratio = 2.0 * std::sqrt(double(la) * lb) / (double(la) + lb);
        const double cosine = double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
        const double expected =
            std::pow(ratio, kBeta) * std::exp(kBeta * double(la) * lb / (double(la) + lb) * (cosine - 1.0));
        const float w = exp(lobeLogWeightPrepared(a, preparedSharpness(la), b, preparedSharpness(lb), kBeta));
        ASSERT_TRUE(isWeight(w));
        EXPECT_NEAR(w, expected, 2e-5 + 2e-4 * expected) << la << " " << lb;
    }
    // Identical lobes: exactly 1; a NaN sharpness or axis: exactly 0, never NaN or 1.
    EXPECT_EQ(exp(lobeLogWeightPrepared(vec3(0, 0, 1), preparedSharpness(3.0f), vec3(0, 0, 1),
                                        preparedSharpness(3.0f), kBeta)),
              1.0f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(exp(lobeLogWeightPrepared(vec3(0, 0, 1), preparedSharpness(nan), vec3(0, 0, 1),
                                        preparedSharpness(3.0f), kBeta)),
              0.0f);
    EXPECT_EQ(exp(lobeLogWeightPrepared(vec3(nan), preparedSharpness(3.0f), vec3(0, 0, 1),
                                        preparedSharpness(3.0f), kBeta)),
              0.0f);
}

// The weight upsample.comp takes from lobePairWeightFolded's (ln e, f): e·f.
static float foldedWeight(vec3 a, float la, vec3 b, float lb, float beta, int power) {
    const vec2 w = lobePairWeightFolded(foldedLobe(a, la), foldedLobe(b, lb), beta, power);
    return exp(w.x) * w.y;
}

TEST(UpsampleWeights, RatioPowerIsHalfBetaWhenWhole) {
    EXPECT_EQ(sgRatioPower(20.0f), 10);  // the default β: r¹⁰
    EXPECT_EQ(sgRatioPower(2.0f), 1);
    EXPECT_EQ(sgRatioPower(254.0f), SG_RATIO_POWER_MAX);
    for (const float beta :
         {0.01f, 1.0f, 21.0f, 20.5f, 256.0f, 1000.0f, std::numeric_limits<float>::quiet_NaN()})
        EXPECT_EQ(sgRatioPower(beta), 0) << beta;
}

TEST(UpsampleWeights, FoldedLobeWeightMatchesPrepared) {
    // lobePairWeightFolded (the ratio term as the power r^(β/2) of r = 4h/(λ̄a + λ̄b), what upsample.comp evaluates
    // per pixel and sample) against lobeLogWeightPrepared (trace.comp's, checked against the definition above),
    // over random lobes with sharpnesses across [κ/(1+2κ), κ]: at the default β by multiplies (power 10) and by
    // the logarithm (power 0), and at the ends of the --beta range (0.01 and 1000: power 0; 254: the largest
    // power).
    Rng rng;
    for (const auto& [beta, power] : std::vector<std::pair<float, int>>{{kBeta, sgRatioPower(kBeta)},
                                                                        {kBeta, 0},
                                                                        {0.01f, 0},
                                                                        {1000.0f, 0},
                                                                        {254.0f, SG_RATIO_POWER_MAX}}) {
        double worst = 0.0;
        for (int i = 0; i < 4000; ++i) {
            const vec3 a = rng.unitVector(), b = rng.unitVector();
            const float la = kKappa * rng.uniform(0.005f, 1.0f), lb = kKappa * rng.uniform(0.005f, 1.0f);
            const float prepared =
                exp(lobeLogWeightPrepared(a, preparedSharpness(la), b, preparedSharpness(lb), beta));
            const float folded = foldedWeight(a, la, b, lb, beta, power);
            ASSERT_TRUE(isWeight(folded));
            worst = std::max(worst, double(std::abs(folded - prepared)) / (1e-6 + prepared));
        }
        // Relative difference (of weights above 1e-6), measured: 7.1e-6 (power 10) and 1.1e-5 (power 0) at β 20,
        // 2.4e-7 at β 0.01, 1.3e-5 at β 1000, 2.8e-6 at β 254 (power 127): float rounding of the terms regrouped.
        EXPECT_LT(worst, 4e-5) << "beta " << beta << " power " << power;
    }
    // The power and the logarithm agree on pairs with real weight (axes 0–20° apart, sharpnesses up to 4× apart):
    // measured 8.5e-7.
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
        const vec3 a = rng.unitVector();
        const vec3 b = normalize(a + rng.unitVector() * rng.uniform(0.0f, 0.35f));
        const float la = rng.uniform(1.0f, kKappa), lb = la * rng.uniform(0.25f, 4.0f);
        const float byPower = foldedWeight(a, la, b, lb, kBeta, 10),
                    byLog = foldedWeight(a, la, b, lb, kBeta, 0);
        worst = std::max(worst, double(std::abs(byPower - byLog)) / (1e-6 + byLog));
    }
    EXPECT_LT(worst, 2e-6);
    // Identical lobes: exactly 1, either way.
    const vec3 z(0, 0, 1);
    EXPECT_EQ(foldedWeight(z, 3.0f, z, 3.0f, kBeta, 10), 1.0f);
    EXPECT_EQ(foldedWeight(z, 3.0f, z, 3.0f, kBeta, 0), 1.0f);
    EXPECT_EQ(foldedWeight(z, 1e-30f, z, 1e-30f, kBeta, 10), 1.0f);  // floored λ̄: still equal lobes
    // A NaN or infinite axis or sharpness on either side, or on both: exactly 0, never NaN or 1.
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const vec3 tilted = normalize(vec3(0.2f, 0.1f, 1.0f));
    for (const int power : {10, 0})
        for (const auto& [axis, sharpness] : std::vector<std::pair<vec3, float>>{
                 {z, nan}, {z, inf}, {vec3(nan), 3.0f}, {vec3(inf, 0, 0), 3.0f}, {vec3(nan), nan}}) {
            EXPECT_EQ(foldedWeight(axis, sharpness, tilted, 30.0f, kBeta, power), 0.0f) << sharpness;
            EXPECT_EQ(foldedWeight(z, 3.0f, axis, sharpness, kBeta, power), 0.0f) << sharpness;
            EXPECT_EQ(foldedWeight(axis, sharpness, axis, sharpness, kBeta, power), 0.0f) << sharpness;
        }
}

TEST(UpsampleWeights, ScaledPlaneMatchesPlaneWeight) {
    Rng rng;
    for (int i = 0; i < 1000; ++i) {
        const vec3 n = rng.unitVector();
        const vec3 p(rng.uniform(-50.0f, 50.0f), rng.uniform(-50.0f, 50.0f), rng.uniform(-50.0f, 50.0f));
        const vec3 q = p + rng.unitVector() * rng.uniform(0.0f, 0.5f);
        const float dist = rng.uniform(0.5f, 40.0f);
        const float direct = planeWeight(n, p, q, dist);
        const float scaled = exp(planeLogWeightScaled(scaledTangentPlane(n, p, dist), q));
        ASSERT_TRUE(isWeight(scaled));
        // n·q − n·p rounds at the ulp of |p| (≤ 50 here) against a tolerance σ_z·dist down to 0.01.
        EXPECT_NEAR(scaled, direct, 1e-3f);
    }
}

TEST(UpsampleWeights, BsplineKernelIsAPartitionOfUnityOverThe3x3Nearest) {
    Rng rng;
    for (int i = 0; i < 500; ++i) {
        const vec2 f(rng.uniform(-4.0f, 4.0f), rng.uniform(-4.0f, 4.0f));
        const ivec2 nearest(int(std::lround(f.x)), int(std::lround(f.y)));
        double sum = 0.0, outside = 0.0;
        for (int y = nearest.y - 2; y <= nearest.y + 2; ++y)
            for (int x = nearest.x - 2; x <= nearest.x + 2; ++x) {
                const float k = bsplineKernel(vec2(float(x), float(y)) - f);
                ASSERT_GE(k, 0.0f);
                sum += k;
                if (std::abs(x - nearest.x) > 1 || std::abs(y - nearest.y) > 1) outside += k;
            }
        EXPECT_NEAR(sum, 1.0, 1e-5) << f.x << ", " << f.y;
        EXPECT_EQ(outside, 0.0) << "only the 3×3 nearest samples contribute";
    }
    // Continuous at the knots, even and separable.
    EXPECT_NEAR(bsplineKernel(vec2(0.5f - 1e-6f, 0.0f)), bsplineKernel(vec2(0.5f + 1e-6f, 0.0f)), 1e-5f);
    EXPECT_EQ(bsplineKernel(vec2(1.5f, 0.0f)), 0.0f);
    EXPECT_FLOAT_EQ(bsplineKernel(vec2(0.3f, -0.6f)), bsplineKernel(vec2(-0.3f, 0.6f)));
    EXPECT_FLOAT_EQ(bsplineKernel(vec2(0.0f)), 0.75f * 0.75f);
}

TEST(IndirectPack, RoundTripsBfloat16) {
    // Exactly representable in bfloat16 (8-bit significand): exact round trips, beyond fp16's range too.
    const vec4 diffuse(0.25f, 3.5f, 0.0009765625f, 8.0f), specular(65536.0f * 4.0f, 0.0f, 1.5f, 0.125f);
    const uvec4 packed = packIndirect(diffuse, specular);
    EXPECT_EQ(unpackIndirectDiffuse(packed), diffuse);
    EXPECT_EQ(unpackIndirectSpecular(packed), specular);
    // Anything else within 2^-8 relative (half a step of the 8-bit significand), unbiased over many values.
    Rng rng;
    double signedError = 0.0;
    for (int i = 0; i < 10000; ++i) {
        const float x = std::exp(rng.uniform(-20.0f, 20.0f));
        const float back = unpackBfloat16x2(packBfloat16x2(x, 0.0f)).x;
        ASSERT_LE(std::abs(back - x), x * (1.0f / 256.0f)) << x;
        signedError += (double(back) - x) / x;
    }
    EXPECT_LT(std::abs(signedError / 10000.0), 2e-4);
    // Huge values stay finite (fp16 would overflow at 65504); inf and NaN pass through.
    EXPECT_TRUE(std::isfinite(unpackBfloat16x2(packBfloat16x2(1e30f, 0.0f)).x));
    EXPECT_TRUE(std::isinf(unpackBfloat16x2(packBfloat16x2(kInf, 0.0f)).x));
    EXPECT_TRUE(
        std::isnan(unpackBfloat16x2(packBfloat16x2(std::numeric_limits<float>::quiet_NaN(), 0.0f)).x));
}

// --- jitter sequence -----------------------------------------------------------------------------------------------

TEST(UpsampleWeights, JitterOffsetVisitsEveryOffsetOncePerCycle) {
    for (uint32_t frame : {0u, 1u, 7u, 12345u, 0xFFFFFFFFu}) EXPECT_EQ(jitterOffset(frame, 1), ivec2(0));
    for (int s : {1, 2, 4}) {
        const uint32_t cells = uint32_t(s * s);
        // Every window of s² consecutive frames, including ones across the 32-bit wrap of the frame counter.
        std::vector<uint32_t> starts;
        for (uint32_t start = 0; start < 3 * cells; ++start) starts.push_back(start);
        for (uint32_t back = 1; back <= 2 * cells; ++back) starts.push_back(0u - back);
        for (uint32_t start : starts) {
            std::set<std::pair<int, int>> seen;
            for (uint32_t k = 0; k < cells; ++k) {
                const ivec2 o = jitterOffset(start + k, s);
                ASSERT_GE(o.x, 0);
                ASSERT_GE(o.y, 0);
                ASSERT_LT(o.x, s);
                ASSERT_LT(o.y, s);
                seen.insert({o.x, o.y});
            }
            EXPECT_EQ(seen.size(), size_t(cells)) << "s = " << s << " from frame " << start;
        }
    }
    // s = 4: the first 4 offsets (and any 4 consecutive ones) fall in the 4 different 2×2 quadrants.
    for (uint32_t start = 0; start < 32; ++start) {
        std::set<std::pair<int, int>> quadrants;
        for (uint32_t k = 0; k < 4; ++k) {
            const ivec2 o = jitterOffset(start + k, 4);
            quadrants.insert({o.x / 2, o.y / 2});
        }
        EXPECT_EQ(quadrants.size(), 4u) << "from frame " << start;
    }
    // The 2×2 Bayer order: (0,0), (1,1), (1,0), (0,1).
    EXPECT_EQ(jitterOffset(0, 2), ivec2(0, 0));
    EXPECT_EQ(jitterOffset(1, 2), ivec2(1, 1));
    EXPECT_EQ(jitterOffset(2, 2), ivec2(1, 0));
    EXPECT_EQ(jitterOffset(3, 2), ivec2(0, 1));
    // The 4×4 Bayer matrix, ranks by row: offset (x, y) of frame k is where rank k sits.
    const int bayer4[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(jitterOffset(uint32_t(bayer4[y][x]), 4), ivec2(x, y));
}

}  // namespace

// The renderer's history cap and weights view count pixel-own samples with the weight the shaders give them.
TEST(UpsampleWeights, ExactSampleWeightIsTheShadersOne) {
    EXPECT_EQ(vct::kExactSampleWeight, EXACT_SAMPLE_WEIGHT);
    EXPECT_EQ(vct::kHistoryWeightCap, 8.0f * EXACT_SAMPLE_WEIGHT);
}
