// vct voxelize: renders the frame at t = 0 with GI on (so the voxels are voxelized, resolved and lit), reads the
// voxel grid back and writes it as sparse OpenVDB grids (io/vdb_io.h): what the renderer's volumes hold
// (albedo, normal, emission, opacity, injected radiance) and the static geometry's exact accumulator, which
// `vct render --voxel-cache FILE` loads instead of voxelizing the static instances.
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "app/cli/session.h"
#include "core/error.h"
#include "io/safe_write.h"
#include "io/vdb_io.h"

namespace vct {

namespace {

const CommandSpec& voxelizeSpec() {
    static const CommandSpec spec(
        "voxelize",
        "Voxelizes the scene at t = 0 (and lights the voxels) and writes FILE.vdb: sparse OpenVDB grids "
        "albedo, normal,\n"
        "emission, opacity, radiance and the static geometry's accumulator (static_*), read back by\n"
        "vct render --voxel-cache FILE.vdb.",
        {{"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
         settingOption("voxels"),
         {"out", "FILE.vdb", "the OpenVDB file to write (required; its directory is created if missing)", ""},
         {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
         {"validate", "", "enable the Khronos validation layer; any message fails the run", ""},
         {"voxel-cache", "FILE.vdb",
          "start from this file's static voxelization (a re-export gives the same file)", ""}});
    return spec;
}

// The frame that lights the voxels is never shown: a small image keeps its other passes cheap. Nothing the
// voxel passes compute depends on the image size (the shadow map has its own fixed size).
constexpr uint32_t kFrameSize = 64;

std::string megabytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

// The sparse voxel list of the volumes the frame left in the grid: occupied = opacity (albedo.a) > 0.
std::vector<VoxelSample> readFrameVoxels(VoxelGrid& grid) {
    const uint32_t n = grid.resolution();
    std::vector<VoxelSample> voxels;
    std::vector<size_t> linear;  // index into the dense volumes of each voxel
    {
        const std::vector<glm::vec4> albedo = grid.readVolume(grid.albedo());
        for (size_t i = 0; i < albedo.size(); ++i) {
            if (albedo[i].a <= 0.0f) continue;
            VoxelSample v;
            v.ijk = glm::ivec3(int(i % n), int((i / n) % n), int(i / (size_t(n) * n)));
            v.albedo = glm::vec3(albedo[i]);
            v.opacity = albedo[i].a;
            voxels.push_back(v);
            linear.push_back(i);
        }
    }
    // One volume at a time: at 256³ each dense copy is 256 MiB.
    auto fill = [&](vk::Image& image, glm::vec3 VoxelSample::*field) {
        const std::vector<glm::vec4> volume = grid.readVolume(image);
        for (size_t k = 0; k < voxels.size(); ++k) voxels[k].*field = glm::vec3(volume[linear[k]]);
    };
    fill(grid.normal(), &VoxelSample::normal);
    fill(grid.emission(), &VoxelSample::emission);
    // Mip 0 premultiplied (= radiance, as opacity is 0 or 1), the brightest of the six directions.
    const std::vector<glm::vec4> radiance = grid.readRadiance();
    for (size_t k = 0; k < voxels.size(); ++k) voxels[k].radiance = glm::vec3(radiance[linear[k]]);
    return voxels;
}

}  // namespace

int runVoxelizeCommand(int argc, char** argv, int first) {
    auto parsed = voxelizeSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    const std::filesystem::path out = args.get("out");
    if (out.empty()) throw UsageError("vct voxelize: --out FILE.vdb is required");
    if (out.extension() != ".vdb")
        throw UsageError("--out '" + out.string() + "': expected a .vdb file name");

    SessionOptions options;
    options.scene = args.get("scene");
    options.settings.width = options.settings.height = kFrameSize;
    options.settings.gi = true;
    // --voxels (absent: the device's default, or the cache's N) and --voxel-cache, as the setting table
    // parses them.
    applySettingArgs(args, options.settings);
    options.context.deviceSubstring = args.get("device");
    options.context.validation = args.has("validate");

    // Before any work: where the file goes must be a directory, and the file not one.
    if (out.has_parent_path()) prepareOutputDirectory(out.parent_path(), "--out");
    std::error_code error;
    if (std::filesystem::is_directory(out, error))
        throw UsageError("--out '" + out.string() + "' is a directory, expected a .vdb file name");
    {
        Session session(options);
        Renderer& renderer = session.renderer();
        const FrameInput input = fixedStepFrame(session.scene(), 0, /*warmup=*/1);  // t = 0, untimed
        renderer.render(input);

        VoxelGrid& grid = *renderer.voxelGrid();
        VoxelFile file;
        file.info.resolution = grid.resolution();
        file.info.origin = grid.origin();
        file.info.voxelSize = grid.voxelSize();
        file.info.scene = options.scene;
        file.info.time = input.timeSeconds;
        file.info.sceneHash = sceneContentHash(session.scene());
        file.voxels = readFrameVoxels(grid);
        file.staticAccum = grid.readStaticAccumulator();

        const std::vector<VoxelGridSummary> grids = writeVoxelFile(out, file);

        const uint32_t n = grid.resolution();
        const uint64_t total = uint64_t(n) * n * n;
        std::printf("voxels: %u^3, origin (%g, %g, %g), voxel size %g, t = 0\n", n, double(grid.origin().x),
                    double(grid.origin().y), double(grid.origin().z), double(grid.voxelSize()));
        for (const VoxelGridSummary& g : grids)
            std::printf("  %-20s %-6s %9llu active voxels (%.1f%%)\n", g.name.c_str(), g.type.c_str(),
                        static_cast<unsigned long long>(g.activeVoxels),
                        100.0 * double(g.activeVoxels) / double(total));
        const uint64_t fileBytes = std::filesystem::file_size(out, error);
        const uint64_t denseBytes = denseVoxelBytes(n);
        std::printf("wrote %s: %s (%llu bytes), dense %s (%.1f%% of it)\n", out.c_str(),
                    megabytes(fileBytes).c_str(), static_cast<unsigned long long>(fileBytes),
                    megabytes(denseBytes).c_str(), 100.0 * double(fileBytes) / double(denseBytes));
    }
    // Counted after the device is destroyed, so leaks reported at teardown fail the run too.
    checkValidation(options);
    return 0;
}

}  // namespace vct
