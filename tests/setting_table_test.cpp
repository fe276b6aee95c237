// The setting table (engine/render/setting_table.h) on the CPU: every row well formed, the command line, the
// demo and the JSON reports made from it agree (names, ranges, defaults, messages), and what a change needs.
#include "render/setting_table.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <set>
#include <string>

#include "app/cli/session.h"
#include "app/demo/demo_controls.h"
#include "core/error.h"
#include "report/settings_json.h"

namespace vct {
namespace {

std::string usageError(const std::function<void()>& f) {
    try {
        f();
    } catch (const UsageError& e) {
        return e.what();
    }
    return "no error";
}

TEST(SettingTable, RowsAreWellFormed) {
    std::set<std::string> names;
    for (const SettingSpec& spec : settingTable()) {
        SCOPED_TRACE(spec.name);
        EXPECT_TRUE(names.insert(spec.name).second) << "listed twice";
        EXPECT_FALSE(std::string(spec.help).empty());
        const bool internal = spec.group == SettingGroup::Internal;
        if (internal) {
            EXPECT_FALSE(spec.demo || spec.json || spec.widget != SettingWidget::None || spec.sideB);
            continue;
        }
        // A switch has no value on the command line; every other flag names one.
        EXPECT_EQ(std::holds_alternative<SwitchValue>(spec.value), std::string(spec.valueName).empty());
        EXPECT_EQ(spec.widget != SettingWidget::None, spec.label != nullptr);
        EXPECT_TRUE(!spec.sideB || spec.widget != SettingWidget::None);
        EXPECT_TRUE(spec.widget == SettingWidget::None || spec.demo) << "a widget the demo cannot apply";
        switch (spec.widget) {
            case SettingWidget::None:
                break;
            case SettingWidget::Checkbox:
                EXPECT_TRUE(std::holds_alternative<OnOffValue>(spec.value));
                break;
            case SettingWidget::Combo:
                EXPECT_TRUE(std::holds_alternative<ChoiceValue>(spec.value) ||
                            std::holds_alternative<NamedValue>(spec.value));
                break;
            case SettingWidget::Slider:
            case SettingWidget::LogSlider: {
                const auto* v = std::get_if<FloatValue>(&spec.value);
                ASSERT_TRUE(v);
                EXPECT_TRUE(spec.widget == SettingWidget::Slider || v->min > 0.0f)
                    << "a log slider needs min > 0";
                break;
            }
        }
        // The default is a value the row accepts, and reads back as itself.
        const RenderSettings defaults;
        const std::string text = settingDefaultText(spec);
        if (text.empty()) continue;
        RenderSettings parsed;
        parseSetting(spec, text, spec.name, parsed);
        EXPECT_TRUE(sameSetting(spec, defaults, parsed)) << text;
        EXPECT_EQ(settingText(spec, parsed), text);
    }
}

// One range per setting: the command line and the demo accept and refuse the same values, with one message.
TEST(SettingTable, CommandLineAndDemoShareRangesAndMessages) {
    const SettingSpec* beta = findSetting("beta");
    ASSERT_TRUE(beta);
    for (const char* value : {"0.01", "1000", "20"}) {
        RenderSettings a;
        EXPECT_NO_THROW(parseSetting(*beta, value, "--beta", a)) << value;
        EXPECT_TRUE(applySetting(a, "beta", value)) << value;
    }
    for (const char* value : {"0.001", "1001", "nan", "inf", "", "2x"}) {
        RenderSettings a;
        const std::string cli = usageError([&] { parseSetting(*beta, value, "--beta", a); });
        const std::string demo = usageError([&] { applySetting(a, "beta", value); });
        EXPECT_EQ(cli, "--beta '" + std::string(value) + "': expected a number from 0.01 to 1000");
        EXPECT_EQ(demo, "beta '" + std::string(value) + "': expected a number from 0.01 to 1000");
        EXPECT_FLOAT_EQ(a.beta, RenderSettings{}.beta);  // a refused value changes nothing
    }
    RenderSettings s;
    EXPECT_EQ(usageError([&] { applySetting(s, "trace-scale", "3"); }),
              "trace-scale '3': expected 1, 2 or 4");
    EXPECT_EQ(usageError([&] { parseSetting(*findSetting("anisotropy"), "3", "--anisotropy", s); }),
              "--anisotropy '3': expected 0, 2, 4, 8 or 16");
    // A choice with a word: `--bounces all`, a number internally, the word everywhere it is written.
    EXPECT_EQ(usageError([&] { parseSetting(*findSetting("bounces"), "9", "--bounces", s); }),
              "--bounces '9': expected 1, 2, 3, 4, 5, 6, 7, 8 or all");
    RenderSettings all;
    parseSetting(*findSetting("bounces"), "all", "--bounces", all);
    EXPECT_EQ(all.bounces, kAllBounces);
    EXPECT_EQ(settingText(*findSetting("bounces"), all), "all");
    EXPECT_EQ(settingsJson(all)["bounces"], "all");
    EXPECT_EQ(settingsJson(RenderSettings{})["bounces"], "all");
    RenderSettings one;
    one.bounces = 1;
    EXPECT_EQ(settingsJson(one)["bounces"], 1);
    EXPECT_TRUE(applySetting(all, "bounces", "3"));
    EXPECT_EQ(all.bounces, 3u);
    EXPECT_EQ(usageError([&] { applySetting(s, "weights", "lobe"); }),
              "weights 'lobe': expected bilinear, normal or sg");
    EXPECT_EQ(usageError([&] { applySetting(s, "gi", "maybe"); }), "gi 'maybe': expected on or off");
    EXPECT_EQ(usageError([&] { parseSetting(*findSetting("voxel-cache"), "", "--voxel-cache", s); }),
              "--voxel-cache: expected a file name");
    // The demo takes every setting it marks, and no other (a diagnostic switch, the size, an internal one).
    EXPECT_TRUE(applySetting(s, "diffuse-sharpness", "3"));
    EXPECT_FLOAT_EQ(s.diffuseSharpness, 3.0f);
    for (const char* name :
         {"texture-lod0", "recompute-every-frame", "size", "voxel-cache", "write-weight-sum"})
        EXPECT_FALSE(applySetting(s, name, "on")) << name;
}

TEST(SettingTable, HelpListsTheFlagsWithTheirDefaults) {
    std::map<std::string, std::string> upsample;
    for (const Option& option : settingOptions(SettingGroup::Upsample))
        upsample[option.name] = option.defaultValue;
    // Today's flags and the defaults their --help printed before the table (more rows may follow).
    const std::map<std::string, std::string> expected = {
        {"weights", "sg"},          {"beta", "20"},   {"kappa", "100"}, {"sigma-n", "0.1"},
        {"diffuse-sharpness", "2"}, {"gamma", "0.8"}, {"tau", "0.25"},  {"temporal", "on"},
        {"adaptive", "on"}};
    for (const auto& [name, value] : expected) EXPECT_EQ(upsample[name], value) << name;
    // Resolved by the renderer: described in the help, no default printed.
    EXPECT_EQ(settingOption("voxels").defaultValue, "");
    EXPECT_EQ(settingOption("anisotropy").defaultValue, "");
    EXPECT_EQ(settingOption("size").defaultValue, "1280x720");
    EXPECT_EQ(settingOption("trace-scale").defaultValue, "4");
    EXPECT_EQ(settingOption("texture-lod0").valueName, "");
    EXPECT_THROW(settingOption("write-weight-sum"), Error);
}

TEST(SettingTable, JsonWritesTheMarkedRowsUnderTheirNames) {
    const nlohmann::json json = settingsJson(RenderSettings{});
    std::set<std::string> keys, marked;
    for (const auto& [key, value] : json.items()) keys.insert(key);
    for (const SettingSpec& spec : settingTable())
        if (spec.json) marked.insert(settingJsonKey(spec));
    EXPECT_EQ(keys, marked);
    // What timings.json held before the table, which reports and scripts read.
    for (const char* key :
         {"gi", "voxels", "trace_scale", "weights", "beta", "kappa", "sigma_n", "diffuse_sharpness", "gamma",
          "temporal", "adaptive", "tau", "toksvig", "specular_aa", "anisotropy", "exposure"})
        EXPECT_TRUE(keys.count(key)) << key;
    EXPECT_EQ(json["weights"], "sg");
    EXPECT_EQ(json["trace_scale"], 4);
    EXPECT_EQ(json["temporal"], true);
    EXPECT_FLOAT_EQ(json["tau"].get<float>(), 0.25f);
    EXPECT_FLOAT_EQ(json["sigma_n"].get<float>(), 0.1f);
}

TEST(SettingTable, WhatAChangeNeeds) {
    RenderSettings running;  // as a renderer resolved it
    running.voxelResolution = 64;
    running.anisotropy = 0;
    auto needs = [&](const std::function<void(RenderSettings&)>& change) {
        RenderSettings wanted = running;
        change(wanted);
        return settingsChange(running, wanted);
    };
    EXPECT_EQ(needs([](RenderSettings&) {}), SettingApply::Live);
    for (const char* live : {"beta", "kappa", "sigma-n", "gamma", "tau", "exposure", "diffuse-sharpness"})
        EXPECT_EQ(needs([&](RenderSettings& s) { parseSetting(*findSetting(live), "0.5", live, s); }),
                  SettingApply::Live)
            << live;
    EXPECT_EQ(needs([](RenderSettings& s) { s.weights = RenderSettings::Weights::Normal; }),
              SettingApply::Live);
    EXPECT_EQ(needs([](RenderSettings& s) { s.temporal = false; }), SettingApply::Live);
    EXPECT_EQ(needs([](RenderSettings& s) { s.writeWeightSum = true; }), SettingApply::Live);
    EXPECT_EQ(needs([](RenderSettings& s) { s.width = 640; }), SettingApply::Resize);
    EXPECT_EQ(needs([](RenderSettings& s) { s.traceScale = 2; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.gi = false; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.adaptive = false; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.textureLod0 = true; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.voxelCache = "a.vdb"; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.width = 640, s.traceScale = 2; }), SettingApply::Rebuild);
    // Automatic requests match what the renderer chose; another explicit value does not.
    EXPECT_EQ(needs([](RenderSettings& s) { s.voxelResolution = 0, s.anisotropy = kAnisotropyFromDevice; }),
              SettingApply::Live);
    EXPECT_EQ(needs([](RenderSettings& s) { s.voxelResolution = 128; }), SettingApply::Rebuild);
    EXPECT_EQ(needs([](RenderSettings& s) { s.anisotropy = 4; }), SettingApply::Rebuild);
    RenderSettings automatic = running;
    automatic.voxelResolution = 0;
    automatic.anisotropy = kAnisotropyFromDevice;
    const RenderSettings resolved = withResolvedSettings(running, automatic);
    EXPECT_EQ(resolved.voxelResolution, 64u);
    EXPECT_EQ(resolved.anisotropy, 0u);
}

}  // namespace
}  // namespace vct
