#include "render/setting_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <tuple>

#include "core/error.h"

namespace vct {

namespace {

constexpr uint32_t kTraceScales[] = {1, 2, 4};
constexpr uint32_t kVoxelResolutions[] = {32, 64, 128, 256};
constexpr uint32_t kBounceCounts[] = {1, 2, 3, 4, 5, 6, 7, 8, kAllBounces};
constexpr uint32_t kAnisotropyLevels[] = {0, 2, 4, 8, 16};

using A = SettingApply;
using G = SettingGroup;
using W = SettingWidget;
using S = RenderSettings;

// clang-format off
const SettingSpec kTable[] = {
    // ---- global illumination (docs/design.md §5) ----
    {.name = "gi", .valueName = "on|off",
     .help = "cone-traced indirect light; off: the environment's light, unoccluded, instead",
     .value = OnOffValue{&S::gi}, .apply = A::Rebuild, .group = G::Gi, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "GI (cone tracing)", .sideB = true},
    {.name = "trace-scale", .valueName = "1|2|4",
     .help = "trace indirect light at 1/S of the resolution per axis (1: every pixel)",
     .value = ChoiceValue{&S::traceScale, kTraceScales}, .apply = A::Rebuild, .group = G::Gi, .demo = true,
     .json = true, .widget = W::Combo, .label = "trace scale", .sideB = true},
    {.name = "bounces", .valueName = "1..8|all",
     .help = "bounces of indirect light: 1 = light from directly lit surfaces; N: the voxels also pass on "
             "light that has already bounced (N - 1 gathers in the grid when it is rebuilt); all: the voxels "
             "gather again from the grid a slab at a time, one slab a frame, converging to every bounce over "
             "frames (docs/design.md sec. 5.7)",
     .value = ChoiceValue{&S::bounces, kBounceCounts, std::nullopt, std::pair{kAllBounces, "all"}},
     .apply = A::Rebuild, .group = G::Gi, .demo = true,
     .json = true, .widget = W::Combo, .label = "bounces"},
    {.name = "cone-rotation", .valueName = "on|off",
     .help = "turn each pixel's diffuse cones about its normal, differently every frame (docs/design.md sec. 5.5)",
     .value = OnOffValue{&S::coneRotation}, .apply = A::Live, .group = G::Gi, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "turn the diffuse cones"},
    {.name = "cone-jitter", .valueName = "on|off",
     .help = "jitter each pixel's cones within what they stand for, differently every frame (turn and elevation of "
             "the diffuse cones, the specular cone within its lobe), with narrow footprints that keep the surface's "
             "own voxels out; closest to the path-traced truth once the history has averaged it (trace scale 1), "
             "noisier than turned cones at trace scale 4 (docs/design.md sec. 5.5)",
     .value = OnOffValue{&S::coneJitter}, .apply = A::Live, .group = G::Gi, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "jitter the cones"},
    {.name = "voxel-glossy", .valueName = "on|off",
     .help = "voxels reflect the lights' specular lobes too (glossy-to-diffuse transport, docs/design.md sec. "
             "5.11); off: Lambertian voxels of the diffuse albedo, as vct reference --secondary diffuse",
     .value = OnOffValue{&S::voxelGlossy}, .apply = A::Rebuild, .group = G::Gi, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "glossy voxels"},
    {.name = "voxel-regions", .valueName = "on|off",
     .help = "end cones where they pass from one closed region of the static voxels into another (a room turned off "
             "the grid's axes, two rooms side by side: docs/design.md sec. 5.6), where the closure box does not "
             "close them; off: an opening narrower than a voxel, which the regions seal, passes light again",
     .value = OnOffValue{&S::voxelRegions}, .apply = A::Rebuild, .group = G::Gi, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "closed regions"},
    {.name = "voxels", .valueName = "N",
     .help = "voxel grid resolution N (N^3; 32, 64, 128 or 256); default 64 on a CPU device, 128 on a GPU",
     .value = ChoiceValue{&S::voxelResolution, kVoxelResolutions, 0u}, .apply = A::Rebuild, .group = G::Gi,
     .demo = true, .json = true, .widget = W::Combo, .label = "voxels"},
    {.name = "sparse-mip0-from", .valueName = "N",
     .help = "store the radiance's mip 0 sparse (a brick atlas) from voxel resolution N up; dense below "
             "(faster cone samples near surfaces, N^3 memory)",
     .value = ChoiceValue{&S::sparseMip0From, kVoxelResolutions}, .apply = A::Rebuild, .group = G::Gi,
     .json = true},
    {.name = "voxel-cache", .valueName = "FILE.vdb",
     .help = "load the static voxelization from FILE (written by vct voxelize) instead of computing it",
     .value = TextValue{&S::voxelCache, "a file name"}, .apply = A::Rebuild, .group = G::Gi},
    // ---- the environment (docs/design.md §5.9): with the GI flags, as render and demo take them ----
    {.name = "environment", .valueName = "FILE.exr|FILE.hdr",
     .help = "equirectangular HDR map of the light from afar (default: a clear sky lit by the scene's directional "
             "light; the constant ambient 0.03 in a scene with only point and spot lights)",
     .value = TextValue{&S::environment, "an .exr or .hdr file name"}, .apply = A::Rebuild, .group = G::Gi},
    {.name = "environment-intensity", .valueName = "X", .help = "scale of the environment's radiance (map or sky)",
     .value = FloatValue{&S::environmentIntensity, 1e-3f, 1e4f}, .apply = A::Rebuild, .group = G::Gi,
     .demo = true, .json = true, .widget = W::LogSlider, .label = "environment intensity"},
    {.name = "environment-rotation", .valueName = "DEG",
     .help = "turn the --environment map about +y by DEG degrees (the sky follows its light)",
     .value = FloatValue{&S::environmentRotation, -360.0f, 360.0f}, .apply = A::Rebuild, .group = G::Gi,
     .demo = true, .json = true, .widget = W::Slider, .label = "environment rotation"},
    {.name = "sky-turbidity", .valueName = "T",
     .help = "turbidity of the procedural sky (Preetham): 2 very clear, 3 clear, 6 and more hazy",
     .value = FloatValue{&S::skyTurbidity, 2.0f, 10.0f}, .apply = A::Rebuild, .group = G::Gi, .demo = true,
     .json = true, .widget = W::Slider, .label = "sky turbidity"},
    {.name = "recompute-every-frame", .valueName = "",
     .help = "diagnostic: run every pass every frame, also the shadow map, voxel grid, G-buffer and direct light "
             "when nothing moved, no light changed and the camera stood still",
     .value = SwitchValue{&S::recomputeEveryFrame}, .apply = A::Live, .group = G::Gi},

    // ---- spatio-temporal upsampling and adaptive re-tracing (docs/design.md §6) ----
    {.name = "weights", .valueName = "bilinear|normal|sg",
     .help = "upsampling guide: none, depth x normal, depth x SG lobe (docs/design.md sec. 6.3)",
     .value = NamedValue{&S::weights, kWeightsNames}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::Combo, .label = "weights", .sideB = true},
    {.name = "upsample-layout", .valueName = "auto|cell|pixel",
     .help = "upsample invocations: one per low-res cell (fast on a CPU device) or one per pixel with shared "
             "samples (fast on a GPU); auto: by device type; the same image (docs/design.md sec. 6.8)",
     .value = NamedValue{&S::upsampleLayout, kUpsampleLayoutNames}, .apply = A::Live, .group = G::Upsample,
     .demo = true, .json = true, .widget = W::Combo, .label = "upsample layout"},
    {.name = "trace-layout", .valueName = "auto|pixel|cone",
     .help = "trace, re-trace and voxel-gather invocations: one per pixel or voxel, its cones in turn (fast on a "
             "CPU device), or one per cone (fast on a GPU, where few pixels wait on one invocation's reads); auto: "
             "by device type; the same image (docs/design.md sec. 5.5)",
     .value = NamedValue{&S::traceLayout, kTraceLayoutNames}, .apply = A::Rebuild, .group = G::Upsample,
     .demo = true, .json = true, .widget = W::Combo, .label = "trace layout"},
    {.name = "beta", .valueName = "B", .help = "SG lobe weight exponent",
     .value = FloatValue{&S::beta, 0.01f, 1000.0f}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "beta"},
    {.name = "kappa", .valueName = "K", .help = "SG smoothing kernel sharpness (bounds every lobe's sharpness)",
     .value = FloatValue{&S::kappa, 0.01f, kMaxKappa}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "kappa"},
    {.name = "sigma-n", .valueName = "S", .help = "normal weight width sigma_n (--weights normal)",
     .value = FloatValue{&S::sigmaN, 1e-3f, 10.0f}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "sigma_n"},
    {.name = "diffuse-sharpness", .valueName = "L", .help = "sg diffuse lobe sharpness lambda_d (--weights sg)",
     .value = FloatValue{&S::diffuseSharpness, 1e-3f, 1e4f}, .apply = A::Live, .group = G::Upsample,
     .demo = true, .json = true, .widget = W::LogSlider, .label = "lambda_d"},
    {.name = "gamma", .valueName = "G", .help = "temporal history decay per frame (0..1)",
     .value = FloatValue{&S::gamma, 0.0f, 1.0f}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::Slider, .label = "gamma"},
    {.name = "tau", .valueName = "T", .help = "re-trace pixels whose sum of upsampling weights is below T",
     .value = FloatValue{&S::tau, 1e-6f, 1000.0f}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "tau"},
    {.name = "history-cap", .valueName = "A",
     .help = "cap on the accumulated history weight, in pixel-own samples (docs/design.md sec. 6.5)",
     .value = FloatValue{&S::historyCap, 1.0f, 1000.0f}, .apply = A::Live, .group = G::Upsample, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "A_max"},
    {.name = "temporal", .valueName = "on|off", .help = "reproject and accumulate last frame's indirect light",
     .value = OnOffValue{&S::temporal}, .apply = A::Live, .group = G::Upsample, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "temporal", .sideB = true},
    {.name = "adaptive", .valueName = "on|off", .help = "adaptive re-tracing of low-weight pixels at full resolution",
     .value = OnOffValue{&S::adaptive}, .apply = A::Rebuild, .group = G::Upsample, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "adaptive", .sideB = true},

    // ---- material filtering (docs/design.md §4) ----
    {.name = "toksvig", .valueName = "on|off", .help = "Toksvig roughness from normal-map mips (docs/design.md sec. 4.1)",
     .value = OnOffValue{&S::toksvig}, .apply = A::Live, .group = G::Material, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "Toksvig"},
    {.name = "specular-aa", .valueName = "on|off", .help = "geometric specular anti-aliasing from normal derivatives",
     .value = OnOffValue{&S::specularAA}, .apply = A::Live, .group = G::Material, .demo = true, .json = true,
     .widget = W::Checkbox, .label = "specular AA"},
    {.name = "texture-lod0", .valueName = "",
     .help = "diagnostic: sample material textures at level 0 only (supersampled references)",
     .value = SwitchValue{&S::textureLod0}, .apply = A::Rebuild, .group = G::Material},
    {.name = "anisotropy", .valueName = "0|2|4|8|16",
     .help = "anisotropic texture filtering (0: off); default 0 on a CPU device (very slow there), 8 on a GPU",
     .value = ChoiceValue{&S::anisotropy, kAnisotropyLevels, kAnisotropyFromDevice}, .apply = A::Rebuild,
     .group = G::Material, .demo = true, .json = true, .widget = W::Combo, .label = "anisotropy"},

    // ---- the image ----
    // 16384 is the largest 2D image any current device allows; the Renderer checks the device's own limit.
    {.name = "size", .valueName = "WxH", .help = "image size in pixels",
     .value = SizeValue{16384}, .apply = A::Resize, .group = G::Image},
    {.name = "exposure", .valueName = "X", .help = "linear exposure before tone mapping",
     .value = FloatValue{&S::exposure, 1e-4f, 1e4f}, .apply = A::Live, .group = G::Image, .demo = true,
     .json = true, .widget = W::LogSlider, .label = "exposure"},

    // ---- set by the program ----
    {.name = "ambient", .valueName = "",
     .help = "constant environment radiance of scenes with only point and spot lights (made into the map)",
     .value = ColorValue{&S::ambient}, .apply = A::Rebuild, .group = G::Internal},
    {.name = "shadow-depth-bias", .valueName = "", .help = "shadow map constant depth bias (dynamic state)",
     .value = FloatValue{&S::shadowDepthBias, 0.0f, 1e4f}, .apply = A::Live, .group = G::Internal},
    {.name = "shadow-slope-bias", .valueName = "", .help = "shadow map slope depth bias (dynamic state)",
     .value = FloatValue{&S::shadowSlopeBias, 0.0f, 1e4f}, .apply = A::Live, .group = G::Internal},
    {.name = "write-weight-sum", .valueName = "",
     .help = "write the sum-of-weights image (--aux, the weights and resample views; a specialization constant)",
     .value = OnOffValue{&S::writeWeightSum}, .apply = A::Live, .group = G::Internal},
};
// clang-format on

// "a, b or c"
template <typename T, typename Text>
std::string alternatives(std::span<const T> values, Text text) {
    std::string list;
    for (size_t i = 0; i < values.size(); ++i)
        list += (i == 0 ? "" : i + 1 == values.size() ? " or " : ", ") + std::string(text(values[i]));
    return list;
}

std::string numberText(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", double(value));
    return buffer;
}

}  // namespace

bool parseOnOff(const std::string& text, const std::string& spelling) {
    if (text == "on" || text == "true" || text == "1") return true;
    if (text == "off" || text == "false" || text == "0") return false;
    throw UsageError(spelling + " '" + text + "': expected on or off");
}

std::span<const SettingSpec> settingTable() {
    return kTable;
}

const SettingSpec* findSetting(std::string_view name) {
    for (const SettingSpec& spec : kTable)
        if (name == spec.name) return &spec;
    return nullptr;
}

float parseNumber(const std::string& text, const std::string& spelling, float min, float max) {
    float value = 0.0f;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
        value < min || value > max) {
        std::ostringstream message;
        message << spelling << " '" << text << "': expected a number from " << min << " to " << max;
        throw UsageError(message.str());
    }
    return value;
}

std::pair<uint32_t, uint32_t> parseSize(const std::string& text, const std::string& spelling,
                                        uint32_t maxDimension) {
    const size_t x = text.find('x');
    uint64_t w = 0, h = 0;
    bool ok = x != std::string::npos;
    if (ok) {
        auto [endW, errorW] = std::from_chars(text.data(), text.data() + x, w);
        auto [endH, errorH] = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
        ok = errorW == std::errc() && errorH == std::errc() && endW == text.data() + x &&
             endH == text.data() + text.size();
    }
    if (!ok) throw UsageError(spelling + " '" + text + "': expected WIDTHxHEIGHT, e.g. 1280x720");
    if (w < 1 || h < 1 || w > maxDimension || h > maxDimension)
        throw UsageError(spelling + " " + text + ": width and height must be from 1 to " +
                         std::to_string(maxDimension));
    return {uint32_t(w), uint32_t(h)};
}

void parseSetting(const SettingSpec& spec, const std::string& text, const std::string& spelling,
                  RenderSettings& s) {
    std::visit(
        Overloaded{
            [&](const FloatValue& v) { s.*v.member = parseNumber(text, spelling, v.min, v.max); },
            [&](const OnOffValue& v) { s.*v.member = parseOnOff(text, spelling); },
            [&](const SwitchValue& v) { s.*v.member = parseOnOff(text, spelling); },
            [&](const ChoiceValue& v) {
                for (uint32_t choice : v.choices)
                    if (text == v.text(choice)) {
                        s.*v.member = choice;
                        return;
                    }
                throw UsageError(spelling + " '" + text + "': expected " +
                                 alternatives(v.choices, [&](uint32_t c) { return v.text(c); }));
            },
            [&](const NamedValue& v) {
                for (size_t i = 0; i < v.names.size(); ++i)
                    if (text == v.names[i]) {
                        v.set(s, i);
                        return;
                    }
                throw UsageError(spelling + " '" + text + "': expected " +
                                 alternatives(v.names, [](const char* n) { return n; }));
            },
            [&](const TextValue& v) {
                if (text.empty()) throw UsageError(spelling + ": expected " + v.expected);
                s.*v.member = text;
            },
            [&](const SizeValue& v) {
                std::tie(s.width, s.height) = parseSize(text, spelling, v.maxDimension);
            },
            [&](const ColorValue&) -> void {
                throw Error(std::string("setting '") + spec.name + "' is set by the program, not by name");
            },
        },
        spec.value);
}

std::string settingText(const SettingSpec& spec, const RenderSettings& s) {
    return std::visit(
        Overloaded{
            [&](const FloatValue& v) { return numberText(s.*v.member); },
            [&](const OnOffValue& v) { return std::string(s.*v.member ? "on" : "off"); },
            [&](const SwitchValue& v) { return std::string(s.*v.member ? "on" : "off"); },
            [&](const ChoiceValue& v) { return v.text(s.*v.member); },
            [&](const NamedValue& v) { return std::string(v.names[v.get(s)]); },
            [&](const TextValue& v) { return s.*v.member; },
            [&](const SizeValue&) { return std::to_string(s.width) + "x" + std::to_string(s.height); },
            [&](const ColorValue& v) {
                const glm::vec3 c = s.*v.member;
                return numberText(c.r) + "," + numberText(c.g) + "," + numberText(c.b);
            },
        },
        spec.value);
}

std::string settingDefaultText(const SettingSpec& spec) {
    const RenderSettings defaults;
    const bool nothing =
        std::visit(Overloaded{
                       [](const SwitchValue&) { return true; },
                       [&](const ChoiceValue& v) { return v.automatic == defaults.*v.member; },
                       [&](const TextValue& v) { return (defaults.*v.member).empty(); },
                       [](const ColorValue&) { return true; },
                       [](const auto&) { return false; },
                   },
                   spec.value);
    return nothing ? std::string() : settingText(spec, defaults);
}

std::string settingJsonKey(const SettingSpec& spec) {
    std::string key = spec.name;
    std::replace(key.begin(), key.end(), '-', '_');
    return key;
}

bool sameSetting(const SettingSpec& spec, const RenderSettings& current, const RenderSettings& wanted) {
    return std::visit(Overloaded{
                          [&](const ChoiceValue& v) {
                              return wanted.*v.member == current.*v.member || v.automatic == wanted.*v.member;
                          },
                          [&](const SizeValue&) {
                              return wanted.width == current.width && wanted.height == current.height;
                          },
                          [&](const NamedValue& v) { return v.get(wanted) == v.get(current); },
                          [&](const auto& v) { return wanted.*v.member == current.*v.member; },
                      },
                      spec.value);
}

SettingApply settingsChange(const RenderSettings& current, const RenderSettings& wanted) {
    SettingApply needs = SettingApply::Live;
    for (const SettingSpec& spec : kTable)
        if (spec.apply > needs && !sameSetting(spec, current, wanted)) needs = spec.apply;
    return needs;
}

RenderSettings withResolvedSettings(const RenderSettings& current, RenderSettings wanted) {
    for (const SettingSpec& spec : kTable)
        if (const auto* v = std::get_if<ChoiceValue>(&spec.value))
            if (v->automatic == wanted.*v->member) wanted.*v->member = current.*v->member;
    return wanted;
}

}  // namespace vct
