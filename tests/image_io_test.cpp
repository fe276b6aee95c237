// PNG and EXR round trips, and one-line errors that name the file.
#include "io/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace {

namespace fs = std::filesystem;

fs::path outputDir() {
    fs::path dir = fs::path(VCT_TEST_OUTPUT) / "image_io";
    fs::create_directories(dir);
    return dir;
}

// Runs `f`, which must throw vct::Error with a single-line message that names `path`.
template <typename F>
void expectOneLineError(F f, const fs::path& path) {
    try {
        f();
        ADD_FAILURE() << "no error for " << path;
    } catch (const vct::Error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(ImageIo, PngRoundTrip) {
    const uint32_t width = 7, height = 5;  // odd sizes catch stride mistakes
    std::vector<uint8_t> pixels(width * height * 4);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t((i * 37 + i / 4) % 256);
    const fs::path path = outputDir() / "round_trip.png";
    vct::writePng(path, width, height, pixels);
    vct::ImageRgba8 image = vct::readPng(path);
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(image.pixels, pixels);
}

TEST(ImageIo, ExrRoundTripIsExact) {
    const uint32_t width = 6, height = 3;
    std::vector<float> pixels(width * height * 4);
    const float specials[] = {0.0f, 1.0f, -2.5f, 1e-30f, 3e30f, 0.1f, 65504.0f, 1.0f / 3.0f};
    for (size_t i = 0; i < pixels.size(); ++i) {
        pixels[i] = i < 8 ? specials[i] : std::sin(float(i)) * float(i);  // values half floats cannot hold
    }
    const fs::path path = outputDir() / "round_trip.exr";
    vct::writeExr(path, width, height, pixels);
    vct::ImageRgba32f image = vct::readExr(path);
    EXPECT_EQ(image.width, width);
    EXPECT_EQ(image.height, height);
    EXPECT_EQ(image.pixels, pixels);
}

TEST(ImageIo, ErrorsAreOneLineAndNameThePath) {
    const fs::path missing = outputDir() / "does_not_exist.png";
    const fs::path missingExr = outputDir() / "does_not_exist.exr";
    const fs::path noDir = outputDir() / "no_such_dir" / "x.png";
    const fs::path noDirExr = outputDir() / "no_such_dir" / "x.exr";
    const std::vector<uint8_t> rgba8(4 * 4, 255);
    const std::vector<float> rgba32f(4 * 4, 1.0f);
    expectOneLineError([&] { vct::readPng(missing); }, missing);
    expectOneLineError([&] { vct::readExr(missingExr); }, missingExr);
    expectOneLineError([&] { vct::writePng(noDir, 2, 2, rgba8); }, noDir);
    expectOneLineError([&] { vct::writeExr(noDirExr, 2, 2, rgba32f); }, noDirExr);
    // A size that does not match the pixel count is refused before anything is written.
    const fs::path wrongSize = outputDir() / "wrong_size.png";
    expectOneLineError([&] { vct::writePng(wrongSize, 3, 2, rgba8); }, wrongSize);
    EXPECT_FALSE(fs::exists(wrongSize));
    // A PNG is not an EXR.
    const fs::path png = outputDir() / "not_an.exr";
    vct::writePng(png, 2, 2, rgba8);
    expectOneLineError([&] { vct::readExr(png); }, png);
}

}  // namespace
