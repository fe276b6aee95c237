// vct compare: the error of an image against a reference (linear HDR EXRs), for benchmarks and scripts; or,
// with --reference-dir / --image-dir, a vct render's light buffers against a path-traced ground truth
// (`vct reference`): per-surface light ratios, tone-mapped PSNRs and relative MSE without the reference's
// noise (engine/report/truth_metrics.h, docs/truth_compare.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "report/image_metrics.h"
#include "report/truth_metrics.h"
#include "scene/input_limits.h"

namespace vct {

namespace {

namespace fs = std::filesystem;

// The flags of each mode; giving one of the other mode's is a usage error.
const char* const kFileFlags[] = {"reference", "image", "peak", "tonemap", "error-map", "error-scale"};
const char* const kDirFlags[] = {"reference-dir", "image-dir", "json", "maps", "second-reference-dir"};

// NaN or Inf in an input is a bad input: one line naming the file (it used to end in exit 1, silently).
void requireFinite(const ImageRgba32f& image, const std::string& path) {
    if (auto bad = nonFiniteProblem(image)) throw Error(path + ": " + *bad);
}

int compareFiles(const ParsedArgs& args) {
    const ImageRgba32f reference = readExr(args.get("reference"));
    requireFinite(reference, args.get("reference"));
    const ImageRgba32f image = readExr(args.get("image"));
    requireFinite(image, args.get("image"));
    const ImageError error =
        compareImages(reference, image, args.has("peak") ? args.getFloat("peak", 1e-30f, 1e30f) : 0.0);
    std::printf("%s\n", formatImageError(error).c_str());
    if (args.has("tonemap")) {
        const ImageError display =
            compareToneMapped(reference, image, args.getFloat("exposure", 1e-6f, 1e6f));
        std::printf("tone-mapped sRGB (peak 1): %s\n", formatImageError(display).c_str());
    }
    if (args.has("error-map")) {
        const ImageRgba8 map = errorHeatMap(reference, image, args.getFloat("error-scale", 1e-30f, 1e30f));
        writePng(args.get("error-map"), map.width, map.height, map.pixels);
    }
    return error.nonFinite ? 1 : 0;
}

// One EXR of a directory, checked: a regular file, the size of the reference's final (when one is given),
// and no value `problem` objects to. Every failure is one line naming the file.
using ImageProblem = std::function<std::optional<std::string>(const ImageRgba32f&)>;

ImageRgba32f loadChecked(const fs::path& path, const ImageProblem& problem, const ImageRgba32f* sizeOf,
                         const fs::path& sizePath) {
    if (auto notFile = regularFileProblem(path)) throw Error(path.string() + ": " + *notFile);
    ImageRgba32f image = readExr(path);  // its errors name the file
    if (sizeOf && (image.width != sizeOf->width || image.height != sizeOf->height))
        throw Error(path.string() + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    ", but " + sizePath.string() + " is " + std::to_string(sizeOf->width) + "x" +
                    std::to_string(sizeOf->height));
    if (auto bad = problem(image)) throw Error(path.string() + ": " + *bad);
    return image;
}

// reference.json: the surfaces' names, an exposure when it has one, and the settings worth recording.
struct ReferenceInfo {
    std::map<int, std::string> names;
    std::optional<float> exposure;
    nlohmann::json settings = nlohmann::json::object();
};

ReferenceInfo readReferenceJson(const fs::path& path) {
    const std::string name = path.string() + ": ";
    const FileRead read = readRegularFile(path, uint64_t(1) << 26);
    if (!read.error.empty()) throw Error(name + read.error);
    const std::string_view text(reinterpret_cast<const char*>(read.bytes.data()), read.bytes.size());
    if (jsonNestingDepth(text, kMaxJsonDepth) > kMaxJsonDepth)
        throw Error(name + "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(name + "not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!root.is_object()) throw Error(name + "not a JSON object");
    ReferenceInfo info;
    if (root.contains("surfaces")) {
        const nlohmann::json& surfaces = root["surfaces"];
        if (!surfaces.is_array()) throw Error(name + "\"surfaces\" is not an array");
        for (size_t i = 0; i < surfaces.size(); ++i) {
            const nlohmann::json& s = surfaces[i];
            const std::string where = name + "surfaces[" + std::to_string(i) + "] ";
            if (!s.is_object() || !s.contains("id") || !s["id"].is_number_integer())
                throw Error(where + "has no integer \"id\"");
            const int64_t id = s["id"].get<int64_t>();
            if (id < 0 || id > kMaxSurfaceId)
                throw Error(where + "id " + std::to_string(id) + " is not from 0 to " +
                            std::to_string(kMaxSurfaceId));
            if (s.contains("name") && !s["name"].is_string()) throw Error(where + "\"name\" is not a string");
            info.names[int(id)] =
                s.contains("name") ? s["name"].get<std::string>() : "surface " + std::to_string(id);
        }
    }
    if (root.contains("exposure") && !root["exposure"].is_null()) {
        const nlohmann::json& e = root["exposure"];
        if (!e.is_number() || !std::isfinite(e.get<double>()) || !(e.get<double>() > 0.0) ||
            e.get<double>() > 1e6)
            throw Error(name + "\"exposure\" is not a number in (0, 1e6]");
        info.exposure = e.get<float>();
    }
    for (const char* key : {"scene", "size", "spp", "seed", "bounces", "secondary", "frame", "camera_path"})
        if (root.contains(key)) info.settings[key] = root[key];
    return info;
}

// Checks that a second reference (compareWithTruth's `second`) estimates the same image as the first with independent
// samples: the same scene, size, frame, bounces, secondary transport and camera path, and another seed (the same
// seed repeats the same samples). Throws naming the second reference.json.
void requireIndependentEstimate(const ReferenceInfo& first, const fs::path& firstDir,
                                const ReferenceInfo& second, const fs::path& secondDir) {
    const std::string where = (secondDir / "reference.json").string() + ": ";
    for (const char* key : {"scene", "size", "frame", "bounces", "secondary", "camera_path"}) {
        const bool inFirst = first.settings.contains(key), inSecond = second.settings.contains(key);
        if (inFirst != inSecond || (inFirst && first.settings[key] != second.settings[key]))
            throw Error(where + "\"" + key + "\" is " + (inSecond ? second.settings[key].dump() : "missing") +
                        ", but " + (firstDir / "reference.json").string() + " has " +
                        (inFirst ? first.settings[key].dump() : "none") + ": not the same image");
    }
    if (!first.settings.contains("seed") || !second.settings.contains("seed") ||
        first.settings["seed"] == second.settings["seed"])
        throw Error(where + "the same \"seed\" as " + (firstDir / "reference.json").string() +
                    " (or none): the same samples, not an independent estimate of the noise");
}

LightBuffers loadLight(const fs::path& dir, const std::string& suffix, const ImageProblem& problem,
                       const ImageRgba32f* sizeOf, const fs::path& sizePath) {
    LightBuffers light;
    const std::pair<ImageRgba32f*, const char*> files[] = {{&light.finalImage, "final"},
                                                           {&light.direct, "direct"},
                                                           {&light.diffuse, "diffuse_indirect"},
                                                           {&light.specular, "specular_indirect"}};
    for (const auto& [image, base] : files) {
        const fs::path path = dir / (std::string(base) + suffix + ".exr");
        *image = loadChecked(path, problem,
                             sizeOf ? sizeOf : (image == &light.finalImage ? nullptr : &light.finalImage),
                             sizeOf ? sizePath : dir / ("final" + suffix + ".exr"));
    }
    return light;
}

int compareDirectories(const ParsedArgs& args) {
    const fs::path referenceDir = args.get("reference-dir"), imageDir = args.get("image-dir");
    const std::optional<fs::path> secondDir = args.has("second-reference-dir")
                                                  ? std::optional<fs::path>(args.get("second-reference-dir"))
                                                  : std::nullopt;
    const fs::path jsonPath = args.has("json") ? fs::path(args.get("json")) : imageDir / "truth.json";
    std::optional<float> exposure;
    if (args.has("exposure")) exposure = args.getFloat("exposure", 1e-6f, 1e6f);
    if (args.has("maps")) prepareOutputDirectory(args.get("maps"), "--maps");
    for (const fs::path& dir : {referenceDir, imageDir, secondDir.value_or(referenceDir)}) {
        std::error_code error;
        if (!fs::is_directory(dir, error))
            throw Error(dir.string() + ": " +
                        (fs::exists(dir, error) ? "not a directory" : "no such directory"));
    }

    TruthReference reference;
    const ReferenceInfo info = readReferenceJson(referenceDir / "reference.json");
    reference.names = info.names;
    reference.mean = loadLight(referenceDir, "", nonFiniteProblem, nullptr, {});
    const fs::path referenceFinal = referenceDir / "final.exr";
    reference.variance =
        loadLight(referenceDir, "_variance", varianceProblem, &reference.mean.finalImage, referenceFinal);
    if (const fs::path indirect = referenceDir / "indirect_variance.exr"; fs::exists(indirect))
        reference.variance.indirect =
            loadChecked(indirect, varianceProblem, &reference.mean.finalImage, referenceFinal);
    reference.surfaceId = loadChecked(referenceDir / "surface_id.exr", surfaceIdProblem,
                                      &reference.mean.finalImage, referenceFinal);
    const LightBuffers vct =
        loadLight(imageDir, "", nonFiniteProblem, &reference.mean.finalImage, referenceFinal);

    const float usedExposure = exposure.value_or(info.exposure.value_or(1.0f));
    std::optional<LightBuffers> second;
    if (secondDir) {
        requireIndependentEstimate(info, referenceDir, readReferenceJson(*secondDir / "reference.json"),
                                   *secondDir);
        second = loadLight(*secondDir, "", nonFiniteProblem, &reference.mean.finalImage, referenceFinal);
    }
    const TruthComparison comparison =
        compareWithTruth(reference, vct, usedExposure, second ? &*second : nullptr);
    std::printf("%s against the reference %s\n%s", imageDir.c_str(), referenceDir.c_str(),
                formatTruthTable(comparison).c_str());

    nlohmann::json json = truthJson(comparison);
    json["reference_dir"] = referenceDir.string();
    json["image_dir"] = imageDir.string();
    json["reference"] = info.settings;
    if (secondDir) json["second_reference_dir"] = secondDir->string();
    if (args.has("maps")) {
        const fs::path mapsDir = args.get("maps");
        const std::vector<int> ids = surfaceIds(reference.surfaceId);
        nlohmann::json maps = nlohmann::json::array();
        for (Light light : {Light::Indirect, Light::Diffuse, Light::Specular}) {
            const std::string base = std::string("log2_") + lightName(light);
            const std::vector<float> values = log2RatioMap(reference, vct, light);
            const ImageRgba8 png = log2RatioPng(values, ids, comparison.width, comparison.height);
            writePng(mapsDir / (base + ".png"), png.width, png.height, png.pixels);
            writeExr(mapsDir / (base + ".exr"), comparison.width, comparison.height, log2RatioRgba(values));
            maps.push_back((mapsDir / (base + ".png")).string());
            maps.push_back((mapsDir / (base + ".exr")).string());
        }
        json["maps"] = std::move(maps);
        std::printf("log2 ratio maps (blue -2, white 0, red +2) in %s\n", mapsDir.c_str());
    }
    writeTextReplacing(jsonPath, json.dump(2) + "\n");
    std::printf("wrote %s\n", jsonPath.c_str());
    return 0;
}

}  // namespace

int runCompareCommand(int argc, char** argv, int first) {
    static const CommandSpec spec(
        "compare",
        "Prints MSE, relative MSE, PSNR and max error of --image against --reference (EXR files); or, with\n"
        "--reference-dir and --image-dir, a vct render (render --aux --out DIR) against a path-traced "
        "reference\n"
        "(vct reference --out REF): per-surface light ratios, tone-mapped PSNRs, relative MSE without the\n"
        "reference's noise, written as JSON (default DIR/truth.json).",
        {{"reference", "FILE", "reference image (.exr)", ""},
         {"image", "FILE", "image to measure (.exr)", ""},
         {"peak", "X", "PSNR peak (default: the reference's largest value)", ""},
         {"tonemap", "", "also compare as displayed: exposure, ACES, sRGB, PSNR with peak 1 (for final.exr)",
          ""},
         {"exposure", "X",
          "tone map exposure, as vct render's (--tonemap; --reference-dir: if not given, reference.json's "
          "when "
          "it has one)",
          "1"},
         {"error-map", "FILE.png", "write |image - reference| as a heat map (white at --error-scale)", ""},
         {"error-scale", "X", "error shown as white in --error-map", "0.05"},
         {"reference-dir", "DIR", "ground-truth directory written by vct reference --out", ""},
         {"image-dir", "DIR", "vct render --aux --out directory to measure against --reference-dir", ""},
         {"second-reference-dir", "DIR",
          "a second vct reference of the frame (another --seed): prints the PSNRs without the reference's "
          "noise",
          ""},
         {"json", "FILE", "where --reference-dir writes its metrics (default IMAGE-DIR/truth.json)", ""},
         {"maps", "DIR",
          "with --reference-dir: write log2 ratio maps (log2_{indirect,diffuse,specular}.png/.exr)", ""}});
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    auto anyOf = [&](const auto& flags) -> const char* {
        for (const char* flag : flags)
            if (args.has(flag)) return flag;
        return nullptr;
    };
    const char* fileFlag = anyOf(kFileFlags);
    const char* dirFlag = anyOf(kDirFlags);
    if (fileFlag && dirFlag)
        throw UsageError(std::string("compare: --") + fileFlag + " and --" + dirFlag +
                         " belong to different modes (--reference/--image or --reference-dir/--image-dir)");
    if (dirFlag) {
        if (!args.has("reference-dir") || !args.has("image-dir"))
            throw UsageError("compare needs both --reference-dir DIR and --image-dir DIR");
        return compareDirectories(args);
    }
    if (!args.has("reference") || !args.has("image"))
        throw UsageError(
            "compare needs --reference FILE and --image FILE (or --reference-dir DIR and --image-dir DIR)");
    return compareFiles(args);
}

}  // namespace vct
