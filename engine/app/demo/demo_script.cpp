#include "app/demo/demo_script.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/demo/demo_controls.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "scene/input_limits.h"

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

// Where a script's screenshot goes: a relative path is taken from `outputDir` (the script's directory; the
// current one for text without a file), and the result must stay under it unless `anywhere`; its directory
// must exist (checked at load time, not after the frames it took to get there).
std::string screenshotPath(const std::string& file, const std::string& where,
                           const std::filesystem::path& outputDir, bool anywhere) {
    const std::filesystem::path given(file);
    const std::filesystem::path base = outputDir.empty() ? std::filesystem::path(".") : outputDir;
    const std::filesystem::path path = given.is_absolute() || outputDir.empty() ? given : outputDir / given;
    if (file.empty()) throw Error(where + ": screenshot needs a file name");
    if (!anywhere && !pathWithin(path, base))
        throw Error(where + ": screenshot '" + file + "' is outside the script's directory '" +
                    base.string() + "' (vct demo --script-outputs-anywhere allows it)");
    std::error_code error;
    const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : ".";
    if (!std::filesystem::is_directory(parent, error))
        throw Error(where + ": screenshot '" + file + "': directory '" + parent.string() +
                    "' does not exist");
    return path.string();
}

}  // namespace

DemoScript parseDemoScript(const std::string& text, const std::string& source,
                           const std::filesystem::path& outputDir, bool outputsAnywhere) {
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
        // Read wide: a frame of 2^32 + 1 must not run at frame 1.
        const uint64_t frame = entry["frame"].get<uint64_t>();
        if (frame > kMaxScriptFrame)
            throw Error(where + ": frame " + std::to_string(frame) +
                        " is beyond the last frame a script may "
                        "name (" +
                        std::to_string(kMaxScriptFrame) + ")");
        step.frame = uint32_t(frame);
        for (const auto& [key, value] : entry.items()) {
            if (key == "frame" || key == "ui") continue;
            if (key == "set") {
                if (!value.is_object()) throw Error(where + ": \"set\" must be an object {option: value}");
                for (const auto& [name, v] : value.items())
                    step.options.emplace_back(name, optionText(v, where));
            } else if (key == "screenshot") {
                const bool ui = entry.contains("ui") && entry["ui"].is_boolean() && entry["ui"].get<bool>();
                const std::string file =
                    screenshotPath(optionText(value, where), where, outputDir, outputsAnywhere);
                step.options.emplace_back(ui ? "screenshot-ui" : "screenshot", file);
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

DemoScript loadDemoScript(const std::filesystem::path& file, bool outputsAnywhere) {
    // The one checked open: a FIFO or /dev/zero is refused, not read until memory runs out.
    const FileRead read = readRegularFile(file, uint64_t(1) << 24);
    if (!read.error.empty()) throw Error("cannot read script '" + file.string() + "': " + read.error);
    const std::filesystem::path dir = std::filesystem::absolute(file).parent_path();
    return parseDemoScript(std::string(read.bytes.begin(), read.bytes.end()), file.string(), dir,
                           outputsAnywhere);
}

}  // namespace vct
