#include "io/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>        // implementation in Debian's libstb
#include <stb/stb_image_write.h>  // implementation in Debian's libstb

#include <algorithm>
#include <exception>
#include <memory>
#include <string>

#include "core/error.h"
#include "io/safe_write.h"

namespace vct {
namespace {

// Library messages (OpenEXR's in particular) may span lines; errors here are one line.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

void checkSize(const std::filesystem::path& path, uint32_t width, uint32_t height, size_t count) {
    if (width == 0 || height == 0 || count != size_t(width) * height * 4) {
        throw Error("cannot write " + path.string() + ": " + std::to_string(count) + " values for a " +
                    std::to_string(width) + "x" + std::to_string(height) + " RGBA image");
    }
}

constexpr const char* kChannels[4] = {"R", "G", "B", "A"};

void writeExrFile(const std::filesystem::path& temporary, const std::filesystem::path& path, uint32_t width,
                  uint32_t height, const std::vector<float>& rgba32f) {
    try {
        Imf::Header header(static_cast<int>(width), static_cast<int>(height));
        Imf::FrameBuffer frameBuffer;
        const size_t xStride = 4 * sizeof(float);
        const size_t yStride = xStride * width;
        for (int c = 0; c < 4; ++c) {
            header.channels().insert(kChannels[c], Imf::Channel(Imf::FLOAT));
            frameBuffer.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, rgba32f.data() + c,
                                                              header.dataWindow(), xStride, yStride));
        }
        Imf::OutputFile file(temporary.c_str(), header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(int(height));
    } catch (const std::exception& e) {
        throw Error("cannot write EXR " + path.string() + ": " + oneLine(e.what()));
    }
}

}  // namespace

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height,
              const std::vector<uint8_t>& rgba8) {
    checkSize(path, width, height, rgba8.size());
    writeReplacing(path, [&](const std::filesystem::path& temporary) {
        if (stbi_write_png(temporary.c_str(), int(width), int(height), 4, rgba8.data(), int(width * 4)) == 0)
            throw Error("cannot write PNG " + path.string());
    });
}

ImageRgba8 readPng(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> data(
        stbi_load(path.string().c_str(), &width, &height, &channels, 4), stbi_image_free);
    const char* reason = stbi_failure_reason();
    if (!data) {
        throw Error("cannot read PNG " + path.string() + ": " + oneLine(reason ? reason : "unknown error"));
    }
    ImageRgba8 image{uint32_t(width), uint32_t(height), {}};
    image.pixels.assign(data.get(), data.get() + size_t(width) * size_t(height) * 4);
    return image;
}

void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height,
              const std::vector<float>& rgba32f) {
    checkSize(path, width, height, rgba32f.size());
    writeReplacing(path, [&](const std::filesystem::path& temporary) {
        writeExrFile(temporary, path, width, height, rgba32f);
    });
}

ImageRgba32f readExr(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.string().c_str());
        const Imath::Box2i window = file.header().dataWindow();
        ImageRgba32f image;
        image.width = uint32_t(window.max.x - window.min.x + 1);
        image.height = uint32_t(window.max.y - window.min.y + 1);
        image.pixels.resize(size_t(image.width) * image.height * 4);
        Imf::FrameBuffer frameBuffer;
        const size_t xStride = 4 * sizeof(float);
        const size_t yStride = xStride * image.width;
        for (int c = 0; c < 4; ++c) {
            // Slice::Make offsets the base by the data window's origin; absent channels get the fill value.
            const double fill = c == 3 ? 1.0 : 0.0;
            frameBuffer.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window,
                                                              xStride, yStride, 1, 1, fill));
        }
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const std::exception& e) {
        throw Error("cannot read EXR " + path.string() + ": " + oneLine(e.what()));
    }
}

}  // namespace vct
