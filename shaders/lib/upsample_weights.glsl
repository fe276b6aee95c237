// The weights of the spatio-temporal upsampling (docs/design.md §6, Tokuyoshi 2015 §4): spherical-Gaussian
// (SG) approximations of each pixel's specular and diffuse lobes, the lobe-aware weight that compares two of
// them, the normal-aware baseline it replaces, the geometric (plane-distance) weight and the spatial kernel.
// Shared by GLSL (upsample.comp) and C++ (tests/upsample_weights_test.cpp) through lib/cpp_glsl.h: pure
// functions, `f` literals.
//
// A lobe is a vec4: xyz the unit axis ξ, w the INVERSE sharpness 1/λ of G(ω) = exp(λ(ω·ξ − 1)). The inverse
// form keeps a mirror (α = 0, λ = ∞) finite: 1/λ = 0, and the κ-smoothed sharpness below is then exactly κ.
#ifndef VCT_UPSAMPLE_WEIGHTS_GLSL
#define VCT_UPSAMPLE_WEIGHTS_GLSL

#include "lib/constants.glsl"
#include "lib/cone.glsl"

// Tokuyoshi 2015's parameters: β sharpens the lobe weight, κ is the sharpness of the smoothing kernel that bounds
// every lobe's sharpness (λ̄ ≤ κ), so no two lobes are "infinitely" different.
const float SG_DEFAULT_BETA = 20.0f;
const float SG_DEFAULT_KAPPA = 100.0f;
// The largest κ: the trace stores each sample's λ̄ (≤ κ) in a 16-bit float (trace.comp's guide normal image),
// whose largest finite value is 65504. A larger κ stored +inf for the mirror-like lobes (cornell's floor stripe
// of roughness 0.05 reaches λ̄ ≈ 1.4e5 at κ = 1e6), and inf − inf in the weight below. The command line rejects
// a larger --kappa (engine/app/cli/session.cpp); smoothedSharpness clamps whatever κ arrives to it.
const float SG_MAX_KAPPA = 65504.0f;
// The normal-aware baseline: σ_n² = 0.01.
const float NORMAL_WEIGHT_DEFAULT_SIGMA2 = 0.01f;
// Diffuse lobe sharpness λ_d: the cosine lobe max(n·ω, 0) is best fitted by an SG of sharpness ≈ 2.
const float SG_DIFFUSE_SHARPNESS = 2.0f;

// Specular lobe of a pixel (docs/design.md §6.2): the GGX NDF as an SG warped into the reflected direction
// ξ = 2(n·v)n − v (lib/cone.glsl, specularLobeInverseSharpness).
// n, v unit; alpha the effective (Toksvig, AA) GGX roughness α = perceptual².
VCT_INLINE vec4 specularLobe(vec3 n, vec3 v, float alpha) {
    // The axis is the specular cone's (lib/cone.glsl), so the lobe compared is the one the trace sampled.
    return vec4(specularConeDirection(n, v), specularLobeInverseSharpness(alpha, dot(n, v)));
}

// Diffuse lobe: the clamped cosine around n, one fixed sharpness.
VCT_INLINE vec4 diffuseLobe(vec3 n) { return vec4(n, 1.0f / SG_DIFFUSE_SHARPNESS); }

// Sharpness after convolution with the smoothing kernel of sharpness κ: λ̄ = λκ/(λ+κ) = κ / (1 + κ/λ).
// In [0, κ]: κ for a mirror (1/λ = 0), → 0 as 1/λ → ∞. κ is clamped to SG_MAX_KAPPA, so λ̄ fits fp16.
VCT_INLINE float smoothedSharpness(float invLambda, float kappa) {
    const float k = min(kappa, SG_MAX_KAPPA);
    return k / (1.0f + k * max(invLambda, 0.0f));
}

// Lobe-aware weight of Tokuyoshi 2015 §4.2 (docs/design.md §6.3) between lobes a and b, in [0, 1],
// symmetric, 1 for identical lobes:
//   w = ( 2√(λ̄a λ̄b) / (λ̄a + λ̄b) )^β · exp( β · λ̄a λ̄b / (λ̄a + λ̄b) · (ξa·ξb − 1) ).
// The first factor penalises a sharpness mismatch, the second the angle between the axes. ξa·ξb − 1 is taken
// as −½‖ξa − ξb‖², exact for unit axes and free of the cancellation of 1 − cos near 0. The exponent reaches
// about −βκ (−2000): exp underflows to 0, which is the right answer.
// The same from the axes and the smoothed sharpnesses λ̄ (smoothedSharpness), for callers that keep λ̄ per
// sample. Evaluated as one exp: exp(β·(ln ratio + h·(ξa·ξb − 1))); ln 0 is avoided by a floor whose β-th power
// is 0 in float anyway.
// The weights below come in two forms: the weight w and its logarithm ln w (the *LogWeight functions), so
// that a caller multiplying several weights (plane × lobe) pays for one exp instead of one per factor — on a
// CPU driver (lavapipe) the exps are a large part of the upsample's cost.
// A smoothed sharpness λ̄ prepared for many lobe weights against it: (λ̄, ln λ̄, 1/λ̄), so that a pair costs one
// log and one division (lobeLogWeightPrepared) instead of a square root, a log and three divisions. λ̄ is
// floored at 1e-30 (λ̄ = 0 only in the limit 1/λ → ∞; its weights are those of the floor: 1 between two such
// lobes). A NaN stays NaN and is caught by lobeLogWeightPrepared.
VCT_INLINE vec3 preparedSharpness(float smoothed) {
    const float l = smoothed < 1e-30f ? 1e-30f : smoothed;  // NaN < x is false: NaN stays
    return vec3(l, log(l), 1.0f / l);
}

// ln w of the lobe-aware weight from prepared sharpnesses: with ln of the ratio term
//   ln(2√(λ̄a λ̄b)/(λ̄a + λ̄b)) = ln 2 + ½(ln λ̄a + ln λ̄b) − ln(λ̄a + λ̄b)   (≤ 0; exactly 0 for equal λ̄)
// and λ̄a λ̄b/(λ̄a + λ̄b) = 1/(1/λ̄a + 1/λ̄b), which cannot underflow to 0/0 for tiny λ̄. Exactly symmetric.
// A NaN lobe (a NaN axis or sharpness, or an infinite sharpness: inf − inf) weighs 0, never 1 or NaN, on every
// device: the NaN is carried to the end (no min(): GPUs may return the other operand of min(NaN, 0), which gave
// ln ratio = 0, the weight of EQUAL sharpness, for an fp16-overflowed λ̄ = inf against a finite one, while the
// CPU kept the NaN) and then replaced by −1e30 with an explicit isnan (exp gives 0).
VCT_INLINE float lobeLogWeightPrepared(vec3 axisA, vec3 a, vec3 axisB, vec3 b, float beta) {
    const float ratioTerm = 0.6931472f + 0.5f * (a.y + b.y) - log(a.x + b.x);  // ≤ 0 but for rounding
    const float logRatio = a.x == b.x ? 0.0f : (ratioTerm > 0.0f ? 0.0f : ratioTerm);  // NaN > 0 is false
    const vec3 d = axisA - axisB;
    const float cosMinusOne = -0.5f * dot(d, d);
    const float result = beta * (logRatio + cosMinusOne / (a.z + b.z));
    return isnan(result) || result < -1e30f ? -1e30f : result;
}

// The form upsample.comp evaluates for every (pixel, sample) pair (docs/design.md §6.3): the same weight with
// the ratio term as a power instead of a logarithm. With h = λ̄a λ̄b/(λ̄a + λ̄b) and the ratio term's square
//   r = (2√(λ̄a λ̄b)/(λ̄a + λ̄b))² = 4h/(λ̄a + λ̄b)  (≤ 1; exactly 1 for equal λ̄),
//   w = r^(β/2) · exp(−(β/2)·h·‖ξa − ξb‖²):
// one division per pair. When β/2 is a whole number (the default β = 20: r¹⁰; sgRatioPower) the power is a few
// multiplies by repeated squaring; upsample.comp makes it a specialization constant, so the bit loop unrolls
// into exactly those multiplies. Otherwise (power 0) (β/2)·ln r joins the exponent, which the caller evaluates
// with its plane weight in one exp. On lavapipe this made the SG upsample 0.93–0.96× (§6.8).
// The NaN check is done once per lobe (foldedLobe): a lobe that is not finite (NaN or infinite axis or
// sharpness) becomes a finite stand-in with `valid` 0, and every pair it takes part in weighs exactly 0.
struct FoldedLobe {
    vec3 axis;
    float sharpness;  // λ̄, floored at SG_FOLDED_MIN_SHARPNESS
    float valid;      // 1, or 0 for a lobe that is not finite
};
// λ̄ ≥ 1e-6 keeps λ̄a λ̄b (≥ 1e-12) from underflowing to 0, which would give two equal tiny lobes no weight.
// Within the settings' ranges λ̄ ≥ 0.0098 (κ ≥ 0.01, and λ ≥ 0.5: α = 1 seen head-on), so it changes no lobe's
// weight.
const float SG_FOLDED_MIN_SHARPNESS = 1e-6f;
// The largest whole β/2 taken as a power (7 bits: at most 6 squarings and 7 multiplies).
const int SG_RATIO_POWER_MAX = 127;

VCT_INLINE FoldedLobe foldedLobe(vec3 axis, float smoothed) {
    // NaN < x is false: a NaN stays, and is caught by the finiteness test.
    const float l = smoothed < SG_FOLDED_MIN_SHARPNESS ? SG_FOLDED_MIN_SHARPNESS : smoothed;
    const bool finite = all(lessThan(abs(vec4(axis, l)), vec4(1e30f)));  // false for NaN and ±inf
    FoldedLobe lobe;
    lobe.axis = finite ? axis : vec3(0.0f, 0.0f, 1.0f);
    lobe.sharpness = finite ? l : 1.0f;
    lobe.valid = finite ? 1.0f : 0.0f;
    return lobe;
}

// β/2 when it is a whole number in 1 .. SG_RATIO_POWER_MAX (the power lobePairWeightFolded raises r to by
// multiplies), else 0 (r's logarithm).
VCT_INLINE int sgRatioPower(float beta) {
    const float halfBeta = 0.5f * beta;
    return halfBeta >= 1.0f && halfBeta <= float(SG_RATIO_POWER_MAX) && halfBeta == floor(halfBeta)
               ? int(halfBeta)
               : 0;
}

// The lobe-aware weight of two folded lobes as (ln e, f), w = e·f: ln e the angle term (with (β/2)·ln r when
// `power` is 0), f the ratio term r^power (1 when `power` is 0) times both lobes' validity. `power` =
// sgRatioPower(β).
VCT_INLINE vec2 lobePairWeightFolded(FoldedLobe a, FoldedLobe b, float beta, int power) {
    const float inverseSum = 1.0f / (a.sharpness + b.sharpness);
    const float harmonic = a.sharpness * b.sharpness * inverseSum;
    const float r = a.sharpness == b.sharpness ? 1.0f : min(4.0f * harmonic * inverseSum, 1.0f);
    const vec3 d = a.axis - b.axis;
    float logAngle = -0.5f * beta * harmonic * dot(d, d);
    float factor = a.valid * b.valid;
    if (power > 0) {
        float p = r;
        for (int bit = 0; bit < 7; ++bit) {
            if (((power >> bit) & 1) != 0) factor *= p;
            p *= p;
        }
    } else {
        logAngle += 0.5f * beta * log(r);  // r = 0: −inf, a weight of exactly 0
    }
    return vec2(logAngle, factor);
}

VCT_INLINE float lobeLogWeightSmoothed(vec3 axisA, float la, vec3 axisB, float lb, float beta) {
    return lobeLogWeightPrepared(axisA, preparedSharpness(la), axisB, preparedSharpness(lb), beta);
}

VCT_INLINE float lobeWeightSmoothed(vec3 axisA, float la, vec3 axisB, float lb, float beta) {
    return exp(lobeLogWeightSmoothed(axisA, la, axisB, lb, beta));
}

// Two lobes of the same smoothed sharpness λ̄ (the diffuse lobes: one fixed λ_d): the ratio term is 1 and the
// weight is exp(β·λ̄/2·(ξa·ξb − 1)), a normal weight with 1/σ² = β·λ̄/2.
VCT_INLINE float equalLobeLogWeight(vec3 axisA, vec3 axisB, float smoothed, float beta) {
    const vec3 d = axisA - axisB;
    return -0.25f * beta * smoothed * dot(d, d);
}

VCT_INLINE float lobeWeight(vec4 a, vec4 b, float beta, float kappa) {
    return lobeWeightSmoothed(vec3(a), smoothedSharpness(a.w, kappa), vec3(b), smoothedSharpness(b.w, kappa),
                              beta);
}

// Normal-aware baseline: w_n = exp((na·nb − 1) / σ_n²), again with na·nb − 1 = −½‖na − nb‖².
VCT_INLINE float normalLogWeight(vec3 na, vec3 nb, float sigma2) {
    const vec3 d = na - nb;
    return -0.5f * dot(d, d) / max(sigma2, 1e-8f);
}
VCT_INLINE float normalWeight(vec3 na, vec3 nb, float sigma2) { return exp(normalLogWeight(na, nb, sigma2)); }

// Geometric weight: distance of sample point q from the tangent plane of pixel p (unit normal n), relative to
// p's distance from the camera (so the tolerance follows the depth precision and the pixel footprint):
//   w_z = exp(−(|n·(q − p)| / (σ_z·dist))²). Slanted surfaces keep their neighbours (a plain depth difference
// would reject them); a step in depth (another object, a fold) is rejected.
const float PLANE_WEIGHT_SIGMA = 0.02f;
VCT_INLINE float planeLogWeight(vec3 n, vec3 p, vec3 q, float cameraDistance) {
    const float d = abs(dot(n, q - p)) / (PLANE_WEIGHT_SIGMA * max(cameraDistance, 1e-6f));
    return -d * d;
}
// The same for many points q against one pixel, with the division done once: the pixel's tangent plane scaled
// by 1/(σ_z·dist), so that ln w_z = −(plane.xyz·q + plane.w)². (n·q − n·p instead of n·(q − p) rounds at the
// ulp of |p|: weights within 1e-3 of planeWeight for |p| ≤ 50 and σ_z·dist ≥ 0.01, tests/upsample_weights_test.)
VCT_INLINE vec4 scaledTangentPlane(vec3 n, vec3 p, float cameraDistance) {
    const float inverseTolerance = 1.0f / (PLANE_WEIGHT_SIGMA * max(cameraDistance, 1e-6f));
    return vec4(n * inverseTolerance, -dot(n, p) * inverseTolerance);
}
VCT_INLINE float planeLogWeightScaled(vec4 scaledPlane, vec3 q) {
    const float d = dot(vec3(scaledPlane), q) + scaledPlane.w;
    return -d * d;
}

VCT_INLINE float planeWeight(vec3 n, vec3 p, vec3 q, float cameraDistance) {
    return exp(planeLogWeight(n, p, q, cameraDistance));
}

// Spatial kernel f: a separable tent of radius r (in low-res texels) normalised by 1/r per axis, so that on a
// regular grid of samples with integer r the weights sum to 1 (partition of unity): the sum of weights of the
// spatial part then reads as "the fraction of a full neighbourhood that agreed". r = 1 is bilinear.
VCT_INLINE float tentKernel(vec2 offsetLowTexels, float radius) {
    const vec2 t = max(vec2(1.0f) - abs(offsetLowTexels) / radius, vec2(0.0f)) / radius;
    return t.x * t.y;
}

// Spatial kernel f of the guided upsampling: the separable quadratic B-spline (support radius 1.5 low-res
// texels), like the tent a partition of unity on the sample grid, but smooth and narrower (variance 1/4 texel²
// against 2/3 for the tent of radius 2): a pixel reaches only its 3×3 nearest samples, 9 guide weights instead
// of 16, and less spatial blur goes into the converged history.
VCT_INLINE float bsplineKernel(vec2 offsetLowTexels) {
    const vec2 x = abs(offsetLowTexels);
    const vec2 outerWeight = max(vec2(1.5f) - x, vec2(0.0f));
    const vec2 t = mix(0.5f * outerWeight * outerWeight, vec2(0.75f) - x * x, vec2(lessThan(x, vec2(0.5f))));
    return t.x * t.y;
}

// The quadratic B-spline's value at its centre (per axis 3/4): the kernel weight of a sample traced at the
// pixel itself.
const float BSPLINE_CENTRE = 0.5625f;

// Weight of a sample traced at the pixel itself in the accumulated history, in units of one interpolated
// neighbourhood (the spatial kernel sums to 1). The neighbourhood is a blur (the B-spline spans ±1.5 low-res
// texels): if its samples counted as much as the pixel's own, the history would converge to the blurred trace,
// not to the traced pixels, however many frames the jitter covers. Counted this much less, they fill a pixel
// until its own sample arrives (alone they still give a full, normalised estimate) and then mostly step aside,
// while still bringing this frame's light where a moving object changed it (cornell's cube: 64 measured best
// at γ 0.8 against 16, 32, 256 and 4096; benchmarks/README.md). The sum of weights that τ tests counts every
// sample by its plain kernel weight (upsample.comp keeps both sums); the re-trace writes this weight too.
const float EXACT_SAMPLE_WEIGHT = 64.0f;

// Low-res sample offsets o_k (docs/design.md §6.1): frame k traces low-res pixel (x, y) at full-res pixel
// s·(x, y) + o_k. The sequence visits all s×s offsets every s² frames in an order that spreads consecutive
// offsets apart (the 2×2 and 4×4 Bayer matrices' ranks), so a partial history already covers the block evenly.
VCT_INLINE ivec2 jitterOffset(uint frameIndex, int scale) {
    if (scale <= 1) return ivec2(0);
    // Inverse of the Bayer order: rank k → position, recursively over 2×2 quadrants, least significant first.
    const uint cells = uint(scale * scale);
    uint k = frameIndex % cells;
    ivec2 o = ivec2(0);
    int bit = scale / 2;
    for (int level = 0; level < 2 && bit > 0; ++level) {
        // Rank within a 2×2 Bayer block: 0 → (0,0), 1 → (1,1), 2 → (1,0), 3 → (0,1).
        const uint r = k % 4u;
        const ivec2 step =
            r == 0u ? ivec2(0, 0) : (r == 1u ? ivec2(1, 1) : (r == 2u ? ivec2(1, 0) : ivec2(0, 1)));
        o += step * bit;
        k /= 4u;
        bit /= 2;
    }
    return o;
}

#endif  // VCT_UPSAMPLE_WEIGHTS_GLSL
