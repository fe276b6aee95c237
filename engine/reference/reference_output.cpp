#include "reference/reference_output.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "io/image_io.h"
#include "io/safe_write.h"
#include "render/shader_math.h"

namespace vct::reference {

namespace {

std::vector<float> rgba(const std::vector<glm::vec3>& rgb) {
    std::vector<float> out(rgb.size() * 4);
    for (size_t i = 0; i < rgb.size(); ++i) {
        out[4 * i + 0] = rgb[i].r;
        out[4 * i + 1] = rgb[i].g;
        out[4 * i + 2] = rgb[i].b;
        out[4 * i + 3] = 1.0f;
    }
    return out;
}

nlohmann::json rgbJson(glm::dvec3 c) {
    return nlohmann::json::array({c.r, c.g, c.b});
}

// Luminance weights (Rec. 709) in double.
double luminance(glm::dvec3 c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}
double luminanceVariance(glm::dvec3 variance) {
    return 0.2126 * 0.2126 * variance.r + 0.7152 * 0.7152 * variance.g + 0.0722 * 0.0722 * variance.b;
}

// Per-surface sum of one buffer (RGB and luminance) and the standard deviation of the luminance sum.
struct SurfaceSum {
    glm::dvec3 rgb{0.0};
    double varianceLuminance = 0.0;
};

nlohmann::json sumJson(const SurfaceSum& sum) {
    const double lum = luminance(sum.rgb);
    return {{"rgb", rgbJson(sum.rgb)},
            {"luminance", lum},
            {"std_luminance", std::sqrt(sum.varianceLuminance)},
            {"relative_std", lum > 0.0 ? std::sqrt(sum.varianceLuminance) / lum : 0.0}};
}

// Mean over the pixels and channels of var / (mean² + 1e-3): the relative MSE this reference's own noise adds
// to any comparison with it.
double relativeNoise(const EstimateImage& image, const std::vector<int32_t>& ids) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t p = 0; p < image.mean.size(); ++p) {
        if (ids[p] < 0) continue;
        for (int c = 0; c < 3; ++c)
            sum += image.variance[p][c] / (double(image.mean[p][c]) * image.mean[p][c] + 1e-3);
        count += 3;
    }
    return count ? sum / double(count) : 0.0;
}

}  // namespace

std::vector<std::string> writeReferenceDirectory(const std::filesystem::path& dir, const PathTracer& tracer,
                                                 const ReferenceImages& images,
                                                 const ReferenceRunInfo& info) {
    const uint32_t w = images.width, h = images.height;
    std::vector<std::string> written;
    const std::pair<const char*, const EstimateImage*> buffers[] = {
        {"final", &images.final},
        {"direct", &images.direct},
        {"diffuse_indirect", &images.diffuseIndirect},
        {"specular_indirect", &images.specularIndirect},
        {"indirect", &images.indirect}};
    for (const auto& [name, image] : buffers) {
        writeExr(dir / (std::string(name) + ".exr"), w, h, rgba(image->mean));
        writeExr(dir / (std::string(name) + "_variance.exr"), w, h, rgba(image->variance));
        written.push_back(std::string(name) + ".exr");
        written.push_back(std::string(name) + "_variance.exr");
    }
    std::vector<float> ids(size_t(w) * h * 4, 0.0f);
    for (size_t p = 0; p < images.surfaceId.size(); ++p) {
        ids[4 * p] = float(images.surfaceId[p]);
        ids[4 * p + 3] = 1.0f;
    }
    writeExr(dir / "surface_id.exr", w, h, ids);
    written.push_back("surface_id.exr");
    std::vector<uint8_t> ldr(size_t(w) * h * 4);
    for (size_t p = 0; p < images.final.mean.size(); ++p) {
        const glm::vec3 c = glsl::linearToSrgb(glsl::toneMapAces(images.final.mean[p], info.exposure));
        for (int k = 0; k < 3; ++k)
            ldr[4 * p + k] = uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
        ldr[4 * p + 3] = 255;
    }
    writePng(dir / "final.png", w, h, ldr);
    written.push_back("final.png");

    // Per-surface sums over the pixels whose centre sees the surface.
    const std::vector<Surface>& surfaces = tracer.surfaces();
    std::vector<size_t> pixels(surfaces.size(), 0);
    std::vector<SurfaceSum> direct(surfaces.size()), diffuse(surfaces.size()), specular(surfaces.size()),
        indirect(surfaces.size());
    for (size_t p = 0; p < images.surfaceId.size(); ++p) {
        const int32_t id = images.surfaceId[p];
        if (id < 0) continue;
        const size_t s = size_t(id);
        ++pixels[s];
        direct[s].rgb += glm::dvec3(images.direct.mean[p]);
        direct[s].varianceLuminance += luminanceVariance(glm::dvec3(images.direct.variance[p]));
        diffuse[s].rgb += glm::dvec3(images.diffuseIndirect.mean[p]);
        diffuse[s].varianceLuminance += luminanceVariance(glm::dvec3(images.diffuseIndirect.variance[p]));
        specular[s].rgb += glm::dvec3(images.specularIndirect.mean[p]);
        specular[s].varianceLuminance += luminanceVariance(glm::dvec3(images.specularIndirect.variance[p]));
        indirect[s].rgb += glm::dvec3(images.indirect.mean[p]);
        indirect[s].varianceLuminance += luminanceVariance(glm::dvec3(images.indirect.variance[p]));
    }
    nlohmann::json surfaceList = nlohmann::json::array();
    for (size_t s = 0; s < surfaces.size(); ++s)
        surfaceList.push_back({{"id", s},
                               {"name", surfaces[s].name},
                               {"node", surfaces[s].node},
                               {"primitive", surfaces[s].primitive},
                               {"material", surfaces[s].material},
                               {"pixels", pixels[s]},
                               {"direct", sumJson(direct[s])},
                               {"diffuse_indirect", sumJson(diffuse[s])},
                               {"specular_indirect", sumJson(specular[s])},
                               {"indirect", sumJson(indirect[s])}});

    const ReferenceSettings& settings = tracer.settings();
    const ReferenceStats& stats = tracer.stats();
    nlohmann::json doc = {
        {"scene", info.scene},
        {"size", {w, h}},
        {"frame", info.frame},
        {"time_seconds", info.timeSeconds},
        {"camera_path", info.cameraPath},
        {"spp", images.samplesPerPixel},
        {"seed", settings.seed},
        {"bounces",
         settings.bounces == kUnlimitedBounces ? nlohmann::json("all") : nlohmann::json(settings.bounces)},
        {"secondary", settings.secondary == SecondaryBrdf::Full ? "full" : "diffuse"},
        {"environment", rgbJson(glm::dvec3(settings.environment))},
        {"exposure", info.exposure},
        {"threads", settings.threads == 0 ? std::thread::hardware_concurrency() : settings.threads},
        {"rays", stats.rays},
        {"seconds", stats.seconds},
        {"rays_per_second", stats.raysPerSecond()},
        {"noise",
         {{"final_relative_mse", relativeNoise(images.final, images.surfaceId)},
          {"direct_relative_mse", relativeNoise(images.direct, images.surfaceId)},
          {"diffuse_indirect_relative_mse", relativeNoise(images.diffuseIndirect, images.surfaceId)},
          {"specular_indirect_relative_mse", relativeNoise(images.specularIndirect, images.surfaceId)},
          {"indirect_relative_mse", relativeNoise(images.indirect, images.surfaceId)}}},
        {"units",
         "direct: emission + punctual lights (every light shadowed by a ray); diffuse_indirect: (1/pi) * "
         "integral of "
         "incoming indirect radiance * cos; specular_indirect: integral of f_s * incoming indirect radiance "
         "* cos / "
         "(F0*scale + bias); final: direct + occlusion*albedo*diffuse + specularDfg(F0, DFG)*specular; "
         "*_variance: "
         "variance of each pixel's mean from two independent halves of the samples"},
        {"surfaces", surfaceList}};
    writeTextReplacing(dir / "reference.json", doc.dump(2) + "\n");
    written.push_back("reference.json");
    return written;
}

}  // namespace vct::reference
