// glTF 2.0 import (.gltf with external or embedded buffers, and .glb) into the flat vct::Scene.
#pragma once

#include <string>

#include "scene/scene.h"

namespace vct {

// Loads the default scene (or scene 0) of a glTF file: triangle meshes (strips and fans converted),
// metallic-roughness materials, textures with mip chains, cameras, KHR_lights_punctual lights and rigid
// TRS animations, skins (two weight sets) and morph targets (POSITION, NORMAL, TANGENT; weights animated).
// Missing normals become flat normals; missing tangents are generated. Unsupported features are ignored and
// recorded in Scene::notes. A default camera and
// light are added when the file has none. Throws vct::Error with one line "<path>: <problem>" when the
// file cannot be used (missing file, bad JSON, truncated buffer, missing image, non-finite data, ...).
Scene loadGltf(const std::string& path);

}  // namespace vct
