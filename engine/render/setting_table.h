// The setting table: every RenderSettings field declared once, in one row (setting_table.cpp): its name (the
// command-line flag --NAME, the demo's option and script key NAME, side B's b-NAME, the JSON key with '_' for
// '-'), the member, the values it takes (range or choices; the default is the member's initializer in
// settings.h), whether a change applies to a running renderer, the --help text and the demo panel's widget.
// What reads it:
//   app/session.cpp        the flags of every command that renders, their --help lines and their parsing
//   app/demo_controls.cpp  applySetting / settingText / demoOptionNames: the panel, the keys and --script
//   app/demo_panel.cpp     one widget per row that has one, side B's controls
//   io/settings_json.cpp   the "settings" object of timings.json and benchmark.json
//   render/renderer.cpp    canApplyLive / applyLive (settingsChange below)
// Adding a setting: its member in RenderSettings, its row here, and the code that uses its value.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "render/settings.h"

namespace vct {

// What a change of the setting needs, in increasing order.
enum class SettingApply {
    Live,  // read by the next frame (uniforms, specialization constants, dynamic state): Renderer::applyLive
    Resize,   // new frame targets, same passes and voxel grid: Renderer::resize
    Rebuild,  // new passes, pipelines' layouts or voxel grid: a new Renderer
};

// The commands' option groups (app/session.h settingOptions), in --help order.
enum class SettingGroup {
    Gi,        // global illumination: render, demo
    Upsample,  // upsampling and adaptive re-tracing: render, demo
    Material,  // material filtering: render, demo, benchmark
    Image,     // size and exposure: each command picks them (settingOption)
    Internal,  // set by the program, never by a flag (what a view needs, fixed biases)
};

// The demo panel's control for a setting (app/demo_panel.cpp).
enum class SettingWidget {
    None,       // not in the panel
    Checkbox,   // OnOffValue
    Combo,      // ChoiceValue, NamedValue: one entry per value
    Slider,     // FloatValue, linear over [min, max]
    LogSlider,  // FloatValue, logarithmic over [min, max] (min > 0)
};

// The kinds of value, each naming its RenderSettings member.
struct FloatValue {  // a number in [min, max]
    float RenderSettings::*member;
    float min, max;
};
struct OnOffValue {  // on|off (also true|false, 1|0)
    bool RenderSettings::*member;
};
struct SwitchValue {  // a flag without a value: given means true (the command line only)
    bool RenderSettings::*member;
};
struct ChoiceValue {  // one of a few unsigned integers
    uint32_t RenderSettings::*member;
    std::span<const uint32_t> choices;
    // A request the Renderer resolves from the device (0 voxels, kAnisotropyFromDevice): not a choice on the
    // command line, it matches whatever the renderer chose (settingsChange), and --help describes it.
    std::optional<uint32_t> automatic = std::nullopt;
    // One choice written as a word on the command line, in the demo and in JSON ("all" bounces), else none.
    std::optional<std::pair<uint32_t, const char*>> word = std::nullopt;
    // The word `choice` is written as, or null for a number.
    const char* wordOf(uint32_t choice) const {
        return word && word->first == choice ? word->second : nullptr;
    }
    // A choice as written: its word, or its number.
    std::string text(uint32_t choice) const {
        const char* w = wordOf(choice);
        return w ? std::string(w) : std::to_string(choice);
    }
};
struct NamedValue {  // an enum by name: names[i] is the enumerator of value i
    std::variant<RenderSettings::Weights RenderSettings::*, RenderSettings::UpsampleLayout RenderSettings::*,
                 RenderSettings::TraceLayout RenderSettings::*>
        member;
    std::span<const char* const> names;
    size_t get(const RenderSettings& s) const {
        return std::visit([&](auto m) { return size_t(s.*m); }, member);
    }
    void set(RenderSettings& s, size_t i) const {
        std::visit([&](auto m) { s.*m = std::remove_reference_t<decltype(s.*m)>(i); }, member);
    }
};
struct TextValue {  // a non-empty string (a file name)
    std::string RenderSettings::*member;
    const char* expected;  // what the error says is expected, e.g. "a file name"
};
struct SizeValue {  // width and height, "WxH"
    uint32_t maxDimension;
};
struct ColorValue {  // an rgb triple (internal settings only)
    glm::vec3 RenderSettings::*member;
};
using SettingValue = std::variant<FloatValue, OnOffValue, SwitchValue, ChoiceValue, NamedValue, TextValue,
                                  SizeValue, ColorValue>;

struct SettingSpec {
    const char* name;       // --name on the command line, name in the demo and its scripts
    const char* valueName;  // what --help shows after the flag ("B", "on|off", "1|2|4"); "" for a switch
    const char* help;       // the --help line, without the default (printed from RenderSettings{})
    SettingValue value;
    SettingApply apply;
    SettingGroup group;
    bool demo = false;  // the demo's panel, keys and --script may change it (applySetting, b-NAME)
    bool json = false;  // written to the "settings" of timings.json / benchmark.json (key: name with '_')
    SettingWidget widget = SettingWidget::None;
    const char* label = nullptr;  // the panel's label (widget != None)
    bool sideB = false;           // also among the split view's side-B controls
};

// Every row, in --help and panel order.
std::span<const SettingSpec> settingTable();
// The row named `name`, or null.
const SettingSpec* findSetting(std::string_view name);

// Sets the row's member(s) from `text` as the command line spells it. A bad value is a UsageError of one
// line,
// "<spelling> '<text>': expected ...", `spelling` being "--name" on the command line and "name" in the demo.
void parseSetting(const SettingSpec& spec, const std::string& text, const std::string& spelling,
                  RenderSettings& settings);
// The row's value in `settings` as parseSetting takes it ("sg", "4", "on", "0.25", "1280x720").
std::string settingText(const SettingSpec& spec, const RenderSettings& settings);
// What --help prints as the default: settingText of RenderSettings{}, or "" where there is nothing to print
// (a switch, an empty file name, an automatic value).
std::string settingDefaultText(const SettingSpec& spec);
// The key in the JSON reports: the name with '_' for '-'.
std::string settingJsonKey(const SettingSpec& spec);

// Whether `a` and `b` hold the same value of this row; an automatic request in `wanted` matches any value in
// `current` (what a renderer resolved it to).
bool sameSetting(const SettingSpec& spec, const RenderSettings& current, const RenderSettings& wanted);
// What going from the settings a renderer runs with (`current`, automatic values resolved) to `wanted` needs:
// the largest SettingApply among the rows that differ (Live when none does).
SettingApply settingsChange(const RenderSettings& current, const RenderSettings& wanted);
// `wanted` with the automatic requests replaced by what `current` resolved them to.
RenderSettings withResolvedSettings(const RenderSettings& current, RenderSettings wanted);

// Overloaded lambdas for std::visit over a SettingValue.
template <typename... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <typename... F>
Overloaded(F...) -> Overloaded<F...>;

// The number and size parsers of the command line (app/cli.cpp uses them too, so every message has one form):
// "<spelling> '<text>': expected on or off", "... expected a number from <min> to <max>", "... expected
// WIDTHxHEIGHT, e.g. 1280x720".
bool parseOnOff(const std::string& text, const std::string& spelling);  // on|off, true|false, 1|0
float parseNumber(const std::string& text, const std::string& spelling, float min, float max);
std::pair<uint32_t, uint32_t> parseSize(const std::string& text, const std::string& spelling,
                                        uint32_t maxDimension);

}  // namespace vct
