// vct: real-time global illumination by voxel cone tracing. Entry point: dispatches the subcommand and turns
// every error into one line on stderr and a non-zero exit (2: bad usage, 1: anything else).
#include <cstdio>
#include <cstring>
#include <string>

#include "app/bench/benchmark_command.h"
#include "app/cli/commands.h"
#include "app/demo/demo_command.h"
#include "core/error.h"
#include "io/vdb_io.h"
#include "scene/input_limits.h"

namespace {

const char* kUsage =
    "usage: vct COMMAND [options]\n"
    "Voxel cone tracing global illumination on glTF scenes (Vulkan).\n\n"
    "commands:\n"
    "  render   render frames headless; write final.png, final.exr, timings.json\n"
    "  demo     open a window and show the frame live (WASD + mouse, Esc quits)\n"
    "  scenes   list the built-in scenes\n"
    "  voxelize voxelize the scene at t = 0 into OpenVDB grids (a cache for --voxel-cache)\n"
    "  benchmark  per-pass timings and error of the upsampling configurations, in one run\n"
    "  reference  path-trace the ground truth of a frame on the CPU (Embree), in the units of render --aux\n"
    "  compare  error metrics of an EXR image against a reference\n"
    "  export-scene  write a scene (built-in or loaded) as glTF 2.0 binary (.glb)\n\n"
    "Run 'vct COMMAND --help' for a command's options.\n";

// Messages are one line whatever their source (tinygltf, the driver, ...), of bounded length (a 40 MB data
// uri quoted by a library stays out of the terminal), with control characters escaped (a file name holding
// an escape sequence cannot drive the terminal).
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return vct::printableText(text, 600);
}

int dispatch(int argc, char** argv) {
    if (argc < 2) throw vct::UsageError("no command given (usage: vct COMMAND [options]; see vct --help)");
    const std::string command = argv[1];
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (command == "render") return vct::runRenderCommand(argc, argv, 2);
    if (command == "demo") return vct::runDemoCommand(argc, argv, 2);
    if (command == "scenes") return vct::runScenesCommand(argc, argv, 2);
    if (command == "voxelize") return vct::runVoxelizeCommand(argc, argv, 2);
    if (command == "compare") return vct::runCompareCommand(argc, argv, 2);
    if (command == "benchmark") return vct::runBenchmarkCommand(argc, argv, 2);
    if (command == "reference") return vct::runReferenceCommand(argc, argv, 2);
    if (command == "export-scene") return vct::runExportSceneCommand(argc, argv, 2);
    throw vct::UsageError("unknown command '" + command + "' (see vct --help)");
}

}  // namespace

int main(int argc, char** argv) {
    // Voxel caches are parsed by OpenVDB in a process of their own first (io/vdb_io.h): this program.
    if (argc == 4 && std::strcmp(argv[1], vct::kCheckVoxelFileFlag) == 0)
        return vct::checkVoxelFileInIsolation(argv[2], argv[3]);
    vct::setVoxelFileIsolation("/proc/self/exe");
    try {
        return dispatch(argc, argv);
    } catch (const vct::UsageError& e) {
        std::fprintf(stderr, "vct: error: %s\n", oneLine(e.what()).c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vct: error: %s\n", oneLine(e.what()).c_str());
        return 1;
    }
}
