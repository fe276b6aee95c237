#include "render/sky_model.h"

#include <algorithm>
#include <cmath>

namespace vct {

namespace {

constexpr float kPi = 3.14159265358979f;

// Perez et al. 1993: F(θ, γ) = (1 + A·e^(B / cos θ)) (1 + C·e^(D·γ) + E·cos² γ), θ the view's zenith angle,
// γ its angle to the sun.
struct Perez {
    float a, b, c, d, e;
    float operator()(float cosTheta, float gamma) const {
        const float cosGamma = std::cos(gamma);
        return (1.0f + a * std::exp(b / std::max(cosTheta, 0.01f))) *
               (1.0f + c * std::exp(d * gamma) + e * cosGamma * cosGamma);
    }
};

// Preetham et al. 1999, Appendix A.2: the distributions' coefficients as linear functions of turbidity.
Perez perezY(float t) {
    return {0.1787f * t - 1.4630f, -0.3554f * t + 0.4275f, -0.0227f * t + 5.3251f, 0.1206f * t - 2.5771f,
            -0.0670f * t + 0.3703f};
}
Perez perezX(float t) {
    return {-0.0193f * t - 0.2592f, -0.0665f * t + 0.0008f, -0.0004f * t + 0.2125f, -0.0641f * t - 0.8989f,
            -0.0033f * t + 0.0452f};
}
Perez perezYChroma(float t) {
    return {-0.0167f * t - 0.2608f, -0.0950f * t + 0.0092f, -0.0079f * t + 0.2102f, -0.0441f * t - 1.6537f,
            -0.0109f * t + 0.0529f};
}

// Zenith chromaticity (Preetham et al. 1999, A.2): T² (…) + T (…) + (…), cubic in θ_s.
float zenithChroma(float t, float s, const float (&k)[3][4]) {
    auto cubic = [&](const float(&c)[4]) { return ((c[0] * s + c[1]) * s + c[2]) * s + c[3]; };
    return t * t * cubic(k[0]) + t * cubic(k[1]) + cubic(k[2]);
}
constexpr float kZenithX[3][4] = {{0.00166f, -0.00375f, 0.00209f, 0.0f},
                                  {-0.02903f, 0.06377f, -0.03202f, 0.00394f},
                                  {0.11693f, -0.21196f, 0.06052f, 0.25886f}};
constexpr float kZenithY[3][4] = {{0.00275f, -0.00610f, 0.00317f, 0.0f},
                                  {-0.04214f, 0.08970f, -0.04153f, 0.00516f},
                                  {0.15346f, -0.26756f, 0.06670f, 0.26688f}};

// CIE xyY → linear Rec.709 (sRGB primaries, D65).
glm::vec3 rgbFromXyY(float x, float y, float luminance) {
    if (!(y > 1e-4f)) return glm::vec3(0.0f);
    const float X = x / y * luminance, Y = luminance, Z = (1.0f - x - y) / y * luminance;
    return glm::max(
        glm::vec3(3.2406f * X - 1.5372f * Y - 0.4986f * Z, -0.9689f * X + 1.8758f * Y + 0.0415f * Z,
                  0.0557f * X - 0.2040f * Y + 1.0570f * Z),
        glm::vec3(0.0f));
}

// The model holds for the sun above the horizon: its angles are taken at most at the horizon, and the sky
// fades to kNightFloor of that over kTwilight radians of sun depression.
constexpr float kTwilight = 12.0f * kPi / 180.0f;
constexpr float kNightFloor = 1e-3f;
// E_dn at the horizon tends to 0 (air mass 38): the sky/sun ratio is taken at most at 85°, where the model's
// ratio is still that of the higher sun (0.08 sr⁻¹ at T = 3), not the ratio of two vanishing numbers.
constexpr float kMaxRatioZenithAngle = 85.0f * kPi / 180.0f;

}  // namespace

float skyZenithLuminance(float turbidity, float sunZenithAngle) {
    const float s = std::clamp(sunZenithAngle, 0.0f, 0.5f * kPi);
    const float chi = (4.0f / 9.0f - turbidity / 120.0f) * (kPi - 2.0f * s);
    return std::max((4.0453f * turbidity - 4.9710f) * std::tan(chi) - 0.2155f * turbidity + 2.4192f, 1e-3f);
}

float sunDirectNormalIlluminance(float turbidity, float sunZenithAngle) {
    const float s = std::clamp(sunZenithAngle, 0.0f, 0.5f * kPi);
    // Kasten and Young 1989 relative optical air mass.
    const float degrees = s * 180.0f / kPi;
    const float m = 1.0f / (std::cos(s) + 0.50572f * std::pow(96.07995f - degrees, -1.6364f));
    // Kasten 1996 Rayleigh optical thickness (m ≤ 20).
    const float mc = std::min(m, 20.0f);
    const float rayleigh =
        1.0f / (6.6296f + mc * (1.7513f + mc * (-0.1202f + mc * (0.0065f - mc * 0.00013f))));
    constexpr float kSolarIlluminance = 127.5f;  // klux outside the atmosphere
    return kSolarIlluminance * std::exp(-0.8662f * turbidity * m * rayleigh);
}

glm::vec3 skyRadiance(glm::vec3 dir, const SkyParameters& sky) {
    const float t = std::clamp(sky.turbidity, 2.0f, 10.0f);
    const glm::vec3 sun = glm::normalize(sky.sunDirection);
    const float sunZenith = std::acos(std::clamp(sun.y, -1.0f, 1.0f));
    const float depression = std::max(sunZenith - 0.5f * kPi, 0.0f);
    const float twilight = std::max(1.0f - depression / kTwilight, 0.0f);
    const float fade = kNightFloor + (1.0f - kNightFloor) * twilight * twilight;
    // Above the horizon the model's own angles; the sun below it is taken on the horizon, same azimuth.
    glm::vec3 sunModel = sun;
    if (sunModel.y < 0.0f) {
        sunModel.y = 0.0f;
        const float len = glm::length(sunModel);
        sunModel = len > 1e-6f ? sunModel / len : glm::vec3(1.0f, 0.0f, 0.0f);
    }
    const float s = std::min(sunZenith, 0.5f * kPi);
    const glm::vec3 d = glm::normalize(glm::vec3(dir.x, std::max(dir.y, 0.0f), dir.z));
    const float cosTheta = d.y;
    const float gamma = std::acos(std::clamp(glm::dot(d, sunModel), -1.0f, 1.0f));
    const float luminance = skyZenithLuminance(t, s) * perezY(t)(cosTheta, gamma) / perezY(t)(1.0f, s);
    const float x = zenithChroma(t, s, kZenithX) * perezX(t)(cosTheta, gamma) / perezX(t)(1.0f, s);
    const float y =
        zenithChroma(t, s, kZenithY) * perezYChroma(t)(cosTheta, gamma) / perezYChroma(t)(1.0f, s);
    // kcd/m² of sky per klux of sun, times the scene's sun: the scene's units.
    const float scale =
        sky.sunIrradiance / sunDirectNormalIlluminance(t, std::min(sunZenith, kMaxRatioZenithAngle));
    const glm::vec3 rgb = rgbFromXyY(x, y, std::max(luminance, 0.0f)) * scale * fade;
    return (std::isfinite(rgb.x) && std::isfinite(rgb.y) && std::isfinite(rgb.z)) ? rgb : glm::vec3(0.0f);
}

}  // namespace vct
