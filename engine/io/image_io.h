// Image files: PNG (8-bit, for screenshots and references) through stb, EXR (32-bit float, exact HDR) through
// OpenEXR. Pixels are RGBA, row-major, top row first. Failures throw vct::Error naming the path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace vct {

struct ImageRgba8 {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> pixels;  // width * height * 4
};

struct ImageRgba32f {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> pixels;  // width * height * 4
};

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height,
              const std::vector<uint8_t>& rgba8);
// FLOAT channels R, G, B, A (lossless ZIP compression), so values read back bit for bit.
void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height,
              const std::vector<float>& rgba32f);

// Any PNG stb reads, converted to 8-bit RGBA.
ImageRgba8 readPng(const std::filesystem::path& path);
// Any EXR with R, G, B (A optional, 1 when absent; HALF or UINT channels are converted to float).
ImageRgba32f readExr(const std::filesystem::path& path);

}  // namespace vct
