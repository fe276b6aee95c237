#include "io/image_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <stb/stb_image.h>        // implementation in Debian's libstb
#include <stb/stb_image_write.h>  // implementation in Debian's libstb

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "io/safe_write.h"
#include "scene/input_limits.h"

namespace vct {
namespace {

// Library messages (OpenEXR's in particular) may span lines and quote the file; errors here are one line.
std::string oneLine(const std::string& text) {
    return printableText(text, 240);
}

// The most pixels an image read back may have (16384 x 16384 RGBA float is 4 GB): a header of a few bytes
// can declare any size.
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

// OpenEXR files in memory: written whole, then through the checked writer; read from the checked open.
class MemoryOStream : public Imf::OStream {
  public:
    MemoryOStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (position_ + size_t(n) > bytes_.size()) bytes_.resize(position_ + size_t(n));
        std::memcpy(bytes_.data() + position_, c, size_t(n));
        position_ += size_t(n);
    }
    uint64_t tellp() override { return position_; }
    void seekp(uint64_t pos) override { position_ = size_t(pos); }
    const std::string& bytes() const { return bytes_; }

  private:
    std::string bytes_;
    size_t position_ = 0;
};

class MemoryIStream : public Imf::IStream {
  public:
    explicit MemoryIStream(const std::vector<unsigned char>& bytes, const std::string& name)
        : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || position_ > bytes_.size() || size_t(n) > bytes_.size() - position_)
            throw std::runtime_error("unexpected end of file");
        std::memcpy(c, bytes_.data() + position_, size_t(n));
        position_ += size_t(n);
        return position_ < bytes_.size();
    }
    uint64_t tellg() override { return position_; }
    void seekg(uint64_t pos) override { position_ = size_t(std::min<uint64_t>(pos, bytes_.size())); }

  private:
    const std::vector<unsigned char>& bytes_;
    size_t position_ = 0;
};

// The bytes of an input image through the one checked open (a FIFO never blocks, a device is refused).
std::vector<unsigned char> readImageFile(const std::filesystem::path& path, const char* kind) {
    FileRead file = readRegularFile(path);
    if (!file.error.empty())
        throw Error("cannot read " + std::string(kind) + " " + path.string() + ": " + file.error);
    return std::move(file.bytes);
}

void checkReadSize(const std::filesystem::path& path, const char* kind, uint64_t width, uint64_t height) {
    if (width == 0 || height == 0 || width * height > kMaxImagePixels)
        throw Error("cannot read " + std::string(kind) + " " + path.string() + ": it declares " +
                    std::to_string(width) + "x" + std::to_string(height) + " pixels (at most " +
                    std::to_string(kMaxImagePixels) + " allowed)");
}

void checkSize(const std::filesystem::path& path, uint32_t width, uint32_t height, size_t count) {
    if (width == 0 || height == 0 || count != size_t(width) * height * 4) {
        throw Error("cannot write " + path.string() + ": " + std::to_string(count) + " values for a " +
                    std::to_string(width) + "x" + std::to_string(height) + " RGBA image");
    }
}

constexpr const char* kChannels[4] = {"R", "G", "B", "A"};

std::string exrBytes(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<float>& rgba32f) {
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
        MemoryOStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(frameBuffer);
            file.writePixels(int(height));
        }
        return stream.bytes();
    } catch (const std::exception& e) {
        throw Error("cannot write EXR " + path.string() + ": " + oneLine(e.what()));
    }
}

}  // namespace

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height,
              const std::vector<uint8_t>& rgba8) {
    checkSize(path, width, height, rgba8.size());
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (stbi_write_png_to_func(append, &bytes, int(width), int(height), 4, rgba8.data(), int(width * 4)) == 0)
        throw Error("cannot write PNG " + path.string());
    writeFileReplacing(path, bytes);
}

ImageRgba8 readPng(const std::filesystem::path& path) {
    const std::vector<unsigned char> bytes = readImageFile(path, "PNG");
    if (bytes.size() > size_t(INT32_MAX)) throw Error("cannot read PNG " + path.string() + ": too large");
    int width = 0, height = 0, channels = 0;
    if (stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels))
        checkReadSize(path, "PNG", uint64_t(std::max(width, 0)), uint64_t(std::max(height, 0)));
    std::unique_ptr<stbi_uc, void (*)(void*)> data(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 4),
        stbi_image_free);
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
    writeFileReplacing(path, exrBytes(path, width, height, rgba32f));
}

ImageRgba32f readExr(const std::filesystem::path& path) {
    const std::vector<unsigned char> bytes = readImageFile(path, "EXR");
    try {
        MemoryIStream stream(bytes, path.string());
        Imf::InputFile file(stream);
        const Imath::Box2i window = file.header().dataWindow();
        checkReadSize(path, "EXR", uint64_t(int64_t(window.max.x) - window.min.x + 1),
                      uint64_t(int64_t(window.max.y) - window.min.y + 1));
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
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read EXR " + path.string() + ": " + oneLine(e.what()));
    }
}

}  // namespace vct
