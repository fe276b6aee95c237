// The render settings a run used, as JSON (timings.json, benchmark.json): what a number was measured with.
// The rows of the setting table marked `json` (render/setting_table.h), keyed by name with '_' for '-'.
#pragma once

#include <nlohmann/json.hpp>

#include "render/settings.h"

namespace vct {

nlohmann::json settingsJson(const RenderSettings& settings);

}  // namespace vct
