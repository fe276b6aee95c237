#include "app/demo_controls.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "reference/path_tracer.h"

namespace vct {

namespace {

bool onOff(const std::string& name, const std::string& value) {
    if (value == "on" || value == "true" || value == "1") return true;
    if (value == "off" || value == "false" || value == "0") return false;
    throw UsageError(name + " '" + value + "': expected on or off");
}

float number(const std::string& name, const std::string& value, float min, float max) {
    char* end = nullptr;
    const float v = std::strtof(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(v) || v < min || v > max) {
        char range[64];
        std::snprintf(range, sizeof(range), "expected a number in [%g, %g]", double(min), double(max));
        throw UsageError(name + " '" + value + "': " + range);
    }
    return v;
}

uint32_t oneOf(const std::string& name, const std::string& value, std::initializer_list<uint32_t> allowed) {
    std::string list;
    for (uint32_t a : allowed) {
        if (value == std::to_string(a)) return a;
        list += (list.empty() ? "" : ", ") + std::to_string(a);
    }
    throw UsageError(name + " '" + value + "': expected one of " + list);
}

std::string text(float value) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", double(value));
    return buffer;
}

}  // namespace

bool applySetting(RenderSettings& s, const std::string& name, const std::string& value) {
    if (name == "weights") {
        if (value == "bilinear")
            s.weights = RenderSettings::Weights::Bilinear;
        else if (value == "normal")
            s.weights = RenderSettings::Weights::Normal;
        else if (value == "sg")
            s.weights = RenderSettings::Weights::Sg;
        else
            throw UsageError("weights '" + value + "': expected bilinear, normal or sg");
    } else if (name == "trace-scale") {
        s.traceScale = oneOf(name, value, {1, 2, 4});
    } else if (name == "beta") {
        s.beta = number(name, value, 0.01f, 1000.0f);
    } else if (name == "kappa") {
        s.kappa = number(name, value, 0.01f, kMaxKappa);
    } else if (name == "sigma-n") {
        s.sigmaN = number(name, value, 1e-3f, 10.0f);
    } else if (name == "gamma") {
        s.gamma = number(name, value, 0.0f, 1.0f);
    } else if (name == "tau") {
        s.tau = number(name, value, 1e-6f, 1000.0f);
    } else if (name == "temporal") {
        s.temporal = onOff(name, value);
    } else if (name == "adaptive") {
        s.adaptive = onOff(name, value);
    } else if (name == "toksvig") {
        s.toksvig = onOff(name, value);
    } else if (name == "specular-aa") {
        s.specularAA = onOff(name, value);
    } else if (name == "anisotropy") {
        s.anisotropy = oneOf(name, value, {0, 2, 4, 8, 16});
    } else if (name == "exposure") {
        s.exposure = number(name, value, 1e-4f, 1e4f);
    } else if (name == "gi") {
        s.gi = onOff(name, value);
    } else if (name == "voxels") {
        s.voxelResolution = oneOf(name, value, {32, 64, 128, 256});
    } else {
        return false;
    }
    return true;
}

std::string settingText(const RenderSettings& s, const std::string& name) {
    auto flag = [](bool b) { return std::string(b ? "on" : "off"); };
    if (name == "weights") return weightsName(s.weights);
    if (name == "trace-scale") return std::to_string(s.traceScale);
    if (name == "beta") return text(s.beta);
    if (name == "kappa") return text(s.kappa);
    if (name == "sigma-n") return text(s.sigmaN);
    if (name == "gamma") return text(s.gamma);
    if (name == "tau") return text(resampleThreshold(s));
    if (name == "temporal") return flag(s.temporal);
    if (name == "adaptive") return flag(s.adaptive);
    if (name == "toksvig") return flag(s.toksvig);
    if (name == "specular-aa") return flag(s.specularAA);
    if (name == "anisotropy") return std::to_string(s.anisotropy);
    if (name == "exposure") return text(s.exposure);
    if (name == "gi") return flag(s.gi);
    if (name == "voxels") return std::to_string(s.voxelResolution);
    return "";
}

RenderSettings DemoControls::settingsB() const {
    RenderSettings b = settings;
    for (const auto& [name, value] : splitOverrides) applySetting(b, name, value);
    return b;
}

const char* splitSourceName(SplitSource source) {
    return source == SplitSource::Reference ? "reference" : "vct";
}

std::string referenceBouncesText(int bounces) {
    return bounces == reference::kUnlimitedBounces ? "all" : std::to_string(bounces);
}

const std::vector<std::string>& demoOptionNames() {
    // clang-format off
    static const std::vector<std::string> names = {
        "weights", "trace-scale", "beta", "kappa", "sigma-n", "gamma", "tau", "temporal", "adaptive", "toksvig",
        "specular-aa", "anisotropy", "exposure", "gi", "voxels", "view", "voxel-mip", "split", "wipe",
        "split-source", "reference-bounces", "b-NAME", "panel", "pause", "play-path", "camera-cut",
        "reset-history", "step", "hot-reload", "record", "screenshot", "screenshot-ui", "scene", "quit"};
    // clang-format on
    return names;
}

void applyOption(DemoControls& c, const std::string& name, const std::string& value) {
    if (applySetting(c.settings, name, value)) return;
    if (name.rfind("b-", 0) == 0) {
        // Checked on a copy, so a bad value leaves side B as it was.
        const std::string setting = name.substr(2);
        RenderSettings probe = c.settings;
        if (!applySetting(probe, setting, value))
            throw UsageError(name + ": '" + setting + "' is not a render setting");
        c.splitOverrides[setting] = value;
        return;
    }
    if (name == "view") {
        c.view = parseAuxView(value);
    } else if (name == "voxel-mip") {
        c.voxelMip = uint32_t(number(name, value, 0.0f, 8.0f));
    } else if (name == "split") {
        c.split = onOff(name, value);
    } else if (name == "wipe") {
        c.wipe = number(name, value, 0.0f, 1.0f);
    } else if (name == "split-source") {
        if (value == "vct")
            c.splitSource = SplitSource::Vct;
        else if (value == "reference")
            c.splitSource = SplitSource::Reference;
        else
            throw UsageError("split-source '" + value + "': expected vct or reference");
    } else if (name == "reference-bounces") {
        // As `vct reference --bounces`: 0 direct light only, 1 what vct's cones estimate, N, all (full GI).
        if (value == "all") {
            c.referenceBounces = reference::kUnlimitedBounces;
        } else {
            int bounces = -1;
            const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), bounces);
            if (value.empty() || error != std::errc() || end != value.data() + value.size() || bounces < 0 ||
                bounces > 64)
                throw UsageError(name + " '" + value + "': expected 0 to 64 or all");
            c.referenceBounces = bounces;
        }
    } else if (name == "panel") {
        c.panel = onOff(name, value);
    } else if (name == "pause") {
        c.paused = onOff(name, value);
    } else if (name == "play-path") {
        c.playPath = onOff(name, value);
    } else if (name == "camera-cut") {
        c.cameraCut = true;
    } else if (name == "reset-history") {
        c.resetHistory = true;
    } else if (name == "step") {
        c.step = true;
    } else if (name == "hot-reload") {
        c.hotReload = true;
    } else if (name == "record") {
        c.toggleRecording = true;
    } else if (name == "quit") {
        c.quit = true;
    } else if (name == "screenshot" || name == "screenshot-ui") {
        if (value.empty()) throw UsageError(name + ": expected a file name");
        c.screenshot = value;
        c.screenshotUi = name == "screenshot-ui";
    } else if (name == "scene") {
        if (value.empty()) throw UsageError("scene: expected a built-in scene name or a .gltf/.glb file");
        c.openScene = value;
    } else {
        std::string list;
        for (const std::string& n : demoOptionNames()) list += (list.empty() ? "" : ", ") + n;
        throw UsageError("unknown demo option '" + name + "' (expected " + list + ")");
    }
}

}  // namespace vct
