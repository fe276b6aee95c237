// A clear sky as a function of direction (docs/design.md §5.9): Preetham, Shirley and Smits 1999 ("A practical
// analytic model for daylight"), the Perez et al. 1993 luminance and chromaticity distributions with their
// turbidity fits, scaled to the scene's sun light. No sun disc: the scene's directional light is the sun's
// direct light, so the sky map holds only the scattered light (the sun is never counted twice).
#pragma once

#include <glm/glm.hpp>

namespace vct {

struct SkyParameters {
    glm::vec3 sunDirection{0.0f, 1.0f, 0.0f};  // unit, towards the sun (may lie below the horizon)
    float turbidity = 3.0f;                    // T in [2, 10]: 2 a very clear sky, 3 clear, 6+ hazy
    // The sun light's irradiance on a surface facing it (the directional light's luminance, in the scene's
    // units): the sky is scaled by E_sun / E_dn, E_dn the model atmosphere's direct normal illuminance.
    float sunIrradiance = 1.0f;
    float groundAlbedo = 0.2f;  // below the horizon: a diffuse ground lit by the sun light and the sky
};

// Sky radiance (linear Rec.709 rgb, the scene's units) arriving from unit direction `dir` above the horizon
// (dir.y ≥ 0; below it, the ground is added by the map: skyEnvironment). Finite and ≥ 0 for every sun
// direction; the sun below the horizon dims the sky to 10⁻³ of its horizon level over 12° (twilight).
glm::vec3 skyRadiance(glm::vec3 dir, const SkyParameters& sky);

// Preetham's zenith luminance Y_z(T, θ_s) in kcd/m² and the direct normal illuminance of the sun through the
// same atmosphere, E_dn(T, θ_s) in klux (Kasten–Young air mass, Kasten's Rayleigh optical depth, Linke
// turbidity ≈ T; the ESRA clear-sky model, Rigollier et al. 2000). Their ratio scales the sky.
float skyZenithLuminance(float turbidity, float sunZenithAngle);
float sunDirectNormalIlluminance(float turbidity, float sunZenithAngle);

}  // namespace vct
