// vct scenes: the built-in scenes, one per line with a description.
#include <cstdio>

#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "scene/builtin_scenes.h"

namespace vct {

int runScenesCommand(int argc, char** argv, int first) {
    static const CommandSpec spec("scenes", "Lists the built-in scenes (made in code; no files needed).", {});
    if (!spec.parse(argc, argv, first)) return 0;
    for (const std::string& name : builtinSceneNames())
        std::printf("%-10s %s\n", name.c_str(), builtinSceneDescription(name).c_str());
    return 0;
}

}  // namespace vct
