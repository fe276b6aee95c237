#include "render/environment.h"

#include <stb/stb_image.h>  // Radiance .hdr; implementation in Debian's libstb

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/error.h"
#include "io/image_io.h"
#include "render/scene_lights.h"
#include "render/shader_math.h"
#include "render/sky_model.h"
#include "scene/input_limits.h"

namespace vct {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The procedural sky's map: smooth (no sun disc), so 256 × 128 texels (1.4° each) hold it; its mips reach the
// 1×1 mean in 9 levels.
constexpr uint32_t kSkyWidth = 256, kSkyHeight = 128;
// Largest map accepted from a file (texels of level 0): 2^26, the cap on any decoded texture.
constexpr uint64_t kMaxEnvironmentTexels = kMaxTexturePixels;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
    throw Error("environment " + path.string() + ": " + problem);
}

}  // namespace

double equirectTexelSolidAngle(uint32_t y, uint32_t width, uint32_t height) {
    const double theta0 = kPi * double(y) / double(height), theta1 = kPi * double(y + 1) / double(height);
    return 2.0 * kPi / double(width) * (std::cos(theta0) - std::cos(theta1));
}

glm::vec3 EnvironmentMap::radiance(glm::vec3 dir) const {
    const glm::vec2 uv = glsl::equirectUv(dir, rotation);
    const uint32_t x = std::min(uint32_t(std::max(uv.x, 0.0f) * float(width())), width() - 1);
    const uint32_t y = std::min(uint32_t(std::max(uv.y, 0.0f) * float(height())), height() - 1);
    return texel(0, x, y);
}

void buildEnvironmentMips(EnvironmentMap& map) {
    map.widths.resize(1);
    map.heights.resize(1);
    map.levels.resize(1);
    while (map.widths.back() > 1 || map.heights.back() > 1) {
        const size_t l = map.levels.size() - 1;
        const uint32_t w = map.widths[l], h = map.heights[l];
        const uint32_t pw = std::max(1u, w / 2), ph = std::max(1u, h / 2);
        std::vector<glm::dvec3> sum(size_t(pw) * ph, glm::dvec3(0.0));
        std::vector<double> weight(size_t(pw) * ph, 0.0);
        // Each child texel into the parent that covers it (an odd last row or column into the last parent),
        // weighted by its solid angle: the parent is the child's mean radiance over the parent's solid angle.
        for (uint32_t y = 0; y < h; ++y) {
            const double omega = equirectTexelSolidAngle(y, w, h);
            const uint32_t py = std::min(y * ph / h, ph - 1);
            for (uint32_t x = 0; x < w; ++x) {
                const size_t p = size_t(py) * pw + std::min(x * pw / w, pw - 1);
                sum[p] += omega * glm::dvec3(map.levels[l][size_t(y) * w + x]);
                weight[p] += omega;
            }
        }
        std::vector<glm::vec3> level(sum.size());
        for (size_t i = 0; i < level.size(); ++i)
            level[i] = weight[i] > 0.0 ? glm::vec3(sum[i] / weight[i]) : glm::vec3(0.0f);
        map.widths.push_back(pw);
        map.heights.push_back(ph);
        map.levels.push_back(std::move(level));
    }
}

EnvironmentMap constantEnvironment(glm::vec3 radiance) {
    EnvironmentMap map;
    map.description = "constant";
    map.widths = {1};
    map.heights = {1};
    map.levels = {{radiance}};
    return map;
}

EnvironmentMap loadEnvironmentMap(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    EnvironmentMap map;
    map.description = "file " + path.filename().string();
    std::vector<glm::vec3> texels;
    uint32_t width = 0, height = 0;
    if (extension == ".exr") {
        ImageRgba32f image;
        try {
            image = readExr(path);
        } catch (const Error& e) {
            fail(path, e.what());
        }
        width = image.width;
        height = image.height;
        texels.resize(size_t(width) * height);
        for (size_t i = 0; i < texels.size(); ++i)
            texels[i] = glm::vec3(image.pixels[i * 4], image.pixels[i * 4 + 1], image.pixels[i * 4 + 2]);
    } else if (extension == ".hdr") {
        FileRead file = readRegularFile(path);
        if (!file.error.empty()) fail(path, file.error);
        if (file.bytes.size() > size_t(INT32_MAX)) fail(path, "too large");
        int w = 0, h = 0, channels = 0;
        if (!stbi_info_from_memory(file.bytes.data(), int(file.bytes.size()), &w, &h, &channels))
            fail(path, std::string("not a Radiance HDR image (") +
                           (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
        if (w <= 0 || h <= 0 || uint64_t(w) * uint64_t(h) > kMaxEnvironmentTexels)
            fail(path, "it declares " + std::to_string(w) + "x" + std::to_string(h) + " texels (at most " +
                           std::to_string(kMaxEnvironmentTexels) + ")");
        std::unique_ptr<float, void (*)(void*)> data(
            stbi_loadf_from_memory(file.bytes.data(), int(file.bytes.size()), &w, &h, &channels, 3),
            stbi_image_free);
        if (!data)
            fail(path, std::string("cannot decode (") +
                           (stbi_failure_reason() ? stbi_failure_reason() : "unknown") + ")");
        width = uint32_t(w);
        height = uint32_t(h);
        texels.resize(size_t(width) * height);
        for (size_t i = 0; i < texels.size(); ++i)
            texels[i] = glm::vec3(data.get()[i * 3], data.get()[i * 3 + 1], data.get()[i * 3 + 2]);
    } else {
        fail(path, "unsupported format '" + extension + "' (expected an equirectangular .exr or .hdr)");
    }
    if (uint64_t(width) * height > kMaxEnvironmentTexels)
        fail(path, std::to_string(width) + "x" + std::to_string(height) + " texels, more than the " +
                       std::to_string(kMaxEnvironmentTexels) + " allowed");
    if (width != 2 * height)
        fail(path, std::to_string(width) + "x" + std::to_string(height) +
                       " is not an equirectangular map (width must be twice the height)");
    for (size_t i = 0; i < texels.size(); ++i) {
        const glm::vec3& t = texels[i];
        if (!(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) ||
            glm::any(glm::lessThan(t, glm::vec3(0.0f))))
            fail(path, "texel (" + std::to_string(i % width) + ", " + std::to_string(i / width) +
                           ") is negative or not finite");
    }
    map.widths = {width};
    map.heights = {height};
    map.levels = {std::move(texels)};
    buildEnvironmentMips(map);
    return map;
}

namespace {

// The procedural sky for a sun light (render/sky_model.h), with a diffuse ground below the horizon lit by the
// sun light and the sky (ρ/π · E_horizontal): light the sun reflects off a ground that the scene does not
// model, not the sun's own light.
EnvironmentMap skyEnvironment(const SkyParameters& sky) {
    EnvironmentMap map;
    map.widths = {kSkyWidth};
    map.heights = {kSkyHeight};
    std::vector<glm::vec3> texels(size_t(kSkyWidth) * kSkyHeight, glm::vec3(0.0f));
    glm::dvec3 skyIrradiance(0.0);  // on a horizontal surface facing up
    for (uint32_t y = 0; y < kSkyHeight / 2; ++y) {
        const double omega = equirectTexelSolidAngle(y, kSkyWidth, kSkyHeight);
        for (uint32_t x = 0; x < kSkyWidth; ++x) {
            const glm::vec3 d = glsl::equirectDirection(
                glm::vec2((float(x) + 0.5f) / float(kSkyWidth), (float(y) + 0.5f) / float(kSkyHeight)), 0.0f);
            const glm::vec3 l = skyRadiance(d, sky);
            texels[size_t(y) * kSkyWidth + x] = l;
            skyIrradiance += glm::dvec3(l) * omega * double(std::max(d.y, 0.0f));
        }
    }
    const float sunCos = std::max(glm::normalize(sky.sunDirection).y, 0.0f);
    const glm::vec3 ground = sky.groundAlbedo * float(1.0 / kPi) *
                             (glm::vec3(skyIrradiance) + glm::vec3(sky.sunIrradiance * sunCos));
    for (uint32_t y = kSkyHeight / 2; y < kSkyHeight; ++y)
        for (uint32_t x = 0; x < kSkyWidth; ++x) texels[size_t(y) * kSkyWidth + x] = ground;
    map.levels = {std::move(texels)};
    buildEnvironmentMips(map);
    return map;
}

void scaleEnvironment(EnvironmentMap& map, float factor) {
    if (factor == 1.0f) return;
    for (auto& level : map.levels)
        for (glm::vec3& t : level) t *= factor;
}

}  // namespace

EnvironmentMap sceneEnvironment(const Scene& scene, const RenderSettings& settings) {
    EnvironmentMap map;
    if (!settings.environment.empty()) {
        map = loadEnvironmentMap(settings.environment);
        map.rotation = glm::radians(settings.environmentRotation);
    } else {
        std::vector<glm::quat> rotations;
        const std::vector<glm::mat4> world = scene.evaluate(0.0f, &rotations);
        const std::vector<gpu::GpuLight> lights = sceneLights(scene, world, rotations);
        const auto sun = std::find_if(lights.begin(), lights.end(), [](const gpu::GpuLight& l) {
            return int(l.directionType.w) == VCT_LIGHT_DIRECTIONAL;
        });
        if (sun != lights.end()) {
            SkyParameters sky;
            sky.sunDirection = -glm::vec3(sun->directionType);
            sky.turbidity = settings.skyTurbidity;
            sky.sunIrradiance = glsl::luminance(glm::vec3(sun->colorIntensity));
            map = skyEnvironment(sky);
            char text[160];
            std::snprintf(text, sizeof text, "sky, turbidity %.3g, sun elevation %.1f deg",
                          double(sky.turbidity),
                          double(glm::degrees(std::asin(std::clamp(sky.sunDirection.y, -1.0f, 1.0f)))));
            map.description = text;
        } else {
            map = constantEnvironment(settings.ambient);
        }
    }
    scaleEnvironment(map, settings.environmentIntensity);
    return map;
}

}  // namespace vct
