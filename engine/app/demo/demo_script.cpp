#include "app/demo/demo_script.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/demo/demo_controls.h"
#include "core/error.h"

namespace vct {

namespace {

// A JSON value as the command line would spell it.
std::string optionText(const nlohmann::ordered_json& value, const std::string& where) {
    if (value.is_string()) return value.get<std::string>();
    if (value.is_boolean()) return value.get<bool>() ? "on" : "off";
    if (value.is_number_integer()) return std::to_string(value.get<int64_t>());
    if (value.is_number()) {
        std::ostringstream s;
        s << value.get<double>();
        return s.str();
    }
    throw Error(where + ": expected a string, number or boolean, got " + value.dump());
}

}  // namespace

DemoScript parseDemoScript(const std::string& text, const std::string& source) {
    // ordered_json keeps each "set" object's options in file order ("split" before "b-weights" or after).
    nlohmann::ordered_json json;
    try {
        json = nlohmann::ordered_json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(source + ": not valid JSON (" + e.what() + ")");
    }
    if (!json.is_array()) throw Error(source + ": expected a list of steps [{\"frame\": N, ...}, ...]");
    DemoScript script;
    DemoControls scratch;  // every option is applied once here, so a bad one fails before any window opens
    for (size_t i = 0; i < json.size(); ++i) {
        const auto& entry = json[i];
        const std::string where = source + " step " + std::to_string(i);
        if (!entry.is_object() || !entry.contains("frame") || !entry["frame"].is_number_unsigned())
            throw Error(where + ": expected {\"frame\": N, ...} with N >= 0");
        ScriptStep step;
        step.frame = entry["frame"].get<uint32_t>();
        for (const auto& [key, value] : entry.items()) {
            if (key == "frame" || key == "ui") continue;
            if (key == "set") {
                if (!value.is_object()) throw Error(where + ": \"set\" must be an object {option: value}");
                for (const auto& [name, v] : value.items())
                    step.options.emplace_back(name, optionText(v, where));
            } else if (key == "screenshot") {
                const bool ui = entry.contains("ui") && entry["ui"].is_boolean() && entry["ui"].get<bool>();
                step.options.emplace_back(ui ? "screenshot-ui" : "screenshot", optionText(value, where));
            } else {
                throw Error(where + ": unknown key '" + key + "' (expected frame, set, screenshot, ui)");
            }
        }
        for (const auto& [name, value] : step.options) {
            try {
                applyOption(scratch, name, value);
            } catch (const UsageError& e) {
                throw UsageError(where + ": " + e.what());
            }
        }
        script.steps.push_back(std::move(step));
    }
    std::stable_sort(script.steps.begin(), script.steps.end(),
                     [](const ScriptStep& a, const ScriptStep& b) { return a.frame < b.frame; });
    return script;
}

DemoScript loadDemoScript(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw Error("cannot read script '" + file.string() + "'");
    std::stringstream text;
    text << in.rdbuf();
    return parseDemoScript(text.str(), file.string());
}

}  // namespace vct
