// vct benchmark --mode study: Tokuyoshi 2015's parameter study (Fig. 6; docs/design.md §8.4). The paper
// measures, for materials of different specular sharpness, the error of lobe-aware and normal-aware filtering
// against their parameter, and finds the lobe-aware optima clustered (one β serves every material) where the
// normal-aware ones spread. Here: the upsampling alone (trace scale 4, no history, no re-tracing, so that only
// the weights decide), static camera, errors averaged over s² = 16 frames (every jitter offset once) against the
// reference of the same frame, per material class of the reference's G-buffer:
//   metal (metallic ≥ 0.5), glossy dielectric (perceptual roughness < 0.35), rough dielectric (the rest).
// Sweeps: sg β × κ (log grid) on the specular light; normal σ_n on specular and diffuse; the sg diffuse lobe
// sharpness λ_d on the diffuse light. Writes DIR/study.json (heat maps: benchmarks/plot_report.py) and
// study.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "app/bench/benchmark_modes.h"
#include "app/bench/benchmark_run.h"
#include "core/error.h"
#include "scene/builtin_scenes.h"

namespace vct {

namespace {

using nlohmann::json;

const std::array<float, 7> kBetas = {2.5f, 5.0f, 10.0f, 20.0f, 40.0f, 80.0f, 160.0f};
const std::array<float, 5> kKappas = {10.0f, 30.0f, 100.0f, 300.0f, 1000.0f};
const std::array<float, 7> kSigmas = {0.03f, 0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 1.0f};
const std::array<float, 6> kDiffuseSharpness = {0.5f, 1.0f, 2.0f, 5.0f, 11.0f, 30.0f};
constexpr int kClasses = 4;  // all, metal, glossy, rough
const char* const kClassNames[kClasses] = {"all", "metal", "glossy dielectric", "rough dielectric"};
constexpr float kGlossyRoughness = 0.35f;

// Per pixel, the classes it belongs to as a bit set (bit 0: all non-background pixels).
std::vector<uint8_t> materialClasses(Renderer& reference) {
    const std::vector<float> depth = reference.readFloatImage(reference.targets().depth);
    const std::vector<float> normalRoughness = reference.readFloatImage(reference.targets().normalRoughness);
    const std::vector<float> baseMetallic = reference.readFloatImage(reference.targets().baseColorMetallic);
    std::vector<uint8_t> classes(depth.size() / 4, 0);
    for (size_t i = 0; i < classes.size(); ++i) {
        if (!(depth[i * 4] < 1.0f)) continue;  // background
        const bool metal = baseMetallic[i * 4 + 3] >= 0.5f;
        const bool glossy = normalRoughness[i * 4 + 3] < kGlossyRoughness;
        classes[i] = uint8_t(1u | (metal ? 2u : glossy ? 4u : 8u));
    }
    return classes;
}

// Sum of squared errors (RGB mean) per class of two RGBA32F images.
std::array<double, kClasses> classSquaredErrors(const std::vector<float>& reference,
                                                const std::vector<float>& image,
                                                const std::vector<uint8_t>& classes) {
    std::array<double, kClasses> sums{};
    for (size_t i = 0; i < classes.size(); ++i) {
        if (!classes[i]) continue;
        double e = 0.0;
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(image[i * 4 + c]) - double(reference[i * 4 + c]);
            e += std::isfinite(d) ? d * d / 3.0 : 1e30;  // a non-finite value ruins the configuration's score
        }
        for (int k = 0; k < kClasses; ++k)
            if (classes[i] & (1u << k)) sums[size_t(k)] += e;
    }
    return sums;
}

struct StudyConfig {
    std::string kind;  // "sg", "normal", "sg-diffuse"
    float beta = 20.0f, kappa = 100.0f, sigma = 0.1f, diffuseSharpness = 2.0f;
};

// Build: run 0 is the reference (trace scale 1), then the sweeps in the order the report reads them: sg β × κ,
// normal σ_n, sg λ_d. The upsampling alone: no history, no re-tracing.
std::vector<BenchmarkRun> buildStudyRuns(vk::Context& context, const Scene& scene,
                                         const RenderSettings& settings) {
    std::vector<StudyConfig> studies;
    for (float beta : kBetas)
        for (float kappa : kKappas) studies.push_back({"sg", beta, kappa, 0.1f, 2.0f});
    for (float sigma : kSigmas) studies.push_back({"normal", 20.0f, 100.0f, sigma, 2.0f});
    for (float sharpness : kDiffuseSharpness)
        studies.push_back({"sg-diffuse", 20.0f, 100.0f, 0.1f, sharpness});
    std::vector<BenchmarkRun> runs;
    RenderSettings base = settings;
    base.temporal = false;
    base.adaptive = false;
    runs.push_back({"reference", &scene, base, nullptr, ""});
    runs.back().settings.traceScale = 1;
    for (const StudyConfig& study : studies) {
        RenderSettings s = base;
        s.traceScale = 4;
        s.weights = study.kind == "normal" ? RenderSettings::Weights::Normal : RenderSettings::Weights::Sg;
        s.beta = study.beta;
        s.kappa = study.kappa;
        s.sigmaN = study.sigma;
        s.diffuseSharpness = study.diffuseSharpness;
        runs.push_back({study.kind, &scene, s, nullptr, ""});
    }
    for (BenchmarkRun& run : runs) run.renderer = std::make_unique<Renderer>(context, scene, run.settings);
    return runs;
}

// Errors per configuration and class (diffuse, specular), summed over frames; pixel counts per class.
struct StudyErrors {
    std::vector<std::array<double, kClasses>> diffuse, specular;
    std::array<double, kClasses> pixels{};
};

// Run: every configuration renders the same frames as the reference, whose frame is read just before.
StudyErrors runStudy(std::vector<BenchmarkRun>& runs, uint32_t frames) {
    StudyErrors errors;
    errors.diffuse.resize(runs.size());
    errors.specular.resize(runs.size());
    std::vector<uint8_t> classes;
    Renderer::IndirectLight referenceLight;
    FrameHooks hooks;
    hooks.afterFrame = [&](size_t index, uint32_t) {
        Renderer& renderer = *runs[index].renderer;
        if (index == 0) {
            classes = materialClasses(renderer);
            referenceLight = renderer.readIndirect();
            for (uint8_t c : classes)
                for (int k = 0; k < kClasses; ++k) errors.pixels[size_t(k)] += (c >> k) & 1u;
            return;
        }
        const Renderer::IndirectLight light = renderer.readIndirect();
        const auto d = classSquaredErrors(referenceLight.diffuse, light.diffuse, classes);
        const auto s = classSquaredErrors(referenceLight.specular, light.specular, classes);
        for (int k = 0; k < kClasses; ++k) {
            errors.diffuse[index][size_t(k)] += d[size_t(k)];
            errors.specular[index][size_t(k)] += s[size_t(k)];
        }
    };
    // Block 1: the reference's frame is read just before every configuration renders the same frame.
    renderInterleaved(runs, frames, 0, 1, hooks);
    return errors;
}

// Report: for each class with pixels, the MSE heat maps and optima (JSON) and one row of the table.
void reportStudyScene(const std::string& sceneName, const std::vector<BenchmarkRun>& runs,
                      const StudyErrors& errors, uint32_t frames, json& sceneJson, std::string& table) {
    for (int k = 0; k < kClasses; ++k) {
        const double pixels = errors.pixels[size_t(k)];
        if (pixels < 1.0) continue;
        auto mse = [&](const std::vector<std::array<double, kClasses>>& sums, size_t run) {
            return sums[run][size_t(k)] / pixels;
        };
        const auto& specularSums = errors.specular;
        const auto& diffuseSums = errors.diffuse;
        json sg = json::array(), normalSpecular = json::array(), normalDiffuse = json::array(),
             sgDiffuse = json::array();
        size_t run = 1;
        size_t bestSg = 0, bestNormal = 0, bestNormalDiffuse = 0, bestSgDiffuse = 0, defaultSg = 0,
               defaultNormal = 0, defaultSgDiffuse = 0;
        double bestSgMse = 1e300, bestNormalMse = 1e300, bestNormalDiffuseMse = 1e300,
               bestSgDiffuseMse = 1e300;
        for (size_t b = 0; b < kBetas.size(); ++b) {
            json row = json::array();
            for (size_t q = 0; q < kKappas.size(); ++q, ++run) {
                row.push_back(mse(specularSums, run));
                if (mse(specularSums, run) < bestSgMse) bestSgMse = mse(specularSums, run), bestSg = run;
                if (kBetas[b] == 20.0f && kKappas[q] == 100.0f) defaultSg = run;
            }
            sg.push_back(row);
        }
        for (size_t i = 0; i < kSigmas.size(); ++i, ++run) {
            normalSpecular.push_back(mse(specularSums, run));
            normalDiffuse.push_back(mse(diffuseSums, run));
            if (mse(specularSums, run) < bestNormalMse)
                bestNormalMse = mse(specularSums, run), bestNormal = run;
            if (mse(diffuseSums, run) < bestNormalDiffuseMse)
                bestNormalDiffuseMse = mse(diffuseSums, run), bestNormalDiffuse = run;
            if (kSigmas[i] == 0.1f) defaultNormal = run;
        }
        for (size_t i = 0; i < kDiffuseSharpness.size(); ++i, ++run) {
            sgDiffuse.push_back(mse(diffuseSums, run));
            if (mse(diffuseSums, run) < bestSgDiffuseMse)
                bestSgDiffuseMse = mse(diffuseSums, run), bestSgDiffuse = run;
            if (kDiffuseSharpness[i] == 2.0f) defaultSgDiffuse = run;
        }
        const RenderSettings& sgBest = runs[bestSg].settings;
        const RenderSettings& normalBest = runs[bestNormal].settings;
        sceneJson["classes"].push_back(
            {{"class", kClassNames[k]},
             {"pixels", pixels / frames},
             {"sg_specular_mse", sg},
             {"normal_specular_mse", normalSpecular},
             {"normal_diffuse_mse", normalDiffuse},
             {"sg_diffuse_mse", sgDiffuse},
             {"sg_optimum", {{"beta", sgBest.beta}, {"kappa", sgBest.kappa}, {"mse", bestSgMse}}},
             {"normal_optimum", {{"sigma_n", normalBest.sigmaN}, {"mse", bestNormalMse}}},
             {"sg_diffuse_optimum",
              {{"diffuse_sharpness", runs[bestSgDiffuse].settings.diffuseSharpness},
               {"mse", bestSgDiffuseMse}}},
             {"normal_diffuse_optimum",
              {{"sigma_n", runs[bestNormalDiffuse].settings.sigmaN}, {"mse", bestNormalDiffuseMse}}}});
        char line[600];
        std::snprintf(line, sizeof(line),
                      "| %s | %s | %.0f | %g, %g (%.3g) | %.3g | %g (%.3g) | %.3g | %g (%.3g) | %.3g "
                      "| %g (%.3g) | "
                      "%.3g |\n",
                      sceneName.c_str(), kClassNames[k], pixels / frames, sgBest.beta, sgBest.kappa,
                      bestSgMse, mse(specularSums, defaultSg), normalBest.sigmaN, bestNormalMse,
                      mse(specularSums, defaultNormal), runs[bestSgDiffuse].settings.diffuseSharpness,
                      bestSgDiffuseMse, mse(diffuseSums, defaultSgDiffuse),
                      runs[bestNormalDiffuse].settings.sigmaN, bestNormalDiffuseMse,
                      mse(diffuseSums, defaultNormal));
        table += line;
    }
}

}  // namespace

int runStudyBenchmark(const ParsedArgs& args, const SessionOptions& session, const BenchmarkFrames& timing,
                      const std::filesystem::path& outDir) {
    const std::vector<ReportScene> scenes = reportScenes(args);
    const uint32_t frames = 16;  // every jitter offset of trace scale 4 once
    json report = {{"width", session.settings.width},
                   {"height", session.settings.height},
                   {"frames", frames},
                   {"betas", kBetas},
                   {"kappas", kKappas},
                   {"sigmas", kSigmas},
                   {"diffuse_sharpness", kDiffuseSharpness},
                   {"classes", kClassNames},
                   {"scenes", json::array()}};
    (void)timing;
    std::string table =
        "| scene | class | pixels | sg optimum β, κ (specular MSE) | sg at 20, 100 | normal optimum σ_n "
        "(specular MSE) | normal at 0.1 | diffuse: sg optimum λ_d | sg at λ_d 2 | normal optimum σ_n | "
        "normal at 0.1 |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    {
        vk::Context context(session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        report["device"] = context.deviceName();
        for (const ReportScene& entry : scenes) {
            const Scene scene = loadScene(entry.scene);
            std::vector<BenchmarkRun> runs = buildStudyRuns(context, scene, session.settings);
            std::fprintf(stderr, "study: %s, %zu configurations\n", entry.name.c_str(), runs.size());
            const StudyErrors errors = runStudy(runs, frames);
            json sceneJson = {{"scene", entry.name}, {"classes", json::array()}};
            reportStudyScene(entry.name, runs, errors, frames, sceneJson, table);
            report["scenes"].push_back(sceneJson);
        }
    }
    checkValidation(session);
    char caption[800];
    std::snprintf(
        caption, sizeof(caption),
        "Device: %s, %ux%u. Tokuyoshi 2015 Fig. 6: upsampling alone (trace scale 4, no history, no "
        "re-tracing), "
        "MSE of the demodulated indirect light against trace scale 1, mean over %u frames (every jitter "
        "offset), per material class of the G-buffer (metal: metallic >= 0.5; glossy: roughness < %.2f).",
        report["device"].get<std::string>().c_str(), session.settings.width, session.settings.height, frames,
        kGlossyRoughness);
    writeBenchmarkReport(outDir, "study", report, caption, table);
    return 0;
}

}  // namespace vct
