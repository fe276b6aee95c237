// CPU tests of the shared shader math in shaders/lib/brdf.glsl and color.glsl (the code the GPU runs).
// Integrals are done in double with the BRDF itself evaluated through the float shader functions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <random>
#include <vector>

#include "render/dfg_table.h"
#include "render/shader_math.h"

namespace {

namespace g = vct::glsl;
using glm::vec2;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;

bool finite(vec3 c) {
    return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
}

// Substitution tan θ = α·tan(sπ/2), s ∈ (0, 1): puts the quadrature points where GGX's peak and tail are at
// any α (uniform in θ at α = 1), so a midpoint rule in s resolves α = 0.01 as well as α = 1.
struct ThetaSample {
    double theta;
    double dThetaDs;
};
ThetaSample thetaFromS(double s, double alpha) {
    double t = std::tan(s * kPi / 2.0);
    return {std::atan(alpha * t), alpha * (kPi / 2.0) * (1.0 + t * t) / (1.0 + alpha * alpha * t * t)};
}

// ∫ D(h) (n·h) dω_h over the hemisphere.
double integrateNdf(float alpha, int thetaSteps) {
    double sum = 0.0;
    for (int i = 0; i < thetaSteps; ++i) {
        ThetaSample ts = thetaFromS((i + 0.5) / thetaSteps, alpha);
        double cosTheta = std::cos(ts.theta);
        sum += g::D_GGX(float(cosTheta), alpha) * cosTheta * std::sin(ts.theta) * ts.dThetaDs;
    }
    return 2.0 * kPi * sum / thetaSteps;
}

// Directional albedo ∫ f_s(v, l) (n·l) dω_l of the specular lobe with F0 = 1, integrated over half vectors
// (dω_l = 4 (v·h) dω_h). v lies in the xz plane, so the integrand is symmetric in φ: integrate [0, π],
// double.
double specularAlbedo(float NoV, float alpha, int thetaSteps, int phiSteps) {
    vec3 v(std::sqrt(1.0f - NoV * NoV), 0.0f, NoV);
    double sum = 0.0;
    for (int i = 0; i < thetaSteps; ++i) {
        ThetaSample ts = thetaFromS((i + 0.5) / thetaSteps, alpha);
        double sinTheta = std::sin(ts.theta);
        for (int j = 0; j < phiSteps; ++j) {
            double phi = kPi * (j + 0.5) / phiSteps;
            vec3 h(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)),
                   float(std::cos(ts.theta)));
            float VoH = glm::dot(v, h);
            vec3 l = 2.0f * VoH * h - v;
            if (VoH <= 0.0f || l.z <= 0.0f) continue;
            float f = g::specularBrdf(NoV, l.z, h.z, VoH, vec3(1.0f), alpha).x;
            sum += double(f) * l.z * 4.0 * VoH * sinTheta * ts.dThetaDs;
        }
    }
    return 2.0 * sum * (kPi / phiSteps) / thetaSteps;
}

TEST(Brdf, GgxNdfIsNormalised) {
    for (float alpha : {0.002f, 0.005f, 0.01f, 0.05f, 0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        EXPECT_NEAR(integrateNdf(alpha, 20000), 1.0, 0.01) << "alpha " << alpha;
    }
}

// White furnace: with F0 = 1 the single-scattering lobe may lose energy (to multiple scattering) but never
// create it. The independent integral also checks integrateDFG, which the DFG table is made of.
TEST(Brdf, WhiteFurnaceSpecularAlbedoAtMostOne) {
    for (float alpha : {0.01f, 0.02f, 0.05f, 0.1f, 0.2f, 0.35f, 0.5f, 0.75f, 1.0f}) {
        for (float NoV : {0.01f, 0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f}) {
            double albedo = specularAlbedo(NoV, alpha, 1000, 128);
            EXPECT_LE(albedo, 1.0 + 2e-3) << "alpha " << alpha << " NoV " << NoV;
            EXPECT_GT(albedo, 0.3) << "alpha " << alpha << " NoV " << NoV;  // GGX-Smith loses < 70%
            vec2 dfg = g::integrateDFG(NoV, alpha, 4096);
            EXPECT_NEAR(dfg.x + dfg.y, albedo, 0.01) << "alpha " << alpha << " NoV " << NoV;
        }
    }
    // Smooth surfaces lose (almost) nothing.
    EXPECT_GT(specularAlbedo(0.5f, 0.01f, 1000, 128), 0.995);
}

TEST(Brdf, Reciprocity) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    auto randomAbove = [&](vec3 n) {
        for (;;) {
            vec3 d(uniform(rng), uniform(rng), uniform(rng));
            float len = glm::length(d);
            if (len > 0.1f && len <= 1.0f && glm::dot(d, n) / len > 0.01f) return d / len;
        }
    };
    const vec3 n = glm::normalize(vec3(0.3f, -0.2f, 1.0f));
    const vec3 baseColor(0.9f, 0.5f, 0.2f);
    for (float roughness : {0.0f, 0.1f, 0.5f, 1.0f}) {
        for (float metallic : {0.0f, 0.5f, 1.0f}) {
            for (int k = 0; k < 200; ++k) {
                vec3 v = randomAbove(n), l = randomAbove(n);
                vec3 a = g::evalBrdf(n, v, l, baseColor, metallic, roughness);
                vec3 b = g::evalBrdf(n, l, v, baseColor, metallic, roughness);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-4f * std::max(a[c], 1.0f));
            }
        }
    }
}

// Hard cases (docs/design.md §7): α = 0, roughness 0 and 1, grazing and back-facing v, light at and below the
// horizon.
TEST(Brdf, HardCasesStayFinite) {
    const vec3 n(0.0f, 0.0f, 1.0f);
    std::vector<vec3> dirs;
    for (float cosTheta : {1.0f, 0.5f, 0.01f, 0.0f, -0.3f, -1.0f}) {
        float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
        dirs.push_back(vec3(sinTheta, 0.0f, cosTheta));
        dirs.push_back(vec3(-sinTheta, 0.0f, cosTheta));
        dirs.push_back(vec3(0.0f, sinTheta, cosTheta));
    }
    for (float roughness : {0.0f, 0.01f, 0.5f, 1.0f}) {
        for (float metallic : {0.0f, 1.0f}) {
            for (vec3 v : dirs) {
                for (vec3 l : dirs) {
                    vec3 f = g::evalBrdf(n, v, l, vec3(1.0f), metallic, roughness);
                    vec3 fc = g::evalBrdfCosine(n, v, l, vec3(1.0f), metallic, roughness);
                    ASSERT_TRUE(finite(f) && finite(fc))
                        << "roughness " << roughness << " NoV " << v.z << " NoL " << l.z;
                    EXPECT_GE(glm::min(f.x, glm::min(f.y, f.z)), 0.0f);
                    if (l.z <= 0.0f) {
                        EXPECT_EQ(fc, vec3(0.0f));
                    }
                }
            }
        }
    }
    for (float alpha : {0.0f, 1e-6f, 0.002f, 1.0f}) {
        for (float c : {-1.0f, 0.0f, 1e-4f, 0.5f, 1.0f, 1.0000001f}) {
            EXPECT_TRUE(std::isfinite(g::D_GGX(c, alpha))) << alpha << " " << c;
            EXPECT_TRUE(std::isfinite(g::V_SmithGGXCorrelated(c, c, alpha))) << alpha << " " << c;
            EXPECT_TRUE(std::isfinite(g::V_SmithGGXCorrelated(c, 0.0f, alpha))) << alpha << " " << c;
            EXPECT_TRUE(finite(g::F_Schlick(vec3(0.04f), c)));
            vec2 dfg = g::integrateDFG(c, alpha, 256);
            EXPECT_TRUE(std::isfinite(dfg.x) && std::isfinite(dfg.y)) << alpha << " " << c;
        }
    }
    EXPECT_EQ(g::D_GGX(-0.5f, 0.5f), 0.0f);                             // χ⁺
    EXPECT_FLOAT_EQ(g::V_SmithGGXCorrelated(1.0f, 1.0f, 0.0f), 0.25f);  // G = 1: V = 1/(4 n·l n·v)
    EXPECT_FLOAT_EQ(g::F_Schlick(0.04f, 1.0f), 0.04f);
    EXPECT_FLOAT_EQ(g::F_Schlick(0.04f, 0.0f), 1.0f);
}

TEST(Brdf, MaterialParameters) {
    EXPECT_FLOAT_EQ(g::alphaFromPerceptual(0.5f), 0.25f);
    EXPECT_EQ(g::alphaFromPerceptual(0.0f), 0.0f);
    EXPECT_EQ(g::f0FromMetallic(vec3(0.8f, 0.5f, 0.1f), 0.0f), vec3(0.04f));
    EXPECT_EQ(g::f0FromMetallic(vec3(0.8f, 0.5f, 0.1f), 1.0f), vec3(0.8f, 0.5f, 0.1f));
    EXPECT_EQ(g::diffuseAlbedo(vec3(0.8f), 1.0f), vec3(0.0f));
    EXPECT_EQ(g::diffuseAlbedo(vec3(0.8f), 0.0f), vec3(0.8f));
}

TEST(Dfg, MirrorIsExact) {
    for (float NoV : {0.1f, 0.5f, 1.0f}) {
        vec2 dfg = g::integrateDFG(NoV, 0.0f, 64);
        float Fc = std::pow(1.0f - NoV, 5.0f);
        EXPECT_NEAR(dfg.x, 1.0f - Fc, 1e-5f);
        EXPECT_NEAR(dfg.y, Fc, 1e-5f);
    }
}

TEST(Dfg, TableBoundsAndEnergyCompensation) {
    const uint32_t size = 32;
    std::vector<vec2> table = vct::makeDfgTable(size);
    ASSERT_EQ(table.size(), size_t(size) * size);
    for (uint32_t row = 0; row < size; ++row) {
        for (uint32_t col = 0; col < size; ++col) {
            vec2 dfg = table[row * size + col];
            EXPECT_GE(dfg.x, 0.0f);
            EXPECT_LE(dfg.x, 1.0f);
            EXPECT_GE(dfg.y, 0.0f);
            EXPECT_LE(dfg.y, 1.0f);
            EXPECT_LE(dfg.x + dfg.y, 1.0f + 1e-3f) << row << " " << col;
            for (float f0 : {0.0f, 0.04f, 0.5f, 1.0f}) {
                vec3 comp = g::specularEnergyCompensation(vec3(f0), dfg);
                EXPECT_TRUE(finite(comp));
                EXPECT_GE(comp.x, 1.0f - 1e-6f);
            }
            // With compensation a white lobe reflects everything (the point of the term).
            EXPECT_NEAR(g::specularDfg(vec3(1.0f), dfg).x, 1.0f, 1e-5f);
        }
    }
    // Layout: rows are roughness, so the smoothest row keeps (almost) all energy, the roughest loses some.
    float smoothE = table[size / 2].x + table[size / 2].y;
    float roughE = table[(size - 1) * size + size / 2].x + table[(size - 1) * size + size / 2].y;
    EXPECT_GT(smoothE, 0.999f);
    EXPECT_LT(roughE, 0.9f);
}

TEST(Color, SrgbRoundTrip) {
    for (int i = 0; i <= 1000; ++i) {
        float x = i / 1000.0f;
        EXPECT_NEAR(g::srgbToLinear(g::linearToSrgb(vec3(x))).x, x, 1e-5f);
        EXPECT_NEAR(g::linearToSrgb(g::srgbToLinear(vec3(x))).x, x, 1e-5f);
    }
    for (int b = 0; b < 256; ++b) {  // every 8-bit code survives decode + encode
        float linear = g::srgbToLinear(b / 255.0f);
        EXPECT_EQ(int(std::lround(g::linearToSrgb(linear) * 255.0f)), b);
    }
    EXPECT_NEAR(g::linearToSrgb(0.5f), 0.735357f, 1e-5f);  // reference value of the sRGB curve
    EXPECT_TRUE(finite(g::linearToSrgb(vec3(-1.0f))));
    EXPECT_NEAR(g::luminance(vec3(1.0f)), 1.0f, 1e-6f);
}

TEST(Color, ToneMapMonotonicAndBounded) {
    float previous = -1.0f;
    for (int i = 0; i <= 4000; ++i) {
        float x = i == 0 ? 0.0f : std::pow(10.0f, -4.0f + 8.0f * i / 4000.0f);  // 1e-4 … 1e4
        float y = g::toneMapAces(vec3(x), 1.0f).x;
        EXPECT_GE(y, 0.0f);
        EXPECT_LE(y, 1.0f);
        EXPECT_GE(y, previous) << "x " << x;
        previous = y;
    }
    EXPECT_EQ(g::toneMapAces(vec3(0.0f), 1.0f), vec3(0.0f));
    EXPECT_EQ(g::toneMapAces(vec3(INFINITY, 1e30f, -5.0f), 1.0f), vec3(1.0f, 1.0f, 0.0f));
    EXPECT_GT(g::toneMapAces(vec3(1.0f), 2.0f).x, g::toneMapAces(vec3(1.0f), 1.0f).x);  // exposure brightens
}

}  // namespace
