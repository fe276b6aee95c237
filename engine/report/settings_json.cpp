#include "report/settings_json.h"

#include <variant>

#include "core/error.h"
#include "render/setting_table.h"

namespace vct {

nlohmann::json settingsJson(const RenderSettings& s) {
    nlohmann::json json = nlohmann::json::object();
    for (const SettingSpec& spec : settingTable()) {
        if (!spec.json) continue;
        json[settingJsonKey(spec)] = std::visit(
            Overloaded{
                [&](const FloatValue& v) { return nlohmann::json(s.*v.member); },
                [&](const OnOffValue& v) { return nlohmann::json(s.*v.member); },
                [&](const ChoiceValue& v) {
                    const char* word = v.wordOf(s.*v.member);
                    return word ? nlohmann::json(word) : nlohmann::json(s.*v.member);
                },
                [&](const NamedValue& v) { return nlohmann::json(v.names[v.get(s)]); },
                [&](const auto&) -> nlohmann::json {
                    throw Error(std::string("settingsJson: no JSON form for setting '") + spec.name + "'");
                },
            },
            spec.value);
    }
    return json;
}

}  // namespace vct
