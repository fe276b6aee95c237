// `vct demo --script FILE.json`: a session replayed frame by frame through the same applyOption calls the
// panel and keys make (app/demo/demo_controls.h), so tests and benchmarks can drive the demo.
//
//   [{"frame": 0, "set": {"weights": "sg", "trace-scale": 4}},
//    {"frame": 8, "screenshot": "a.png"},                 // the frame as shown, without the panel
//    {"frame": 9, "screenshot": "b.png", "ui": true},     // with the panel and timers
//    {"frame": 9, "set": {"camera-cut": true}}]
//
// "set" values are what the command line takes ("sg", 4, "on"; JSON true/false mean on/off). A step applies
// before its frame is rendered; a screenshot is taken after it. The file is checked whole at load time:
// a relative screenshot path is taken from the script's directory, and every screenshot must lie under that
// directory (unless --script-outputs-anywhere) in a directory that exists; frames are at most kMaxScriptFrame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace vct {

// The last frame a script may name (as --frames).
inline constexpr uint64_t kMaxScriptFrame = 100000000;

struct ScriptStep {
    uint32_t frame = 0;
    std::vector<std::pair<std::string, std::string>> options;  // applyOption(name, value), in file order
};

struct DemoScript {
    std::vector<ScriptStep> steps;  // sorted by frame (stable: file order within a frame)

    // The last frame a step names (the scripted run ends after rendering it).
    uint32_t lastFrame() const { return steps.empty() ? 0 : steps.back().frame; }
};

// Reads and checks a script (every option name and value); throws Error naming the file and the step.
DemoScript loadDemoScript(const std::filesystem::path& file, bool outputsAnywhere = false);
// The same from JSON text (tests); `source` names it in errors. Screenshots are confined to `outputDir` (the
// current directory when empty, their paths then kept as written).
DemoScript parseDemoScript(const std::string& text, const std::string& source,
                           const std::filesystem::path& outputDir = {}, bool outputsAnywhere = false);

}  // namespace vct
