// Scenes made in code (no asset files): the default `cornell` room and the `plane` used by the
// normal-map filtering (Toksvig) tests. loadScene() is the one entry point for "--scene NAME|PATH".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace vct {

// Names of the built-in scenes; the first is the default.
std::vector<std::string> builtinSceneNames();
// One line describing a built-in scene ("" for an unknown name).
std::string builtinSceneDescription(const std::string& name);
// The built-in scene with this name, validated, or nullopt.
std::optional<Scene> makeBuiltinScene(const std::string& name);
// A built-in scene by name, else a .gltf/.glb file. Throws vct::Error
// "unknown scene 'x' (not a built-in scene and no such file)" when it is neither.
Scene loadScene(const std::string& nameOrPath);

}  // namespace vct
