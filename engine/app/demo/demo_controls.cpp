#include "app/demo/demo_controls.h"

#include <charconv>

#include "core/error.h"
#include "reference/path_tracer.h"
#include "render/setting_table.h"

namespace vct {

namespace {

// The demo's own options parse as settings do (render/setting_table.h).
bool onOff(const std::string& name, const std::string& value) {
    return parseOnOff(value, name);
}
float number(const std::string& name, const std::string& value, float min, float max) {
    return parseNumber(value, name, min, max);
}

}  // namespace

bool applySetting(RenderSettings& settings, const std::string& name, const std::string& value) {
    const SettingSpec* spec = findSetting(name);
    if (!spec || !spec->demo) return false;
    parseSetting(*spec, value, name, settings);
    return true;
}

std::string settingText(const RenderSettings& settings, const std::string& name) {
    const SettingSpec* spec = findSetting(name);
    return spec && spec->demo ? settingText(*spec, settings) : std::string();
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
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        for (const SettingSpec& spec : settingTable())
            if (spec.demo) list.push_back(spec.name);
        for (const char* name :
             {"view", "voxel-mip", "split", "wipe", "split-source", "reference-bounces", "b-NAME", "panel",
              "pause", "play-path", "camera-cut", "reset-history", "step", "hot-reload", "record",
              "screenshot", "screenshot-ui", "scene", "quit"})
            list.push_back(name);
        return list;
    }();
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
