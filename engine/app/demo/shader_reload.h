// Shader hot reload for the demo: compiles every shader source (shaders/*.comp|vert|frag|geom) with
// glslangValidator, the one the build uses, into a fresh directory, and on success points the pipeline loader
// there (VCT_SHADER_DIR, read by vk::loadShaderModule whenever a pipeline is made). The caller then makes new
// renderers; on a compile error nothing changes and the compiler's output is returned for the panel.
#pragma once

#include <filesystem>
#include <string>

namespace vct {

struct ShaderBuild {
    bool ok = false;
    std::string log;            // the compiler's output for the failing shader (or a summary)
    std::filesystem::path dir;  // where the SPIR-V went (ok only)
    int shaders = 0;
};

// The shader sources: $VCT_SHADER_SOURCE_DIR, else this checkout's shaders/ (a compile definition).
std::filesystem::path shaderSourceDir();

// Compiles every shader into `outDir` (created); stops at the first error. Safe to run on another thread.
ShaderBuild compileShaders(const std::filesystem::path& sourceDir, const std::filesystem::path& outDir);

// Makes vk::loadShaderModule read from `dir` (process environment: call between frames, on the main thread).
void useShaderDir(const std::filesystem::path& dir);
// The directory pipelines load from now.
std::filesystem::path currentShaderDir();

}  // namespace vct
