#include "app/demo/shader_reload.h"

#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <vector>

namespace vct {

namespace {

// Single quotes for /bin/sh, with embedded quotes closed and escaped.
std::string quoted(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Runs a shell command; returns its exit status and everything it printed.
int run(const std::string& command, std::string& output) {
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) {
        output = "cannot start: " + command;
        return -1;
    }
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) output.append(buffer, n);
    return pclose(pipe);
}

}  // namespace

std::filesystem::path shaderSourceDir() {
    const char* dir = std::getenv("VCT_SHADER_SOURCE_DIR");
    return dir && *dir ? std::filesystem::path(dir) : std::filesystem::path(VCT_SHADER_SOURCE_DIR);
}

ShaderBuild compileShaders(const std::filesystem::path& sourceDir, const std::filesystem::path& outDir) {
    ShaderBuild build;
    build.dir = outDir;
    std::error_code error;
    std::vector<std::filesystem::path> sources;
    for (const auto& entry : std::filesystem::directory_iterator(sourceDir, error)) {
        const std::string ext = entry.path().extension().string();
        if (ext == ".comp" || ext == ".vert" || ext == ".frag" || ext == ".geom")
            sources.push_back(entry.path());
    }
    if (error || sources.empty()) {
        build.log = "no shader sources in " + sourceDir.string() + (error ? ": " + error.message() : "");
        return build;
    }
    std::filesystem::create_directories(outDir, error);
    if (error) {
        build.log = "cannot create " + outDir.string() + ": " + error.message();
        return build;
    }
    // The same flags as the build (CMakeLists.txt), so a reload gives the SPIR-V a rebuild would.
    for (const auto& source : sources) {
        const std::filesystem::path spirv = outDir / (source.filename().string() + ".spv");
        const std::string command = quoted(VCT_GLSLANG) + " --target-env vulkan1.3 -I" +
                                    quoted(sourceDir.string()) + " -o " + quoted(spirv.string()) + " " +
                                    quoted(source.string());
        std::string output;
        if (run(command, output) != 0) {
            build.log = source.filename().string() + ":\n" + output;
            return build;
        }
        ++build.shaders;
    }
    build.ok = true;
    build.log = std::to_string(build.shaders) + " shaders compiled";
    return build;
}

void useShaderDir(const std::filesystem::path& dir) {
    setenv("VCT_SHADER_DIR", dir.c_str(), 1);
}

std::filesystem::path currentShaderDir() {
    const char* dir = std::getenv("VCT_SHADER_DIR");
    return dir && *dir ? std::filesystem::path(dir) : std::filesystem::path(VCT_SHADER_DIR);
}

}  // namespace vct
