// The render settings a run used, as JSON (timings.json, benchmark.json): what a number was measured with.
#pragma once

#include <nlohmann/json.hpp>

#include "render/settings.h"

namespace vct {

nlohmann::json settingsJson(const RenderSettings& settings);

}  // namespace vct
