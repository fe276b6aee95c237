#include "app/demo/demo_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/error.h"
#include "render/setting_table.h"

namespace vct {

namespace {

std::string fmt(const char* format, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), format, value);
    return buffer;
}

// Applies an option as the panel's widgets request it; a refused value becomes the panel's error line.
struct Setter {
    DemoControls& controls;
    PanelInfo& info;
    void operator()(const std::string& name, const std::string& value) {
        try {
            applyOption(controls, name, value);
        } catch (const Error& e) {
            info.error = e.what();
        }
    }
};

// One combo over command-line values.
void choice(Setter& set, const char* label, const std::string& name, const std::string& current,
            std::initializer_list<const char*> values) {
    if (!ImGui::BeginCombo(label, current.c_str())) return;
    for (const char* v : values)
        if (ImGui::Selectable(v, current == v)) set(name, v);
    ImGui::EndCombo();
}

void toggle(Setter& set, const char* label, const std::string& name, bool current) {
    bool value = current;
    if (ImGui::Checkbox(label, &value)) set(name, value ? "on" : "off");
}

void slider(Setter& set, const char* label, const std::string& name, float current, float lo, float hi,
            bool logarithmic) {
    float value = current;
    if (ImGui::SliderFloat(label, &value, lo, hi, "%.3g", logarithmic ? ImGuiSliderFlags_Logarithmic : 0))
        set(name, fmt("%g", double(value)));
}

// The widgets of the setting table's rows (render/setting_table.h) that have one, in table order, showing
// `shown`; `prefix` "b-" makes them side B's (the rows marked sideB only). Two checkboxes in a row share a
// line.
void settingWidgets(Setter& set, const RenderSettings& shown, const std::string& prefix) {
    const bool sideB = !prefix.empty();
    const std::string labelPrefix = sideB ? "B " : "";
    bool checkboxStartedLine = false;
    for (const SettingSpec& spec : settingTable()) {
        if (spec.widget == SettingWidget::None || (sideB && !spec.sideB)) continue;
        const std::string name = prefix + spec.name;
        const std::string label = labelPrefix + spec.label;
        const std::string current = settingText(spec, shown);
        const bool checkbox = spec.widget == SettingWidget::Checkbox;
        if (checkbox && checkboxStartedLine) ImGui::SameLine();
        checkboxStartedLine = checkbox && !checkboxStartedLine;
        std::visit(Overloaded{
                       [&](const OnOffValue& v) { toggle(set, label.c_str(), name, shown.*v.member); },
                       [&](const FloatValue& v) {
                           slider(set, label.c_str(), name, shown.*v.member, v.min, v.max,
                                  spec.widget == SettingWidget::LogSlider);
                       },
                       [&](const auto& v) {
                           std::vector<std::string> values;
                           if constexpr (std::is_same_v<std::decay_t<decltype(v)>, ChoiceValue>)
                               for (uint32_t c : v.choices) values.push_back(v.text(c));
                           if constexpr (std::is_same_v<std::decay_t<decltype(v)>, NamedValue>)
                               for (const char* n : v.names) values.push_back(n);
                           if (values.empty() || !ImGui::BeginCombo(label.c_str(), current.c_str())) return;
                           for (const std::string& value : values)
                               if (ImGui::Selectable(value.c_str(), current == value)) set(name, value);
                           ImGui::EndCombo();
                       },
                   },
                   spec.value);
    }
}

// Per-pass medians as horizontal bars, all on the scale of the longest.
void bars(const RollingTimers& timers, const char* id) {
    const std::vector<RollingTimers::Bar> medians = timers.medians();
    double longest = 0.01;
    for (const auto& bar : medians) longest = std::max(longest, bar.medianMs);
    ImGui::PushID(id);
    for (const auto& bar : medians) {
        ImGui::TextUnformatted(bar.name.c_str());
        ImGui::SameLine(90.0f);
        ImGui::ProgressBar(float(bar.medianMs / longest), ImVec2(-1.0f, 0.0f),
                           fmt("%.2f ms", bar.medianMs).c_str());
    }
    ImGui::PopID();
}

// The reference's progress, in the panel and the timer overlay.
void referenceLine(const PanelInfo& info) {
    if (info.referenceSpp > 0)
        ImGui::TextWrapped("reference: %u spp, %.2f Mrays/s (%u CPU thread%s)", info.referenceSpp,
                           info.referenceRaysPerSecond * 1e-6, info.referenceThreads,
                           info.referenceThreads == 1 ? "" : "s");
    else if (info.referenceState.rfind("failed", 0) == 0)
        ImGui::TextWrapped("reference %s", info.referenceState.c_str());
    else if (info.referenceShownSpp > 0)
        ImGui::TextWrapped("reference: %s, first pass (showing %u spp of the previous view)",
                           info.referenceState.c_str(), info.referenceShownSpp);
    else
        ImGui::TextWrapped("reference: %s, first pass", info.referenceState.c_str());
}

void timerWindow(const PanelInfo& info) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(viewport->Size.x - 8.0f, 8.0f), ImGuiCond_Always, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(300.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("GPU timers", nullptr,
                 ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoFocusOnAppearing);
    ImGui::TextUnformatted(info.device.c_str());
    ImGui::Text("%ux%u, trace %ux%u (1/%u)", info.width, info.height,
                (info.width + info.traceScale - 1) / info.traceScale,
                (info.height + info.traceScale - 1) / info.traceScale, info.traceScale);
    const double gpu = info.timersA ? info.timersA->frameMedianMs() : 0.0;
    ImGui::Text("%.1f fps  frame %.1f ms  GPU %.2f ms",
                info.cpuFrameMs > 0.0 ? 1000.0 / info.cpuFrameMs : 0.0, info.cpuFrameMs, gpu);
    if (info.gi) ImGui::Text("re-traced %.3f%% of the pixels", 100.0 * double(info.resampled));
    if (info.frameTimes && !info.frameTimes->values().empty()) {
        const auto& values = info.frameTimes->values();
        ImGui::PlotLines("##frametime", values.data(), int(values.size()), 0, "frame ms (CPU wall clock)",
                         0.0f, std::max(info.frameTimes->max() * 1.1f, 1.0f),
                         // an explicit width: PlotLines (1.86) does not take -1 as "fill"
                         ImVec2(ImGui::GetContentRegionAvail().x, 50.0f));
    }
    ImGui::Separator();
    ImGui::TextUnformatted("GPU median of the last 60 frames");
    if (info.timersA) bars(*info.timersA, "a");
    if (info.reference) {
        ImGui::Separator();
        referenceLine(info);
    }
    if (info.timersB) {
        ImGui::Separator();
        const double b = info.timersB->frameMedianMs();
        ImGui::TextWrapped("split view: B %.2f ms, A + B = %.2f ms GPU per frame", b, gpu + b);
        if (ImGui::CollapsingHeader("B per pass")) bars(*info.timersB, "b");
    }
    if (info.timersDisplay) {
        ImGui::Separator();
        ImGui::Text("window: %.2f ms GPU (view, panel, blit)", info.timersDisplay->frameMedianMs());
        if (ImGui::CollapsingHeader("window per step")) bars(*info.timersDisplay, "d");
    }
    ImGui::End();
}

}  // namespace

namespace {

// The split view's wipe, and a handle the user drags (app/demo/demo_command.cpp moves it).
void wipeHandle(float wipe) {
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    const float x = wipe * viewport->Size.x;
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    draw->AddLine(ImVec2(x, 0.0f), ImVec2(x, viewport->Size.y), IM_COL32(255, 255, 255, 200), 2.0f);
    draw->AddText(ImVec2(x - 18.0f, viewport->Size.y - 20.0f), IM_COL32(255, 255, 255, 255), "A|B");
}

// Progress, a refused value (dismissable) and the last script or loader message, above the sections.
void messageLines(PanelInfo& info) {
    if (!info.progress.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.3f, 1.0f), "%s", info.progress.c_str());
    if (!info.error.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", info.error.c_str());
        ImGui::PopStyleColor();
        if (ImGui::SmallButton("dismiss")) info.error.clear();
    }
    if (!info.message.empty()) ImGui::TextWrapped("%s", info.message.c_str());
}

// What is shown: the view, the voxel mip, and the split view with its B side (settings or the reference).
void viewSection(Setter& set, DemoControls& c, PanelInfo& info) {
    const RenderSettings& s = c.settings;
    choice(
        set, "view", "view", auxViewName(c.view),
        {"final", "direct", "diffuse", "specular", "normals", "roughness", "weights", "resample", "voxels"});
    if (c.view == AuxView::Voxels) {
        int mip = int(c.voxelMip);
        if (ImGui::SliderInt("voxel mip", &mip, 0, int(info.voxelMips) - 1))
            set("voxel-mip", std::to_string(mip));
    }
    if (auxViewNeedsGi(c.view) && !s.gi) ImGui::TextUnformatted("(needs GI: showing final)");
    toggle(set, "split view (B right of the wipe)", "split", c.split);
    if (c.split) {
        slider(set, "wipe", "wipe", c.wipe, 0.0f, 1.0f, false);
        const bool reference = c.splitSource == SplitSource::Reference;
        if (ImGui::BeginCombo("B source", reference ? "path-traced reference" : "vct settings")) {
            if (ImGui::Selectable("vct settings", !reference)) set("split-source", "vct");
            if (ImGui::Selectable("path-traced reference", reference)) set("split-source", "reference");
            ImGui::EndCombo();
        }
    }
    if (c.showsReference()) {
        choice(set, "B bounces", "reference-bounces", referenceBouncesText(c.referenceBounces), {"1", "all"});
        referenceLine(info);
        ImGui::TextWrapped(
            "B is the path-traced truth of A's frame, converging on the CPU: a camera move restarts it, "
            "a playing animation rebuilds it every frame (pause to let it converge).");
    } else if (c.split) {
        ImGui::PushID("b");
        settingWidgets(set, c.settingsB(), "b-");
        ImGui::PopID();
        ImGui::TextWrapped(
            "Both sides are rendered in full every frame: the split view costs a second frame "
            "(B's GPU time in the timers).");
    }
}

// Time, history and camera controls.
void animationSection(Setter& set, const DemoControls& c, const PanelInfo& info) {
    ImGui::Text("t = %.2f s", double(info.animationTime));
    ImGui::SameLine();
    toggle(set, "pause (P)", "pause", c.paused);
    ImGui::SameLine();
    if (ImGui::Button("step (N)")) set("step", "on");
    if (ImGui::Button("reset history (H)")) set("reset-history", "on");
    ImGui::SameLine();
    if (ImGui::Button("camera cut (C)")) set("camera-cut", "on");
    if (info.hasCameraPath) toggle(set, "play camera path", "play-path", c.playPath);
    if (ImGui::Button(info.recording ? "stop recording (R)" : "record camera path (R)")) set("record", "on");
    if (info.recording) {
        ImGui::SameLine();
        ImGui::Text("%zu keys", info.recordedKeys);
    }
    if (!info.recordPath.empty()) ImGui::TextDisabled("-> %s", info.recordPath.c_str());
}

// The scene field (or drag and drop), shader reload and the screenshot button.
void sceneSection(Setter& set, const PanelInfo& info, char* sceneField, size_t sceneFieldSize) {
    ImGui::Text("scene: %s", info.scene.c_str());
    ImGui::InputText("##scene", sceneField, sceneFieldSize);
    ImGui::SameLine();
    if (ImGui::Button("open")) set("scene", sceneField);
    ImGui::TextDisabled("or drop a .gltf/.glb on the window");
    if (ImGui::Button("reload shaders (F5)")) set("hot-reload", "on");
    ImGui::SameLine();
    if (ImGui::Button("screenshot (F12)")) set("screenshot", "vct-demo.png");
}

}  // namespace

void drawPanel(DemoControls& c, PanelInfo& info, char* sceneField, size_t sceneFieldSize) {
    Setter set{c, info};
    if (c.split) wipeHandle(c.wipe);
    timerWindow(info);

    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(330.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("vct (F1 hides)");
    messageLines(info);
    if (ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen)) {
        // What a renderer resolves (voxels, anisotropy) is shown as renderer A chose it.
        settingWidgets(set, withResolvedSettings(info.resolved, c.settings), "");
    }
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) viewSection(set, c, info);
    if (ImGui::CollapsingHeader("Animation and camera", ImGuiTreeNodeFlags_DefaultOpen))
        animationSection(set, c, info);
    if (ImGui::CollapsingHeader("Scene and shaders", ImGuiTreeNodeFlags_DefaultOpen))
        sceneSection(set, info, sceneField, sceneFieldSize);
    ImGui::End();
}

}  // namespace vct
