// glTF 2.0 export of a vct::Scene as one binary file (.glb), so that other tools can open exactly the scene
// that is rendered and measured (`vct export-scene`; the built-in rooms in scenes/*.glb).
#pragma once

#include <filesystem>

#include "scene/scene.h"

namespace vct {

struct GlbOptions {
    // Encode every texture's level 0 as PNG, also those loaded from a PNG or JPEG file (which are otherwise
    // written as the bytes loaded: a JPEG re-encoded as PNG is several times larger).
    bool reencodeImages = false;
};

// Writes `scene` to `path` as a .glb (JSON chunk + one BIN chunk holding every buffer and image): meshes
// (POSITION, NORMAL, TANGENT, TEXCOORD_0, COLOR_0 where present, indices), metallic-roughness materials with
// all their textures, the textures' images as loaded (else level 0 as PNG) with their wrap modes, the node hierarchy (TRS or matrix), perspective
// cameras, KHR_lights_punctual lights and rigid TRS animations. loadGltf() reads the file back into the same
// Scene (see gltf_writer.cpp for what that means exactly and for the few things glTF cannot hold). Throws
// vct::Error "cannot write <path>: ..." when the scene cannot be written.
void writeGlb(const Scene& scene, const std::filesystem::path& path, const GlbOptions& options = {});

}  // namespace vct
