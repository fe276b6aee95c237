// vct export-scene: writes a scene, built-in or loaded, as one glTF 2.0 binary (.glb), so that other tools
// can open exactly what vct renders (scenes/cornell.glb and scenes/plane.glb are made with it).
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

#include "app/cli/cli.h"
#include "app/cli/commands.h"
#include "core/error.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"

namespace vct {

int runExportSceneCommand(int argc, char** argv, int first) {
    static const CommandSpec spec(
        "export-scene",
        "Writes the scene as glTF 2.0 binary (FILE.glb): meshes, materials, textures (the PNG and JPEG "
        "files\n"
        "as loaded, others as PNG), nodes, cameras, KHR_lights_punctual lights and animations; loading it "
        "back\n"
        "gives the same scene. The built-in rooms in scenes/ are made with it:\n"
        "vct export-scene --scene cornell --out scenes/cornell.glb",
        {{"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
         {"out", "FILE.glb", "the file to write (required; its directory is created if missing)", ""},
         {"reencode-images", "", "encode every texture as PNG, also those loaded from PNG or JPEG files",
          ""}});
    auto parsed = spec.parse(argc, argv, first);
    if (!parsed) return 0;
    const std::filesystem::path out = parsed->get("out");
    if (out.empty()) throw UsageError("vct export-scene: --out FILE.glb is required");
    if (out.extension() != ".glb")
        throw UsageError("--out '" + out.string() + "': expected a .glb file name");
    const std::string sceneName = parsed->get("scene");
    if (sceneName.empty()) throw UsageError("--scene: expected a scene name or a glTF file");

    const Scene scene = loadScene(sceneName);
    for (const std::string& note : scene.notes) std::printf("note: %s\n", note.c_str());
    if (out.has_parent_path()) {
        std::error_code error;
        std::filesystem::create_directories(out.parent_path(), error);
        if (error)
            throw Error("cannot create directory '" + out.parent_path().string() + "': " + error.message());
    }
    GlbOptions options;
    options.reencodeImages = parsed->has("reencode-images");
    writeGlb(scene, out, options);

    std::error_code error;
    const auto bytes = static_cast<unsigned long long>(std::filesystem::file_size(out, error));
    std::printf(
        "wrote %s (%llu bytes): %zu meshes, %zu materials, %zu textures, %zu nodes, %zu cameras, "
        "%zu lights, %zu animations\n",
        out.c_str(), bytes, scene.meshes.size(), scene.materials.size(), scene.textures.size(),
        scene.nodes.size(), scene.cameras.size(), scene.lights.size(), scene.animations.size());
    return 0;
}

}  // namespace vct
